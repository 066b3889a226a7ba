"""Digital surfaces of revolution: a curve of revolution times a generatrix.

The axis is the last coordinate (z in 3D, w in 4D). The curve of revolution C
(2D in x, y; or 3D in x, y, z for a 4D object) is normalised so that its
farthest point from the axis is at distance 1; its slice at height z is scaled
by the generatrix's radius. The generatrix lives in the (ρ, z) half-plane:

- a region (closed drawing, bitmap, implicit ``G(x=ρ, y=z)``):
  ``F = G(ρ_C(p), z)`` where ρ_C is the gauge of C (``p / ρ_C(p)`` lies on C),
  computed by bisection along the ray; C must be star-shaped about the axis;
- an explicit radius ``x = g(y)`` (the text's left side is ``x`` alone and
  its right side does not use ``x``): the solid ``ρ <= g(z)`` between the
  heights ``z_range`` (default ``-1 .. 1``), capped at both ends, so
  ``x = 0.6 + 0.3*sin(3*y)`` needs no bounding term;
- open drawn polylines: split into z-monotone runs (explicit radius r(z)) and
  horizontal runs. Each monotone run is digitized with the explicit form
  ``ρ_C - r(z)`` (``C(p / r(z))`` for a curve with several components) and
  flakes cropped to the run's slab ``z_a <= Z <= z_b``; each horizontal run at
  z0 keeps the voxels whose flake segments cross the plane inside the region
  swept by ``λ·C``, ``λ ∈ [r1, r2]``.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

from ._curves import (
    BITMAP_SUFFIXES,
    DRAWING_SUFFIXES,
    Curve2D,
    estimate_bounds,
    load_curve,
    open_star_curve,
    star_radius,
)
from ._expr import Expression, compile_expression
from ._fit import Field, Mode, fit
from ._flake import check_arc, digitize_sector, flake_vertices, half_coordinates
from ._flake import digitize as flake_digitize

__all__ = [
    "RevolutionCurve",
    "Run",
    "load_revolution_curve",
    "split_runs",
    "revolution_field",
    "revolution",
    "slices",
]


@dataclass(frozen=True)
class RevolutionCurve:
    """A curve of revolution about the origin, normalised to maximal radius 1.

    Attributes
    ----------
    func : callable
        ``func(*coords)`` over n - 1 coordinates (2 or 3), < 0 inside.
    lo, hi : ndarray
        Its bounding box (within ``[-1, 1]``).
    star : bool
        Whether every ray from the axis crosses it once.
    name : str
    """

    func: Callable[..., np.ndarray]
    lo: np.ndarray
    hi: np.ndarray
    star: bool
    name: str
    table: np.ndarray | None = field(default=None, compare=False, repr=False)
    _cache: dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def dim(self) -> int:
        return len(self.lo)

    def gauge(self, *coords: np.ndarray) -> np.ndarray:
        """ρ_C(p): the factor λ such that ``p / λ`` is on the curve (0 on the axis)."""
        if not self.star:
            raise InvalidShapeError(
                f"{self.name}: not star-shaped about the axis (the axis is outside it or a ray crosses it "
                "several times); "
                "use it with an open drawn generatrix"
            )
        if self.table is not None:
            # polar table R(θ) of the star-shaped 2D curve, periodic linear interpolation
            x, y = (np.asarray(c, dtype=np.float64) for c in coords)
            m = len(self.table)
            pos = (np.arctan2(y, x) + np.pi) * (m / (2 * np.pi))
            i0 = np.floor(pos).astype(np.int64)
            frac = pos - i0
            i0 %= m
            radius = self.table[i0] * (1 - frac) + self.table[(i0 + 1) % m] * frac
            return np.hypot(x, y) / radius
        key = tuple((c.shape, c.tobytes()) for c in (np.asarray(x) for x in coords))
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        pts = np.broadcast_arrays(*[np.asarray(c, dtype=np.float64) for c in coords])
        r = np.sqrt(sum(p * p for p in pts))
        safe = np.where(r > 0, r, 1.0)
        rho = np.where(r > 0, r / _ray_bisect(self.func, [p / safe for p in pts], 1.05), 0.0)
        if len(self._cache) > 8:
            self._cache.clear()
        self._cache[key] = rho
        return rho

    def scaled(self, coords: Sequence[np.ndarray], r: np.ndarray) -> np.ndarray:
        """``C(p / r)``: the sign of p against the curve scaled by r (r clamped above 0)."""
        rr = np.maximum(np.asarray(r, dtype=np.float64), 1e-9)
        with np.errstate(all="ignore"):
            return np.asarray(self.func(*[np.asarray(c) / rr for c in coords]), dtype=np.float64)


def load_revolution_curve(
    source: str | Callable[..., npt.ArrayLike] | Curve2D,
    *,
    base_dir: Path | None = None,
    threshold: float = 0.5,
    dim: int | None = None,
    name: str = "curve",
) -> RevolutionCurve:
    """Load and normalise a curve of revolution.

    Implicit curves keep their origin as the axis; drawings and bitmaps are
    centred on their bounding box. An expression using ``z`` (or ``dim=3``
    with a callable) is a 3D surface of revolution for 4D objects.
    """
    if isinstance(source, str) and Path(source).suffix.lower() not in DRAWING_SUFFIXES + BITMAP_SUFFIXES:
        expr3 = compile_expression(source, ("x", "y", "z"), name=name)
        if "z" in expr3.used or dim == 3:
            lo, hi = estimate_bounds(expr3, 3, name=name)
            return _normalised(expr3, lo, hi, name=name)
    if callable(source) and not isinstance(source, Curve2D) and dim == 3:
        lo, hi = estimate_bounds(source, 3, name=name)
        return _normalised(source, lo, hi, name=name)
    curve = source if isinstance(source, Curve2D) else load_curve(
        source, base_dir=base_dir, name=name, threshold=threshold, closed=True
    )
    if curve.kind != "implicit":
        curve = curve.transformed(curve.center, 1.0)
    return _normalised(curve, curve.lo, curve.hi, name=name)


#: Angles in the polar table of a star-shaped 2D curve of revolution.
_TABLE = 1024


def _ray_bisect(func: Callable[..., np.ndarray], dirs: Sequence[np.ndarray], hi: float) -> np.ndarray:
    """Distance along unit directions ``dirs`` where ``func`` turns positive (star-shaped region)."""
    lo_t = np.zeros(np.broadcast_shapes(*[d.shape for d in dirs]))
    hi_t = np.full_like(lo_t, hi)
    for _ in range(30):
        mid = 0.5 * (lo_t + hi_t)
        with np.errstate(all="ignore"):
            inside = np.asarray(func(*[d * mid for d in dirs])) <= 0
        lo_t = np.where(inside, mid, lo_t)
        hi_t = np.where(inside, hi_t, mid)
    return 0.5 * (lo_t + hi_t)


def _normalised(func: Callable[..., np.ndarray], lo: np.ndarray, hi: np.ndarray, *, name: str) -> RevolutionCurve:
    n = len(lo)
    corner = float(np.sqrt(np.sum(np.maximum(np.abs(lo), np.abs(hi)) ** 2)))
    star, radius = star_radius(func, n, name=name, r_max=corner * 1.05)
    table = None
    if star:
        if n == 2:
            a = -np.pi + np.arange(_TABLE) * (2 * np.pi / _TABLE)
            table = _ray_bisect(func, [np.cos(a), np.sin(a)], radius * 1.1)
            radius = float(table.max())
            table = table / radius
            dirs = None
        else:
            i = np.arange(2000) + 0.5
            phi, th = np.arccos(1 - 2 * i / 2000), np.pi * (1 + 5**0.5) * i
            dirs = [np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)]
        if dirs is not None:
            radius = float(np.max(_ray_bisect(func, dirs, radius * 1.1)))
    else:
        radius = corner

    def unit(*coords: np.ndarray) -> np.ndarray:
        return func(*[c * radius for c in coords])

    return RevolutionCurve(unit, np.asarray(lo) / radius, np.asarray(hi) / radius, star, name, table)


@dataclass(frozen=True)
class Run:
    """A piece of an open generatrix: z-monotone (explicit r(z)) or horizontal.

    ``z`` ascending and ``r`` the radii there; a horizontal run has two equal
    ``z`` and ``r = (r1, r2)`` with r1 <= r2.
    """

    z: np.ndarray
    r: np.ndarray
    horizontal: bool

    @property
    def z_range(self) -> tuple[float, float]:
        return float(self.z[0]), float(self.z[-1])


def split_runs(points: npt.ArrayLike, *, name: str = "generatrix") -> list[Run]:
    """Split an open polyline ``(ρ, z)`` into strictly z-monotone and horizontal runs sharing endpoints."""
    p = np.asarray(points, dtype=np.float64)
    keep = np.ones(len(p), dtype=bool)
    keep[1:] = np.any(np.diff(p, axis=0) != 0, axis=1)
    p = p[keep]
    if len(p) < 2:
        raise InvalidShapeError(f"{name}: degenerate generatrix (fewer than 2 distinct points)")
    dz = np.sign(np.diff(p[:, 1]))
    runs: list[Run] = []
    start = 0
    for i in range(1, len(dz) + 1):
        if i == len(dz) or dz[i] != dz[start]:
            seg = p[start : i + 1]
            if dz[start] == 0:
                runs.append(Run(np.array([seg[0, 1], seg[0, 1]]), np.array([seg[:, 0].min(), seg[:, 0].max()]), True))
            else:
                order = np.argsort(seg[:, 1], kind="stable")
                runs.append(Run(seg[order, 1], seg[order, 0], False))
            start = i
    return runs


#: An open drawn generatrix's end this close to the axis (as a share of the drawing's size: its height or
#: its diameter, whichever is larger) lies on the axis: one voxel of a 25³ shape.  A hand stroke from the
#: axis round the profile and back never lands exactly on the axis, and an end off it left the axis
#: column open, so "solid" gave a hollow shell.
AXIS_SNAP = 0.04

#: Samples of an explicit radius r(z) for its bounds and, with a curve that is not star-shaped, its run.
_EXPLICIT_SAMPLES = 4097

_EXPLICIT = re.compile(r"^\s*x\s*=(?!=)(.*)$", re.DOTALL)


def explicit_radius(text: str, *, name: str = "generatrix") -> Expression | None:
    """The radius function ``g(y)`` of an explicit generatrix ``x = g(y)``, or None for other texts.

    Explicit means: the left side is ``x`` alone and the right side uses ``y`` at most.
    """
    m = _EXPLICIT.match(text) if isinstance(text, str) else None
    if m is None or Path(text).suffix.lower() in DRAWING_SUFFIXES + BITMAP_SUFFIXES:
        return None
    rhs = compile_expression(m.group(1), ("x", "y"), name=name)
    if "x" in rhs.used:
        return None
    return rhs


def _check_z_range(z_range: Sequence[float] | None) -> tuple[float, float]:
    if z_range is None:
        return -1.0, 1.0
    try:
        lo, hi = (float(v) for v in z_range)
    except (TypeError, ValueError):
        raise InvalidShapeError(f"z_range: expected two heights [low, high], got {z_range!r}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise InvalidShapeError(f"z_range: expected finite heights with low < high, got {z_range!r}")
    return lo, hi


def _explicit_generatrix(
    g: Expression, z_range: Sequence[float] | None, *, star: bool, name: str
) -> tuple[Curve2D | None, list[np.ndarray]]:
    """An explicit radius r = g(z) on ``z_range``, capped at both ends.

    With a star-shaped curve of revolution it is the region ``ρ <= g(z)`` cut by
    the two end planes (exact, no sampling); otherwise the sampled profile
    ``(0, z0) → (g(z0), z0) → ... → (g(z1), z1) → (0, z1)``, an open polyline
    whose runs are digitized like a drawing.
    """
    z0, z1 = _check_z_range(z_range)
    zs = np.linspace(z0, z1, _EXPLICIT_SAMPLES)
    rs = np.broadcast_to(g(np.zeros_like(zs), zs), zs.shape)
    rs = np.where(np.isfinite(rs), rs, 0.0)
    rho_max = float(rs.max())
    if rho_max <= 0:
        raise InvalidShapeError(f"{name}: the radius {g.text.strip()!r} is never positive for y in [{z0:g}, {z1:g}]")
    if not star:
        prof = np.vstack([[0.0, z0], np.stack([np.maximum(rs, 0.0), zs], axis=1), [0.0, z1]])
        return None, [prof]

    def func(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        r = np.asarray(g(x, y), dtype=np.float64)
        # outside the radius function's domain (NaN) counts as outside the solid
        r = np.where(np.isfinite(r), r, -np.inf)
        return np.maximum(np.maximum(x - r, z0 - y), y - z1)

    return Curve2D(func, np.array([0.0, z0]), np.array([rho_max, z1]), "implicit", name), []


def _load_generatrix(
    source: str | Callable[..., npt.ArrayLike] | Curve2D | np.ndarray | Sequence[Sequence[float]],
    *,
    base_dir: Path | None,
    threshold: float,
    axis: float | None,
    name: str,
) -> tuple[Curve2D | None, list[np.ndarray]]:
    """Return ``(region, [])`` for a region generatrix, ``(None, open polylines)`` otherwise; ρ measured from the axis."""
    curve = source if isinstance(source, Curve2D) else load_curve(
        source, base_dir=base_dir, name=name, threshold=threshold, half_plane=True
    )
    if curve.kind == "drawn":
        if any(curve.closed) and not all(curve.closed):
            raise InvalidShapeError(f"{curve.name}: mixes open and closed polylines; use one kind")
        pts = np.vstack(curve.polylines)
        ax = float(pts[:, 0].min()) if axis is None else float(axis)
        tol = 1e-9 * max(1.0, float(np.ptp(pts)))
        if pts[:, 0].min() < ax - tol:
            raise InvalidShapeError(
                f"{curve.name}: the generatrix crosses the axis (x = {ax:g}): it reaches x = {pts[:, 0].min():g}"
            )
        if not all(curve.closed):
            polys = [p - np.array([ax, 0.0]) for p in curve.polylines]
            every = np.vstack(polys)
            snap = AXIS_SNAP * max(2.0 * float(every[:, 0].max()), float(np.ptp(every[:, 1])))
            for q in polys:
                q[:, 0] = np.maximum(q[:, 0], 0.0)
                for end in (0, -1):
                    if q[end, 0] <= snap:
                        q[end, 0] = 0.0
            return None, polys
        return curve.transformed((ax, 0.0), 1.0), []
    ax = (float(curve.lo[0]) if curve.kind == "bitmap" else 0.0) if axis is None else float(axis)
    shifted = curve.transformed((ax, 0.0), 1.0) if ax != 0.0 else curve
    if curve.kind == "bitmap" and curve.lo[0] < ax - 1e-9:
        raise InvalidShapeError(f"{curve.name}: the generatrix crosses the axis (x = {ax:g}): dark pixels at x = {curve.lo[0]:g}")
    return shifted, []


def _half_plane_bounds(g: Curve2D) -> tuple[float, float, float]:
    """(ρ max, z min, z max) of the region ``G <= 0`` within ρ >= 0."""
    if g.hi[0] <= 0:
        raise InvalidShapeError(f"{g.name}: the generatrix region lies entirely left of the axis")
    return float(g.hi[0]), float(g.lo[1]), float(g.hi[1])


def _runs_digitizer(curve: RevolutionCurve, runs: list[Run]) -> Callable[..., tuple[np.ndarray, np.ndarray]]:
    def radial(lead: Sequence[np.ndarray], r: np.ndarray) -> np.ndarray:
        if curve.star:
            return curve.gauge(*lead) - r
        return curve.scaled(lead, r)

    def digitizer(
        shape: tuple[int, ...], origin: np.ndarray, step: np.ndarray, k: int, *, interior: bool = True
    ) -> tuple[np.ndarray, np.ndarray]:
        from scipy import ndimage

        n = len(shape)
        if n != curve.dim + 1:
            raise InvalidShapeError(f"{curve.name}: a {curve.dim}D curve of revolution makes {curve.dim + 1}D shapes, not {n}D")
        surf = np.zeros(shape, dtype=bool)
        nl, oz, sz = shape[-1], origin[-1], step[-1]
        zc = half_coordinates(oz, sz, 2 * np.arange(nl) + 1)
        verts = flake_vertices(n, k)
        lead_shape = shape[:-1]

        def lead_coords(tau: float, v: np.ndarray) -> list[np.ndarray]:
            return [
                half_coordinates(origin[d], step[d], 2 * np.arange(shape[d]) + 1 + 2 * tau * v[d]).reshape(
                    [-1 if e == d else 1 for e in range(n - 1)]
                )
                for d in range(n - 1)
            ]

        for run in runs:
            za, zb = run.z_range
            meets = np.flatnonzero((zc + 0.5 * sz >= za) & (zc - 0.5 * sz <= zb))
            if run.horizontal:
                r1, r2 = float(run.r[0]), float(run.r[1])

                def region(lead: list[np.ndarray], r1: float = r1, r2: float = r2) -> np.ndarray:
                    if curve.star:
                        rho = curve.gauge(*lead)
                        return (rho <= r2) & (rho >= r1)
                    inside = curve.scaled(lead, np.array(r2)) <= 0
                    if r1 > 0:
                        inside &= curve.scaled(lead, np.array(r1)) >= 0
                    return inside

                for layer in meets:
                    hit = np.zeros(lead_shape, dtype=bool)
                    for v in verts:
                        if v[-1] > 0:
                            tau = (za - zc[layer]) / (v[-1] * sz)
                        elif v[-1] == 0 and zc[layer] == za:
                            tau = 1.0
                        else:
                            continue
                        hit |= np.broadcast_to(region(lead_coords(tau, v)), lead_shape)
                    if zc[layer] == za:
                        hit |= np.broadcast_to(region(lead_coords(0.0, verts[0])), lead_shape)
                    surf[..., layer] |= hit
                continue

            def f(*coords: np.ndarray, run: Run = run) -> np.ndarray:
                return radial(coords[:-1], np.interp(coords[-1], run.z, run.r))

            full = (zc - 0.5 * sz >= za) & (zc + 0.5 * sz <= zb)
            idx = np.flatnonzero(full)
            if len(idx):
                a, b = int(idx[0]), int(idx[-1]) + 1
                s, _ = flake_digitize(f, shape, k, origin, step, layers=(a, b))
                surf[..., a:b] |= s
            for layer in meets[~full[meets]]:
                any_le = np.zeros(lead_shape, dtype=bool)
                any_ge = np.zeros(lead_shape, dtype=bool)
                z0 = zc[layer]
                for v in verts:
                    if v[-1] == 0:
                        if not za <= z0 <= zb:
                            continue
                        tau, zv = 1.0, z0
                    else:
                        t1, t2 = (za - z0) / (v[-1] * sz), (zb - z0) / (v[-1] * sz)
                        lo_t, hi_t = max(-1.0, min(t1, t2)), min(1.0, max(t1, t2))
                        if lo_t > hi_t:
                            continue
                        tau = hi_t
                        zv = half_coordinates(oz, sz, 2 * layer + 1 + 2 * v[-1]) if tau == 1.0 else min(
                            max(z0 + tau * v[-1] * sz, za), zb
                        )
                    val = np.broadcast_to(f(*lead_coords(tau, v), np.asarray(zv)), lead_shape)
                    any_le |= val <= 0
                    any_ge |= ~(val < 0)
                surf[..., layer] |= any_le & any_ge
        if not interior:
            return surf, np.zeros_like(surf)
        # interior: the empty voxels not 6-connected to the grid's border
        labels, _ = ndimage.label(~surf, structure=ndimage.generate_binary_structure(n, 1))
        border = np.zeros(labels.max() + 1, dtype=bool)
        for axis in range(n):
            border[np.take(labels, 0, axis=axis)] = True
            border[np.take(labels, -1, axis=axis)] = True
        border[0] = True
        return surf, ~border[labels]

    return digitizer


def _sector_digitizer(
    f: Callable[..., np.ndarray], rc: RevolutionCurve, arc: tuple[float, float], option: str = "arc"
) -> Callable[..., tuple[np.ndarray, np.ndarray]]:
    """Digitizer of the surface swept by the part of ``rc`` within the angles ``arc`` (radians).

    ``option`` names what made the curve open, in messages.
    """

    def planar(*coords: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return coords[0], coords[1]

    def digitizer(
        shape: tuple[int, ...], origin: np.ndarray, step: np.ndarray, k: int, *, interior: bool = True
    ) -> tuple[np.ndarray, np.ndarray]:
        if interior:
            raise InvalidShapeError(f'{option}: an open curve of revolution bounds no solid; use mode = "surface"')
        if len(shape) != 3 or rc.dim != 2:
            raise InvalidShapeError(f"{option}: open curves of revolution make 3D shapes only")
        surf = digitize_sector(f, planar, arc, shape, k, origin, step)
        return surf, np.zeros_like(surf)

    return digitizer


def revolution_field(
    curve: str | Callable[..., npt.ArrayLike] | Curve2D | RevolutionCurve,
    generatrix: str | Callable[..., npt.ArrayLike] | Curve2D | np.ndarray | Sequence[Sequence[float]],
    *,
    base_dir: Path | None = None,
    curve_threshold: float = 0.5,
    generatrix_threshold: float = 0.5,
    axis: float | None = None,
    curve_dim: int | None = None,
    z_range: Sequence[float] | None = None,
    arc: Sequence[float] | None = None,
    curve_open: bool = False,
) -> Field:
    """The continuous surface of revolution as a :class:`Field` (3D, or 4D for a 3D curve).

    Parameters
    ----------
    curve : str, callable, Curve2D or RevolutionCurve
        Curve of revolution: an expression in ``x, y`` (or ``x, y, z``), a
        callable, or a file (SVG/JSON/CSV drawing, PNG bitmap).
    generatrix : str, callable, Curve2D or (P, 2) points
        In the (ρ = x, z = y) half-plane: an expression ``G(x, y)`` (region
        ``G <= 0``), a file, or points. Open drawings become runs.
        An explicit radius ``x = g(y)`` is the solid under it between the
        heights ``z_range``.
    axis : float, optional
        x of the axis in the generatrix drawing or bitmap (default: its
        leftmost point; 0 for expressions).
    z_range : (float, float), optional
        Heights ``y`` spanned by an explicit generatrix ``x = g(y)`` (default
        ``(-1, 1)``); not allowed with other generatrices.
    arc : (float, float), optional
        Make the curve of revolution open: only its part between the angles
        ``start .. end`` (degrees, counter-clockwise from +x about the axis).
        The result is the surface swept by that open curve (mode
        ``"surface"`` only), its flakes cropped at the two end half-planes.
    curve_open : bool
        The curve of revolution is an open drawn stroke (a JSON, SVG or CSV
        drawing of one polyline turning one way about its bounding box's centre,
        the axis): the surface swept by the stroke between its two ends, as
        ``arc`` makes it for a closed curve (see :class:`voxfab.digitize.OpenCurve`).
    """
    sector, option = (check_arc(arc), "arc") if arc is not None else (None, "arc")
    if curve_open:
        if arc is not None:
            raise InvalidShapeError("arc: an open drawn curve ends where it is drawn; give arc or curve_open, not both")
        if isinstance(curve, (RevolutionCurve, Curve2D)) or callable(curve):
            raise InvalidShapeError("curve_open: the curve of revolution must be a drawing (.json, .svg or .csv)")
        drawn = open_star_curve(curve, base_dir=base_dir, name="curve")
        rc = _normalised(drawn.curve, drawn.curve.lo, drawn.curve.hi, name=drawn.curve.name)
        sector, option = drawn.arc, "curve_open"
    else:
        rc = curve if isinstance(curve, RevolutionCurve) else load_revolution_curve(
            curve, base_dir=base_dir, threshold=curve_threshold, dim=curve_dim
        )
    radius = explicit_radius(generatrix, name="generatrix") if isinstance(generatrix, str) else None
    if radius is not None:
        region, polys = _explicit_generatrix(radius, z_range, star=rc.star, name="generatrix")
    else:
        if z_range is not None:
            raise InvalidShapeError("z_range: only an explicit generatrix x = g(y) takes a height range")
        region, polys = _load_generatrix(
            generatrix, base_dir=base_dir, threshold=generatrix_threshold, axis=axis, name="generatrix"
        )
    d = rc.dim
    if region is not None:
        if not rc.star:
            raise InvalidShapeError(
                f"{rc.name}: a curve of revolution that is not star-shaped about the axis (several components, "
                "or the axis outside it) needs an open drawn generatrix"
            )
        rho_max, z0, z1 = _half_plane_bounds(region)
        g = region.func

        def f(*coords: np.ndarray) -> np.ndarray:
            return g(rc.gauge(*coords[:-1]), coords[-1])

        lo = np.append(rc.lo * rho_max, z0)
        hi = np.append(rc.hi * rho_max, z1)
        if sector is not None:
            return Field(None, lo, hi, "open surface of revolution", _sector_digitizer(f, rc, sector, option))
        return Field(f, lo, hi, "surface of revolution")
    if sector is not None:
        raise InvalidShapeError(f"{option}: an open curve of revolution needs a region generatrix (expression, "
                                "closed drawing or bitmap)")
    runs = [r for p in polys for r in split_runs(p, name="generatrix")]
    rho_max = max(float(np.max(r.r)) for r in runs)
    if rho_max <= 0:
        raise InvalidShapeError("generatrix: degenerate generatrix (it lies on the axis)")
    zs = np.concatenate([r.z for r in runs])
    lo = np.append(rc.lo * rho_max, zs.min())
    hi = np.append(rc.hi * rho_max, zs.max())
    if d + 1 != len(lo):
        raise InvalidShapeError("curve: dimension mismatch")
    return Field(None, lo, hi, "surface of revolution", _runs_digitizer(rc, runs))


def revolution(
    curve: str | Callable[..., npt.ArrayLike] | Curve2D | RevolutionCurve,
    generatrix: str | Callable[..., npt.ArrayLike] | Curve2D | np.ndarray | Sequence[Sequence[float]],
    *,
    k: int = 0,
    mode: Mode | str = "solid",
    size: int = 25,
    scale: float | None = None,
    at: float | None = None,
    base_dir: Path | None = None,
    curve_threshold: float = 0.5,
    generatrix_threshold: float = 0.5,
    axis: float | None = None,
    curve_dim: int | None = None,
    z_range: Sequence[float] | None = None,
    arc: Sequence[float] | None = None,
    center: Sequence[float] | None = None,
    curve_open: bool = False,
) -> np.ndarray:
    """Digital surface (or solid) of revolution fitted in a ``size``³ grid (``size``⁴ for a 3D curve).

    See :func:`revolution_field` for the sources and :func:`voxfab.digitize.fit`
    for ``k``, ``mode``, ``size``, ``scale``, ``center`` (fixed placement) and
    ``at`` (3D slice of a 4D object).
    """
    fld = revolution_field(
        curve, generatrix, base_dir=base_dir, curve_threshold=curve_threshold,
        generatrix_threshold=generatrix_threshold, axis=axis, curve_dim=curve_dim, z_range=z_range, arc=arc,
        curve_open=curve_open,
    )
    return fit(fld, k=k, mode=mode, size=size, scale=scale, at=at, center=center)


def slices(grid: npt.ArrayLike, axis: int = -1) -> Iterator[np.ndarray]:
    """Yield the (n-1)-D slices of an n-D grid along ``axis`` (3D slices of a 4D object)."""
    g = np.asarray(grid)
    if g.ndim < 3:
        raise InvalidShapeError(f"grid: expected at least 3 dimensions, got {g.ndim}")
    for i in range(g.shape[axis]):
        yield np.take(g, i, axis=axis)
