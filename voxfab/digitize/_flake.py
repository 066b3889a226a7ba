"""k-flake digitization of implicit functions in any dimension n >= 2.

Voxel ``i`` stands for the point ``origin + i * step``. Its k-flake vertices are
the centres of the k-faces of its cube: k coordinates at the centre, n - k at
``± step / 2``. Every such vertex is a point of the doubled (half-step) lattice
with exactly k "odd" (voxel-centre) coordinates. The lattice is split into the
C(n, k) classes of points sharing the same set of odd axes; each class is
evaluated once, slab by slab along the last axis (the plane shared by two slabs
is carried over, not recomputed), and the flake test reads the vertex values by
slicing. Two voxels sharing a vertex thus read the very same value, which is
all the k-separation proof needs.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

__all__ = ["surface", "solid", "flake_vertices", "digitize"]

ImplicitFunction = Callable[..., npt.ArrayLike]

#: Points evaluated per call of f (bounds the memory of a slab).
_SLAB_POINTS = 1 << 21


def flake_vertices(n: int, k: int) -> np.ndarray:
    """Return the k-flake vertex set V_k of the unit n-cube.

    Returns
    -------
    (C(n, k) * 2**(n - k), n) float ndarray
        Centres of the k-faces of ``[-1/2, 1/2]^n``.
    """
    n, k = _check_nk(n, k)
    rows = []
    for odd in itertools.combinations(range(n), k):
        even = [d for d in range(n) if d not in odd]
        for signs in itertools.product((-0.5, 0.5), repeat=len(even)):
            v = np.zeros(n)
            v[even] = signs
            rows.append(v)
    return np.array(rows)


def _check_nk(n: int, k: int) -> tuple[int, int]:
    if int(n) != n or n < 2:
        raise InvalidShapeError(f"shape: expected a dimension n >= 2, got {n}")
    if isinstance(k, bool) or int(k) != k or not 0 <= k <= n - 1:
        raise InvalidShapeError(f"k: expected an integer in 0..{n - 1} for dimension {n}, got {k!r}")
    return int(n), int(k)


def _check_args(
    shape: Sequence[int], k: int, origin: npt.ArrayLike | None, step: float | npt.ArrayLike
) -> tuple[tuple[int, ...], int, np.ndarray, np.ndarray]:
    try:
        shp = tuple(int(s) for s in shape)
    except TypeError:
        raise InvalidShapeError(f"shape: expected a sequence of sizes, got {shape!r}") from None
    n, k = _check_nk(len(shp), k)
    if any(s < 1 for s in shp):
        raise InvalidShapeError(f"shape: every size must be >= 1, got {shp}")
    org = np.zeros(n) if origin is None else np.asarray(origin, dtype=np.float64).reshape(-1)
    if org.shape != (n,) or not np.all(np.isfinite(org)):
        raise InvalidShapeError(f"origin: expected {n} finite numbers, got {origin!r}")
    stp = np.broadcast_to(np.asarray(step, dtype=np.float64), (n,)).copy()
    if not np.all(np.isfinite(stp)) or np.any(stp <= 0):
        raise InvalidShapeError(f"step: expected positive numbers, got {step!r}")
    return shp, k, org, stp


def half_coordinates(origin: float, step: float, m: np.ndarray) -> np.ndarray:
    """Coordinates of doubled-lattice indices ``m`` (odd: voxel centres, even: cube faces)."""
    return origin + (np.asarray(m, dtype=np.float64) - 1.0) * (0.5 * step)


def _signs(values: npt.ArrayLike, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """``(v <= 0, v >= 0)`` with NaN counted as outside (positive)."""
    v = np.broadcast_to(np.asarray(values), shape)
    if v.dtype.kind not in "fiub":
        raise InvalidShapeError(f"f: expected real values, got dtype {v.dtype}")
    with np.errstate(invalid="ignore"):
        return v <= 0, ~(v < 0)


def digitize(
    f: ImplicitFunction,
    shape: Sequence[int],
    k: int = 0,
    origin: npt.ArrayLike | None = None,
    step: float | npt.ArrayLike = 1.0,
    *,
    layers: tuple[int, int] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(surface, interior)`` of the k-flake digitization of ``f``.

    Parameters
    ----------
    f, shape, k, origin, step
        As in :func:`surface`.
    layers : (a, b), optional
        Only voxel layers ``a <= i < b`` along the last axis (the arrays then
        have ``b - a`` layers); coordinates still follow ``origin``.

    Returns
    -------
    surface, interior : bool ndarray
        Voxels whose vertex values take both signs (zero counts as both), and
        voxels whose vertex values are all negative.
    """
    shp, k, org, stp = _check_args(shape, k, origin, step)
    n = len(shp)
    a, b = (0, shp[-1]) if layers is None else (int(layers[0]), int(layers[1]))
    if not 0 <= a <= b <= shp[-1]:
        raise InvalidShapeError(f"layers: expected 0 <= a <= b <= {shp[-1]}, got {layers}")
    out_shape = (*shp[:-1], b - a)
    any_le = np.zeros(out_shape, dtype=bool)
    any_ge = np.zeros(out_shape, dtype=bool)
    if b == a:
        return any_le, ~any_ge
    lead = shp[:-1]
    per_layer = math.prod(s + 1 for s in lead)
    thick = max(1, _SLAB_POINTS // per_layer)
    for odd in itertools.combinations(range(n), k):
        odd_set = set(odd)
        coords = []
        for d in range(n - 1):
            m = 2 * np.arange(shp[d]) + 1 if d in odd_set else 2 * np.arange(shp[d] + 1)
            c = half_coordinates(org[d], stp[d], m)
            coords.append(c.reshape([-1 if e == d else 1 for e in range(n)]))
        even_lead = [d for d in range(n - 1) if d not in odd_set]
        last_odd = (n - 1) in odd_set
        carry: tuple[np.ndarray, np.ndarray] | None = None
        for s0 in range(a, b, thick):
            s1 = min(b, s0 + thick)
            if last_odd:
                m = 2 * np.arange(s0, s1) + 1
            else:
                # even planes s0..s1; plane s0 was the previous slab's last one
                m = 2 * np.arange(s0 + (carry is not None), s1 + 1)
            zc = half_coordinates(org[-1], stp[-1], m).reshape([1] * (n - 1) + [-1])
            full = tuple([shp[d] if d in odd_set else shp[d] + 1 for d in range(n - 1)] + [len(m)])
            le, ge = _signs(f(*coords, zc), full)
            if carry is not None:
                le = np.concatenate([carry[0], le], axis=-1)
                ge = np.concatenate([carry[1], ge], axis=-1)
            if not last_odd:
                carry = (le[..., -1:].copy(), ge[..., -1:].copy())
            nl = s1 - s0
            dst = (..., slice(s0 - a, s1 - a))
            last_offsets = (0,) if last_odd else (0, 1)
            for offs in itertools.product((0, 1), repeat=len(even_lead)):
                sl = [slice(None)] * n
                for d, o in zip(even_lead, offs):
                    sl[d] = slice(o, o + shp[d])
                for o in last_offsets:
                    sl[-1] = slice(o, o + nl)
                    any_le[dst] |= le[tuple(sl)]
                    any_ge[dst] |= ge[tuple(sl)]
    return any_le & any_ge, ~any_ge


def surface(
    f: ImplicitFunction,
    shape: Sequence[int],
    k: int = 0,
    origin: npt.ArrayLike | None = None,
    step: float | npt.ArrayLike = 1.0,
) -> np.ndarray:
    """k-flake digital surface of ``{f = 0}``.

    Parameters
    ----------
    f : callable
        Vectorized ``f(x0, x1, ..., x_{n-1})`` over broadcastable coordinate
        arrays; < 0 inside, > 0 outside. Only the sign is used; NaN is outside.
    shape : sequence of int
        Output shape, any dimension n >= 2.
    k : int
        Flake dimension 0..n-1: the surface is k-separating (k = 0 is
        tunnel-free, k = n - 1 the thinnest).
    origin : (n,) array_like, optional
        Point of voxel index 0 (default zeros), in the units of f.
    step : float or (n,) array_like
        Voxel size in the units of f.

    Returns
    -------
    bool ndarray of ``shape``
        Voxels whose k-flake vertices see both signs of f (zero counts as both).
    """
    return digitize(f, shape, k, origin, step)[0]


def solid(
    f: ImplicitFunction,
    shape: Sequence[int],
    k: int = 0,
    origin: npt.ArrayLike | None = None,
    step: float | npt.ArrayLike = 1.0,
) -> np.ndarray:
    """The k-flake surface of ``{f = 0}`` plus the voxels whose flake vertices are all negative.

    Same parameters as :func:`surface`; returns a bool ndarray of ``shape``.
    """
    s, inside = digitize(f, shape, k, origin, step)
    return s | inside


def check_arc(arc: Sequence[float]) -> tuple[float, float]:
    """``(start, end)`` in radians from an arc in degrees with ``start < end <= start + 360``."""
    try:
        start, end = (float(v) for v in arc)
    except (TypeError, ValueError):
        raise InvalidShapeError(f"arc: expected two angles [start, end] in degrees, got {arc!r}") from None
    if not (np.isfinite(start) and np.isfinite(end) and start < end <= start + 360.0):
        raise InvalidShapeError(f"arc: expected finite angles with start < end <= start + 360, got {arc!r}")
    return float(np.radians(start)), float(np.radians(end))


#: Bisection steps that locate where a flake segment crosses an end of an open arc.
_CROP_STEPS = 48


def _in_sector(a: np.ndarray, b: np.ndarray, start: float, span: float) -> np.ndarray:
    """Points ``(a, b)`` of the plane whose angle lies in ``[start, start + span]``.

    The origin counts as inside, and so does NaN: a point with no plane
    coordinates lies outside the field's support, where ``f`` has its one
    fixed outside value for every arc alike.
    """
    with np.errstate(invalid="ignore"):
        rel = np.mod(np.arctan2(b, a) - start, 2 * np.pi)
    return (rel <= span + 1e-12) | ((a == 0) & (b == 0)) | np.isnan(a) | np.isnan(b)


def digitize_sector(
    f: ImplicitFunction,
    planar: Callable[..., tuple[np.ndarray, np.ndarray]],
    arc: tuple[float, float],
    shape: Sequence[int],
    k: int,
    origin: npt.ArrayLike | None = None,
    step: float | npt.ArrayLike = 1.0,
) -> np.ndarray:
    """k-flake surface of ``f = 0`` restricted to an angular sector, flakes cropped at its two end rays.

    ``planar(*coords) -> (a, b)`` maps points to the plane in which the sector
    ``arc = (start, end)`` (radians, ``start < end <= start + 2π``) is measured
    about the origin. Each half-segment of a voxel's flake (centre to vertex)
    keeps its vertex when the vertex lies in the sector; where it crosses an
    end ray, the crossing point becomes a test vertex, as the ends of an open
    generatrix crop the flake to its slab. The crossing is located by the same
    bisection for every sector sharing that ray, so two arcs meeting at a ray
    test the very same point there: a voxel whose full flake shows both signs
    shows both signs within one of the two arcs.

    A voxel is kept when its cropped flake shows both signs *and* its full
    flake does (``f`` is the field of the whole closed curve, defined beyond
    the arc). The cut points are test points the closed curve's flake test
    never sees, so the cropped test alone can find a double crossing of one
    flake segment that the closed test misses; requiring the full flake's sign
    change as well makes the digitization morphological: the arcs of a closed
    curve, split at shared rays, give together exactly its digitization.

    Returns
    -------
    bool ndarray of ``shape``
        The surface voxels.
    """
    shp, k, org, stp = _check_args(shape, k, origin, step)
    n = len(shp)
    start, end = (float(v) for v in arc)
    span = end - start
    axes = [(org[d] + np.arange(shp[d]) * stp[d]).reshape([-1 if e == d else 1 for e in range(n)]) for d in range(n)]
    centre = [np.broadcast_to(a, shp).reshape(-1) for a in axes]
    le = np.zeros(centre[0].shape, dtype=bool)
    ge = np.zeros_like(le)
    full_le, full_ge = np.zeros_like(le), np.zeros_like(le)

    def mark(where: np.ndarray, pts: Sequence[np.ndarray]) -> None:
        if not len(where):
            return
        at_le, at_ge = _signs(f(*[p[where] for p in pts]), where.shape)
        le[where] |= at_le
        ge[where] |= at_ge

    rays = [(math.cos(t), math.sin(t)) for t in ((start, end) if span < 2 * np.pi - 1e-12 else ())]
    ca, cb = planar(*centre)
    ca, cb = np.broadcast_to(ca, le.shape), np.broadcast_to(cb, le.shape)
    for c, s in rays:
        # a voxel centre on an end ray is itself a crossing of every segment through it
        mark(np.flatnonzero((c * cb - s * ca == 0) & (c * ca + s * cb >= 0)), centre)
    for v in flake_vertices(n, k):
        tip = [centre[d] + v[d] * stp[d] for d in range(n)]
        ta, tb = planar(*tip)
        ta, tb = np.broadcast_to(ta, le.shape), np.broadcast_to(tb, le.shape)
        tip_le, tip_ge = _signs(f(*tip), le.shape)
        full_le |= tip_le
        full_ge |= tip_ge
        kept = _in_sector(ta, tb, start, span)
        le |= kept & tip_le
        ge |= kept & tip_ge
        for c, s in rays:
            phi0, phi1 = c * cb - s * ca, c * tb - s * ta
            sel = np.flatnonzero((phi0 * phi1 <= 0) & ~((phi0 == 0) & (phi1 == 0)) & (phi0 != 0))
            if not len(sel):
                continue
            lo_t, hi_t = np.zeros(len(sel)), np.ones(len(sel))
            side = np.sign(phi0[sel])
            for _ in range(_CROP_STEPS):
                mid = 0.5 * (lo_t + hi_t)
                ma, mb = planar(*[centre[d][sel] + mid * (v[d] * stp[d]) for d in range(n)])
                same = np.sign(c * mb - s * ma) == side
                lo_t, hi_t = np.where(same, mid, lo_t), np.where(same, hi_t, mid)
            cut = [centre[d][sel] + hi_t * (v[d] * stp[d]) for d in range(n)]
            xa, xb = planar(*cut)
            on_ray = np.broadcast_to(c * xa + s * xb >= 0, sel.shape)
            pts = [np.zeros(le.shape) for _ in range(n)]
            for d in range(n):
                pts[d][sel] = cut[d]
            mark(sel[on_ray], pts)
    return (le & ge & full_le & full_ge).reshape(shp)
