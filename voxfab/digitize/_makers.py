"""Name → shape maker table for recipes, imported lazily.

A maker is a function ``make(*, base_dir, **params) -> (X, Y, Z) bool ndarray``.
Its keyword-only parameters, with their type hints, are the recipe keys it
accepts; ``base_dir`` is the recipe's folder, for relative file names.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable

import numpy as np

from voxfab.errors import UnknownFormatError

#: Maker name → ``"module:function"``.
MAKERS: dict[str, str] = {
    "focal": "voxfab.digitize._recipes:make_focal",
    "implicit": "voxfab.digitize._recipes:make_implicit",
    "revolution": "voxfab.digitize._recipes:make_revolution",
    "tube": "voxfab.digitize._recipes:make_tube",
}


def available_makers() -> list[str]:
    """Names of the registered makers."""
    return sorted(MAKERS)


def get_maker(name: str) -> Callable[..., np.ndarray]:
    """Return the maker registered under ``name``."""
    if name not in MAKERS:
        known = ", ".join(available_makers()) or "(none)"
        raise UnknownFormatError(f"unknown maker {name!r}; expected one of {known}")
    module, func = MAKERS[name].split(":")
    return getattr(importlib.import_module(module), func)
