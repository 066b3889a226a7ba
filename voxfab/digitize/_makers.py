"""The table of shape makers: one row per maker, naming its function and describing its keys.

A maker is a function ``make(*, base_dir, **params) -> (X, Y, Z) bool ndarray``.
Its keyword-only parameters are the recipe keys it accepts; ``base_dir`` is the
recipe's folder, for relative file names.  The function's signature is where a
key's type and default live; the row adds what a signature cannot say: the
key's meaning and range, and the function that draws random parameters for
``voxfab explore``.  Recipes, the studio, ``explore`` and the README read the
table, so adding a maker is one function and one row.

Functions are named ``"module:function"`` and imported when first used, so
reading the table costs no import of the digitizers.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import inspect
import math
import types
import typing
from collections.abc import Callable
from typing import Any

import numpy as np

from voxfab._shared.limits import MAX_SAMPLES
from voxfab._shared.options import quote
from voxfab._shared.validate import finite_number, type_fits, type_name
from voxfab.errors import UnknownFormatError

__all__ = ["MAKERS", "Maker", "Param", "available_makers", "get_maker", "get_random_params", "maker_markdown",
           "maker_params", "random_makers"]


@dataclasses.dataclass(frozen=True)
class Param:
    """One key of a maker.

    The row gives ``name``, ``help`` and an optional inclusive range; :func:`maker_params`
    fills ``hint``, ``required`` and ``default`` from the maker's signature.
    """

    name: str
    help: str
    low: float | None = None
    high: float | None = None
    hint: Any = None
    required: bool = False
    default: Any = None
    #: Plain words for a form's field, where the key's own name is not (``curve_threshold``).
    label: str = ""

    @property
    def words(self) -> str:
        """What a form calls the key: its label, else its name in words (``t_min`` is ``t min``)."""
        return self.label or self.name.replace("_", " ")

    def problem(self, value: Any) -> str | None:
        """Why ``value`` (a TOML or JSON value) does not fit this key, or None when it does."""
        if not type_fits(value, self.hint):
            return f"expected {type_name(self.hint)}, got {type(value).__name__} {value!r:.80}"
        if isinstance(value, float) and not math.isfinite(value):
            return f"expected a finite number, got {value!r}"
        if isinstance(value, int) and not isinstance(value, bool) and finite_number(value) is None:
            # JSON's 10**400: past every float, so past every range (and float() of it would raise)
            return f"expected a finite number, got {quote(value)}"
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            low, high = self.low, self.high
            if (low is not None and value < low) or (high is not None and value > high):
                what = "an integer" if isinstance(value, int) and int in self._alternatives else "a number"
                span = f"in {low:g}..{high:g}" if low is not None and high is not None else \
                    f">= {low:g}" if low is not None else f"<= {high:g}"
                return f"expected {what} {span}, got {value!r}"
        if isinstance(value, list):
            for i, item in enumerate(value):
                if isinstance(item, (int, float)) and not isinstance(item, bool) and finite_number(item) is None:
                    # TOML's nan and inf, JSON's 10**400: no place in a list of coordinates or bounds
                    return f"expected finite numbers, got {quote(item)} at [{i}]"
        return None

    def normal(self, value: Any) -> Any:
        """``value`` as the maker takes it: a whole number given for a float key becomes a float."""
        takes = self._alternatives
        if isinstance(value, int) and not isinstance(value, bool) and float in takes and int not in takes:
            return float(value)
        if isinstance(value, list) and list[float] in takes:
            return [float(v) if isinstance(v, int) and not isinstance(v, bool) else v for v in value]
        return value

    @property
    def kind(self) -> str | None:
        """What a value of the key is, for a form that asks for it.

        ``"flag"``, ``"integer"``, ``"number"``, ``"word"`` (one of :attr:`choices`) or
        ``"numbers"`` (a list of numbers: a point, bounds, weights); None for a text, a file
        name or nested lists, which a front end asks for in its own way (an expression, a drawing).
        """
        takes = [a for a in self._alternatives if a is not type(None)]
        if not takes:
            return None
        if all(typing.get_origin(a) is typing.Literal for a in takes):
            return "word"
        if takes == [bool]:
            return "flag"
        if takes == [int]:
            return "integer"
        if set(takes) <= {int, float}:
            return "number"
        if all(a in (list[float], list[int]) for a in takes):
            return "numbers"
        return None

    @property
    def choices(self) -> tuple[Any, ...]:
        """The words a ``"word"`` key takes (its Literal's values), in the signature's order."""
        return tuple(c for a in self._alternatives if typing.get_origin(a) is typing.Literal
                     for c in typing.get_args(a))

    @property
    def is_scalar(self) -> bool:
        """A number, a word or a flag (not a list, a file or an expression that may be a file)."""
        return self.kind in ("flag", "integer", "number", "word")

    @property
    def type_words(self) -> str:
        """The key's type in words, as the README's tables and the studio show it: ``float``, ``"solid" or "surface"``."""
        return type_name(self.hint).replace("'", '"').replace(" or none", "")

    @property
    def _alternatives(self) -> tuple[Any, ...]:
        """The members of a union hint (``float | None``), or the hint itself."""
        union = typing.get_origin(self.hint) in (typing.Union, types.UnionType)
        return typing.get_args(self.hint) if union else (self.hint,)


@dataclasses.dataclass(frozen=True)
class Maker:
    """One row of the table: a maker's name, function, keys and random parameters."""

    name: str
    #: ``"module:function"`` of the maker.
    make: str
    help: str
    params: tuple[Param, ...]
    #: ``"module:function"`` drawing random keyword arguments from a ``numpy.random.Generator``,
    #: for ``voxfab explore``; None when the maker has no random form.
    random: str | None = None


# --- keys several makers share ---------------------------------------------------------------

_K = Param("k", "flake: 0 gives tunnel-free surfaces, 1 and 2 thinner ones", 0, 2)
_MODE = Param("mode", '"solid" (the region) or "surface" (its boundary)')
_SIZE = Param("size", "side of the voxel grid", 2, 256)
_SCALE = Param("scale", "voxels per model unit; without it the shape is fitted to the grid and centred", label="voxels per unit")
_CENTER = Param("center", "[x, y, z]: the model point at the grid's middle (with scale): a fixed placement", label="centre point")
_ARC = Param("arc", "[start, end], degrees: keep only that open part of the curve (mode surface)", label="open arc (degrees)")
_AT = Param("at", "a 4D field's last coordinate at the 3D slice (default its middle)", label="4D slice at w")
_COMMON = (_K, _MODE, _SIZE, _SCALE)

#: Maker name → row.
MAKERS: dict[str, Maker] = {m.name: m for m in (
    Maker(
        "revolution", "voxfab.digitize._recipes:make_revolution",
        "a curve of revolution times a generatrix, each an expression, a drawing (SVG, JSON, CSV) or a bitmap",
        (
            Param("generatrix", "the profile in the (radius, height) half-plane: an expression, a drawing or a "
                                "bitmap; x = g(y) is the solid under a radius function"),
            Param("curve", "the curve of revolution: an expression in x, y (or x, y, z), a drawing or a bitmap"),
            Param("axis", "x of the axis in a drawn or bitmap generatrix (default its leftmost point)", label="axis position"),
            Param("curve_threshold", "grey level between inside and outside of a bitmap curve (between 0 and 1)", label="curve grey level"),
            Param("generatrix_threshold", "grey level between inside and outside of a bitmap generatrix (between 0 and 1)", label="generatrix grey level"),
            *_COMMON,
            _AT,
            Param("z_range", "[low, high]: the heights an explicit generatrix x = g(y) spans (default [-1, 1])", label="heights of g(y)"),
            _ARC,
            _CENTER,
            Param("curve_open", "take a drawn curve as the open stroke it is: the surface between its ends", label="open curve (a surface between its ends)"),
        ),
        random="voxfab.digitize._recipes:random_revolution",
    ),
    Maker(
        "tube", "voxfab.digitize._recipes:make_tube",
        "a 2D profile swept along a 3D spine",
        (
            Param("spine", "[x(t), y(t), z(t)] expressions, a JSON or CSV file of 3D points, or a list of points"),
            Param("profile", "the cross-section: an expression in x, y, a drawing or a bitmap"),
            Param("radius", "largest radius of the profile, in model units"),
            Param("twist", "total rotation of the profile along the spine, degrees"),
            Param("phase", "constant rotation of the profile, degrees"),
            Param("frame", '"rmf" (rotation-minimising) or "frenet": how the profile turns along the spine', label="profile frame"),
            Param("cap", '"flat" or "round": the ends of an open spine'),
            Param("closed", "force the spine closed or open (default: closed when its ends meet)"),
            Param("t_min", "first value of t of an expression spine", label="first t"),
            Param("t_max", "last value of t of an expression spine", label="last t"),
            Param("samples", "samples of t along an expression spine", 2, MAX_SAMPLES, label="samples along the spine"),
            Param("threshold", "grey level between inside and outside of a bitmap profile (between 0 and 1)", label="grey level"),
            Param("stroke", "full width of the open strokes of a drawn profile (default 1/100 of its diagonal)", label="stroke width"),
            *_COMMON,
            _ARC,
            _CENTER,
            Param("profile_open", "take a drawn profile as the open stroke it is: a ribbon between its ends", label="open profile (a ribbon)"),
        ),
        random="voxfab.digitize._recipes:random_tube",
    ),
    Maker(
        "focal", "voxfab.digitize._recipes:make_focal",
        "weighted focus points: the level set sum of w_i |x - f_i| = radius (an egg with two unequal weights)",
        (
            Param("foci", "[[x, y, z], ...]: the focus points"),
            Param("radius", "the weighted sum of distances on the surface"),
            Param("weights", "one weight per focus (default all 1)"),
            *_COMMON,
        ),
        random="voxfab.digitize._recipes:random_focal",
    ),
    Maker(
        "implicit", "voxfab.digitize._recipes:make_implicit",
        "an expression in x, y, z (or x, y, z, w: a 3D slice of a 4D object)",
        (
            Param("expression", "the region expression <= 0 (or an equation), in x, y, z and optionally w"),
            Param("bounds", "[x0, x1, y0, y1, z0, z1(, w0, w1)]: the model box, instead of the sampled estimate", label="model box"),
            _AT,
            *_COMMON,
        ),
    ),
)}


def available_makers() -> list[str]:
    """Names of the registered makers."""
    return sorted(MAKERS)


def random_makers() -> tuple[str, ...]:
    """The makers with random parameters, in table order: ``explore``'s maker generators."""
    return tuple(name for name, row in MAKERS.items() if row.random is not None)


def _row(name: str) -> Maker:
    if name not in MAKERS:
        known = ", ".join(available_makers()) or "(none)"
        raise UnknownFormatError(f"unknown maker {name!r}; expected one of {known}")
    return MAKERS[name]


def _load(target: str) -> Callable[..., Any]:
    module, func = target.split(":")
    return getattr(importlib.import_module(module), func)


def get_maker(name: str) -> Callable[..., np.ndarray]:
    """Return the maker registered under ``name``."""
    return _load(_row(name).make)


def get_random_params(name: str) -> Callable[[np.random.Generator], dict[str, Any]]:
    """Return the function drawing random keyword arguments for maker ``name``."""
    row = _row(name)
    if row.random is None:
        raise UnknownFormatError(f"maker {name!r} has no random parameters; expected one of "
                                 f"{', '.join(random_makers())}")
    return _load(row.random)


@functools.cache
def maker_params(name: str) -> dict[str, Param]:
    """The keys of maker ``name``, in its row's order, with type, default and requirement from its signature.

    Raises
    ------
    UnknownFormatError
        For an unknown maker.
    TypeError
        When the row and the signature name different keys (a table that drifted from its code).
    """
    row = _row(name)
    func = get_maker(name)
    signature = inspect.signature(func)
    hints = typing.get_type_hints(func)
    keywords = {p.name: p for p in signature.parameters.values()
                if p.kind is inspect.Parameter.KEYWORD_ONLY and p.name != "base_dir"}
    described = [p.name for p in row.params]
    if sorted(described) != sorted(keywords) or len(set(described)) != len(described):
        raise TypeError(f"maker {name!r}: its row describes {sorted(described)}, its function takes {sorted(keywords)}")
    out = {}
    for p in row.params:
        sig = keywords[p.name]
        required = sig.default is inspect.Parameter.empty
        out[p.name] = dataclasses.replace(p, hint=hints.get(p.name, Any), required=required,
                                          default=None if required else sig.default)
    return out


def maker_markdown(name: str) -> str:
    """The README's table of maker ``name``'s keys."""
    rows = ["| key | type | default | range | meaning |", "|---|---|---|---|---|"]
    for p in maker_params(name).values():
        default = "required" if p.required else "-" if p.default is None else f"`{_toml(p.default)}`"
        bounds = " .. ".join("" if b is None else f"{b:g}" for b in (p.low, p.high)) \
            if (p.low, p.high) != (None, None) else ""
        rows.append(f"| `{p.name}` | {p.type_words} | {default} | {bounds} | {p.help} |")
    return "\n".join(rows)


def _toml(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    return f"{value:g}" if isinstance(value, float) else str(value)
