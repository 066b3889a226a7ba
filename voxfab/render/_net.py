"""Net pictures: the net drawing of :mod:`voxfab.fabricate.netdraw`, rasterized for people.

The picture is the same drawing the paper sheets get (cut outline, glue tabs,
folds typed mountain/valley/coplanar, seam labels), laid out to fill the
picture and drawn by the PNG backend of :mod:`voxfab.drawing`, with the faces
tinted by their outward direction like the 3D picture.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab.drawing import LAYERS, Fill, Legend, LineStyle, Polylines
from voxfab.errors import InvalidShapeError
from voxfab.shape import VoxelShape

from ._raster import DEFAULT_COLOR, parse_color
from ._render import Color, check_size, shape_grid

if TYPE_CHECKING:
    from PIL import Image

    from voxfab.fabricate.netdraw._placement import Placement
    from voxfab.unfold import Net

__all__ = ["DEFAULT_STYLES", "HIDDEN", "LineStyle", "as_pieces", "net_picture"]

#: A fold style that leaves the line out of the picture (beside the dash styles of :class:`LineStyle`).
HIDDEN = "none"

#: Fold kind → the drawing layer that carries it.
FOLD_LAYERS: dict[str, str] = {"mountain": "MOUNTAIN", "valley": "VALLEY", "flat": "GRID"}
#: Default fold styles: the layers' own (Blender's paper-model convention: convex dashed, concave dash-dot).
DEFAULT_STYLES: dict[str, str] = {kind: LAYERS[layer].style.value for kind, layer in FOLD_LAYERS.items()}
#: Face edge in mm of the picture's drawing: tabs, numbers and line widths follow the sheets' defaults at this size.
_PICTURE_PITCH = 12.0
#: Smallest digit height drawn, pixels.
_MIN_DIGIT_PX = 7.0
#: Margin and tab height of the picture's drawing, in face edges.
_MARGIN = 0.1
_TAB = 0.4
#: Shade of the six face directions (+x, -x, +y, -y, +z, -z), as in the 3D picture.
_TINT = np.array([0.62, 0.86, 0.70, 0.93, 1.0, 0.78])
#: Faces of paper round a net in pieces and between two of its pieces: room for their tabs.
_BORDER = 1
_GAP = 2


def as_pieces(net: Net | Sequence[Net]) -> list[Net]:
    """A net as the list of its pieces: a one-piece net, or a net in pieces as the gallery and the net output give it."""
    return list(net) if isinstance(net, Sequence) else [net]


def _scale(net: Net, width: int, height: int) -> float:
    """Pixels per mm at which the net, drawn at the picture pitch with room for tabs, fills the picture."""
    corners = net.corners2d.reshape(-1, 2)
    ex, ey = (corners.max(axis=0) - corners.min(axis=0)).tolist()
    room = 2.0 * (_MARGIN + _TAB) * _PICTURE_PITCH
    # The drawing may turn the net a quarter turn: take the better way round.
    best = max(min(width / (a * _PICTURE_PITCH + room), height / (b * _PICTURE_PITCH + room))
               for a, b in ((ex, ey), (ey, ex)))
    return best * (1.0 - 1e-6)


def _fold_styles(styles: dict[str, str] | None) -> dict[str, str]:
    style = dict(DEFAULT_STYLES)
    allowed = [s.value for s in LineStyle] + [HIDDEN]
    for kind, value in (styles or {}).items():
        if kind not in DEFAULT_STYLES:
            raise InvalidShapeError(f"styles: unknown fold kind {kind!r}; expected mountain, valley or flat")
        name = value.value if isinstance(value, LineStyle) else str(value)
        if name not in allowed:
            raise InvalidShapeError(f"styles.{kind}: expected one of {', '.join(allowed)}, got {value!r}")
        style[kind] = name
    return style


def _shelves(extents: list[tuple[int, int]], width: int) -> tuple[list[tuple[int, int]], int, int]:
    """Pieces of ``extents`` faces in rows at most ``width`` faces wide, :data:`_GAP` apart, in piece order:
    each piece's lowest corner and the rows' extent, in faces."""
    spots: list[tuple[int, int]] = []
    x = y = row = used = 0
    for w, h in extents:
        if x and x + w > width:
            y, x, row = y + row + _GAP, 0, 0
        spots.append((x, y))
        used = max(used, x + w)
        x, row = x + w + _GAP, max(row, h)
    return spots, used, y + row


def _pieces_sheet(pieces: list[Net], width: int, height: int) -> tuple[float, Placement]:
    """Pixels per mm and the placement that lay a net's pieces on one sheet filling ``width`` x ``height`` pixels.

    Every piece is drawn whole, its own cut outline apart from the others, in rows whose
    width is chosen (over every possible break) to make the faces largest.
    """
    from voxfab.fabricate.netdraw._placement import PiecePlace, Placement

    p, m = _PICTURE_PITCH, _MARGIN * _PICTURE_PITCH
    lows = [piece.corners2d.reshape(-1, 2).min(axis=0) for piece in pieces]
    extents = [tuple(int(v) for v in piece.corners2d.reshape(-1, 2).max(axis=0) - lo) for piece, lo in zip(pieces, lows)]

    def fitted(rows: int) -> tuple[float, list[tuple[int, int]], int, int]:
        spots, w, h = _shelves(extents, rows)
        w, h = w + 2 * _BORDER, h + 2 * _BORDER
        return min(width / (w * p + 2 * m), height / (h * p + 2 * m)), spots, w, h

    widest = sum(w for w, _ in extents) + _GAP * (len(extents) - 1)
    scale, spots, w, h = max((fitted(r) for r in range(max(w for w, _ in extents), widest + 1)),
                             key=lambda f: f[0])
    # rows from the top down (the sheet's y is up), so the pieces read in their order
    places = tuple(PiecePlace(i, 0, m + (x + _BORDER - float(lo[0])) * p,
                              m + (h - _BORDER - y - ext[1] - float(lo[1])) * p)
                   for i, ((x, y), lo, ext) in enumerate(zip(spots, lows, extents)))
    return scale * (1.0 - 1e-6), Placement((w * p + 2 * m, h * p + 2 * m), m, p, 1, places)


def _face_fills(normal: npt.NDArray[np.int64], faces: npt.NDArray[np.float64], index: npt.NDArray[np.int64],
                fg: npt.NDArray[np.float64], face_rgb: npt.NDArray[np.uint8] | None = None) -> list[Fill]:
    """One fill per face direction, or with ``face_rgb`` (the colour of each net face) per direction and colour."""
    normal = normal[index]
    direction = np.argmax(np.abs(normal), axis=1) * 2 + (normal.sum(axis=1) < 0)
    if face_rgb is None:
        colour = np.zeros(len(index), dtype=np.int64)
        bases = fg[None, :]
    else:
        bases, colour = np.unique(np.asarray(face_rgb, dtype=np.float64)[index], axis=0, return_inverse=True)
        colour = colour.reshape(-1)
    fills = []
    for d in range(6):
        for c, base in enumerate(bases):
            sel = (direction == d) & (colour == c)
            if sel.any():
                rgb = np.rint(base * (0.55 + 0.45 * _TINT[d])).astype(int)
                rings = Polylines.from_list(list(faces[sel]), [True] * int(sel.sum()))
                fills.append(Fill(rings, "#{:02x}{:02x}{:02x}".format(*rgb.tolist())))
    return fills


def unfolded_shape(shape: VoxelShape | npt.ArrayLike, net: Net | Sequence[Net]) -> VoxelShape | npt.ArrayLike:
    """The shape ``net`` (or its pieces) unfolds: ``shape``, or with its cavities filled for a net of the
    outer surface (the filled voxels taking their nearest voxel's colour)."""
    if not as_pieces(net)[0].filled:
        return shape
    from voxfab.shape import fill_cavities

    full = fill_cavities(shape_grid(shape))
    if isinstance(shape, VoxelShape):
        return VoxelShape(full, shape.pitch, None if shape.colours is None else shape.colours.fitted(full))
    return full


def net_picture(
    net: Net | Sequence[Net],
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
    """Draw a net: faces tinted by direction, the sheet's cut outline, folds, tabs and numbers.

    Parameters
    ----------
    net : Net or sequence of Net
        A net of ``shape`` (face i of the net is face i of the shape's surface graph), or
        the pieces of one: each piece is drawn with its own cut outline, apart from the others.
    shape : VoxelShape or (X, Y, Z) bool array_like
        The shape the net unfolds; it gives fold types and which cut edges glue together.
    size : int
        Picture width in pixels.
    height : int or None
        Picture height in pixels; default ``size``.
    background, color : str or (r, g, b)
        Paper and face colours; a coloured shape's faces take their voxels' colours.
    styles : dict or None
        Line style per fold kind (``"mountain"``, ``"valley"``, ``"flat"``), each one of
        ``"solid"``, ``"dashed"``, ``"dashdot"``, ``"dotted"``, ``"none"``.
    tabs, numbers, legend : bool
        Draw glue tabs, seam labels (when they come out at least 7 pixels tall)
        and a legend of the line styles.

    Returns
    -------
    PIL.Image.Image
        An RGB picture.

    Raises
    ------
    FormatError
        When ``net`` is not a net of ``shape``.
    """
    from voxfab.drawing.png import page_image
    from voxfab.fabricate.netdraw import DrawingOptions, draw_net

    width = check_size(size)
    h_total = check_size(height, name="height") if height is not None else width
    bg = parse_color(background, name="background")
    fg = np.asarray(parse_color(color, name="color"), dtype=np.float64)
    style = _fold_styles(styles)
    grid = shape_grid(shape)
    from voxfab.fabricate.netdraw._labels import label_length
    from voxfab.fabricate.netdraw._legible import number_ratio

    strip = max(18, h_total // 22) if legend else 0
    pieces = as_pieces(net)
    placement = None
    if len(pieces) == 1:
        scale = _scale(pieces[0], width, h_total - strip)
    else:
        scale, placement = _pieces_sheet(pieces, width, h_total - strip)
    # Labels under a few pixels are specks, not characters: leave them out of small pictures.
    seams_max = 2 * sum(piece.face_count for piece in pieces)
    numbers = numbers and number_ratio(label_length(seams_max)) * _PICTURE_PITCH * scale >= _MIN_DIGIT_PX
    colors = ",".join(f"{FOLD_LAYERS[k]}={LAYERS[FOLD_LAYERS[k]].color}:{v}"
                      for k, v in style.items() if v != HIDDEN)
    room = (width / scale, (h_total - strip) / scale)  # mm the picture holds above its legend
    sheet_mm = room if placement is None else placement.sheet
    options = DrawingOptions(
        pitch=_PICTURE_PITCH, sheet=f"{sheet_mm[0]:.6f}x{sheet_mm[1]:.6f}",
        margin=_MARGIN * _PICTURE_PITCH, tab_width=_TAB * _PICTURE_PITCH, grid_lines=style["flat"] != HIDDEN,
        colors=colors, numbers=numbers, tabs=tabs, heading=False,
        # A picture shows the net however small its marks come out on screen.
        min_label_height=0.01, min_tab_depth=0.01,
    )
    if placement is None:
        drawing = draw_net(grid, pieces[0], options=options)
    else:
        from voxfab.fabricate.netdraw import draw_pieces

        # the placement's sheet as the options read it back, so the two agree to the micron
        placement = dataclasses.replace(placement, sheet=options.sheet_size)
        drawing = draw_pieces(grid, pieces, options=options, placement=placement)
    sheet = drawing.sheets[0]
    page = sheet.page()
    normal = np.concatenate([piece.normal for piece in pieces])
    colours = shape.colours if isinstance(shape, VoxelShape) else None
    # the pieces' voxels index the grid the net unfolds: the shape's own, uncropped
    face_rgb = None if colours is None else colours.at(np.concatenate([piece.voxel for piece in pieces]))[:, :3]
    page = dataclasses.replace(page, fills=(*_face_fills(normal, sheet.faces, sheet.face_index, fg, face_rgb),
                                            *page.fills))
    # The legend goes in a strip below the net; pieces on a sheet of their own are centred in the room left.
    centring = ((room[0] - sheet_mm[0]) / 2, (room[1] - sheet_mm[1]) / 2) if placement is not None else (0.0, 0.0)
    page = page.shifted((centring[0], strip / scale + centring[1]), width=width / scale, height=h_total / scale)
    hidden = frozenset(FOLD_LAYERS[k] for k, v in style.items() if v == HIDDEN)
    key = Legend(y=0.25 * strip / scale, right=0.5 * strip / scale, height=0.5 * strip / scale) if legend else None
    image = page_image(page, scale=scale, styles=options.styles, background=bg, legend=key, hidden=hidden)
    return image if image.size == (width, h_total) else image.resize((width, h_total))
