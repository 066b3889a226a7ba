"""Swept tubes: a 2D profile moved along a 3D spine by a moving frame.

The implicit value at a point x is the profile's value at the coordinates of x
in the normal plane of its closest spine point: ``u = (x - γ)·N``,
``v = (x - γ)·B`` (rotated by the twist angle). Frames are rotation-minimizing
(double reflection, Wang et al. 2008; the holonomy of a closed spine is removed
by a linear counter-twist) or Frenet–Serret. The closest point is the nearer
projection onto the two polyline segments at the nearest spine sample; where
the sweep folds (profile larger than the spine's reach) the result follows the
closest point, not the self-intersecting sweep.
"""

from __future__ import annotations

import functools
import inspect
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab._shared.limits import MAX_SAMPLES, MAX_SEARCH_CELLS, check_count, parse_json, read_input_bytes
from voxfab._shared.validate import check_choice, resolve_input
from voxfab.errors import InvalidShapeError, LimitError, VoxfabError

from ._curves import Curve2D, load_curve, open_star_curve
from ._expr import compile_expression
from ._fit import Field, Mode, _extent, fit, fit_scale, render
from ._flake import check_arc, digitize_sector

__all__ = ["Frame", "Cap", "Spine", "load_spine", "spine_frames", "tube_field", "tube", "tube_rotations"]


class Frame(Enum):
    """Moving frame along the spine."""

    RMF = "rmf"
    FRENET = "frenet"


class Cap(Enum):
    """End caps of an open spine."""

    FLAT = "flat"
    ROUND = "round"


@dataclass(frozen=True)
class Spine:
    """A sampled spine with its frames.

    Attributes
    ----------
    points : (M, 3) float ndarray
        Samples (a closed spine does not repeat its first point).
    closed : bool
    s : (M,) float ndarray
        Arc length at each sample; ``length`` is the total (including the
        closing segment of a closed spine).
    tangent, normal, binormal : (M, 3) float ndarray
        The frame at each sample (holonomy-corrected for a closed RMF).
    holonomy : float
        Angle (radians) by which the uncorrected RMF came back rotated.
    """

    points: np.ndarray
    closed: bool
    s: np.ndarray
    length: float
    tangent: np.ndarray
    normal: np.ndarray
    binormal: np.ndarray
    holonomy: float
    _cache: dict = field(default_factory=dict, compare=False, repr=False)

    def tree(self):  # noqa: ANN201 - scipy type
        if "tree" not in self._cache:
            from scipy.spatial import cKDTree

            self._cache["tree"] = cKDTree(self.points)
        return self._cache["tree"]


def load_spine(
    spine: str | Sequence[str] | npt.ArrayLike,
    *,
    base_dir: Path | None = None,
    t_min: float = 0.0,
    t_max: float = 1.0,
    samples: int = 1024,
    closed: bool | None = None,
) -> tuple[np.ndarray, bool]:
    """Spine points from three expressions in ``t``, a JSON/CSV file of 3D points, or a (P, 3) array.

    Expressions are sampled at ``samples + 1`` values of ``t``; ``samples`` is at
    most 100,000 (:data:`voxfab._shared.limits.MAX_SAMPLES`).  A file name is
    resolved in ``base_dir``, and must stay in it while a recipe is built (see
    :func:`voxfab._shared.validate.confine_inputs`).

    Raises
    ------
    LimitError
        ``samples`` over 100,000, or a JSON file over the nesting or integer limits.
    """
    if isinstance(spine, (list, tuple)) and len(spine) == 3 and all(isinstance(e, str) for e in spine):
        if not t_max > t_min:
            raise InvalidShapeError(f"t_max: expected > t_min = {t_min}, got {t_max}")
        n = check_count(samples, MAX_SAMPLES, name="samples", least=2)
        t = np.linspace(t_min, t_max, n + 1)
        cols = []
        for name, text in zip("xyz", spine):
            e = compile_expression(text, ("t",), name=f"spine {name}(t)")
            cols.append(np.broadcast_to(e(t), t.shape))
        pts = np.stack(cols, axis=1)
    elif isinstance(spine, str):
        import io

        path = resolve_input(spine, base_dir, name="spine")
        if not path.exists():
            raise InvalidShapeError(f"spine: file not found: {path}")
        raw = read_input_bytes(path, what="a spine")
        try:
            if path.suffix.lower() == ".json":
                data = parse_json(raw.decode("utf-8"), name=f"spine: {path.name}")
                pts = np.asarray(data["points"] if isinstance(data, dict) else data, dtype=np.float64)
            else:
                pts = np.loadtxt(io.BytesIO(raw), delimiter=",", ndmin=2)
        except VoxfabError:
            raise
        except (ValueError, KeyError, TypeError) as exc:
            raise InvalidShapeError(f"spine: cannot read 3D points from {path.name}: {exc}") from None
    elif isinstance(spine, (list, tuple)) and spine and all(isinstance(e, str) for e in spine):
        raise InvalidShapeError(f"spine: expected three expressions x(t), y(t), z(t), got {len(spine)}")
    else:
        try:
            pts = np.asarray(spine, dtype=np.float64)
        except (TypeError, ValueError):
            raise InvalidShapeError("spine: expected (x, y, z) points or three expressions in t") from None
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise InvalidShapeError(f"spine: expected (x, y, z) points, got an array of shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise InvalidShapeError("spine: points must be finite (check the expressions' domain)")
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.any(np.diff(pts, axis=0) != 0, axis=1)
    pts = pts[keep]
    if len(pts) < 2:
        raise InvalidShapeError("spine: degenerate spine (fewer than 2 distinct points)")
    span = float(np.ptp(pts, axis=0).max())
    is_closed = len(pts) > 3 and bool(np.linalg.norm(pts[0] - pts[-1]) <= 1e-9 * span)
    if is_closed:
        pts = pts[:-1]
    if closed is not None:
        is_closed = bool(closed)
    return pts, is_closed


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0, n, 1.0)


def _any_normal(t: np.ndarray) -> np.ndarray:
    a = np.eye(3)[int(np.argmin(np.abs(t)))]
    return _unit(a - (a @ t) * t)


def _rotate_about(v: np.ndarray, axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotate rows of v about unit rows of axis by angle (Rodrigues; v ⟂ axis)."""
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return v * c + np.cross(axis, v) * s + axis * (np.sum(axis * v, axis=1) * (1 - c[:, 0]))[:, None]


def spine_frames(points: npt.ArrayLike, closed: bool, frame: Frame | str = "rmf") -> Spine:
    """Sample frames along a spine polyline (see :class:`Spine`)."""
    fr = check_choice(frame, Frame, name="frame")
    x = np.ascontiguousarray(points, dtype=np.float64)
    m = len(x)
    seg = (np.roll(x, -1, axis=0) - x) if closed else np.diff(x, axis=0)
    seg_len = np.linalg.norm(seg, axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg_len[: m - 1])])
    length = float(s[-1] + (seg_len[-1] if closed else 0.0))
    if length <= 0:
        raise InvalidShapeError("spine: degenerate spine (zero length)")
    if closed:
        d1 = (np.roll(x, -1, axis=0) - np.roll(x, 1, axis=0)) / 2.0
        d2 = np.roll(x, -1, axis=0) - 2 * x + np.roll(x, 1, axis=0)
    else:
        d1 = np.gradient(x, axis=0)
        d2 = np.gradient(d1, axis=0)
    t = _unit(d1)
    holonomy = 0.0
    if fr is Frame.FRENET:
        b = np.cross(d1, d2)
        bn = np.linalg.norm(b, axis=1)
        ok = bn > 1e-10 * np.linalg.norm(d1, axis=1) ** 2
        if not ok.any():
            b = np.repeat(np.cross(t[0], _any_normal(t[0]))[None], m, axis=0)
        else:
            # undefined on straight parts: keep the last defined binormal
            idx = np.where(ok, np.arange(m), 0)
            np.maximum.accumulate(idx, out=idx)
            idx[: np.argmax(ok)] = np.argmax(ok)
            b = b[idx]
        b = _unit(b - np.sum(b * t, axis=1)[:, None] * t)
        n = np.cross(b, t)
    else:
        from ._kernels import transport

        xs, ts = (np.vstack([x, x[:1]]), np.vstack([t, t[:1]])) if closed else (x, t)
        r = transport(np.ascontiguousarray(xs), np.ascontiguousarray(ts), _any_normal(t[0]))
        if closed:
            r_end = r[-1]
            holonomy = math.atan2(float(np.cross(r[0], r_end) @ t[0]), float(r[0] @ r_end))
            r = r[:-1]
            r = _rotate_about(r, t, -holonomy * s / length)
        n = _unit(r - np.sum(r * t, axis=1)[:, None] * t)
        b = np.cross(t, n)
    return Spine(x, closed, s, length, t, n, b, holonomy)


def _max_radius(curve: Curve2D, centre: np.ndarray) -> float:
    """Largest distance from ``centre`` of the region's sampled points."""
    lo, hi = curve.lo, curve.hi
    xs = np.linspace(lo[0], hi[0], 129)
    ys = np.linspace(lo[1], hi[1], 129)
    inside = np.broadcast_to(curve(xs[:, None], ys[None, :]) <= 0, (129, 129))
    if not inside.any():
        raise InvalidShapeError(f"{curve.name}: empty profile")
    d = np.hypot(xs[:, None] - centre[0], ys[None, :] - centre[1])
    pad = float(np.hypot(xs[1] - xs[0], ys[1] - ys[0]))
    return float(d[inside].max()) + 0.5 * pad


def _profile(
    profile: str | Callable[..., npt.ArrayLike] | Curve2D, *, base_dir: Path | None, threshold: float, stroke: float | None
) -> Curve2D:
    curve = profile if isinstance(profile, Curve2D) else load_curve(
        profile, base_dir=base_dir, name="profile", threshold=threshold, stroke=stroke
    )
    centre = np.zeros(2) if curve.kind == "implicit" else curve.center
    return curve.transformed(centre, 1.0 / _max_radius(curve, centre))


def tube_field(
    spine: Spine,
    profile: Curve2D,
    *,
    radius: float = 1.0,
    twist: float = 0.0,
    phase: float = 0.0,
    cap: Cap | str = "flat",
    arc: Sequence[float] | None = None,
) -> Field:
    """The swept tube as a :class:`Field`.

    Parameters
    ----------
    spine : Spine
        From :func:`spine_frames`.
    profile : Curve2D
        Normalised profile (largest radius 1 about the origin).
    radius : float
        Profile's largest radius in spine units.
    twist : float
        Total rotation of the profile along the spine, degrees.
    phase : float
        Constant rotation of the profile, degrees.
    cap : {"flat", "round"}
        Ends of an open spine.
    arc : (float, float), optional
        Make the profile open: only its part between the angles ``start ..
        end`` (degrees, counter-clockwise in the profile plane, after twist and
        phase). The result is the ribbon swept by that open profile (mode
        ``"surface"`` only), its flakes cropped at the ribbon's two edges.
    """
    cp = check_choice(cap, Cap, name="cap")
    if not np.isfinite(radius) or radius <= 0:
        raise InvalidShapeError(f"radius: expected a positive profile radius, got {radius}")
    x, m = spine.points, len(spine.points)
    h = float(np.max(np.linalg.norm(np.diff(x, axis=0), axis=1))) if m > 1 else 0.0
    reach = radius * (1.0 if cp is Cap.FLAT else 1.0) + 2.0 * h
    box_lo, box_hi = x.min(axis=0) - reach, x.max(axis=0) + reach
    with np.errstate(all="ignore"):
        cells = np.floor((box_hi - box_lo) / reach) + 1
    # The search grid has one cell per `reach` of the spine's box: a profile tiny next to
    # its spine would need more cells than memory holds.
    count = float(np.prod(cells))
    if not np.isfinite(count) or count > MAX_SEARCH_CELLS:
        raise LimitError(
            f"radius: {radius:g} is too small for a spine {float(np.max(np.abs(x))):g} from its origin: the tube's "
            f"search grid would need {f'{count:,.0f}' if np.isfinite(count) else 'countless'} cells, over the "
            f"limit of {MAX_SEARCH_CELLS:,}"
        )
    cells_shape = tuple(int(c) for c in cells.astype(np.int64))
    occ = np.zeros(cells_shape, dtype=bool)
    ci = np.floor((x - box_lo) / reach).astype(np.int64)
    for off in np.ndindex(3, 3, 3):
        c = np.clip(ci + np.array(off) - 1, 0, np.array(cells_shape) - 1)
        occ[c[:, 0], c[:, 1], c[:, 2]] = True
    occupied = occ.reshape(-1)
    tw, ph = math.radians(twist), math.radians(phase)
    pf = profile.func

    def closest(coords: Sequence[np.ndarray]) -> tuple[tuple[int, ...], np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Flat indices of points near the spine, with the points, segment and raw parameter."""
        shape = np.broadcast_shapes(*[np.shape(c) for c in coords])
        axes = [np.asarray(c, dtype=np.float64) for c in coords]
        grid = len(shape) == 3 and all(
            a.ndim == 3 and all(a.shape[e] == 1 for e in range(3) if e != d) for d, a in enumerate(axes)
        )
        if grid and all(np.all(np.diff(a.reshape(-1)) > 0) for a in axes):
            from ._kernels import closest_on_grid

            xs, ys, zs = (np.ascontiguousarray(a.reshape(-1)) for a in axes)
            _, seg, par = closest_on_grid(xs, ys, zs, x, spine.closed, reach)
            sel = np.flatnonzero(seg.reshape(-1) >= 0)
            ii, jj, kk = np.unravel_index(sel, shape)
            p = np.stack([xs[ii], ys[jj], zs[kk]], axis=1)
            return shape, sel, p, seg.reshape(-1)[sel], par.reshape(-1)[sel]
        bx = [np.broadcast_to(c, shape).reshape(-1) for c in axes]
        cell = np.zeros(bx[0].shape, dtype=np.int64)
        near = np.ones(bx[0].shape, dtype=bool)
        for d in range(3):
            idx = np.floor((bx[d] - box_lo[d]) / reach).astype(np.int64)
            near &= (idx >= 0) & (idx < cells_shape[d])
            cell = cell * cells_shape[d] + np.clip(idx, 0, cells_shape[d] - 1)
        near &= occupied[cell]
        sel = np.flatnonzero(near)
        p = np.stack([b[sel] for b in bx], axis=1)
        dist, j = spine.tree().query(p, distance_upper_bound=reach)
        ok = np.isfinite(dist)
        sel, p, j = sel[ok], p[ok], j[ok]
        # candidate segments a -> a + 1 on both sides of the nearest sample
        best = None
        for a in (j - 1, j):
            a0 = a % m if spine.closed else np.clip(a, 0, m - 2)
            a1 = (a0 + 1) % m
            d = x[a1] - x[a0]
            ll = np.sum(d * d, axis=1)
            traw = np.sum((p - x[a0]) * d, axis=1) / np.where(ll > 0, ll, 1.0)
            tt = np.clip(traw, 0.0, 1.0)
            dd = np.sum((p - x[a0] - tt[:, None] * d) ** 2, axis=1)
            if best is None:
                best = [a0, traw, dd]
            else:
                better = dd < best[2]
                best = [np.where(better, a0, best[0]), np.where(better, traw, best[1]), np.where(better, dd, best[2])]
        return shape, sel, p, best[0], best[1]

    def evaluate(coords: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The profile's value and the profile-plane coordinates (u, v) of points (NaN far from the spine)."""
        shape, sel, p, a0, raw = closest(coords)
        out = np.ones(shape)
        us, vs = np.full(shape, np.nan), np.full(shape, np.nan)
        if not len(sel):
            return out, us, vs
        flat = out.reshape(-1)
        tt = np.clip(raw, 0.0, 1.0)
        a1 = (a0 + 1) % m
        c = x[a0] + tt[:, None] * (x[a1] - x[a0])
        tseg = _unit(x[a1] - x[a0])
        nrm = (1 - tt)[:, None] * spine.normal[a0] + tt[:, None] * spine.normal[a1]
        nrm = _unit(nrm - np.sum(nrm * tseg, axis=1)[:, None] * tseg)
        bin_ = np.cross(tseg, nrm)
        rel = p - c
        u, v = np.sum(rel * nrm, axis=1), np.sum(rel * bin_, axis=1)
        w = np.zeros(len(u))
        if not spine.closed:
            before = (a0 == 0) & (raw < 0)
            after = (a0 == m - 2) & (raw > 1)
            w = np.where(before, -np.sum(rel * tseg, axis=1), w)
            w = np.where(after, np.sum(rel * tseg, axis=1), w)
        arc = spine.s[a0] + tt * np.linalg.norm(x[a1] - x[a0], axis=1)
        ang = tw * arc / spine.length + ph
        ca, sa = np.cos(ang), np.sin(ang)
        uu, vv = (u * ca + v * sa) / radius, (-u * sa + v * ca) / radius
        beyond = w > 0
        if cp is Cap.ROUND and beyond.any():
            q = np.sqrt(uu * uu + vv * vv + (w / radius) ** 2)
            rr = np.hypot(uu, vv)
            safe = np.where(rr > 0, rr, 1.0)
            uu = np.where(beyond, np.where(rr > 0, uu / safe, 1.0) * q, uu)
            vv = np.where(beyond, np.where(rr > 0, vv / safe, 0.0) * q, vv)
        val = np.asarray(pf(uu, vv), dtype=np.float64)
        if cp is Cap.FLAT:
            val = np.where(beyond, np.maximum(val, w), val)
        flat[sel] = np.broadcast_to(val, sel.shape)
        us.reshape(-1)[sel] = uu
        vs.reshape(-1)[sel] = vv
        return out, us, vs

    def f(*coords: np.ndarray) -> np.ndarray:
        return evaluate(coords)[0]

    lo = x.min(axis=0) - radius
    hi = x.max(axis=0) + radius
    if arc is None:
        return Field(f, lo, hi, "tube")
    sector = check_arc(arc)

    def planar(*coords: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        _, us, vs = evaluate(coords)
        return us, vs

    def digitizer(
        shape: tuple[int, ...], origin: np.ndarray, step: np.ndarray, k: int, *, interior: bool = True
    ) -> tuple[np.ndarray, np.ndarray]:
        if interior:
            raise InvalidShapeError('arc: an open profile sweeps a ribbon, which bounds no solid; use mode = "surface"')
        surf = digitize_sector(f, planar, sector, shape, k, origin, step)
        return surf, np.zeros_like(surf)

    return Field(None, lo, hi, "ribbon", digitizer)


def _build(
    spine: str | Sequence[str] | npt.ArrayLike,
    profile: str | Callable[..., npt.ArrayLike] | Curve2D,
    *,
    radius: float,
    twist: float,
    cap: Cap | str,
    base_dir: Path | None,
    t_min: float,
    t_max: float,
    samples: int,
    closed: bool | None,
    frame: Frame | str,
    threshold: float,
    stroke: float | None,
    arc: Sequence[float] | None = None,
    profile_open: bool = False,
) -> Callable[[float], Field]:
    """Read the spine and the profile once; return the tube's field at a profile phase (degrees)."""
    pts, is_closed = load_spine(spine, base_dir=base_dir, t_min=t_min, t_max=t_max, samples=samples, closed=closed)
    sp = spine_frames(pts, is_closed, frame)
    if profile_open:
        pr, arc = _open_profile(profile, arc, base_dir=base_dir)
    else:
        pr = _profile(profile, base_dir=base_dir, threshold=threshold, stroke=stroke)
    return functools.partial(_field_at_phase, sp, pr, radius, twist, cap, arc)


def _open_profile(profile: Any, arc: Sequence[float] | None, *, base_dir: Path | None) -> tuple[Curve2D, list[float]]:
    """An open drawn profile, normalised to largest radius 1, and the arc of its two ends (degrees)."""
    if arc is not None:
        raise InvalidShapeError("arc: an open drawn profile ends where it is drawn; give arc or profile_open, not both")
    if not isinstance(profile, str):
        raise InvalidShapeError("profile_open: the profile must be a drawing (.json, .svg or .csv)")
    drawn = open_star_curve(profile, base_dir=base_dir, name="profile")
    # normalised as a closed drawn profile is, so an open stroke is the same size as the closed one it is part of
    curve = drawn.curve.transformed(np.zeros(2), 1.0 / _max_radius(drawn.curve, np.zeros(2)))
    return curve, [float(np.degrees(a)) for a in drawn.arc]


def _field_at_phase(
    sp: Spine, pr: Curve2D, radius: float, twist: float, cap: Cap | str, arc: Sequence[float] | None, phase: float
) -> Field:
    return tube_field(sp, pr, radius=radius, twist=twist, phase=phase, cap=cap, arc=arc)


def tube(
    spine: str | Sequence[str] | npt.ArrayLike,
    profile: str | Callable[..., npt.ArrayLike] | Curve2D = "x^2 + y^2 - 1",
    *,
    radius: float = 1.0,
    twist: float = 0.0,
    phase: float = 0.0,
    frame: Frame | str = "rmf",
    cap: Cap | str = "flat",
    closed: bool | None = None,
    t_min: float = 0.0,
    t_max: float = 1.0,
    samples: int = 1024,
    k: int = 0,
    mode: Mode | str = "solid",
    size: int = 25,
    scale: float | None = None,
    base_dir: Path | None = None,
    threshold: float = 0.5,
    stroke: float | None = None,
    arc: Sequence[float] | None = None,
    center: Sequence[float] | None = None,
    profile_open: bool = False,
) -> np.ndarray:
    """Digital swept tube fitted in a ``size``³ grid.

    ``spine``: three expressions ``[x(t), y(t), z(t)]`` over ``[t_min, t_max]``
    (``samples`` samples), a JSON/CSV file of 3D points or a (P, 3) array; it
    is closed when its ends meet (or by ``closed``). ``profile``: any 2D curve
    source (:func:`voxfab.digitize.load_curve`), centred and normalised to
    largest radius 1, then scaled to ``radius``. Other options: see
    :func:`tube_field` (``arc``: an open profile, a ribbon) and
    :func:`voxfab.digitize.fit` (``center``: fixed placement). ``profile_open``
    takes a drawn profile as the open stroke it is: a ribbon between its two ends
    (see :class:`voxfab.digitize.OpenCurve`).
    """
    field_at = _build(
        spine, profile, radius=radius, twist=twist, cap=cap, base_dir=base_dir, t_min=t_min, t_max=t_max,
        samples=samples, closed=closed, frame=frame, threshold=threshold, stroke=stroke, arc=arc,
        profile_open=profile_open,
    )
    return fit(field_at(phase), k=k, mode=mode, size=size, scale=scale, center=center)


def tube_rotations(
    spine: str | Sequence[str] | npt.ArrayLike,
    profile: str | Callable[..., npt.ArrayLike] | Curve2D = "x^2 + y^2 - 1",
    *,
    steps: int = 12,
    turn: float = 360.0,
    **tube_options: Any,
) -> Iterator[np.ndarray]:
    """Yield ``steps`` tubes as the profile rotates by ``turn`` degrees in all (for animation).

    ``tube_options`` are the keywords of :func:`tube` (``radius``, ``twist``,
    ``frame``, ``cap``, ``size``, ...) but ``phase``, which each frame sets, and
    ``scale`` and ``center``: every frame uses the scale and grid window fitted
    for the first one, so the frames line up.
    """
    if isinstance(steps, bool) or int(steps) != steps or steps < 1:
        raise InvalidShapeError(f"steps: expected a positive integer, got {steps!r}")
    for own in ("phase", "scale", "center"):
        if own in tube_options:
            raise TypeError(f"tube_rotations() got an unexpected keyword argument {own!r}")
    # One declaration of the tube's keywords and defaults: tube's signature.
    bound = inspect.signature(tube).bind(spine, profile, **tube_options)
    bound.apply_defaults()
    opts = dict(bound.arguments)
    k, mode, size = opts.pop("k"), opts.pop("mode"), opts.pop("size")
    del opts["phase"], opts["scale"], opts["center"]
    field_at = _build(**opts)
    placement, g0 = fit_scale(field_at(0.0), k=k, mode=mode, size=size)
    start = []
    for axis in range(3):
        idx = np.flatnonzero(g0.any(axis=tuple(a for a in range(3) if a != axis)))
        lo = int(idx[0]) - (size - int(idx[-1] - idx[0] + 1)) // 2
        start.append(int(np.clip(lo, 0, g0.shape[axis] - size)))
    window = tuple(slice(s, s + size) for s in start)
    for i in range(int(steps)):
        g = g0 if i == 0 else render(field_at(turn * i / steps), placement, k=k, mode=mode)
        if _extent(g) == 0:
            raise InvalidShapeError(f"tube: frame {i} is empty")
        yield g[window].copy()
