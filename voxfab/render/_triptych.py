"""The artist's triptych: net | slices | 3D, side by side under the shape's name."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab.errors import UnfoldError
from voxfab.shape import VoxelShape

from ._image import font
from ._net import net_picture, unfolded_shape
from ._raster import DEFAULT_COLOR, parse_color
from ._render import Color, check_size, render, shape_grid
from ._slices import slice_sheet

if TYPE_CHECKING:
    from collections.abc import Sequence

    from PIL import Image

    from voxfab.unfold import Net

__all__ = ["TriptychLayout", "triptych_layout", "triptych", "make_net"]

PANEL_TITLES = ("net", "slices", "3D")


@dataclasses.dataclass(frozen=True)
class TriptychLayout:
    """Pixel boxes ``(left, top, right, bottom)`` of the three panels, and the picture size."""

    width: int
    height: int
    title_height: int
    panels: tuple[tuple[int, int, int, int], ...]


def triptych_layout(panel: int) -> TriptychLayout:
    """Three square panels of ``panel`` pixels under a title band, with captions below."""
    gap = max(8, panel // 40)
    title_h = max(30, panel // 9)
    caption_h = max(16, panel // 20)
    width = 3 * panel + 4 * gap
    height = title_h + panel + caption_h + gap
    boxes = tuple(
        (gap + i * (panel + gap), title_h, gap + i * (panel + gap) + panel, title_h + panel) for i in range(3)
    )
    return TriptychLayout(width=width, height=height, title_height=title_h, panels=boxes)


def make_net(shape: VoxelShape | npt.ArrayLike, *, rng: np.random.Generator | int) -> Net:
    """A net of ``shape`` from the net engine (``voxfab.unfold.unfold``)."""
    import voxfab.unfold as unfold_pkg

    unfold = getattr(unfold_pkg, "unfold", None)
    if unfold is None:
        raise UnfoldError("net: the net engine voxfab.unfold.unfold is not available")
    # The seed goes through unchanged so the net matches ``voxfab net --seed`` and the recipe's net output.
    return unfold(shape_grid(shape), rng=rng)


def _message_panel(text: str, panel: int, bg: tuple[int, int, int]) -> Image.Image:
    from PIL import Image, ImageDraw

    image = Image.new("RGB", (panel, panel), bg)
    draw = ImageDraw.Draw(image)
    fnt = font(max(10, panel // 32))
    words, lines, line = text.split(), [], ""
    for w in words:
        trial = f"{line} {w}".strip()
        if fnt.getlength(trial) > panel * 0.85 and line:
            lines.append(line)
            line = w
        else:
            line = trial
    lines.append(line)
    draw.multiline_text((panel / 2, panel / 2), "\n".join(lines), fill=(90, 30, 30), font=fnt, anchor="mm",
                        align="center")
    return image


def triptych(
    shape: VoxelShape | npt.ArrayLike,
    *,
    name: str,
    rng: np.random.Generator | int = 0,
    net: Net | Sequence[Net] | None = None,
    panel: int = 800,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
) -> Image.Image:
    """Draw the net, the slice sheet and the isometric 3D view side by side.

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
        The shape.
    name : str
        Title of the picture (the shape's name).
    rng : numpy Generator or int
        Seed of the net when ``net`` is not given (``voxfab.unfold.unfold(grid, rng=rng)``).
    net : Net, sequence of Net, or None
        A net of the shape (of its outer surface when ``net.filled``) to draw
        instead of a new one, or the pieces of one (a net split to fit a
        sheet): each piece is drawn with its own cut outline.
    panel : int
        Side of each square panel in pixels.
    background, color : str or (r, g, b)
        Paper and shape colours.

    Returns
    -------
    PIL.Image.Image
        An RGB picture about ``3·panel`` wide.  When the shape has no one-piece
        net (an :class:`~voxfab.errors.UnfoldError`), the net panel says why.
    """
    from PIL import Image, ImageDraw

    side = check_size(panel, name="panel", minimum=64)
    grid = shape_grid(shape)
    bg = parse_color(background, name="background")
    fg = parse_color(color, name="color")
    lay = triptych_layout(side)
    try:
        the_net = net if net is not None else make_net(grid, rng=rng)
        # the shape, not its grid: a coloured shape's panels are drawn in its colours
        net_img = net_picture(the_net, unfolded_shape(shape, net) if net is not None else shape, size=side,
                              background=bg, color=fg)
    except UnfoldError as exc:
        net_img = _message_panel(f"no net drawn: {exc}", side, bg)
    pictures = [
        net_img,
        slice_sheet(shape, size=side, height=side, background=bg, color=fg),
        render(shape, view="profile", size=side, background=bg, color=fg),
    ]
    image = Image.new("RGB", (lay.width, lay.height), bg)
    for pic, box in zip(pictures, lay.panels):
        image.paste(pic, box[:2])
    draw = ImageDraw.Draw(image)
    title_font = font(int(lay.title_height * 0.5))
    draw.text((lay.width / 2, lay.title_height * 0.5), name, fill=(20, 20, 20), font=title_font, anchor="mm")
    cap_font = font(max(10, side // 32))
    for caption, (left, _, right, bottom) in zip(PANEL_TITLES, lay.panels):
        draw.text(((left + right) / 2, bottom + 4), caption, fill=(80, 80, 80), font=cap_font, anchor="mt")
    for _, top, right, bottom in lay.panels[:-1]:
        gap_mid = right + (lay.panels[1][0] - lay.panels[0][2]) // 2
        draw.line([(gap_mid, top + 10), (gap_mid, bottom - 10)], fill=(200, 200, 200), width=1)
    return image
