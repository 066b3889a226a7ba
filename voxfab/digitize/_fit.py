"""Fitting continuous shapes into the voxel grid.

A :class:`Field` is a continuous shape: an implicit function (or a custom
digitizer) plus the bounding box of the shape in model units. :func:`fit`
chooses the scale so that the digitized shape's longest extent is exactly
``size`` voxels (by bracketing and bisection on the scale, since flake
thickness and rounding make the extent only roughly proportional to the scale),
and centres it in a ``size``³ grid. With ``scale`` and ``center`` the placement
is fixed instead (:func:`fixed_fit`): the model point ``center`` sits at the
grid's middle, so separate pieces of one shape keep their relative places.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from enum import Enum

import numpy as np

from voxfab._shared.validate import check_choice
from voxfab.errors import InvalidShapeError

from ._flake import digitize as flake_digitize

__all__ = ["Field", "Placement", "Mode", "fit", "fixed_fit", "fixed_placement", "place", "render"]

#: Grid side of the preview fit used before fitting larger grids.
_PREVIEW = 49

Digitizer = Callable[..., tuple[np.ndarray, np.ndarray]]


class Mode(Enum):
    """What a maker returns: the k-flake surface, or surface plus interior."""

    SURFACE = "surface"
    SOLID = "solid"


@dataclass(frozen=True)
class Field:
    """A continuous n-D shape (n = 3, or 4 sliced at a value of the last axis).

    Attributes
    ----------
    f : callable or None
        ``f(*coords)``, < 0 inside; used when ``digitizer`` is None.
    lo, hi : (n,) float ndarray
        Bounding box of the continuous shape, model units.
    name : str
        Used in error messages.
    digitizer : callable, optional
        ``digitizer(shape, origin, step, k, interior=True) -> (surface, interior)``
        replacing the plain flake test (e.g. surfaces of revolution built from
        runs); with ``interior=False`` the interior may be left empty.
    """

    f: Callable[..., np.ndarray] | None
    lo: np.ndarray
    hi: np.ndarray
    name: str
    digitizer: Digitizer | None = field(default=None)

    @property
    def ndim(self) -> int:
        return len(self.lo)

    def digitize(
        self, shape: tuple[int, ...], origin: np.ndarray, step: np.ndarray, k: int, *, interior: bool = True
    ) -> tuple[np.ndarray, np.ndarray]:
        """``(surface, interior)`` bool arrays of ``shape`` (interior possibly empty without ``interior``)."""
        if self.digitizer is not None:
            return self.digitizer(shape, origin, step, k, interior=interior)
        return flake_digitize(self.f, shape, k, origin, step)


@dataclass(frozen=True)
class Placement:
    """Where the voxel grid lies in model units: voxel i is ``origin + i * step``."""

    shape: tuple[int, ...]
    origin: np.ndarray
    step: float
    size: int


def place(
    fld: Field, scale: float, *, size: int, at: float | None = None, shift: float = 0.0, centre: np.ndarray | None = None
) -> Placement:
    """The placement at ``scale`` voxels per model unit, ``centre`` (default: the box's) on the grid's centre voxel."""
    step = 1.0 / scale
    g = size + 6 + (size % 2 == 0)  # odd, so the centre is a voxel centre
    n = fld.ndim
    if centre is None:
        centre = (fld.lo + fld.hi) / 2.0
    origin = centre - ((g - 1) / 2.0 - shift) * step
    if at is not None:
        if n < 4:
            raise InvalidShapeError(f"at: {fld.name} is {n}D; a slice position needs a 4D shape")
        return Placement((*(g,) * (n - 1), 1), np.append(origin[:-1], float(at)), step, size)
    return Placement((g,) * n, origin, step, size)


def render(fld: Field, p: Placement, *, k: int, mode: Mode | str) -> np.ndarray:
    """Digitize ``fld`` on the placement's grid; a 4D slice comes back 3D."""
    m = check_choice(mode, Mode, name="mode")
    surf, inside = fld.digitize(p.shape, p.origin, np.full(len(p.shape), p.step), k, interior=m is Mode.SOLID)
    out = surf | inside if m is Mode.SOLID else surf
    return out.reshape(p.shape[:-1]) if p.shape[-1] == 1 and len(p.shape) == 4 else out


def _extent(g: np.ndarray) -> int:
    """Largest bounding-box extent; a shape touching the grid border counts as too big."""
    if not g.any():
        return 0
    ext = 0
    for axis in range(g.ndim):
        idx = np.flatnonzero(g.any(axis=tuple(a for a in range(g.ndim) if a != axis)))
        if idx[0] == 0 or idx[-1] == g.shape[axis] - 1:
            return 10**9
        ext = max(ext, int(idx[-1] - idx[0] + 1))
    return ext


def _to_grid(g: np.ndarray, size: int) -> np.ndarray:
    """Crop to the bounding box and centre in ``size``³."""
    n = g.ndim
    idx = [np.flatnonzero(g.any(axis=tuple(a for a in range(n) if a != d))) for d in range(n)]
    crop = g[tuple(slice(i[0], i[-1] + 1) for i in idx)]
    out = np.zeros((size,) * n, dtype=bool)
    off = [(size - s) // 2 for s in crop.shape]
    out[tuple(slice(o, o + s) for o, s in zip(off, crop.shape))] = crop
    return out


def fit_scale(fld: Field, *, k: int, mode: Mode | str, size: int, at: float | None = None) -> tuple[Placement, np.ndarray]:
    """Find a placement whose digitization spans exactly ``size`` voxels along its longest axis.

    The centre starts at the bounding box's centre and follows the digitized
    shape's centre when that is off by more than a voxel (loose bounds).
    Returns the placement and the digitized (uncropped) grid.
    """
    with np.errstate(over="ignore"):  # bounds near the float limit give an infinite span, refused next
        span = float(np.max((fld.hi - fld.lo)[: 3 if at is not None else None]))
    if not np.isfinite(span) or span <= 0:
        raise InvalidShapeError(f"{fld.name}: degenerate shape (bounding box {fld.lo} .. {fld.hi})")
    centre = fld.lo + (fld.hi - fld.lo) / 2.0  # lo + hi would overflow for bounds near the float limit
    hi_s = None
    s0 = max(size - 1, 1) / span
    if size > _PREVIEW:
        # a small preview fixes the scale's first guess, so few full-size digitizations remain
        p, _ = fit_scale(fld, k=k, mode=mode, size=_PREVIEW, at=at)
        s0 = (size - 1) / ((_PREVIEW - 1) * p.step)
        centre = p.origin[: len(centre)] + ((np.array(p.shape[: len(centre)]) - 1) / 2.0) * p.step
        if at is not None:
            centre = np.append(centre[:-1], (fld.lo[-1] + fld.hi[-1]) / 2.0)
    # symmetric shapes centred on a voxel have odd extents, on a voxel boundary even ones
    for shift in (0.0, 0.5, 0.25) if size % 2 else (0.5, 0.0, 0.25):
        s = s0
        lo_s = hi_s = None
        e_lo = e_hi = None
        recentred = 0
        bisections = 0
        for _ in range(48):
            p = place(fld, s, size=size, at=at, shift=shift, centre=centre)
            g = render(fld, p, k=k, mode=mode)
            if g.any():
                mid = np.array([
                    np.flatnonzero(g.any(axis=tuple(a for a in range(g.ndim) if a != d)))[[0, -1]].mean()
                    for d in range(g.ndim)
                ])
                off = mid - (np.array(g.shape) - 1) / 2.0
                if np.any(np.abs(off) > 1.0) and recentred < 8:
                    recentred += 1
                    centre = centre.copy()
                    centre[: g.ndim] += np.round(off) * p.step
                    continue
            e = _extent(g)
            if e == size:
                return p, g
            if e < size:
                lo_s, e_lo = s, e
            else:
                hi_s, e_hi = s, e
            if lo_s is not None and hi_s is not None:
                bisections += 1
                # a jump from size - 1 to size + 1 (symmetric shapes): try another sub-voxel shift
                if hi_s - lo_s <= 1e-9 * hi_s or (e_lo == size - 1 and e_hi == size + 1 and bisections > 3):
                    break
                s = 0.5 * (lo_s + hi_s)
            elif e == 0:
                s *= 2.0
            else:
                s *= float(np.clip((size - 1) / max(e - 1, 0.5), 0.25, 4.0))
            if s * span > 1e6:
                break
    raise InvalidShapeError(
        f"{fld.name}: cannot scale the shape so that its longest extent is exactly {size} voxels"
        + (" (the digitized shape stays empty)" if hi_s is None else "")
    )


def fixed_placement(fld: Field, *, size: int, scale: float, center: Sequence[float], at: float | None = None) -> Placement:
    """The placement at ``scale`` voxels per unit with model point ``center`` at the grid's middle.

    The grid has a margin of :data:`_MARGIN` voxels on every side, so that a
    shape reaching past the ``size`` window can be told apart from one that fits.
    """
    if not np.isfinite(scale) or scale <= 0:
        raise InvalidShapeError(f"scale: expected a positive number of voxels per unit, got {scale!r}")
    axes = fld.ndim - (1 if at is not None else 0)
    try:
        c = np.asarray(center, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidShapeError(f"center: expected {axes} numbers, got {center!r}") from None
    if c.shape != (axes,) or not np.all(np.isfinite(c)):
        raise InvalidShapeError(f"center: expected {axes} finite numbers (one per grid axis), got {center!r}")
    step = 1.0 / float(scale)
    g = size + 2 * _MARGIN
    origin = c - ((g - 1) / 2.0) * step
    if at is not None:
        if fld.ndim < 4:
            raise InvalidShapeError(f"at: {fld.name} is {fld.ndim}D; a slice position needs a 4D shape")
        return Placement((*(g,) * axes, 1), np.append(origin, float(at)), step, size)
    return Placement((g,) * axes, origin, step, size)


#: Voxels rendered beyond each side of a fixed-placement grid, to detect a shape that does not fit.
_MARGIN = 2


def fixed_fit(
    fld: Field, *, k: int, mode: Mode | str, size: int, scale: float, center: Sequence[float], at: float | None = None
) -> np.ndarray:
    """Digitize ``fld`` at a fixed placement (see :func:`fixed_placement`); the shape must lie inside the grid."""
    p = fixed_placement(fld, size=size, scale=scale, center=center, at=at)
    g = render(fld, p, k=k, mode=mode)
    window = tuple(slice(_MARGIN, _MARGIN + size) for _ in range(g.ndim))
    out = np.ascontiguousarray(g[window])
    if int(out.sum()) != int(g.sum()):
        raise InvalidShapeError(
            f"center: at scale {scale} around {list(np.asarray(center, dtype=float))} {fld.name} "
            f"reaches outside the {size}-voxel grid"
        )
    if not out.any():
        raise InvalidShapeError(f"{fld.name}: the digitized shape is empty at scale {scale} around center {center!r}")
    return out


def fit(
    fld: Field,
    *,
    k: int = 0,
    mode: Mode | str = "solid",
    size: int = 25,
    scale: float | None = None,
    at: float | None = None,
    center: Sequence[float] | None = None,
) -> np.ndarray:
    """Digitize ``fld`` into a ``size``³ bool grid.

    Parameters
    ----------
    fld : Field
        The continuous shape.
    k : int
        Flake dimension (0: tunnel-free surface).
    mode : {"solid", "surface"}
        Surface plus interior (printable), or the k-flake surface only.
    size : int
        Grid side; without ``scale`` the longest extent is exactly ``size``.
    scale : float, optional
        Voxels per model unit instead of fitting; the shape is centred and
        must fit in the grid.
    at : float, optional
        For a 4D field: the value of the last coordinate of the 3D slice
        (default: the middle of its range).
    center : sequence of float, optional
        With ``scale``: the model point at the middle of the grid (one
        number per axis of the grid). The placement is then fixed: the shape
        is neither cropped nor recentred, so pieces of one curve digitized
        with the same ``scale`` and ``center`` land where the whole would.

    Returns
    -------
    (size,) * n bool ndarray
        n = 3, or 4 for a 4D field without ``at``.
    """
    if isinstance(size, bool) or int(size) != size or not 2 <= size <= 256:
        raise InvalidShapeError(f"size: expected an integer grid side in 2..256, got {size!r}")
    size = int(size)
    check_choice(mode, Mode, name="mode")
    if center is not None:
        if scale is None:
            raise InvalidShapeError("center: a fixed placement needs scale (voxels per model unit) as well")
        return fixed_fit(fld, k=k, mode=mode, size=size, scale=scale, center=center, at=at)
    if scale is None:
        _, g = fit_scale(fld, k=k, mode=mode, size=size, at=at)
    else:
        if not np.isfinite(scale) or scale <= 0:
            raise InvalidShapeError(f"scale: expected a positive number of voxels per unit, got {scale!r}")
        g = render(fld, place(fld, float(scale), size=size, at=at), k=k, mode=mode)
        e = _extent(g)
        if e == 0:
            raise InvalidShapeError(f"{fld.name}: the digitized shape is empty at scale {scale}")
        if e > size:
            raise InvalidShapeError(
                f"scale: at {scale} voxels per unit {fld.name} does not fit in the {size}-voxel grid"
            )
    if not g.any():
        raise InvalidShapeError(f"{fld.name}: the digitized shape is empty")
    return _to_grid(g, size)
