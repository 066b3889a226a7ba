"""Net pictures: faces, fold lines by style, glue tabs and seam numbers.

Fold types and the pairing of cut edges (which edge glues to which) come from
:func:`voxfab.shape.surface_graph` of the shape the net unfolds: face ``i`` of the
net is face ``i`` of that graph.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError
from voxfab.shape import FOLD_FLAT, FOLD_MOUNTAIN, FOLD_VALLEY, VoxelShape, surface_graph

from ._image import font
from ._raster import DEFAULT_COLOR, parse_color
from ._render import Color, check_size, shape_grid

if TYPE_CHECKING:
    from PIL import Image

    from voxfab.unfold import Net

from voxfab.fabricate.netdraw._options import DEFAULT_STYLES as _SHEET_STYLES
from voxfab.fabricate.netdraw._options import LineStyle

__all__ = ["LineStyle", "NetLayout", "Seam", "net_layout", "net_seams", "net_picture", "DEFAULT_STYLES"]

#: A fold style that leaves the line out of the picture (beside the dash styles of :class:`LineStyle`).
HIDDEN = "none"

#: Default fold styles (Blender's paper-model convention: convex dashed, concave dash-dot).
DEFAULT_STYLES: dict[str, str] = {"mountain": "dashed", "valley": "dashdot", "flat": "dotted"}
#: Line colours per kind.
#: The same colours as the cut files (``voxfab.fabricate.netdraw``), so the picture
#: reads like the sheet that comes out of the laser or printer.
LINE_COLORS: dict[str, tuple[int, int, int]] = {
    "cut": _SHEET_STYLES["CUT"].rgb,
    "mountain": _SHEET_STYLES["MOUNTAIN"].rgb,
    "valley": (0, 160, 0),  # the sheets' pure green is unreadable on screen; darker, same hue
    "flat": _SHEET_STYLES["GRID"].rgb,
}
TAB_COLOR = (215, 215, 215)
#: Dash patterns as (on, off, on, off, ...) fractions of a face side.
_PATTERNS: dict[LineStyle, tuple[float, ...]] = {
    LineStyle.SOLID: (1.0,),
    LineStyle.DASHED: (0.14, 0.08),
    LineStyle.DASHDOT: (0.14, 0.06, 0.03, 0.06),
    LineStyle.DOTTED: (0.03, 0.07),
}
#: Tab height as a fraction of a face side; 45° ends keep tabs in one empty cell apart.
TAB_HEIGHT = 0.3


@dataclasses.dataclass(frozen=True)
class NetLayout:
    """Placement of a net in a picture: ``col = ox + unit·x``, ``row = oy − unit·y``."""

    width: int
    height: int
    unit: float
    ox: float
    oy: float

    def to_pixel(self, xy: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Pixel ``(col, row)`` of net points ``(..., 2)`` in face units."""
        p = np.asarray(xy, dtype=np.float64)
        return np.stack([self.ox + self.unit * p[..., 0], self.oy - self.unit * p[..., 1]], axis=-1)


@dataclasses.dataclass(frozen=True)
class Seam:
    """A cut: edge ``edge_a`` of face ``face_a`` glues to edge ``edge_b`` of face ``face_b``.

    ``tab`` is 0 when the tab hangs on face_a's edge, 1 on face_b's, -1 when
    neither side has an empty cell for it.
    """

    number: int
    face_a: int
    edge_a: int
    face_b: int
    edge_b: int
    tab: int


def _check_net(net: Net, grid: npt.NDArray[np.bool_]):  # noqa: ANN202 - SurfaceGraph
    g = surface_graph(grid)
    if g.face_count != net.face_count or not (
        np.array_equal(g.voxel, net.voxel) and np.array_equal(g.normal, net.normal)
    ):
        raise InvalidShapeError(
            f"net: its {net.face_count} faces are not the {g.face_count} surface faces of the shape"
        )
    return g


def _edge_index(graph, folds: npt.NDArray[np.int64]) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:  # noqa: ANN001
    """For folds ``(a, b)``: the edge of a that b lies across, and the edge of b that a lies across."""
    a, b = folds[:, 0], folds[:, 1]
    ka = np.argmax(graph.neighbor[a] == b[:, None], axis=1)
    kb = np.argmax(graph.neighbor[b] == a[:, None], axis=1)
    if folds.size and not ((graph.neighbor[a, ka] == b).all() and (graph.neighbor[b, kb] == a).all()):
        raise InvalidShapeError("net: a fold joins two faces that share no edge")
    return ka, kb


def _seams(net: Net, graph) -> list[Seam]:  # noqa: ANN001
    folds = net.folds.reshape(-1, 2)
    folded = np.zeros((graph.face_count, 4), dtype=bool)
    ka, kb = _edge_index(graph, folds)
    folded[folds[:, 0], ka] = True
    folded[folds[:, 1], kb] = True
    # The net cell beyond each face edge, and whether a face occupies it.
    c = net.corners2d.astype(np.float64)
    mid = (c + np.roll(c, -1, axis=1)) / 2.0
    beyond = np.floor(2.0 * mid - c.mean(axis=1)[:, None, :]).astype(np.int64)
    cells = net.corners2d.min(axis=1)

    def code(xy: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
        return (xy[..., 0] << 32) + xy[..., 1]

    occupied = np.isin(code(beyond), code(cells))
    f, k = np.nonzero(~folded)
    j, kk = graph.neighbor[f, k], graph.neighbor_edge[f, k]
    first = (f < j) | ((f == j) & (k < kk))
    f, k, j, kk = f[first], k[first], j[first], kk[first]
    tab = np.where(~occupied[f, k], 0, np.where(~occupied[j, kk], 1, -1))
    return [
        Seam(n + 1, a, ea, b, eb, t)
        for n, (a, ea, b, eb, t) in enumerate(zip(f.tolist(), k.tolist(), j.tolist(), kk.tolist(), tab.tolist()))
    ]


def net_seams(net: Net, shape: VoxelShape | npt.ArrayLike) -> list[Seam]:
    """The cut edges of ``net``, numbered from 1, each with its tab side.

    A tab goes on the first side (in face order) whose cell beyond the edge is
    free in the net.
    """
    return _seams(net, _check_net(net, shape_grid(shape)))


def net_layout(net: Net, *, width: int, height: int, margin: float = 0.6) -> NetLayout:
    """Fit ``net`` (plus ``margin`` face sides for tabs) in a ``width × height`` picture."""
    x0, y0, x1, y1 = net.bounds()
    sw, sh = (x1 - x0) + 2 * margin, (y1 - y0) + 2 * margin
    unit = min(width / sw, height / sh)
    ox = width / 2.0 - unit * (x0 + x1) / 2.0
    oy = height / 2.0 + unit * (y0 + y1) / 2.0
    return NetLayout(width=int(width), height=int(height), unit=float(unit), ox=float(ox), oy=float(oy))


def _dash_fractions(pattern: tuple[float, ...]) -> list[tuple[float, float]]:
    """The ``(start, end)`` fractions of the dashes of ``pattern`` (on/off lengths) along a unit edge."""
    out, t, i = [], 0.0, 0
    while t < 1.0:
        step = pattern[i % len(pattern)]
        if i % 2 == 0:
            out.append((t, min(t + step, 1.0)))
        t += step
        i += 1
    return out


def _draw_lines(draw, p: npt.NDArray[np.float64], q: npt.NDArray[np.float64], pattern: tuple[float, ...],  # noqa: ANN001
                fill: tuple[int, int, int], width: int, unit: float) -> None:
    """Draw patterned lines from ``p`` to ``q`` (``(E, 2)`` pixels); too-fine patterns are drawn solid."""
    if len(pattern) == 1 or unit * sum(pattern) < 4.0:
        fractions = [(0.0, 1.0)]
    else:
        fractions = _dash_fractions(pattern)
    for a, b in fractions:
        s0 = (p + (q - p) * a).tolist()
        s1 = (p + (q - p) * b).tolist()
        for x0, x1 in zip(s0, s1):
            draw.line([tuple(x0), tuple(x1)], fill=fill, width=width)


def net_picture(
    net: Net,
    shape: VoxelShape | npt.ArrayLike,
    *,
    size: int = 800,
    height: int | None = None,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
    styles: dict[str, str] | None = None,
    tabs: bool = True,
    numbers: bool = True,
    legend: bool = True,
) -> Image.Image:
    """Draw a net: faces tinted by direction, cuts solid, folds by style, tabs and seam numbers.

    Parameters
    ----------
    net : Net
        A net of ``shape`` (face i of the net is face i of the shape's surface graph).
    shape : VoxelShape or (X, Y, Z) bool array_like
        The shape the net unfolds; it gives fold types and which cut edges glue together.
    size : int
        Picture width in pixels.
    height : int or None
        Picture height in pixels; default ``size``.
    background, color : str or (r, g, b)
        Paper and face colours.
    styles : dict or None
        Line style per fold kind (``"mountain"``, ``"valley"``, ``"flat"``), each one of
        ``"solid"``, ``"dashed"``, ``"dashdot"``, ``"dotted"``, ``"none"``.
    tabs, numbers, legend : bool
        Draw glue tabs, seam numbers (on both glued edges; when faces are big
        enough to read them) and a legend strip.

    Returns
    -------
    PIL.Image.Image
        An RGB picture.
    """
    from PIL import Image, ImageDraw

    width = check_size(size)
    h_total = check_size(height, name="height") if height is not None else width
    bg = parse_color(background, name="background")
    fg = np.asarray(parse_color(color, name="color"), dtype=np.float64)
    style = dict(DEFAULT_STYLES)
    for kind, value in (styles or {}).items():
        if kind not in DEFAULT_STYLES:
            raise InvalidShapeError(f"styles: unknown fold kind {kind!r}; expected mountain, valley or flat")
        name = value.value if isinstance(value, LineStyle) else str(value)
        allowed = [s.value for s in LineStyle] + [HIDDEN]
        if name not in allowed:
            raise InvalidShapeError(f"styles.{kind}: expected one of {', '.join(allowed)}, got {value!r}")
        style[kind] = name
    graph = _check_net(net, shape_grid(shape))
    seams = _seams(net, graph)

    legend_h = max(18, h_total // 22) if legend else 0
    info = _info_text(net, seams)
    rows = _legend_rows(style, width, legend_h, info) if legend else 0
    lay = net_layout(net, width=width, height=h_total - legend_h * rows)
    image = Image.new("RGB", (width, h_total), bg)
    draw = ImageDraw.Draw(image)
    u = lay.unit

    # Faces, tinted by their outward direction like the 3D picture.
    tint = np.array([0.62, 0.86, 0.70, 0.93, 1.0, 0.78])
    d_index = np.argmax(np.abs(net.normal), axis=1) * 2 + (net.normal.sum(axis=1) < 0)
    face_rgb = np.rint(fg[None, :] * (0.55 + 0.45 * tint[d_index])[:, None]).astype(np.int64)
    pix = lay.to_pixel(net.corners2d)
    for corners, rgb in zip(pix.tolist(), face_rgb.tolist()):
        draw.polygon([tuple(pt) for pt in corners], fill=tuple(rgb))

    sa = np.array([(x.face_a, x.edge_a, x.face_b, x.edge_b, x.tab) for x in seams], dtype=np.int64).reshape(-1, 5)
    c2 = net.corners2d.astype(np.float64)

    def edge_points(face: npt.NDArray[np.int64], edge: npt.NDArray[np.int64]):  # noqa: ANN202
        return c2[face, edge], c2[face, (edge + 1) % 4]

    # Tabs: trapezoids with 45° ends in the free cell beyond the edge.
    if tabs and len(sa):
        t = sa[sa[:, 4] >= 0]
        face = np.where(t[:, 4] == 0, t[:, 0], t[:, 2])
        edge = np.where(t[:, 4] == 0, t[:, 1], t[:, 3])
        p, q = edge_points(face, edge)
        along = q - p
        out = (p + q) / 2.0 - c2[face].mean(axis=1)
        out *= 2.0  # unit length: the edge midpoint is half a side from the centre
        poly = np.stack([p, q, q + (out - along) * TAB_HEIGHT, p + (out + along) * TAB_HEIGHT], axis=1)
        for pts in lay.to_pixel(poly).tolist():
            draw.polygon([tuple(pt) for pt in pts], fill=TAB_COLOR, outline=LINE_COLORS["cut"])

    # Fold lines, each once, by kind.
    lw = max(1, int(round(u / 22)))
    folds = net.folds.reshape(-1, 2)
    ka, _ = _edge_index(graph, folds)
    fold_kind = graph.fold[folds[:, 0], ka]
    for value, kind in ((FOLD_FLAT, "flat"), (FOLD_MOUNTAIN, "mountain"), (FOLD_VALLEY, "valley")):
        sel = fold_kind == value
        if style[kind] == HIDDEN or not sel.any():
            continue
        p, q = edge_points(folds[sel, 0], ka[sel])
        _draw_lines(draw, lay.to_pixel(p), lay.to_pixel(q), _PATTERNS[LineStyle(style[kind])], LINE_COLORS[kind], lw, u)

    # Cut edges: solid, on both sides of each seam.
    if len(sa):
        faces = np.concatenate([sa[:, 0], sa[:, 2]])
        edges = np.concatenate([sa[:, 1], sa[:, 3]])
        p, q = edge_points(faces, edges)
        _draw_lines(draw, lay.to_pixel(p), lay.to_pixel(q), _PATTERNS[LineStyle.SOLID], LINE_COLORS["cut"],
                    lw + 1, u)

    # Seam numbers inside both glued faces, near the shared edge.
    if numbers and len(sa):
        fsize = int(u * 0.26)
        digits = len(str(len(seams)))
        if fsize >= 7 and fsize * 0.6 * digits < u * 0.8:
            fnt = font(fsize)
            labels = [str(x.number) for x in seams] * 2
            faces = np.concatenate([sa[:, 0], sa[:, 2]])
            edges = np.concatenate([sa[:, 1], sa[:, 3]])
            p, q = edge_points(faces, edges)
            mid = (p + q) / 2.0
            at = mid + (c2[faces].mean(axis=1) - mid) * 0.42
            for text, xy in zip(labels, lay.to_pixel(at).tolist()):
                draw.text((xy[0], xy[1]), text, fill=(20, 20, 20), font=fnt, anchor="mm")

    if legend:
        _draw_legend(draw, style, width, h_total, legend_h, info, rows)
    return image


def _legend_entries(style: dict[str, str]) -> list[tuple[str, str]]:
    return [("cut", "solid")] + [(k, style[k]) for k in ("mountain", "valley", "flat")]


def _legend_width(style: dict[str, str], legend_h: int) -> float:
    fnt = font(int(legend_h * 0.55))
    x = legend_h * 0.5
    for kind, _ in _legend_entries(style):
        x += legend_h * 1.6 + legend_h * 0.25 + fnt.getlength(kind) + legend_h * 0.8
    return x


def _info_text(net: Net, seams: list[Seam]) -> str:
    tabs = sum(1 for s in seams if s.tab >= 0)
    return f"{net.face_count} faces, {len(seams)} seams, {tabs} tabs"


def _legend_rows(style: dict[str, str], width: int, legend_h: int, info: str) -> int:
    fnt = font(int(legend_h * 0.55))
    return 1 if _legend_width(style, legend_h) + fnt.getlength(info) + legend_h * 0.5 <= width else 2


def _draw_legend(draw, style: dict[str, str], width: int, h_total: int, legend_h: int,  # noqa: ANN001
                 info: str, rows: int) -> None:
    y = h_total - legend_h * (rows - 0.5)
    fnt = font(int(legend_h * 0.55))
    x = legend_h * 0.5
    seg = legend_h * 1.6
    lw = max(1, legend_h // 12)
    for kind, ls in _legend_entries(style):
        if ls != HIDDEN:
            p, q = np.array([x, y]), np.array([x + seg, y])
            pattern = _PATTERNS[LineStyle(ls)]
            fractions = [(0.0, 1.0)] if len(pattern) == 1 else _dash_fractions(tuple(v / 1.6 for v in pattern))
            for a, b in fractions:
                draw.line([tuple(p + (q - p) * a), tuple(p + (q - p) * b)], fill=LINE_COLORS[kind], width=lw)
        draw.text((x + seg + legend_h * 0.25, y), kind, fill=(30, 30, 30), font=fnt, anchor="lm")
        x += seg + legend_h * 0.25 + fnt.getlength(kind) + legend_h * 0.8
    if rows == 1:
        draw.text((width - legend_h * 0.5, y), info, fill=(30, 30, 30), font=fnt, anchor="rm")
    else:
        draw.text((legend_h * 0.5, h_total - legend_h * 0.5), info, fill=(30, 30, 30), font=fnt, anchor="lm")
