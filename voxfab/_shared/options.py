"""Options declared once: frozen dataclasses whose fields carry their own documentation.

Each artefact (print mesh, paper net, slice plates, pictures) declares its options
as one frozen dataclass deriving from :class:`Options`, each field made by
:func:`option` with its help text, unit and allowed range or choices.  From that
one declaration come:

* validation of every value when the object is made (``__post_init__``), so a bad
  value fails before any work starts, with a message that names the option;
* the CLI arguments (:mod:`voxfab.cli._options` reads :func:`option_specs`);
* the recipe keys of ``[outputs.NAME]`` (:mod:`voxfab.recipe` uses
  :func:`from_mapping`);
* the README's option tables (:func:`markdown_table`).

>>> import dataclasses
>>> @dataclasses.dataclass(frozen=True)
... class Demo(Options):
...     width: float = option(5.0, help="tab width", unit="mm", low=0.0, low_open=True)
>>> Demo(width=2).width
2.0
>>> try:
...     Demo(width=-3)
... except OptionError as exc:
...     print(exc)
width: expected a positive number of mm, got -3
"""

from __future__ import annotations

import dataclasses
import functools
import math
import types
import typing
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any, TypeVar, Union

from voxfab.errors import InvalidShapeError

__all__ = [
    "MAX_QUOTE",
    "OptionError",
    "OptionSpec",
    "Options",
    "SEED_HIGH",
    "SeedOptions",
    "check_values",
    "from_mapping",
    "markdown_table",
    "option",
    "option_specs",
    "quote",
    "validate",
]

#: Most characters of a user's value quoted in an error message.
MAX_QUOTE = 80
#: Longest text a string option accepts (labels, colour maps, sheet names).
MAX_TEXT = 1000

T = TypeVar("T", bound="Options")


class OptionError(InvalidShapeError):
    """An option value that is of the wrong type, out of range or meaningless.

    Attributes
    ----------
    option : str
        The field name (``tab_width``); front ends rename it (``--tab-width``,
        ``outputs.net.tab_width``).
    reason : str
        What was expected and what was found, without the option's name.
    """

    def __init__(self, option: str, reason: str) -> None:
        super().__init__(f"{option}: {reason}")
        self.option = option
        self.reason = reason


def quote(value: Any, limit: int = MAX_QUOTE) -> str:
    """``repr(value)`` cut to about ``limit`` characters, saying how long it was."""
    text = repr(value)
    if len(text) <= limit:
        return text
    return f"{text[: limit - 1]}… ({len(text)} characters)"


def option(
    default: Any,
    *,
    help: str,
    unit: str = "",
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    choices: Sequence[str] | None = None,
    check: Callable[[Any], str | None] | None = None,
    flag: str | None = None,
    negate: bool = False,
    flag_help: str | None = None,
    metavar: str | None = None,
    cli: bool = True,
    recipe: bool = True,
) -> Any:
    """A dataclass field that documents and bounds itself.

    Parameters
    ----------
    default
        The default value (lists are stored as tuples).
    help : str
        One line saying what the option does, for ``--help`` and the README.
    unit : str
        Unit of a number (``mm``, ``s``, ``px``, ``voxels``, ``degrees``).
    low, high : float, optional
        Inclusive bounds of a number (``low`` exclusive when ``low_open``).
    choices : sequence of str, optional
        Allowed strings (for a tuple field: allowed items).
    check : callable, optional
        ``check(value) -> message or None`` for what a range cannot say (a
        sheet size, a colour map); the message says what was expected.
    flag : str, optional
        CLI flag when it is not ``--field-name``.
    negate : bool
        A bool whose ``flag`` sets it to False (``--keep-cavities`` for ``solid``).
    flag_help : str, optional
        Help of a negating flag (what switching the option off does).
    metavar : str, optional
        CLI placeholder (default from the unit).
    cli, recipe : bool
        Whether the option is offered on the command line and in recipes.
    """
    if isinstance(default, list):
        default = tuple(default)
    meta = {
        "help": help, "unit": unit, "low": low, "high": high, "low_open": low_open,
        "choices": tuple(choices) if choices is not None else None, "check": check,
        "flag": flag, "negate": negate, "flag_help": flag_help, "metavar": metavar, "cli": cli, "recipe": recipe,
    }
    return dataclasses.field(default=default, metadata={"voxfab": meta})


@dataclasses.dataclass(frozen=True)
class OptionSpec:
    """Everything a front end needs to know about one option.

    Attributes
    ----------
    name : str
        Field name, also the recipe key.
    kind : type
        ``bool``, ``int``, ``float``, ``str`` or ``tuple`` (a list of strings).
    optional : bool
        Whether ``None`` is allowed.
    default : Any
    help, unit : str
    low, high : float or None
    low_open : bool
    choices : tuple of str or None
    flag : str
        The CLI flag (``--tab-width``).
    negate : bool
    flag_help : str or None
    metavar : str or None
    cli, recipe : bool
    """

    name: str
    kind: type
    optional: bool
    default: Any
    help: str
    unit: str
    low: float | None
    high: float | None
    low_open: bool
    choices: tuple[str, ...] | None
    flag: str
    negate: bool
    flag_help: str | None
    metavar: str | None
    cli: bool
    recipe: bool

    def describe_range(self) -> str:
        """The allowed values in words (``> 0``, ``0 to 75``, ``iso, x, -x``)."""
        if self.choices is not None:
            return ", ".join(self.choices)
        if self.low is not None and self.high is not None:
            if self.low_open:
                return f"> {_number(self.low)} and <= {_number(self.high)}"
            return f"{_number(self.low)} to {_number(self.high)}"
        if self.low is not None:
            return f"{'>' if self.low_open else '>='} {_number(self.low)}"
        if self.high is not None:
            return f"<= {_number(self.high)}"
        return ""


def _number(x: float) -> str:
    """A bound in words: integers in full (a seed's 9223372036854775807), other numbers short."""
    return str(x) if isinstance(x, int) else f"{x:g}"


def _kind(tp: Any) -> tuple[type, bool]:
    """The base kind of a field's type hint and whether it may be ``None``."""
    optional = False
    if typing.get_origin(tp) in (Union, types.UnionType):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        optional = len(args) < len(typing.get_args(tp))
        tp = args[0] if len(args) == 1 else tp
    origin = typing.get_origin(tp)
    if origin in (tuple, list):
        return tuple, optional
    if tp in (bool, int, float, str):
        return tp, optional
    raise TypeError(f"option type {tp!r} is not one of bool, int, float, str, tuple of str")


def option_specs(cls: type) -> list[OptionSpec]:
    """The :class:`OptionSpec` of each field of an options dataclass, in order.

    A plain dataclass (fields without :func:`option`) gets specs from its type
    hints alone, so its values are type-checked as well.
    """
    return list(_specs(cls))


@functools.cache
def _specs(cls: type) -> tuple[OptionSpec, ...]:
    # Once per class: resolving the type hints compiles every annotation, and a command reads
    # its options classes some twenty times (flags, checks, values).
    hints = typing.get_type_hints(cls)
    specs = []
    for f in dataclasses.fields(cls):
        meta = dict(f.metadata.get("voxfab", {}))
        kind, optional = _kind(hints[f.name])
        default = f.default if f.default is not dataclasses.MISSING else None
        specs.append(OptionSpec(
            name=f.name, kind=kind, optional=optional, default=default,
            help=meta.get("help", ""), unit=meta.get("unit", ""), low=meta.get("low"),
            high=meta.get("high"), low_open=meta.get("low_open", False), choices=meta.get("choices"),
            flag=meta.get("flag") or "--" + f.name.replace("_", "-"), negate=meta.get("negate", False),
            flag_help=meta.get("flag_help"), metavar=meta.get("metavar"), cli=meta.get("cli", True), recipe=meta.get("recipe", True),
        ))
    return tuple(specs)


def _expected(spec: OptionSpec) -> str:
    unit = f" of {spec.unit}" if spec.unit else ""
    if spec.kind is int:
        base = f"an integer{' number' + unit if unit else ''}"
    elif spec.kind is float:
        base = f"a number{unit}"
    elif spec.kind is bool:
        base = "true or false"
    elif spec.kind is tuple:
        base = "a list of strings"
    else:
        base = "a string"
    if spec.kind in (int, float) and spec.low == 0 and spec.low_open:
        # "a positive number of mm up to 1000" reads better than "> 0 and <= 1000"
        base = base.replace("a number", "a positive number").replace("an integer", "a positive integer")
        return base + (f" up to {_number(spec.high)}" if spec.high is not None else "")
    rng = spec.describe_range()
    if rng and spec.choices is None:
        base += f" {rng}" if rng[0] in "<>" else f" from {rng}"
    return base


def _check_value(spec: OptionSpec, value: Any, check: Callable[[Any], str | None] | None) -> Any:
    """Return ``value`` converted to the spec's kind, or raise :class:`OptionError`."""
    if value is None:
        if spec.optional:
            return None
        raise OptionError(spec.name, f"expected {_expected(spec)}, got none")
    kind = spec.kind
    given = value
    ok = True
    if kind is bool:
        ok = isinstance(value, bool)
    elif kind is int:
        ok = isinstance(value, int) and not isinstance(value, bool)
    elif kind is float:
        ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        if ok:
            try:
                value = float(value)
            except OverflowError:  # an int too large for a float
                value = math.inf
    elif kind is str:
        ok = isinstance(value, str)
    else:
        ok = isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value)
        value = tuple(value) if ok else value
    if not ok:
        raise OptionError(spec.name, f"expected {_expected(spec)}, got {type(value).__name__} {quote(value)}")
    if kind is float and not math.isfinite(value):
        raise OptionError(spec.name, f"expected {_expected(spec)}, got {quote(given)}")
    if kind in (int, float):
        low_bad = spec.low is not None and (value <= spec.low if spec.low_open else value < spec.low)
        high_bad = spec.high is not None and value > spec.high
        if low_bad or high_bad:
            raise OptionError(spec.name, f"expected {_expected(spec)}, got {quote(given)}")
    if kind is str and len(value) > MAX_TEXT:
        raise OptionError(spec.name, f"expected at most {MAX_TEXT} characters, got {quote(value)}")
    if spec.choices is not None:
        items = value if kind is tuple else (value,)
        bad = [v for v in items if v not in spec.choices]
        if bad:
            raise OptionError(
                spec.name, f"unknown choice {quote(bad[0])}; expected one of {', '.join(spec.choices)}"
            )
    if check is not None:
        message = check(value)
        if message:
            raise OptionError(spec.name, f"{message}, got {quote(given)}")
    return value


def validate(obj: Any) -> None:
    """Check and normalise every field of an options object in place (ints become floats).

    Raises
    ------
    OptionError
        Naming the first field whose value is not allowed.
    """
    cls = type(obj)
    for spec, f in zip(option_specs(cls), dataclasses.fields(cls)):
        check = f.metadata.get("voxfab", {}).get("check")
        value = _check_value(spec, getattr(obj, f.name), check)
        object.__setattr__(obj, f.name, value)


@dataclasses.dataclass(frozen=True)
class Options:
    """Base of the options dataclasses: every value is checked when the object is made.

    A subclass may override :meth:`check` for rules that tie several options
    together; it raises :class:`OptionError`.
    """

    def __post_init__(self) -> None:
        validate(self)
        self.check()

    def check(self) -> None:
        """Rules between options (none here)."""

    def replace(self: T, **changes: Any) -> T:
        """A copy with some options changed (checked again)."""
        return dataclasses.replace(self, **changes)


#: Largest seed: seeds are stored as signed 64-bit integers (SQLite, numba kernels).
SEED_HIGH = 2**63 - 1


@dataclasses.dataclass(frozen=True)
class SeedOptions(Options):
    """The seed of a run's random choices (nets, candidates), declared once for every front end."""

    seed: int = option(0, help="random seed: the same inputs and seed give byte-identical files",
                       low=0, high=SEED_HIGH)


def check_values(cls: type, values: Mapping[str, Any]) -> dict[str, Any]:
    """Check the types and ranges of some values of ``cls``'s fields without making an object.

    For a dataclass that checks its own rules (a plain dataclass with a
    ``__post_init__``): the type errors come first, worded as everywhere else.
    """
    specs = {s.name: s for s in option_specs(cls)}
    checks = {f.name: f.metadata.get("voxfab", {}).get("check") for f in dataclasses.fields(cls)}
    out = {}
    for key, value in values.items():
        if key not in specs:
            raise OptionError(str(key), f"unknown option; accepted: {', '.join(sorted(specs))}")
        out[key] = _check_value(specs[key], value, checks[key])
    return out


def from_mapping(cls: type[T], values: Mapping[str, Any], *, front: str = "recipe") -> T:
    """Make ``cls`` from a mapping of option names to values, refusing unknown names.

    Parameters
    ----------
    cls : type
        An options dataclass.
    values : mapping
        Option name → value (a recipe table, the given CLI options).
    front : {"recipe", "cli", "any"}
        Which options are offered: those with ``recipe=True``, ``cli=True``, or all.

    Raises
    ------
    OptionError
        For an unknown name (listing the accepted ones) or a bad value.
    """
    offered = {s.name for s in option_specs(cls) if front == "any" or getattr(s, front)}
    for key in values:
        if key not in offered:
            raise OptionError(str(key), f"unknown option; accepted: {', '.join(sorted(offered)) or '(none)'}")
    return cls(**dict(values))


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def _default(spec: OptionSpec) -> str:
    value = spec.default
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, tuple):
        return "[" + ", ".join(f'"{v}"' for v in value) + "]"
    if isinstance(value, str):
        return f'"{value}"'
    return f"{value:g}" if isinstance(value, float) else str(value)


def markdown_table(cls: type, *, exclude: Iterable[str] = ()) -> str:
    """The README table of an options dataclass: recipe key, CLI flag, default, unit/range, meaning."""
    skip = set(exclude)
    rows = ["| recipe key | CLI | default | unit, range | meaning |", "|---|---|---|---|---|"]
    for s in option_specs(cls):
        if s.name in skip:
            continue
        key = f"`{s.name}`" if s.recipe else "-"
        flag = f"`{s.flag}`" if s.cli else "-"
        if s.cli and s.kind is bool and not s.negate and s.default is True:
            flag = f"`{s.flag}`, `--no-{s.flag[2:]}`"
        elif s.cli and s.negate:
            flag = f"`{s.flag}` (sets false)"
        unit = ", ".join(p for p in (s.unit, s.describe_range()) if p)
        rows.append(f"| {key} | {_cell(flag)} | {_cell(_default(s))} | {_cell(unit)} | {_cell(s.help)} |")
    return "\n".join(rows) + "\n"
