"""3D pictures of a voxel shape: shaded cubes with dark voxel edges."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from voxfab._shared.typing import PathLike
from voxfab._shared.validate import as_grid
from voxfab.drawing.png import png_bytes
from voxfab.errors import InvalidShapeError
from voxfab.shape import VoxelColours, VoxelShape, bounding_box, crop

from ._raster import DEFAULT_COLOR, Frame, Raster, fit_frame, parse_color, rasterize, to_rgb
from ._views import Camera, View, camera_for

if TYPE_CHECKING:
    from PIL import Image

__all__ = ["render", "render_raster", "save_render", "supersampling", "shape_grid", "check_size", "Color"]

Color = str | tuple[int, int, int]


def shape_grid(shape: VoxelShape | npt.ArrayLike, *, name: str = "shape") -> npt.NDArray[np.bool_]:
    """The bool grid of a VoxelShape or an array (checked, non-empty)."""
    grid = shape.grid if isinstance(shape, VoxelShape) else shape
    return as_grid(grid, name=name)


def shape_colours(shape: VoxelShape | npt.ArrayLike) -> VoxelColours | None:
    """The colours of a coloured shape, cropped as :func:`render_raster` crops its grid (None when uncoloured)."""
    if isinstance(shape, VoxelShape) and shape.colours is not None:
        return shape.crop().colours
    return None


def check_size(size: int, *, name: str = "size", minimum: int = 16, maximum: int = 8192) -> int:
    """Return ``size`` (pixels) after checking it is an integer in range."""
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)):
        raise InvalidShapeError(f"{name}: expected an integer number of pixels, got {size!r}")
    if not minimum <= int(size) <= maximum:
        raise InvalidShapeError(f"{name}: expected {minimum}..{maximum} pixels, got {size}")
    return int(size)


def render_raster(
    shape: VoxelShape | npt.ArrayLike,
    *,
    view: str | View | Camera = "iso",
    size: int = 800,
    scale: float | None = None,
    margin: float = 0.04,
    supersample: int = 1,
) -> Raster:
    """Rasterize ``shape`` in a square picture of ``size`` pixels.

    The shape's bounding box is centred and fills the picture up to ``margin``
    unless ``scale`` (pixels per voxel) is given.  Axis views use whole pixels
    per voxel, so their coverage is the shape's projection scaled exactly.
    With ``supersample`` k the raster is k times larger in each direction, with
    the same framing (voxel edges stay on the same final pixel boundaries).
    """
    # Cropping first makes the picture independent of where the shape sits in its grid
    # (and the raster's voxels index the cropped grid, which shape_colours crops alike).
    grid = crop(shape_grid(shape))
    n = check_size(size)
    camera = view if isinstance(view, Camera) else camera_for(view, grid)
    lo, hi = bounding_box(grid)
    frame = fit_frame(np.asarray(lo), np.asarray(hi), camera, width=n, height=n, margin=margin, scale=scale)
    k = int(supersample)
    if k != 1:
        frame = Frame(n * k, n * k, frame.scale * k, frame.ox * k, frame.oy * k)
    return rasterize(grid, camera, frame)


#: Below this many pixels per voxel, pictures are drawn larger and averaged down,
#: so that thin voxel edges stay visible without darkening everything.
_SHARP_SCALE = 10.0


def supersampling(shape: VoxelShape | npt.ArrayLike, *, view: str | View | Camera = "iso", size: int = 800,
                  scale: float | None = None) -> int:
    """The automatic anti-aliasing factor: 1 at 10+ pixels per voxel, up to 4 below."""
    grid = shape_grid(shape)
    camera = view if isinstance(view, Camera) else camera_for(view, grid)
    lo, hi = bounding_box(grid)
    n = check_size(size)
    s = fit_frame(np.asarray(lo), np.asarray(hi), camera, width=n, height=n, scale=scale).scale
    return 1 if s >= _SHARP_SCALE else min(4, math.ceil(_SHARP_SCALE / s))


def render(
    shape: VoxelShape | npt.ArrayLike,
    *,
    view: str | View = "iso",
    size: int = 800,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
    scale: float | None = None,
    antialias: int | None = None,
) -> Image.Image:
    """Render a voxel shape as shaded cubes with visible voxel edges.

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
        The shape, indexed ``[x, y, z]`` with z up.
    view : {"iso", "x", "-x", "y", "-y", "z", "-z", "profile"}
        Isometric, the orthographic view from the named side (``"z"``: from above), or the
        view that shows the shape's profile (:func:`voxfab.render.profile_camera`).
    size : int
        Width and height of the picture in pixels.
    background, color : str or (r, g, b)
        Background and cube colours (names or ``#rrggbb``); a coloured shape's
        voxels are drawn in their own colours instead of ``color``.
    scale : float or None
        Pixels per voxel; default: as large as fits.
    antialias : int or None
        Draw k times larger and average down (1: off); default: automatic, on
        only below 10 pixels per voxel.  Axis views keep exact coverage either way.

    Returns
    -------
    PIL.Image.Image
        An RGB picture of ``size × size`` pixels.
    """
    from PIL import Image

    bg = parse_color(background, name="background")
    fg = parse_color(color, name="color")
    if antialias is None:
        k = supersampling(shape, view=view, size=size, scale=scale)
    elif isinstance(antialias, bool) or not isinstance(antialias, (int, np.integer)) or not 1 <= antialias <= 8:
        raise InvalidShapeError(f"antialias: expected an integer in 1..8, got {antialias!r}")
    else:
        k = int(antialias)
    raster = render_raster(shape, view=view, size=size, scale=scale, supersample=k)
    image = Image.fromarray(to_rgb(raster, fg, bg, shape_colours(shape)))
    return image.reduce(k) if k > 1 else image


def save_render(
    shape: VoxelShape | npt.ArrayLike,
    path: PathLike,
    *,
    view: str | View = "iso",
    size: int = 800,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
) -> None:
    """Write :func:`render` of ``shape`` to ``path`` as PNG, atomically."""
    from voxfab._shared.atomic import write_bytes

    write_bytes(path, png_bytes(render(shape, view=view, size=size, background=background, color=color)))

