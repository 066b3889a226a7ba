"""PNG backend: a page rasterized for people, lines at visible widths over the fills.

Pillow draws the lines; fills use an even-odd scanline fill computed with numpy
(holes are rings inside rings), so areas with holes come out right.  Dashes
follow the layer's pattern in mm; when a pattern would be finer than a few
pixels the line is drawn solid, which reads better than noise.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_bytes

from ._layers import DASH_PATTERNS, LAYERS, LayerStyle, Lines
from ._legend import Legend, legend_layers
from ._model import HALO, Fill, Page, PlacedImage
from ._polylines import Polylines

if TYPE_CHECKING:
    from PIL import Image

__all__ = ["dashes", "even_odd_mask", "page_image", "png_bytes", "write_png"]

#: Patterns shorter than this many pixels are drawn solid.
_MIN_DASH_PX = 4.0


def dashes(lines: Polylines, pattern: tuple[float, ...]) -> Polylines:
    """The "on" pieces of ``pattern`` (on, off, ... mm) along every straight piece of ``lines``.

    The pattern restarts at the start of each piece, so a fold line drawn as
    one segment gets the same dashes in every backend that restarts likewise.
    """
    a, b = lines.segments()
    if not pattern or not a.shape[0]:
        return Polylines.from_segments(a, b)
    length = np.linalg.norm(b - a, axis=1)
    period = float(sum(pattern))
    starts = np.cumsum((0.0,) + pattern[:-1])[0::2]
    ons = np.asarray(pattern[0::2])
    reps = np.floor(length / period).astype(np.int64) + 1
    seg = np.repeat(np.arange(a.shape[0]), reps * ons.size)
    k = np.arange(seg.size) - np.repeat(np.cumsum(reps * ons.size) - reps * ons.size, reps * ons.size)
    t0 = (k // ons.size) * period + starts[k % ons.size]
    t1 = np.minimum(t0 + ons[k % ons.size], length[seg])
    keep = t0 < length[seg]
    seg, t0, t1 = seg[keep], t0[keep], t1[keep]
    d = (b - a)[seg] / np.maximum(length[seg], 1e-12)[:, None]
    return Polylines.from_segments(a[seg] + t0[:, None] * d, a[seg] + t1[:, None] * d)


def even_odd_mask(rings: Polylines, width: int, height: int, to_px, *,  # noqa: ANN001
                  nonzero: bool = False, origin: tuple[int, int] = (0, 0)) -> npt.NDArray[np.bool_]:
    """``(height, width)`` pixels whose centres lie inside an odd number of ``rings``.

    ``to_px`` maps ``(N, 2)`` mm points to pixel ``(col, row)``.  With ``nonzero``,
    the pixels of nonzero winding number instead (overlapping rings of one
    orientation make one area).  ``origin`` ``(col, row)``: the mask is the window of
    that many pixels from there, computed in the page's own pixel coordinates.
    """
    a, b = rings.segments()
    if not a.shape[0]:
        return np.zeros((height, width), dtype=bool)
    p, q = to_px(a), to_px(b)
    y0, y1 = np.minimum(p[:, 1], q[:, 1]), np.maximum(p[:, 1], q[:, 1])
    # Rows whose centre (r + 0.5) lies in [y0, y1): each such row crosses the edge once.
    c_lo, r_lo = origin
    r0 = np.clip(np.ceil(y0 - 0.5), r_lo, r_lo + height).astype(np.int64)
    r1 = np.clip(np.ceil(y1 - 0.5), r_lo, r_lo + height).astype(np.int64)
    n = r1 - r0
    e = np.repeat(np.arange(a.shape[0]), n)
    row = np.arange(e.size) - np.repeat(np.cumsum(n) - n, n) + r0[e]
    yc = row + 0.5
    t = (yc - p[e, 1]) / (q[e, 1] - p[e, 1])
    xc = p[e, 0] + t * (q[e, 0] - p[e, 0])
    col = np.clip(np.ceil(xc - 0.5), c_lo, c_lo + width).astype(np.int64) - c_lo
    row = row - r_lo
    toggles = np.zeros((height, width + 1), dtype=np.int64)
    if nonzero:
        np.add.at(toggles, (row, col), np.sign(q[e, 1] - p[e, 1]).astype(np.int64))
        return np.cumsum(toggles, axis=1)[:, :width] != 0
    np.add.at(toggles, (row, col), 1)
    return (np.cumsum(toggles, axis=1)[:, :width] % 2).astype(bool)


def _paint_convex(pixels: npt.NDArray[np.uint8], rings: Polylines, colors: tuple[str, ...], to_px) -> None:  # noqa: ANN001
    """Paint convex ``rings``, each in its colour, later rings over earlier ones.

    A row crosses a convex ring at two points at most, so the ring covers the pixels between
    them: one span per ring and row, found for all rings at once (a net has thousands of faces).
    The pixels are those :func:`even_odd_mask` gives each ring alone.
    """
    h, w = pixels.shape[:2]
    a, b = rings.segments()
    if not a.shape[0]:
        return
    owner = np.repeat(np.arange(len(rings)), np.diff(rings.offsets))  # closed rings: one edge per vertex
    p, q = to_px(a), to_px(b)
    y0, y1 = np.minimum(p[:, 1], q[:, 1]), np.maximum(p[:, 1], q[:, 1])
    r0 = np.clip(np.ceil(y0 - 0.5), 0, h).astype(np.int64)
    r1 = np.clip(np.ceil(y1 - 0.5), 0, h).astype(np.int64)
    n = r1 - r0
    e = np.repeat(np.arange(a.shape[0]), n)
    if not e.size:
        return
    row = np.arange(e.size) - np.repeat(np.cumsum(n) - n, n) + r0[e]
    t = (row + 0.5 - p[e, 1]) / (q[e, 1] - p[e, 1])
    col = np.clip(np.ceil(p[e, 0] + t * (q[e, 0] - p[e, 0]) - 0.5), 0, w).astype(np.int64)
    ring = owner[e]
    order = np.lexsort((col, row, ring))
    ring, row, col = ring[order], row[order], col[order]
    first = np.flatnonzero(np.r_[True, (ring[1:] != ring[:-1]) | (row[1:] != row[:-1])])
    last = np.r_[first[1:], ring.size] - 1
    span_ring, span_row, c0, c1 = ring[first], row[first], col[first], col[last]
    length = c1 - c0
    keep = length > 0
    span_ring, span_row, c0, length = span_ring[keep], span_row[keep], c0[keep], length[keep]
    pix_row = np.repeat(span_row, length)
    pix_col = np.arange(pix_row.size) - np.repeat(np.cumsum(length) - length, length) + np.repeat(c0, length)
    rgb = np.array([[int(c[i:i + 2], 16) for i in (1, 3, 5)] for c in colors], dtype=np.uint8)
    pixels[pix_row, pix_col] = rgb[np.repeat(span_ring, length)]


def _fill(pixels: npt.NDArray[np.uint8], fill: Fill, to_px) -> None:  # noqa: ANN001
    """Paint ``fill`` on ``pixels``, working only in the box round its rings (a net has a fill per face)."""
    h, w = pixels.shape[:2]
    if not len(fill.rings):
        return
    px = to_px(fill.rings.points)
    c0, r0 = (max(int(np.floor(v)) - 1, 0) for v in px.min(axis=0))
    c1, r1 = (int(np.ceil(v)) + 1 for v in px.max(axis=0))
    c1, r1 = min(c1, w), min(r1, h)
    if c1 <= c0 or r1 <= r0:
        return
    mask = even_odd_mask(fill.rings, c1 - c0, r1 - r0, to_px, nonzero=fill.nonzero, origin=(c0, r0))
    pixels[r0:r1, c0:c1][mask] = fill.rgb


def _stroke(draw, to_px, lines: Polylines, pattern: tuple[float, ...], rgb: tuple[int, int, int],  # noqa: ANN001
            px: float) -> None:
    """Draw ``lines`` (dashed by ``pattern`` in mm, solid when empty) ``px`` pixels wide."""
    if pattern:
        lines = dashes(lines, pattern)
    px_width = max(1, int(round(px)))
    for pts, closed in zip(lines.lines(), lines.closed.tolist()):
        pp = to_px(np.concatenate([pts, pts[:1]]) if closed else pts)
        if pp.shape[0] > 1:
            draw.line([tuple(v) for v in pp.tolist()], fill=rgb, width=px_width)


def _paste(pixels: npt.NDArray[np.uint8], placed: PlacedImage, page_height: float, scale: float) -> None:
    """Resample ``placed`` to its box on ``pixels`` (rows top down), cut at the page's edges."""
    from PIL import Image

    left, right = round(placed.x * scale), round((placed.x + placed.width) * scale)
    top, bottom = round((page_height - placed.y - placed.height) * scale), round((page_height - placed.y) * scale)
    if right <= left or bottom <= top:
        return
    src = Image.fromarray(placed.pixels, "RGB")
    box = np.asarray(src if src.size == (right - left, bottom - top)
                     else src.resize((right - left, bottom - top), Image.Resampling.LANCZOS))
    rows, cols = pixels.shape[:2]
    r0, c0 = max(top, 0), max(left, 0)
    r1, c1 = min(bottom, rows), min(right, cols)
    if r1 > r0 and c1 > c0:
        pixels[r0:r1, c0:c1] = box[r0 - top:r1 - top, c0 - left:c1 - left]


#: Most pixels of one rasterized page: a 5 x 5 m sheet at 4 px/mm would be 400 million pixels (1.2 GB of
#: RGB before drawing); a larger page is drawn at the scale that gives this many.
MAX_PAGE_PIXELS = 25_000_000


def page_scale(width: float, height: float, scale: float) -> float:
    """``scale`` in px/mm, lowered so that a ``width`` x ``height`` mm page has at most :data:`MAX_PAGE_PIXELS`."""
    area = max(width * height, 1e-9) * scale * scale
    return scale if area <= MAX_PAGE_PIXELS else scale * (MAX_PAGE_PIXELS / area) ** 0.5


def page_image(page: Page, *, scale: float, styles: Mapping[str, LayerStyle] | None = None,
               background: tuple[int, int, int] = (255, 255, 255), legend: Legend | None = None,
               hidden: frozenset[str] = frozenset()) -> Image.Image:
    """Rasterize ``page`` at ``scale`` pixels per mm.

    Parameters
    ----------
    page : Page
    scale : float
        Pixels per mm.
    styles : mapping of str to LayerStyle, optional
        Colour map (default :data:`~voxfab.drawing.LAYERS`).
    background : (r, g, b)
        Paper colour.
    legend : bool
        Add the legend of :func:`~voxfab.drawing.pdf.page_content`.
    hidden : frozenset of str
        Layers left out.

    Returns
    -------
    PIL.Image.Image
        RGB, ``round(width · scale) × round(height · scale)`` pixels, at most
        :data:`MAX_PAGE_PIXELS` (a larger page is drawn at a lower scale).
    """
    from PIL import Image, ImageDraw

    scale = page_scale(page.width, page.height, scale)
    st_map = LAYERS if styles is None else styles
    w = max(1, int(round(page.width * scale)))
    h = max(1, int(round(page.height * scale)))

    def to_px(xy: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return np.stack([xy[:, 0] * scale, (page.height - xy[:, 1]) * scale], axis=1)

    pixels = np.empty((h, w, 3), dtype=np.uint8)
    pixels[:] = background
    for placed in page.images:
        _paste(pixels, placed, page.height, scale)
    for fill in page.fills:
        if fill.colors:  # each (convex) ring in its own colour, painted row span by row span
            _paint_convex(pixels, fill.rings, fill.colors, to_px)
        else:
            _fill(pixels, fill, to_px)
    image = Image.fromarray(pixels, "RGB")
    draw = ImageDraw.Draw(image)
    extra = legend_layers(page, legend) if legend else {}
    for name in LAYERS:
        if name in hidden:
            continue
        st = st_map[name]
        pattern = DASH_PATTERNS[st.style]
        if not (pattern and sum(pattern) * scale >= _MIN_DASH_PX):
            pattern = ()
        width = st.line_width(Lines.PREVIEW)
        inks = page.inks_of(name)
        for ink in inks or ():  # every halo first, so no halo covers another ink's line
            if ink.halo:
                _stroke(draw, to_px, ink.lines, pattern, ink.halo_rgb, (width + 2 * HALO) * scale)
        for ink in inks or ():
            _stroke(draw, to_px, ink.lines, pattern, ink.rgb, width * scale)
        own = Polylines.empty() if inks else page.lines(name)
        _stroke(draw, to_px, Polylines.concat([own, extra.get(name, Polylines.empty())]), pattern, st.rgb,
                width * scale)
        px_width = max(1, int(round(st.line_width(Lines.PREVIEW) * scale)))
        for x, y, r in page.circles_of(name).tolist():
            cx, cy = x * scale, (page.height - y) * scale
            draw.ellipse([cx - r * scale, cy - r * scale, cx + r * scale, cy + r * scale], outline=st.rgb,
                         width=px_width)
    if len(page.marks):
        marks = even_odd_mask(page.marks, w, h, to_px)
        out = np.asarray(image).copy()
        out[marks] = 0
        image = Image.fromarray(out, "RGB")
    return image


def png_bytes(image: Image.Image, *, dpi: float | None = None) -> bytes:
    """PNG bytes of ``image`` with no text or time chunks; with ``dpi``, its physical resolution (pHYs)."""
    import io

    buf = io.BytesIO()
    extra = {} if dpi is None else {"dpi": (dpi, dpi)}
    image.save(buf, format="PNG", optimize=False, compress_level=6, **extra)
    return buf.getvalue()


def write_png(page: Page, path: Path, *, scale: float, styles: Mapping[str, LayerStyle] | None = None,
              legend: Legend | None = None) -> list[str]:
    """Write ``page`` rasterized at ``scale`` px/mm as PNG (atomically); returns the path written.

    The file says its resolution, so that it prints (and a cutter's program imports it) at the page's
    size in mm, in register with the cut file."""
    image = page_image(page, scale=scale, styles=styles, legend=legend)
    write_bytes(path, png_bytes(image, dpi=image.width / page.width * 25.4))
    return [str(path)]
