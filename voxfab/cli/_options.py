"""Command-line arguments made from the options dataclasses (see :mod:`voxfab._shared.options`).

Every argument defaults to "not given" (``None``), so the dataclass keeps the
one default; values are checked when the options object is made, before any
work, and an error names the flag (``--tab-width: expected ...``).
"""

from __future__ import annotations

import argparse
from collections.abc import Iterable
from typing import Any, TypeVar

from voxfab._shared.options import OptionError, OptionSpec, from_mapping, option_specs

T = TypeVar("T")

_METAVARS = {"mm": "MM", "s": "S", "px": "PX", "voxels": "N", "degrees": "DEG", "mm/voxel": "MM"}


def number_argument(text: str) -> float:
    """An argparse ``type``: a number in ASCII digits (:func:`voxfab._shared.numbers.parse_float`);
    ``nan`` and ``inf`` pass to the option check."""
    from voxfab._shared.numbers import parse_float

    try:
        return parse_float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text[:80]!r}") from None


def integer_argument(text: str) -> int:
    """An argparse ``type``: a whole number in ASCII digits (:func:`voxfab._shared.numbers.parse_int`)."""
    from voxfab._shared.numbers import parse_int

    try:
        return parse_int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text[:80]!r}") from None


def _help(spec: OptionSpec) -> str:
    text = spec.flag_help if spec.negate and spec.flag_help else spec.help
    if spec.default is not None and spec.kind is not bool:
        default = ", ".join(spec.default) if isinstance(spec.default, tuple) else f"{spec.default:g}" \
            if isinstance(spec.default, float) else spec.default
        text += f" (default {default}{' ' + spec.unit if spec.unit and spec.kind is not str else ''})"
    return text.replace("%", "%%")


def add_option_arguments(
    parser: argparse.ArgumentParser | Any, cls: type, *, exclude: Iterable[str] = (), title: str | None = None
) -> None:
    """Add one argument per CLI option of the dataclass ``cls``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    cls : type
        An options dataclass.
    exclude : iterable of str
        Field names the command handles itself.
    title : str, optional
        Put the arguments in a group with this title.
    """
    skip = set(exclude)
    target = parser.add_argument_group(title) if title else parser
    for spec in option_specs(cls):
        if not spec.cli or spec.name in skip:
            continue
        kw: dict[str, Any] = {"dest": spec.name, "default": None, "help": _help(spec)}
        if spec.kind is bool:
            if spec.negate:
                kw.update(action="store_const", const=False)
            elif spec.default is True:
                kw.update(action=argparse.BooleanOptionalAction)
            else:
                kw.update(action="store_const", const=True)
        else:
            if spec.choices is not None and spec.kind is str:
                kw["choices"] = spec.choices
            elif spec.kind is float:
                kw["type"] = number_argument
            elif spec.kind is int:
                kw["type"] = integer_argument
            if spec.kind is tuple:
                kw["nargs"] = "+"
            kw["metavar"] = spec.metavar or _METAVARS.get(spec.unit) or ("N" if spec.kind is int else "TEXT")
            if "choices" in kw:
                del kw["metavar"]
        target.add_argument(spec.flag, **kw)


def options_from_args(cls: type[T], args: argparse.Namespace, **values: Any) -> T:
    """Make ``cls`` from the given CLI options plus ``values``; bad values name the flag.

    Raises
    ------
    OptionError
        With the option named by its flag, e.g. ``--sheet: ...``.
    """
    specs = {s.name: s for s in option_specs(cls)}
    given = {name: getattr(args, name) for name, s in specs.items()
             if s.cli and getattr(args, name, None) is not None}
    given.update(values)
    try:
        return from_mapping(cls, given, front="any")
    except OptionError as exc:
        spec = specs.get(exc.option)
        if spec is None or not spec.cli or getattr(args, exc.option, None) is None:
            raise  # a value the command chose itself, not a flag the user gave
        raise OptionError(spec.flag, exc.reason) from None
