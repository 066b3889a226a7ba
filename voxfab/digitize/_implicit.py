"""General 3D or 4D implicit shapes from an expression (a 4D one is sliced to 3D)."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

from ._curves import estimate_bounds
from ._expr import compile_expression
from ._fit import Field, Mode, fit

__all__ = ["implicit_field", "implicit"]


def implicit_field(
    expression: str | Callable[..., npt.ArrayLike],
    *,
    dim: int | None = None,
    bounds: Sequence[float] | None = None,
) -> Field:
    """An expression in ``x, y, z`` (3D) or ``x, y, z, w`` (4D), < 0 inside, as a :class:`Field`.

    ``bounds`` (``[x0, x1, y0, y1, z0, z1(, w0, w1)]``) skips the sampled estimate.
    """
    if isinstance(expression, str):
        func = compile_expression(expression, ("x", "y", "z", "w"), name="expression")
        n = dim or (4 if "w" in func.used else 3)
        f4 = func

        def f(*coords: np.ndarray) -> np.ndarray:
            return f4(*coords, *([0.0] * (4 - len(coords))))

        if n == 3 and "w" in func.used:
            raise InvalidShapeError("expression: uses w, so it is 4D, but dim = 3 was asked")
    elif callable(expression):
        n = dim or 3
        f = expression  # type: ignore[assignment]
    else:
        raise InvalidShapeError(f"expression: expected a string or a callable, got {type(expression).__name__}")
    if n not in (3, 4):
        raise InvalidShapeError(f"dim: expected 3 or 4, got {n}")
    if bounds is None:
        lo, hi = estimate_bounds(f, n, name="expression")
    else:
        b = np.asarray(bounds, dtype=np.float64)
        if b.shape != (2 * n,) or np.any(b[1::2] <= b[0::2]):
            raise InvalidShapeError(f"bounds: expected {2 * n} numbers [min, max] per axis, got {list(bounds)}")
        lo, hi = b[0::2], b[1::2]
    return Field(f, lo, hi, "implicit shape")


def implicit(
    expression: str | Callable[..., npt.ArrayLike],
    *,
    dim: int | None = None,
    bounds: Sequence[float] | None = None,
    k: int = 0,
    mode: Mode | str = "solid",
    size: int = 25,
    scale: float | None = None,
    at: float | None = None,
) -> np.ndarray:
    """Digitize an implicit 3D shape, a 4D one (``size``⁴), or a 3D slice of a 4D one (``at`` = w)."""
    return fit(implicit_field(expression, dim=dim, bounds=bounds), k=k, mode=mode, size=size, scale=scale, at=at)
