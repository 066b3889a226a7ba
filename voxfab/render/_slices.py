"""Slice sheets: the layers of a shape in a grid of cells, each with its number."""

from __future__ import annotations

import dataclasses
import math
from enum import StrEnum
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import check_choice
from voxfab.errors import InvalidShapeError
from voxfab.shape import VoxelShape, crop

from ._image import font
from ._raster import DEFAULT_COLOR, parse_color
from ._render import Color, check_size, shape_colours, shape_grid

if TYPE_CHECKING:
    from PIL import Image

__all__ = ["SliceAxis", "SliceLayout", "slice_layout", "slice_sheet", "layers"]


class SliceAxis(StrEnum):
    """The axis the layers are stacked along."""

    X = "x"
    Y = "y"
    Z = "z"


@dataclasses.dataclass(frozen=True)
class SliceLayout:
    """Where each layer is drawn on a slice sheet.

    Attributes
    ----------
    width, height : int
        Sheet size in pixels.
    columns, rows : int
        Cells per row and per column.
    cell : int
        Pixels per voxel inside a cell.
    origins : tuple of (col, row)
        Pixel position of the top-left corner of each layer's drawing, layer 1 first.
    layer_shape : (int, int)
        Voxels across (picture columns) and down (picture rows) in each layer.
    label_height : int
        Pixels above each drawing kept for the layer number.
    """

    width: int
    height: int
    columns: int
    rows: int
    cell: int
    origins: tuple[tuple[int, int], ...]
    layer_shape: tuple[int, int]
    label_height: int


def layers(shape: VoxelShape | npt.ArrayLike, *, axis: str | SliceAxis = "z") -> npt.NDArray[np.bool_]:
    """The layers of the cropped shape, bottom first, as pictures.

    Returns
    -------
    (N, R, C) bool ndarray
        Layer ``i`` seen from the positive end of ``axis``: ``R`` rows top to bottom,
        ``C`` columns left to right, with the same orientation as the render views
        ``"z"``, ``"x"`` and ``"y"``.
    """
    return _oriented(crop(shape_grid(shape)), check_choice(axis, SliceAxis, name="axis"))


def _oriented(g: npt.NDArray, a: SliceAxis) -> npt.NDArray:
    """A cropped grid ``[x, y, z, ...]`` as the layers of :func:`layers` (trailing axes, such as RGB, kept)."""
    extra = tuple(range(3, g.ndim))
    if a is SliceAxis.Z:
        stack = np.transpose(g, (2, 1, 0, *extra))[:, ::-1, :]  # rows: y down, columns: x
    elif a is SliceAxis.X:
        stack = np.transpose(g, (0, 2, 1, *extra))[:, ::-1, :]  # rows: z down, columns: y
    else:
        stack = np.transpose(g, (1, 2, 0, *extra))[:, ::-1, ::-1]  # rows: z down, columns: -x
    return np.ascontiguousarray(stack)


def layer_colours(shape: VoxelShape | npt.ArrayLike, *, axis: str | SliceAxis = "z") -> npt.NDArray[np.uint8] | None:
    """The RGB of each cell of :func:`layers`, ``(N, R, C, 3)``; None for an uncoloured shape."""
    colours = shape_colours(shape)
    if colours is None:
        return None
    return _oriented(colours.rgba[..., :3], check_choice(axis, SliceAxis, name="axis"))


def slice_layout(n_layers: int, layer_shape: tuple[int, int], *, width: int, height: int | None = None,
                 columns: int | None = None) -> SliceLayout:
    """Arrange ``n_layers`` drawings of ``layer_shape`` voxels on a sheet ``width`` pixels wide.

    Without ``height`` the sheet is as tall as the rows need; with it, the cells
    shrink to fit both.
    """
    if n_layers < 1:
        raise InvalidShapeError("shape: no layer to draw")
    lr, lc = layer_shape
    cols = columns if columns is not None else max(1, math.ceil(math.sqrt(n_layers * lr / max(lc, 1))))
    if cols < 1:
        raise InvalidShapeError(f"columns: expected at least 1, got {cols}")
    rows = math.ceil(n_layers / cols)
    pad = max(4, width // 80)
    label = min(max(12, width // (cols * 7)), 32)
    per_w = (width - pad * (cols + 1)) / (cols * lc)
    cell = per_w
    if height is not None:
        per_h = (height - pad * (rows + 1) - rows * label) / (rows * lr)
        cell = min(cell, per_h)
    cell_px = max(1, int(math.floor(cell)))
    draw_w, draw_h = lc * cell_px, lr * cell_px
    full_h = height if height is not None else pad * (rows + 1) + rows * (label + draw_h)
    # Spread the cells evenly over the sheet.
    gap_x = (width - cols * draw_w) / (cols + 1)
    gap_y = (full_h - rows * (draw_h + label)) / (rows + 1)
    origins = []
    for i in range(n_layers):
        r, c = divmod(i, cols)
        x0 = int(round(gap_x + c * (draw_w + gap_x)))
        y0 = int(round(gap_y + r * (draw_h + label + gap_y) + label))
        origins.append((x0, y0))
    return SliceLayout(width=int(width), height=int(full_h), columns=cols, rows=rows, cell=cell_px,
                       origins=tuple(origins), layer_shape=(lr, lc), label_height=label)


def _layer_picture(
    layer: npt.NDArray[np.bool_],
    below: npt.NDArray[np.bool_] | None,
    cell: int,
    fg: tuple[int, int, int],
    paper: tuple[int, int, int],
    rgb: npt.NDArray[np.uint8] | None = None,
    rgb_below: npt.NDArray[np.uint8] | None = None,
) -> npt.NDArray[np.uint8]:
    up = np.repeat(np.repeat(layer, cell, axis=0), cell, axis=1)
    lw = min(max(1, cell // 12), 3)
    rr = np.arange(up.shape[0]) % cell
    cc = np.arange(up.shape[1]) % cell
    edge = ((rr < lw) | (rr >= cell - lw))[:, None] | ((cc < lw) | (cc >= cell - lw))[None, :]
    out = np.empty(up.shape + (3,), dtype=np.uint8)
    out[:] = paper
    if rgb is not None:  # each cell in its voxel's colour: the uniform colour becomes a picture of colours
        fg = np.repeat(np.repeat(rgb, cell, axis=0), cell, axis=1)[up]
    if below is not None:
        ghost = np.repeat(np.repeat(below, cell, axis=0), cell, axis=1)
        under = np.asarray(fg) if rgb_below is None else np.repeat(np.repeat(rgb_below, cell, axis=0), cell,
                                                                   axis=1)[ghost]
        tint = np.rint(0.75 * np.asarray(paper) + 0.25 * under * 0.7).astype(np.uint8)
        out[ghost] = tint
    out[up] = fg
    if cell >= 6:  # below that, grid lines would swallow the voxels
        dark = np.rint(np.asarray(fg) * 0.28).astype(np.uint8)
        out[up & edge] = dark if rgb is None else dark[edge[up]]
    # A thin frame shows each layer's full extent.
    frame = np.zeros(up.shape, dtype=bool)
    frame[0, :] = frame[-1, :] = True
    frame[:, 0] = frame[:, -1] = True
    out[frame & ~up] = (170, 170, 170)
    return out


def slice_sheet(
    shape: VoxelShape | npt.ArrayLike,
    *,
    size: int = 800,
    height: int | None = None,
    axis: str | SliceAxis = "z",
    columns: int | None = None,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
    ghost: bool = True,
) -> Image.Image:
    """Draw every layer of a shape in a grid, each numbered from 1 (bottom) up.

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
        The shape; it is cropped to its bounding box first.
    size : int
        Sheet width in pixels.
    height : int or None
        Sheet height in pixels; default: as tall as the rows need.
    axis : {"z", "x", "y"}
        Stacking axis; layer 1 is at the low end.
    columns : int or None
        Cells per row; default: a near-square sheet.
    background, color : str or (r, g, b)
        Sheet and voxel colours; a coloured shape's cells are drawn in their voxels' colours.
    ghost : bool
        Show the layer below each layer faintly, as it lies under it when stacked.

    Returns
    -------
    PIL.Image.Image
        An RGB picture ``size`` pixels wide.
    """
    from PIL import Image, ImageDraw

    width = check_size(size)
    if height is not None:
        check_size(height, name="height")
    bg = parse_color(background, name="background")
    fg = parse_color(color, name="color")
    stack = layers(shape, axis=axis)
    rgb = layer_colours(shape, axis=axis)
    lay = slice_layout(len(stack), stack.shape[1:], width=width, height=height, columns=columns)
    sheet = np.empty((lay.height, lay.width, 3), dtype=np.uint8)
    sheet[:] = bg
    for i, layer in enumerate(stack):
        below = ghost and i > 0
        pic = _layer_picture(layer, stack[i - 1] if below else None, lay.cell, fg, bg,
                             None if rgb is None else rgb[i], None if rgb is None or not below else rgb[i - 1])
        x0, y0 = lay.origins[i]
        sheet[y0 : y0 + pic.shape[0], x0 : x0 + pic.shape[1]] = pic
    image = Image.fromarray(sheet)
    draw = ImageDraw.Draw(image)
    f = font(int(lay.label_height * 0.8))
    for i, (x0, y0) in enumerate(lay.origins):
        draw.text((x0, y0 - 2), str(i + 1), fill=(30, 30, 30), font=f, anchor="ld")
    return image
