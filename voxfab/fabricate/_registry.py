"""Name → output function table, imported lazily so heavy libraries load only when used."""

from __future__ import annotations

import dataclasses
import importlib
from collections.abc import Callable

from voxfab.errors import UnknownFormatError


@dataclasses.dataclass(frozen=True)
class OutputFile:
    """A file written by an output, relative to the recipe's output folder."""

    path: str
    purpose: str


#: Output name → ``"module:function"``.
OUTPUTS: dict[str, str] = {
    "mesh": "voxfab.fabricate.mesh:recipe_output",
    "net": "voxfab.fabricate.netdraw:recipe_output",
    "slices": "voxfab.fabricate.plates:recipe_output",
    "pictures": "voxfab.render:recipe_output",
    "animation": "voxfab.render._animate:recipe_output",
}


def available_outputs() -> list[str]:
    """Names of the recipe outputs."""
    return sorted(OUTPUTS)


def get_output(name: str) -> Callable[..., list[OutputFile]]:
    """Return the output function registered under ``name``."""
    if name not in OUTPUTS:
        raise UnknownFormatError(
            f"unknown output {name!r}; expected one of {', '.join(available_outputs())}"
        )
    module, func = OUTPUTS[name].split(":")
    return getattr(importlib.import_module(module), func)
