"""Contact sheets: many shapes in a grid of small isometric pictures, each with its name."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import progress
from voxfab._shared.typing import PathLike
from voxfab._shared.validate import as_grid
from voxfab.errors import InvalidShapeError, RepositoryError
from voxfab.shape import VoxelShape

from ._image import font
from ._raster import DEFAULT_COLOR, parse_color
from ._render import Color, check_size, render

if TYPE_CHECKING:
    from PIL import Image

__all__ = ["SheetLayout", "sheet_layout", "contact_sheet", "repository_contact_sheet"]


@dataclasses.dataclass(frozen=True)
class SheetLayout:
    """Tile grid of a contact sheet: tile ``i`` has its picture at ``origins[i]`` (left, top)."""

    width: int
    height: int
    columns: int
    tile: int
    label_height: int
    origins: tuple[tuple[int, int], ...]


def sheet_layout(count: int, *, tile: int, columns: int | None = None) -> SheetLayout:
    """Arrange ``count`` square tiles of ``tile`` pixels, each with a label band under it."""
    if count < 1:
        raise InvalidShapeError("shapes: a contact sheet needs at least one shape")
    cols = columns if columns is not None else max(1, math.ceil(math.sqrt(count)))
    if cols < 1:
        raise InvalidShapeError(f"columns: expected at least 1, got {cols}")
    label = max(14, tile // 8)
    rows = math.ceil(count / cols)
    cell_h = tile + label
    origins = tuple(((i % cols) * tile, (i // cols) * cell_h) for i in range(count))
    return SheetLayout(width=cols * tile, height=rows * cell_h, columns=cols, tile=tile, label_height=label,
                       origins=origins)


def contact_sheet(
    shapes: Sequence[tuple[str, npt.ArrayLike]],
    *,
    tile: int = 200,
    columns: int | None = None,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
) -> Image.Image:
    """Draw named shapes in a grid, in the order given, each as an isometric picture over its name.

    Parameters
    ----------
    shapes : sequence of (str, VoxelShape or (X, Y, Z) bool array_like)
        Names and shapes; a coloured shape is drawn in its colours.
    tile : int
        Side of each picture in pixels.
    columns : int or None
        Tiles per row; default: a near-square sheet.
    background, color : str or (r, g, b)
        Paper and cube colours.

    Returns
    -------
    PIL.Image.Image
        An RGB picture ``columns·tile`` wide.
    """
    from PIL import Image, ImageDraw

    side = check_size(tile, name="tile")
    bg = parse_color(background, name="background")
    fg = parse_color(color, name="color")
    lay = sheet_layout(len(shapes), tile=side, columns=columns)
    sheet = np.empty((lay.height, lay.width, 3), dtype=np.uint8)
    sheet[:] = bg
    for (name, grid), (x0, y0) in progress(zip(shapes, lay.origins), total=len(shapes), desc="contact sheet"):
        g = grid if isinstance(grid, VoxelShape) else as_grid(grid, name=f"shape {name}")
        sheet[y0 : y0 + side, x0 : x0 + side] = np.asarray(render(g, view="iso", size=side, background=bg,
                                                                   color=fg))
    image = Image.fromarray(sheet)
    draw = ImageDraw.Draw(image)
    fnt = font(int(lay.label_height * 0.7))
    for (name, _), (x0, y0) in zip(shapes, lay.origins):
        draw.text((x0 + side / 2, y0 + side + lay.label_height / 2), name, fill=(30, 30, 30), font=fnt,
                  anchor="mm")
    return image


def repository_contact_sheet(
    path: PathLike,
    *,
    tile: int = 200,
    columns: int | None = None,
    drafts: bool = True,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
) -> Image.Image:
    """Draw every shape of the repository at ``path``, ordered by volume, each with its name.

    Shapes of equal volume keep the repository's order (named shapes by rank, then drafts).
    """
    from voxfab.repo import Repository

    with Repository(path, create=False) as repo:
        entries = [e for e in repo.list() if drafts or not e.draft]
        if not entries:
            raise RepositoryError(f"{path}: the repository holds no shape to draw")
        order = sorted(range(len(entries)), key=lambda i: (entries[i].volume, i))
        shapes = [(entries[i].name, repo.get(entries[i].name)) for i in order]
    return contact_sheet(shapes, tile=tile, columns=columns, background=background, color=color)
