"""Animations: a turntable around one shape, a GIF of any sequence of grids, a tube's turning profile.

Frames are palette images on the fixed palette of :func:`palette_for` (background
plus 255 shades of the cube colour), which is exactly the colour model of the
rasterizer, so no quantization happens and the bytes are reproducible.  A coloured
shape's turntable is drawn in colour and put on one palette made for all its frames
(:func:`~._image.shared_palette`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_bytes
from voxfab._shared.progress import progress
from voxfab._shared.typing import PathLike
from voxfab._shared.validate import as_grid
from voxfab.errors import InvalidShapeError
from voxfab.fabricate._outputs import Artefact, OutputFile
from voxfab.shape import VoxelShape, bounding_box

from ._image import gif_bytes, shared_palette
from ._raster import DEFAULT_COLOR, Frame, fit_frame, palette_for, parse_color, rasterize, to_indexed, to_rgb
from ._render import Color, check_size, shape_grid
from ._views import ISO_AZIMUTH, ISO_ELEVATION, Camera, View, camera_for, orbit_camera

if TYPE_CHECKING:
    from PIL import Image

    from ._options import AnimationOptions

__all__ = [
    "turntable_frames",
    "animation_frames",
    "save_turntable",
    "save_animation",
    "tube_frames",
    "save_tube_animation",
    "render_animation",
]


def _palette_image(indexed: npt.NDArray[np.uint8], palette: list[int]) -> Image.Image:
    from PIL import Image

    h, w = indexed.shape
    im = Image.frombytes("P", (w, h), np.ascontiguousarray(indexed).tobytes())
    im.putpalette(palette)
    return im


def _frame_image(grid: npt.NDArray[np.bool_], camera: Camera, frame: Frame, palette: list[int],
                 k: int) -> Image.Image:
    """One palette frame; with k > 1 drawn k times larger, averaged down and mapped to the palette."""
    if k == 1:
        return _palette_image(to_indexed(rasterize(grid, camera, frame)), palette)
    big = Frame(frame.width * k, frame.height * k, frame.scale * k, frame.ox * k, frame.oy * k)
    from PIL import Image

    pal = np.asarray(palette, dtype=np.uint8).reshape(-1, 3)
    rgb = Image.fromarray(pal[to_indexed(rasterize(grid, camera, big))]).reduce(k)
    target = _palette_image(np.zeros((1, 1), dtype=np.uint8), palette)
    return rgb.quantize(palette=target, dither=Image.Dither.NONE)


def _colour_frame(grid: npt.NDArray[np.bool_], camera: Camera, frame: Frame, colours: object,
                  fg: tuple[int, int, int], bg: tuple[int, int, int], k: int) -> npt.NDArray[np.uint8]:
    """One RGB frame of a coloured shape (``colours`` of ``grid``); with k > 1 drawn k times larger and averaged."""
    from PIL import Image

    if k > 1:
        frame = Frame(frame.width * k, frame.height * k, frame.scale * k, frame.ox * k, frame.oy * k)
    rgb = to_rgb(rasterize(grid, camera, frame), fg, bg, colours)
    return np.asarray(Image.fromarray(rgb).reduce(k)) if k > 1 else rgb


def _antialias(scale: float, antialias: int | None) -> int:
    if antialias is None:
        return 1 if scale >= 10.0 else min(3, math.ceil(10.0 / scale))
    if isinstance(antialias, bool) or not isinstance(antialias, (int, np.integer)) or not 1 <= antialias <= 8:
        raise InvalidShapeError(f"antialias: expected an integer in 1..8, got {antialias!r}")
    return int(antialias)


def _check_frames(frames: int) -> int:
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) or not 1 <= frames <= 720:
        raise InvalidShapeError(f"frames: expected an integer in 1..720, got {frames!r}")
    return int(frames)


def turntable_frames(
    shape: VoxelShape | npt.ArrayLike,
    *,
    frames: int = 36,
    size: int = 400,
    elevation: float = ISO_ELEVATION,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
    antialias: int | None = None,
) -> list[Image.Image]:
    """Pictures of ``shape`` turning once around the vertical axis.

    The scale is fixed by the bounding box's diagonal, so the shape never jumps
    or leaves the picture; frame 0 is the isometric view.

    Returns
    -------
    list of PIL.Image.Image
        ``frames`` palette pictures of ``size × size`` pixels; a coloured shape's in its
        colours, on one palette made for all frames.
    """
    grid = shape_grid(shape)
    n = _check_frames(frames)
    px = check_size(size)
    if not -90.0 < float(elevation) < 90.0:
        raise InvalidShapeError(f"elevation: expected degrees strictly between -90 and 90, got {elevation}")
    fg, bg = parse_color(color, name="color"), parse_color(background, name="background")
    palette = palette_for(fg, bg)
    colours = shape.colours if isinstance(shape, VoxelShape) else None
    lo, hi = (np.asarray(b) for b in bounding_box(grid))
    diagonal = float(np.linalg.norm(hi - lo))
    scale = 0.92 * px / diagonal
    k = _antialias(scale, antialias)
    out = []
    for i in progress(range(n), total=n, desc="turntable"):
        camera = orbit_camera(ISO_AZIMUTH + 360.0 * i / n, float(elevation))
        # Centre on the box centre itself, not on its projected outline, so the axis stays still.
        centre = (lo + hi) / 2.0
        frame = Frame(px, px, scale, px / 2.0 - scale * float(centre @ camera.right),
                      px / 2.0 + scale * float(centre @ camera.up))
        out.append(_frame_image(grid, camera, frame, palette, k) if colours is None else
                   _colour_frame(grid, camera, frame, colours, fg, bg, k))
    return out if colours is None else shared_palette(out, colours.palette[colours.used, :3])


def animation_frames(
    grids: Iterable[VoxelShape | npt.ArrayLike],
    *,
    view: str | View = "iso",
    size: int = 400,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
    antialias: int | None = None,
) -> list[Image.Image]:
    """Pictures of a sequence of shapes (e.g. a swept tube as its profile turns), one per grid.

    All frames share one framing, fitted to the union of the shapes' bounding
    boxes, so the animation does not jitter.

    Returns
    -------
    list of PIL.Image.Image
        One palette picture of ``size × size`` pixels per grid.
    """
    items = [as_grid(g.grid if isinstance(g, VoxelShape) else g, name=f"grids[{i}]", allow_empty=True)
             for i, g in enumerate(grids)]
    if not items:
        raise InvalidShapeError("grids: an animation needs at least one shape")
    px = check_size(size)
    camera: Camera = camera_for(view, np.logical_or.reduce(items) if view == View.PROFILE else None)
    boxes = [bounding_box(g) for g in items if g.any()]
    if not boxes:
        raise InvalidShapeError("grids: every shape is empty")
    lo = np.min([b[0] for b in boxes], axis=0)
    hi = np.max([b[1] for b in boxes], axis=0)
    frame = fit_frame(lo, hi, camera, width=px, height=px)
    palette = palette_for(parse_color(color, name="color"), parse_color(background, name="background"))
    k = _antialias(frame.scale, antialias)
    return [_frame_image(g, camera, frame, palette, k) for g in progress(items, total=len(items), desc="frames")]


def _check_duration(duration_ms: int) -> int:
    if isinstance(duration_ms, bool) or not isinstance(duration_ms, (int, np.integer)) or duration_ms < 10:
        raise InvalidShapeError(f"duration_ms: expected an integer >= 10, got {duration_ms!r}")
    return int(duration_ms)


def save_turntable(
    shape: VoxelShape | npt.ArrayLike,
    path: PathLike,
    *,
    frames: int = 36,
    size: int = 400,
    duration_ms: int = 80,
    elevation: float = ISO_ELEVATION,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
) -> int:
    """Write a looping turntable GIF of ``shape``; return the number of frames rendered."""
    d = _check_duration(duration_ms)
    pics = turntable_frames(shape, frames=frames, size=size, elevation=elevation, background=background,
                            color=color)
    write_bytes(path, gif_bytes(pics, duration_ms=d))
    return len(pics)


def save_animation(
    grids: Iterable[VoxelShape | npt.ArrayLike],
    path: PathLike,
    *,
    view: str | View = "iso",
    size: int = 400,
    duration_ms: int = 80,
    background: Color = "white",
    color: Color = DEFAULT_COLOR,
) -> int:
    """Write a looping GIF with one frame per shape of ``grids``; return the number of frames rendered."""
    d = _check_duration(duration_ms)
    pics = animation_frames(grids, view=view, size=size, background=background, color=color)
    write_bytes(path, gif_bytes(pics, duration_ms=d))
    return len(pics)



#: Keys of the ``tube`` maker that the rotating-profile animation does not take: it sets the phase
#: itself, and fits one scale for every frame.
_NOT_ANIMATED = ("phase", "scale")


def tube_frames(tube: Mapping[str, Any], *, steps: int = 24, turn: float = 360.0,
                base_dir: PathLike | None = None) -> list[np.ndarray]:
    """The grids of a swept tube as its profile turns by ``turn`` degrees in ``steps`` steps.

    Parameters
    ----------
    tube : mapping
        The keys of the recipe maker ``tube`` (``spine``, ``profile``, ``radius``,
        ``twist``, ``frame``, ``size``, ...; see :func:`voxfab.digitize.tube_rotations`).
    steps : int
        Frames, 1..720.
    turn : float
        Total rotation of the profile in degrees over the animation.
    base_dir : path, optional
        Folder of relative file names (profile drawings, spine files).

    Returns
    -------
    list of (size, size, size) bool ndarray
        Frames on one common grid window, so they line up.
    """
    from voxfab.digitize import tube_rotations

    n = _check_frames(steps)
    if not math.isfinite(float(turn)):
        raise InvalidShapeError(f"turn: expected a finite angle in degrees, got {turn!r}")
    bad = [k for k in _NOT_ANIMATED if tube.get(k) is not None]
    if bad:
        raise InvalidShapeError(f"{bad[0]}: the rotating-profile animation sets it itself; leave it out")
    options = {k: v for k, v in tube.items() if k not in _NOT_ANIMATED}
    if "spine" not in options:
        raise InvalidShapeError("spine: the rotating-profile animation needs the tube's spine")
    spine = options.pop("spine")
    if isinstance(spine, list) and spine and isinstance(spine[0], list):
        spine = np.asarray(spine, dtype=np.float64)
    return list(tube_rotations(spine, steps=n, turn=float(turn),
                               base_dir=None if base_dir is None else Path(base_dir), **options))


def save_tube_animation(path: PathLike, tube: Mapping[str, Any], *, steps: int = 24, turn: float = 360.0,
                        view: str | View = "iso", size: int = 400, duration_ms: int = 80,
                        base_dir: PathLike | None = None) -> int:
    """Write a looping GIF of a tube whose profile turns (interlaced strands); return the frame count.

    See :func:`tube_frames` for the tube and the rotation, :func:`save_animation` for the picture
    (``size`` is the picture's side in pixels; the tube's own ``size`` is its grid side).
    """
    d = _check_duration(duration_ms)
    grids = tube_frames(tube, steps=steps, turn=turn, base_dir=base_dir)
    pics = animation_frames(grids, view=view, size=size)
    write_bytes(path, gif_bytes(pics, duration_ms=d))
    return len(pics)


def render_animation(
    shape: VoxelShape,
    options: AnimationOptions,
    outdir: PathLike,
    *,
    maker: str | None,
    params: Mapping[str, Any],
    base_dir: PathLike | None = None,
) -> Artefact:
    """The animation pipeline: ``animation.gif``, a swept tube's profile turning along its spine.

    The recipe output ``animation`` and the studio's download call it.

    Parameters
    ----------
    shape : VoxelShape
        The shape made by the maker (the animation shows the maker's frames, before any operation).
    options : AnimationOptions
        Frames, turn, view, picture size and frame time.
    outdir : path
        Folder to write into.
    maker, params, base_dir
        The source of the shape: it must be the maker ``tube``; its parameters, and
        the folder its file names are relative to.

    Raises
    ------
    RecipeError
        A source that is not a tube, or tube parameters the animation cannot turn.
    """
    from voxfab.errors import RecipeError, VoxfabError

    del shape
    if maker != "tube":
        raise RecipeError(
            f"outputs.animation: the rotating-profile animation needs a tube source (maker = \"tube\"), "
            f"got {maker or 'a file'!r}"
        )
    o = options
    try:
        frames = save_tube_animation(Path(outdir) / "animation.gif", dict(params), steps=o.steps, turn=o.turn,
                                     view=o.view, size=o.size, duration_ms=o.duration_ms, base_dir=base_dir)
    except VoxfabError as exc:
        raise RecipeError(f"outputs.animation: {exc}") from None
    files = (OutputFile("animation.gif", "the tube's profile turning along its spine, one turn per loop"),)
    return Artefact(files, (), {"frames": frames})
