"""Shapes of a weighted focal set: ``D(x) = Σ w_i ‖x − f_i‖ = r``.

One focus gives a sphere, two equal weights an ellipsoid, two unequal weights
an egg (Cartesian oval), more foci a polyellipse. D is convex, so the shape is
non-empty exactly when r exceeds min D (the weighted Fermat–Weber value).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from voxfab._shared.limits import MAX_FOCI
from voxfab.errors import InvalidShapeError, LimitError

from ._fit import Field, Mode, fit

__all__ = ["focal_field", "focal", "fermat_weber"]


def _check(foci: npt.ArrayLike, weights: npt.ArrayLike | None) -> tuple[np.ndarray, np.ndarray]:
    try:
        f = np.asarray(foci, dtype=np.float64)
    except (TypeError, ValueError):
        raise InvalidShapeError("foci: expected a list of 3D (or 4D) points of numbers") from None
    if f.ndim == 2 and len(f) > MAX_FOCI:
        raise LimitError(f"foci: {len(f):,} foci is over the limit of {MAX_FOCI}")
    if f.ndim != 2 or len(f) == 0 or f.shape[1] not in (3, 4) or not np.all(np.isfinite(f)):
        raise InvalidShapeError(f"foci: expected a list of 3D (or 4D) points, got shape {f.shape}")
    try:
        w = np.ones(len(f)) if weights is None else np.asarray(weights, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidShapeError("weights: expected a list of numbers") from None
    if w.shape != (len(f),):
        raise InvalidShapeError(f"weights: expected {len(f)} weights (one per focus), got {w.size}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise InvalidShapeError(f"weights: every weight must be > 0, got {w.tolist()}")
    return f, w


def fermat_weber(foci: npt.ArrayLike, weights: npt.ArrayLike | None = None) -> float:
    """min over x of Σ w_i ‖x − f_i‖ (Weiszfeld iterations, started at the foci)."""
    f, w = _check(foci, weights)
    d_at = [float(np.sum(w * np.linalg.norm(f - p, axis=1))) for p in f]
    x = np.sum(w[:, None] * f, axis=0) / w.sum()
    best = min(d_at)
    for _ in range(200):
        d = np.linalg.norm(f - x, axis=1)
        if np.any(d < 1e-12):
            break
        x = np.sum((w / d)[:, None] * f, axis=0) / np.sum(w / d)
    best = min(best, float(np.sum(w * np.linalg.norm(f - x, axis=1))))
    return best


def focal_field(foci: npt.ArrayLike, weights: npt.ArrayLike | None, radius: float) -> Field:
    """``Σ w_i ‖x − f_i‖ − radius`` as a :class:`Field` (3D or 4D)."""
    f, w = _check(foci, weights)
    if not np.isfinite(radius) or radius <= 0:
        raise InvalidShapeError(f"radius: expected a positive number, got {radius}")
    m = fermat_weber(f, w)
    if radius <= m * (1 + 1e-12):
        raise InvalidShapeError(
            f"radius: {radius:g} is not above the weighted Fermat-Weber minimum {m:g}: the shape is empty"
        )
    n = f.shape[1]

    def func(*coords: np.ndarray) -> np.ndarray:
        total = 0.0
        for fi, wi in zip(f, w):
            total = total + wi * np.sqrt(sum((coords[d] - fi[d]) ** 2 for d in range(n)))
        return total - radius

    # every point of the shape is within radius / w_i of focus i
    reach = radius / w
    lo = np.max(f - reach[:, None], axis=0)
    hi = np.min(f + reach[:, None], axis=0)
    return Field(func, lo, hi, "focal shape")


def focal(
    foci: Sequence[Sequence[float]] | npt.ArrayLike,
    weights: Sequence[float] | npt.ArrayLike | None = None,
    radius: float = 1.0,
    *,
    k: int = 0,
    mode: Mode | str = "solid",
    size: int = 25,
    scale: float | None = None,
    at: float | None = None,
) -> np.ndarray:
    """Weighted focal shape fitted in a ``size``³ grid: a k-separating surface or a solid.

    See :func:`voxfab.digitize.fit` for ``k``, ``mode``, ``size``, ``scale``, ``at``.
    At most 256 foci (:data:`voxfab._shared.limits.MAX_FOCI`): each adds a
    distance to every evaluation of the field.

    Raises
    ------
    LimitError
        For more than 256 foci.
    InvalidShapeError
        For foci that are not 3D or 4D points, or weights that are not positive.
    """
    return fit(focal_field(foci, weights, radius), k=k, mode=mode, size=size, scale=scale, at=at)
