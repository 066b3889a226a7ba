"""2D curve sources turned into signed functions: implicit, hand-drawn, bitmap.

A :class:`Curve2D` is a vectorized ``f(x, y)`` (< 0 inside, > 0 outside; only
the sign matters to the flake digitizer) with the bounding box of its region and,
for drawings, the polylines it came from.

- implicit: an expression string in ``x, y`` (compiled safely) or a callable;
- hand-drawn: points from JSON or CSV, or the paths of an SVG file, open or
  closed. Closed polylines give an even-odd point-in-polygon sign; open ones a
  stroke ``distance - half_width`` (an unsigned distance would be invisible to
  the sign test);
- bitmap: a PNG whose dark pixels are inside; the grey level is interpolated
  bilinearly and compared with ``threshold``.
"""

from __future__ import annotations

import csv
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

from voxfab._shared.limits import open_image, parse_json, read_input_bytes
from voxfab._shared.validate import resolve_input
from voxfab.errors import FormatError, InvalidShapeError, VoxfabError

from ._expr import compile_expression

__all__ = [
    "Curve2D",
    "OpenCurve",
    "load_curve",
    "open_star_curve",
    "implicit_curve",
    "polyline_curve",
    "bitmap_curve",
    "read_points",
    "estimate_bounds",
    "DRAWING_SUFFIXES",
    "BITMAP_SUFFIXES",
]

DRAWING_SUFFIXES = (".svg", ".json", ".csv")
BITMAP_SUFFIXES = (".png", ".gif", ".bmp")


@dataclass(frozen=True)
class Curve2D:
    """A 2D curve source as a signed function.

    Attributes
    ----------
    func : callable
        ``func(x, y) -> ndarray`` over broadcastable arrays, < 0 inside.
    lo, hi : (2,) float ndarray
        Bounding box of the region ``func <= 0`` (or of the stroked curve).
    kind : str
        ``"implicit"``, ``"drawn"`` or ``"bitmap"``.
    name : str
        The input's name, for messages.
    polylines : tuple of (P, 2) float ndarray
        The drawn polylines (empty for other kinds), in drawing units.
    closed : tuple of bool
        Whether each polyline is closed.
    """

    func: Callable[[np.ndarray, np.ndarray], np.ndarray]
    lo: np.ndarray
    hi: np.ndarray
    kind: str
    name: str
    polylines: tuple[np.ndarray, ...] = field(default=())
    closed: tuple[bool, ...] = field(default=())

    def __call__(self, x: npt.ArrayLike, y: npt.ArrayLike) -> np.ndarray:
        return self.func(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))

    @property
    def center(self) -> np.ndarray:
        """Centre of the bounding box."""
        return (self.lo + self.hi) / 2.0

    def transformed(self, center: npt.ArrayLike, scale: float) -> Curve2D:
        """The same curve with ``center`` moved to the origin and sizes multiplied by ``scale``."""
        c = np.asarray(center, dtype=np.float64)
        s = float(scale)
        base = self.func

        def func(x: np.ndarray, y: np.ndarray) -> np.ndarray:
            return base(x / s + c[0], y / s + c[1])

        return Curve2D(
            func, (self.lo - c) * s, (self.hi - c) * s, self.kind, self.name,
            tuple((p - c) * s for p in self.polylines), self.closed,
        )


def estimate_bounds(
    f: Callable[..., np.ndarray], n: int, *, name: str, windows: Sequence[float] = (2.0, 8.0, 32.0, 128.0, 1024.0)
) -> tuple[np.ndarray, np.ndarray]:
    """Bounding box of ``{f <= 0}`` found by sampling growing centred windows.

    Raises
    ------
    InvalidShapeError
        If the region is empty or reaches every window's border.
    """
    per_axis = {2: 257, 3: 65, 4: 25}.get(n, 13)

    def box(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """Sampled box of the region with a one-sample margin; None if empty or touching."""
        axes = [np.linspace(lo[d], hi[d], per_axis) for d in range(n)]
        grids = [a.reshape([-1 if e == d else 1 for e in range(n)]) for d, a in enumerate(axes)]
        with np.errstate(all="ignore"):
            inside = np.broadcast_to(np.asarray(f(*grids)) <= 0, (per_axis,) * n)
        if not inside.any():
            return None
        out_lo, out_hi = np.empty(n), np.empty(n)
        for d in range(n):
            idx = np.flatnonzero(inside.any(axis=tuple(e for e in range(n) if e != d)))
            if idx[0] == 0 or idx[-1] == per_axis - 1:
                return None
            sp = axes[d][1] - axes[d][0]
            out_lo[d], out_hi[d] = axes[d][idx[0]] - sp, axes[d][idx[-1]] + sp
        return out_lo, out_hi

    for w in windows:
        coarse = box(np.full(n, -w), np.full(n, w))
        if coarse is not None:
            fine = box(*coarse)
            return fine if fine is not None else coarse
    raise InvalidShapeError(
        f"{name}: the region f <= 0 is empty or unbounded within ±{windows[-1]:g} "
        f"(inside must be negative and bounded)"
    )


def implicit_curve(
    source: str | Callable[..., npt.ArrayLike], *, name: str = "curve", half_plane: bool = False
) -> Curve2D:
    """A curve from an expression in ``x, y`` or a vectorized callable ``f(x, y)``.

    With ``half_plane`` only the part ``x >= 0`` must be bounded (generatrices).
    """
    if isinstance(source, str):
        func = compile_expression(source, ("x", "y"), name=name)
    elif callable(source):
        def func(x: np.ndarray, y: np.ndarray) -> np.ndarray:
            with np.errstate(all="ignore"):
                return np.asarray(source(x, y), dtype=np.float64)
    else:
        raise InvalidShapeError(f"{name}: expected an expression string or a callable, got {type(source).__name__}")
    if half_plane:
        def half(x: np.ndarray, y: np.ndarray) -> np.ndarray:
            return np.where(np.asarray(x) >= 0, func(x, y), 1.0)

        lo, hi = estimate_bounds(half, 2, name=name)
    else:
        lo, hi = estimate_bounds(func, 2, name=name)
    return Curve2D(func, lo, hi, "implicit", name)


# --- polylines --------------------------------------------------------------------------------

def _clean_polyline(points: npt.ArrayLike, *, name: str) -> tuple[np.ndarray, bool]:
    """Drop repeated points; a polyline whose last point is its first is closed."""
    p = np.asarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) == 0:
        raise InvalidShapeError(f"{name}: expected a list of (x, y) points, got an array of shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise InvalidShapeError(f"{name}: points must be finite numbers")
    keep = np.ones(len(p), dtype=bool)
    keep[1:] = np.any(np.diff(p, axis=0) != 0, axis=1)
    p = p[keep]
    closed = len(p) > 2 and bool(np.all(p[0] == p[-1]))
    if closed:
        p = p[:-1]
    return p, closed


def _segments(polylines: Sequence[np.ndarray], closed: Sequence[bool]) -> np.ndarray:
    """(S, 4) segments x0, y0, x1, y1 of the polylines."""
    segs = []
    for p, c in zip(polylines, closed):
        q = np.vstack([p, p[:1]]) if c else p
        segs.append(np.hstack([q[:-1], q[1:]]))
    return np.vstack(segs) if segs else np.zeros((0, 4))


@dataclass(frozen=True)
class _Buckets:
    """Segments binned by their y range, so each point tests only its row's segments."""

    segs: np.ndarray
    ylo: float
    bh: float
    start: np.ndarray
    items: np.ndarray

    @classmethod
    def build(cls, segs: np.ndarray, pad: float = 0.0) -> _Buckets:
        y0 = np.minimum(segs[:, 1], segs[:, 3]) - pad
        y1 = np.maximum(segs[:, 1], segs[:, 3]) + pad
        ylo, yhi = float(y0.min()), float(y1.max())
        nb = max(1, min(4096, 2 * len(segs)))
        bh = max((yhi - ylo) / nb, 1e-300)
        b0 = np.clip(((y0 - ylo) / bh).astype(np.int64), 0, nb - 1)
        b1 = np.clip(((y1 - ylo) / bh).astype(np.int64), 0, nb - 1)
        counts = b1 - b0 + 1
        seg_ids = np.repeat(np.arange(len(segs)), counts)
        offs = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        bins = np.repeat(b0, counts) + offs
        order = np.argsort(bins, kind="stable")
        start = np.zeros(nb + 1, dtype=np.int64)
        np.add.at(start, bins + 1, 1)
        return cls(segs, ylo, bh, np.cumsum(start), seg_ids[order].astype(np.int64))


def _get_kernels() -> tuple[Callable[..., np.ndarray], Callable[..., np.ndarray]]:
    from ._kernels import even_odd, stroke

    return even_odd, stroke


def _pointwise(kernel: Callable[..., np.ndarray], x: np.ndarray, y: np.ndarray, *args: object) -> np.ndarray:
    bx, by = np.broadcast_arrays(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
    shape = bx.shape
    out = kernel(np.ascontiguousarray(bx).reshape(-1), np.ascontiguousarray(by).reshape(-1), *args)
    return out.reshape(shape)


def polyline_curve(
    polylines: Sequence[npt.ArrayLike],
    *,
    closed: Sequence[bool | None] | bool | None = None,
    stroke: float | None = None,
    name: str = "drawing",
) -> Curve2D:
    """A curve from hand-drawn polylines.

    Parameters
    ----------
    polylines : sequence of (P, 2) array_like
        Points in drawing units; a polyline ending on its first point is closed.
    closed : bool or sequence of bool, optional
        Force open/closed per polyline (``None``: detect).
    stroke : float, optional
        Full width of open polylines, which become thin bands (default: 1/100
        of the drawing's diagonal).
    """
    polys, flags = [], []
    closed_list = [closed] * len(polylines) if closed is None or isinstance(closed, bool) else list(closed)
    if len(closed_list) != len(polylines):
        raise InvalidShapeError(f"{name}: closed has {len(closed_list)} flags for {len(polylines)} polylines")
    for i, (p, c) in enumerate(zip(polylines, closed_list)):
        label = name if len(polylines) == 1 else f"{name} (polyline {i})"
        q, detected = _clean_polyline(p, name=label)
        if len(q) < 2:
            continue
        is_closed = detected if c is None else bool(c)
        if is_closed and len(q) < 3:
            raise InvalidShapeError(f"{label}: a closed polyline needs 3 distinct points, got {len(q)}")
        if is_closed:
            area = 0.5 * abs(np.sum(q[:, 0] * np.roll(q[:, 1], -1) - np.roll(q[:, 0], -1) * q[:, 1]))
            span = float(np.ptp(q, axis=0).max())
            if area <= 1e-9 * span * span:
                raise InvalidShapeError(f"{label}: degenerate closed polyline (zero area)")
        polys.append(q)
        flags.append(is_closed)
    if not polys:
        raise InvalidShapeError(f"{name}: empty drawing (no polyline with 2 distinct points)")
    pts = np.vstack(polys)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    diag = float(np.hypot(*(hi - lo)))
    if diag == 0:
        raise InvalidShapeError(f"{name}: degenerate drawing (all points equal)")
    half = 0.5 * (diag / 100.0 if stroke is None else float(stroke))
    if half <= 0:
        raise InvalidShapeError(f"{name}: stroke must be > 0, got {stroke}")
    closed_segs = _segments([p for p, c in zip(polys, flags) if c], [True] * sum(flags))
    open_segs = _segments([p for p, c in zip(polys, flags) if not c], [False] * (len(flags) - sum(flags)))
    eo = _Buckets.build(closed_segs) if len(closed_segs) else None
    st = _Buckets.build(open_segs, pad=half) if len(open_segs) else None

    def func(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        even_odd, stroke_k = _get_kernels()
        out = None
        if eo is not None:
            out = _pointwise(even_odd, x, y, eo.segs, eo.ylo, eo.bh, eo.start, eo.items)
        if st is not None:
            s = _pointwise(stroke_k, x, y, st.segs, st.ylo, st.bh, st.start, st.items, half)
            out = s if out is None else np.minimum(out, s)
        return out

    if st is not None:
        lo, hi = lo - half, hi + half
    return Curve2D(func, lo, hi, "drawn", name, tuple(polys), tuple(flags))


# --- files ------------------------------------------------------------------------------------

def read_points(path: Path, *, name: str) -> tuple[list[np.ndarray], list[bool | None]]:
    """Polylines and closed flags (``None``: detect) from a JSON, CSV or SVG file.

    The file must be a regular file of at most 16 MiB; JSON is read within the
    nesting and integer-size limits of :mod:`voxfab._shared.limits`.
    """
    suffix = path.suffix.lower()
    if not path.exists():
        raise InvalidShapeError(f"{name}: file not found: {path}")
    data = read_input_bytes(path, what="a drawing")
    if suffix == ".svg":
        return _read_svg(path, data, name=name)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise FormatError(f"{name}: {path.name} is not UTF-8 text") from None
    if suffix == ".json":
        return _json_polylines(parse_json(text, name=f"{name}: {path.name}"), name=f"{name} ({path.name})")
    if suffix == ".csv":
        polys: list[list[list[float]]] = [[]]
        for row in csv.reader(text.splitlines()):
            cells = [c.strip() for c in row if c.strip()]
            if not cells:
                if polys[-1]:
                    polys.append([])
                continue
            try:
                polys[-1].append([float(cells[0]), float(cells[1])])
            except (ValueError, IndexError):
                if any(polys):
                    raise FormatError(f"{name}: {path.name}: bad CSV row {row!r}, expected x,y") from None
        polys = [p for p in polys if p]
        return [np.array(p) for p in polys], [None] * len(polys)
    raise InvalidShapeError(f"{name}: unsupported drawing format {suffix!r} (expected .svg, .json or .csv)")


def _json_polylines(data: object, *, name: str) -> tuple[list[np.ndarray], list[bool | None]]:
    def one(item: object) -> tuple[np.ndarray, bool | None]:
        if isinstance(item, dict):
            if "points" not in item:
                raise FormatError(f"{name}: a polyline object needs a 'points' list")
            c = item.get("closed")
            return np.asarray(item["points"], dtype=np.float64), (None if c is None else bool(c))
        return np.asarray(item, dtype=np.float64), None

    try:
        if isinstance(data, dict) and "polylines" in data:
            items = [one(i) for i in data["polylines"]]
        elif isinstance(data, dict):
            items = [one(data)]
        elif isinstance(data, list) and data and isinstance(data[0], (list, dict)) and data[0] and (
            isinstance(data[0], dict) or isinstance(data[0][0], list)
        ):
            items = [one(i) for i in data]
        else:
            items = [one(data)]
    except (TypeError, ValueError):
        raise FormatError(f"{name}: expected [[x, y], ...] point lists") from None
    for p, _ in items:
        if p.size == 0:
            raise InvalidShapeError(f"{name}: empty drawing (no points)")
        if p.ndim != 2 or p.shape[1] != 2:
            raise FormatError(f"{name}: expected [[x, y], ...] point lists, got shape {p.shape}")
    return [p for p, _ in items], [c for _, c in items]


def _read_svg(path: Path, data: bytes, *, name: str) -> tuple[list[np.ndarray], list[bool | None]]:
    from io import BytesIO

    from svgelements import SVG, Close, Line, Move, Shape
    from svgelements import Path as SvgPath

    try:
        svg = SVG.parse(BytesIO(data))
    except Exception as exc:  # noqa: BLE001 - svgelements raises many kinds
        raise FormatError(f"{name}: cannot parse SVG {path.name}: {exc}") from None
    polys: list[np.ndarray] = []
    flags: list[bool | None] = []
    for el in svg.elements():
        if not isinstance(el, Shape):
            continue
        for sub in SvgPath(el).as_subpaths():
            pts: list[tuple[float, float]] = []
            closed = False
            for seg in SvgPath(sub):
                if isinstance(seg, Move):
                    pts.append((seg.end.x, seg.end.y))
                elif isinstance(seg, Close):
                    closed = True
                elif isinstance(seg, Line):
                    pts.append((seg.end.x, seg.end.y))
                elif seg.start is not None and seg.end is not None:
                    # curves: sampled finely enough for a 256-voxel model
                    ts = np.linspace(0.0, 1.0, 33)[1:]
                    pts.extend((float(q[0]), float(q[1])) for q in seg.npoint(ts))
            if len(pts) >= 2:
                p = np.array(pts, dtype=np.float64)
                p[:, 1] = -p[:, 1]  # SVG y points down; drawings use y up
                polys.append(p)
                flags.append(True if closed else None)
    if not polys:
        raise InvalidShapeError(f"{name}: empty drawing: no path in {path.name}")
    return polys, flags


def bitmap_curve(path: Path, *, threshold: float = 0.5, name: str = "bitmap") -> Curve2D:
    """A region from an image: pixels darker than ``threshold`` (0..1) are inside.

    One pixel is one unit; x grows to the right, y upwards.
    """
    from PIL import Image

    if not 0.0 < threshold < 1.0:
        raise InvalidShapeError(f"{name}: threshold must be in (0, 1), got {threshold}")
    if not path.exists():
        raise InvalidShapeError(f"{name}: file not found: {path}")
    try:
        # open_image checks the pixel count from the header, before decoding.
        with open_image(path, name=name) as im:
            im.load()
            if im.mode in ("RGBA", "LA", "PA") or (im.mode == "P" and "transparency" in im.info):
                im = im.convert("RGBA")
                bg = Image.new("RGBA", im.size, (255, 255, 255, 255))
                im = Image.alpha_composite(bg, im)
            gray = np.asarray(im.convert("L"), dtype=np.float64) / 255.0
    except VoxfabError:
        raise
    except Exception as exc:  # noqa: BLE001 - Pillow reports corrupt pixel data in many ways
        raise FormatError(f"{name}: cannot read image {path.name}: {type(exc).__name__}") from None
    dark = gray < threshold
    if not dark.any():
        raise InvalidShapeError(f"{name}: empty bitmap: no pixel of {path.name} is darker than {threshold}")
    h, w = gray.shape
    # a white frame makes everything outside the picture "outside"
    img = np.pad(gray, 1, constant_values=1.0) - threshold
    rows = np.flatnonzero(dark.any(axis=1))
    cols = np.flatnonzero(dark.any(axis=0))
    lo = np.array([cols[0], h - rows[-1] - 1], dtype=np.float64)
    hi = np.array([cols[-1] + 1, h - rows[0]], dtype=np.float64)

    def func(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        bx, by = np.broadcast_arrays(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
        # padded-image coordinates of pixel centres: column c+1 at x = c + 0.5
        # NaN compares false: it lands on the white frame (index 0)
        u = np.where(bx + 0.5 > 0.0, np.minimum(bx + 0.5, w + 1.0), 0.0)
        v = np.where(h - by + 0.5 > 0.0, np.minimum(h - by + 0.5, h + 1.0), 0.0)
        c0 = np.minimum(np.floor(u).astype(np.int64), w)
        r0 = np.minimum(np.floor(v).astype(np.int64), h)
        fu, fv = u - c0, v - r0
        top = img[r0, c0] * (1 - fu) + img[r0, c0 + 1] * fu
        bot = img[r0 + 1, c0] * (1 - fu) + img[r0 + 1, c0 + 1] * fu
        return top * (1 - fv) + bot * fv

    return Curve2D(func, lo, hi, "bitmap", name)


def load_curve(
    source: str | Callable[..., npt.ArrayLike] | Sequence[Sequence[float]] | np.ndarray,
    *,
    base_dir: Path | None = None,
    name: str = "curve",
    threshold: float = 0.5,
    closed: bool | None = None,
    stroke: float | None = None,
    half_plane: bool = False,
) -> Curve2D:
    """Load a 2D curve from any source.

    ``source`` is a callable, a point list, a file name (``.svg``, ``.json``,
    ``.csv``: drawing; ``.png``, ``.gif``, ``.bmp``: bitmap; relative names are
    resolved in ``base_dir``), or else an expression in ``x, y``.

    Inputs are bounded (:mod:`voxfab._shared.limits`): only regular files of at
    most 16 MiB, JSON nested at most 64 levels with integers of at most 30
    digits, bitmaps of at most 4096 x 4096 pixels, expressions of at most 1,000
    characters.  While a recipe is built, files must be inside its folder
    (:func:`voxfab._shared.validate.confine_inputs`).

    Raises
    ------
    LimitError
        An input over one of those limits.
    RecipeError
        A file outside the recipe's folder.
    FormatError, InvalidShapeError
        An unreadable or empty drawing or bitmap, or a bad expression.
    """
    if callable(source):
        return implicit_curve(source, name=name, half_plane=half_plane)
    if isinstance(source, str):
        suffix = Path(source).suffix.lower()
        if suffix in DRAWING_SUFFIXES + BITMAP_SUFFIXES:
            path = resolve_input(source, base_dir, name=name)
            label = f"{name} ({Path(source).name})"
            if suffix in BITMAP_SUFFIXES:
                return bitmap_curve(path, threshold=threshold, name=label)
            polys, flags = read_points(path, name=name)
            if closed is not None:
                flags = [closed] * len(polys)
            return polyline_curve(polys, closed=flags, stroke=stroke, name=label)
        return implicit_curve(source, name=name, half_plane=half_plane)
    arr = np.asarray(source, dtype=np.float64)
    return polyline_curve([arr], closed=closed, stroke=stroke, name=name)


def star_radius(
    f: Callable[..., np.ndarray], n: int, *, name: str, r_max: float
) -> tuple[bool, float]:
    """Whether ``{f <= 0}`` is star-shaped about the origin (contains it, one crossing per ray), and its radius.

    Sampled on rays: 256 directions in 2D, 1200 on the sphere in 3D.
    """
    if n == 2:
        a = np.linspace(0.0, 2 * np.pi, 256, endpoint=False)
        dirs = np.stack([np.cos(a), np.sin(a)], axis=1)
    else:
        m = 1200
        i = np.arange(m) + 0.5
        phi = np.arccos(1 - 2 * i / m)
        th = np.pi * (1 + 5**0.5) * i
        dirs = np.stack([np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)], axis=1)
    rs = np.linspace(0.0, r_max, 128)
    pts = dirs[:, None, :] * rs[None, :, None]
    with np.errstate(all="ignore"):
        inside = np.asarray(f(*[pts[..., d] for d in range(n)])) <= 0
    inside = np.broadcast_to(inside, pts.shape[:2])
    if not inside[:, 0].all():
        # the axis is outside: several components or a ring, not star-shaped about the axis
        return False, float(r_max)
    changes = np.count_nonzero(inside[:, 1:] != inside[:, :-1], axis=1)
    last_in = inside.shape[1] - 1 - np.argmax(inside[:, ::-1], axis=1)
    radius = float(rs[min(last_in.max() + 1, len(rs) - 1)])
    return bool(np.all(changes == 1)), radius


# --- open drawn curves ------------------------------------------------------------------------

@dataclass(frozen=True)
class OpenCurve:
    """An open drawn curve that turns one way about its centre, as a part of a closed star-shaped curve.

    The flake digitizer needs a signed function around the whole flake, so the
    open curve is completed into a closed star-shaped curve: its polar radius is
    the drawing's within ``arc`` and, across the gap between the two ends, goes
    linearly in angle from one end's radius to the other's.  Only the part within
    ``arc`` is digitized (the flakes are cropped at the ends' half-planes), so the
    completion never shows.

    Attributes
    ----------
    curve : Curve2D
        The completed curve, centred on the drawing's bounding box (as closed
        drawings are), < 0 inside.
    arc : (float, float)
        The drawn part: angles ``start < end < start + 2π`` in radians about the centre.
    """

    curve: Curve2D
    arc: tuple[float, float]


def open_star_curve(
    source: str | Sequence[Sequence[float]] | np.ndarray, *, base_dir: Path | None = None, name: str = "curve"
) -> OpenCurve:
    """Read one open polyline (a JSON, SVG or CSV drawing, or points) as an :class:`OpenCurve`.

    Raises
    ------
    InvalidShapeError
        Not one open polyline, or one that does not turn one way about its
        centre (a ray from the centre would cross it twice), or turns a full turn.
    """
    if isinstance(source, str):
        if Path(source).suffix.lower() not in DRAWING_SUFFIXES:
            raise InvalidShapeError(f"{name}: an open curve comes from a drawing (.json, .svg or .csv); for an "
                                    "expression give arc = [start, end] instead")
        path = resolve_input(source, base_dir, name=name)
        polys, _ = read_points(path, name=name)
        label = f"{name} ({Path(source).name})"
    else:
        polys, label = [np.asarray(source, dtype=np.float64)], name
    if len(polys) != 1:
        raise InvalidShapeError(f"{label}: an open curve is one stroke, got {len(polys)}")
    pts, _ = _clean_polyline(polys[0], name=label)
    if len(pts) < 2:
        raise InvalidShapeError(f"{label}: an open curve needs 2 distinct points")
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = (lo + hi) / 2.0
    rel = pts - centre
    radii = np.hypot(rel[:, 0], rel[:, 1])
    if np.any(radii <= 1e-12 * max(float(radii.max()), 1e-300)):
        raise InvalidShapeError(f"{label}: an open curve may not pass through its centre, the axis")
    turn = np.diff(np.unwrap(np.arctan2(rel[:, 1], rel[:, 0])))
    if not (np.all(turn > 0) or np.all(turn < 0)):
        raise InvalidShapeError(f"{label}: an open curve must turn one way about its centre (no ray from the centre "
                                "may cross it twice)")
    if turn[0] < 0:
        rel, turn = rel[::-1], -turn[::-1]
    angles = np.concatenate([[0.0], np.cumsum(turn)])  # from the first point, increasing
    span = float(angles[-1])
    if span >= 2 * np.pi - 1e-9:
        raise InvalidShapeError(f"{label}: the curve turns a full turn about its centre; draw it closed instead")
    start = float(np.arctan2(rel[0, 1], rel[0, 0]))
    r_start, r_end = float(np.hypot(*rel[0])), float(np.hypot(*rel[-1]))

    def polar_radius(theta: np.ndarray) -> np.ndarray:
        rel_angle = np.mod(theta - start, 2 * np.pi)
        seg = np.clip(np.searchsorted(angles, rel_angle, side="right") - 1, 0, len(rel) - 2)
        p0, d = rel[seg], rel[seg + 1] - rel[seg]
        ux, uy = np.cos(theta), np.sin(theta)
        with np.errstate(divide="ignore", invalid="ignore"):
            drawn = (p0[..., 0] * d[..., 1] - p0[..., 1] * d[..., 0]) / (ux * d[..., 1] - uy * d[..., 0])
        gap = (rel_angle - span) / (2 * np.pi - span)
        return np.where(rel_angle <= span, drawn, r_end + (r_start - r_end) * gap)

    def func(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        x, y = np.broadcast_arrays(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
        return np.hypot(x, y) - polar_radius(np.arctan2(y, x))

    # The box of the swept part: the drawn points and the axis (scaled copies of the curve fill it).
    box = np.vstack([rel, [[0.0, 0.0]]])
    curve = Curve2D(func, box.min(axis=0), box.max(axis=0), "drawn", label, (rel,), (False,))
    return OpenCurve(curve, (start, start + span))
