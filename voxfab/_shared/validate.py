"""Input checks whose messages name the parameter that failed."""

from __future__ import annotations

import collections.abc
import contextlib
import inspect
import os
import types
import typing
from collections.abc import Iterator
from contextvars import ContextVar
from enum import Enum
from pathlib import Path
from typing import Any, Literal, TypeVar, Union

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError, RecipeError, quote

from .typing import BoolGrid

#: Largest side a grid may have anywhere in voxfab (the artist works at 25).
MAX_SIDE = 256

E = TypeVar("E", bound=Enum)


def as_grid(
    array: npt.ArrayLike,
    *,
    name: str = "shape",
    ndim: int | None = 3,
    max_side: int = MAX_SIDE,
    allow_empty: bool = False,
) -> BoolGrid:
    """Return ``array`` as a bool grid after checking its type and size.

    Parameters
    ----------
    array : array_like
        A bool array, or integers that are all 0 or 1.
    name : str
        The parameter name used in error messages.
    ndim : int or None
        Required number of dimensions (``None``: any, at least 1).
    max_side : int
        Largest allowed side length.
    allow_empty : bool
        Whether a grid with no filled voxel is accepted.

    Returns
    -------
    grid : bool ndarray
        The same data; a view when ``array`` is already bool.

    Raises
    ------
    InvalidShapeError
        On a wrong dtype, dimension, size, or an empty grid.
    """
    a = np.asarray(array)
    if ndim is not None and a.ndim != ndim:
        raise InvalidShapeError(
            f"{name}: expected a {ndim}D grid, got {a.ndim}D with shape {a.shape}"
        )
    if a.ndim == 0:
        raise InvalidShapeError(f"{name}: expected an array, got a scalar")
    if a.dtype != np.bool_:
        if a.dtype.kind not in "biu" and a.dtype.kind != "f":
            raise InvalidShapeError(
                f"{name}: expected a bool or 0/1 array, got dtype {a.dtype}"
            )
        if a.size and not np.isin(a, (0, 1)).all():
            raise InvalidShapeError(
                f"{name}: expected only 0 and 1 values, got dtype {a.dtype} "
                f"with values in [{a.min()}, {a.max()}]"
            )
        a = a.astype(bool)
    if any(s > max_side for s in a.shape):
        raise InvalidShapeError(
            f"{name}: grid {'x'.join(map(str, a.shape))} is over the limit of "
            f"{max_side} voxels per side"
        )
    if not allow_empty and (a.size == 0 or not a.any()):
        raise InvalidShapeError(f"{name}: the grid is empty (no filled voxel)")
    return a


def check_choice(value: str | E, enum: type[E], *, name: str) -> E:
    """Return ``value`` as a member of ``enum``; the error lists valid choices."""
    if isinstance(value, enum):
        return value
    try:
        return enum(value)
    except ValueError:
        choices = ", ".join(repr(m.value) for m in enum)
        raise InvalidShapeError(
            f"{name}: unknown choice {value!r}; expected one of {choices}"
        ) from None


def finite_number(value: object) -> float | None:
    """``value`` as a finite float, or None when it is no number (a bool, a string, NaN, inf, 10**400).

    JSON gives integers of any size: ``math.isfinite(10**400)`` raises OverflowError,
    so every check of a number from outside goes through here first.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        return None
    try:
        v = float(value)
    except OverflowError:
        return None
    return v if np.isfinite(v) else None


def check_positive(value: float, *, name: str) -> float:
    """Return ``value`` as a float after checking it is finite and > 0."""
    v = float(value)
    if not np.isfinite(v) or v <= 0:
        raise InvalidShapeError(f"{name}: expected a positive number, got {value!r}")
    return v


# The folder that input files named by a recipe must stay in (None: anywhere).
_INPUT_ROOT: ContextVar[Path | None] = ContextVar("voxfab_input_root", default=None)


@contextlib.contextmanager
def confine_inputs(root: str | os.PathLike[str] | None) -> Iterator[None]:
    """Within the block, :func:`resolve_input` refuses files outside ``root`` (``None``: no limit).

    A recipe is a file someone may hand over; the files it names (``file =``,
    drawings, profiles, spines) must not reach the rest of the disk, e.g.
    ``../../../../etc/passwd``.  Symbolic links are followed before the check.
    """
    token = _INPUT_ROOT.set(None if root is None else Path(root).resolve())
    try:
        yield
    finally:
        _INPUT_ROOT.reset(token)


def resolve_input(source: str | os.PathLike[str], base_dir: str | os.PathLike[str] | None = None, *,
                  name: str) -> Path:
    """The path of an input file named ``source``, relative to ``base_dir`` unless absolute.

    Raises
    ------
    RecipeError
        Inside :func:`confine_inputs`, when the file resolves outside its folder.
    """
    path = Path(source)
    if not path.is_absolute() and base_dir is not None:
        path = Path(base_dir) / path
    root = _INPUT_ROOT.get()
    if root is not None:
        check_confined(path, root, name=name, shown=str(source))
    return path


def check_confined(path: str | os.PathLike[str], root: str | os.PathLike[str], *, name: str,
                   shown: str | None = None) -> None:
    """Refuse ``path`` unless it resolves (links followed) inside the folder ``root``.

    ``shown`` is the file name as the user wrote it, for the message.
    """
    real = Path(path).resolve()
    if not real.is_relative_to(Path(root).resolve()):
        raise RecipeError(
            f"{name}: {quote(shown or str(path))} is outside the recipe's folder {os.path.abspath(root)}; "
            "pass --allow-outside to read files elsewhere"
        )


# --- TOML and JSON values against type hints (recipe and studio keys) -------------------------

def type_name(tp: Any) -> str:
    """A type hint in words, for messages: ``list of float``, ``'solid' or 'surface'``."""
    origin = typing.get_origin(tp)
    if origin is Literal:
        return " or ".join(repr(a) for a in typing.get_args(tp))
    if origin in (Union, types.UnionType):
        return " or ".join(type_name(a) for a in typing.get_args(tp))
    if origin in (list, tuple):
        args = typing.get_args(tp)
        return f"list of {type_name(args[0])}" if args else "list"
    if tp is type(None):
        return "none"
    return getattr(tp, "__name__", str(tp))


def type_fits(value: Any, tp: Any) -> bool:
    """Whether a TOML value fits a type hint (int fits float; bool fits only bool)."""
    if tp is Any or tp is inspect.Parameter.empty:
        return True
    origin = typing.get_origin(tp)
    if origin is Literal:
        return value in typing.get_args(tp)
    if origin in (Union, types.UnionType):
        return any(type_fits(value, a) for a in typing.get_args(tp))
    if origin in (list, tuple, collections.abc.Sequence):
        if not isinstance(value, list):
            return False
        args = typing.get_args(tp)
        if not args:
            return True
        if origin is tuple and not (len(args) == 2 and args[1] is Ellipsis):
            return len(value) == len(args) and all(type_fits(v, a) for v, a in zip(value, args))
        return all(type_fits(v, args[0]) for v in value)
    if origin is dict:
        return isinstance(value, dict)
    if tp is float:
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if tp is int:
        return isinstance(value, int) and not isinstance(value, bool)
    if tp is Path:
        return isinstance(value, str)
    if tp is type(None):
        return value is None
    if isinstance(tp, type):
        return isinstance(value, tp)
    return True
