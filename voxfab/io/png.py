"""PNG slice stacks: a folder of images, one per z layer from the bottom, read and written in colour.

The files ``*.png`` of the folder are sorted naturally by name (``z2`` before
``z10``); file k is layer ``z = k``; column ``i`` is ``x = i`` and image row 0 is
the highest ``y``, as a map is drawn.  Which pixels are filled voxels:

- in a stack with transparency (any pixel of alpha below 128), the opaque pixels,
  whatever their colour: a coloured voxel may be light;
- otherwise a pixel darker than ``threshold`` (grey level 0..255).

A stack in colour (any pixel not grey) gives each filled voxel its pixel's colour.
A single ``.png`` file reads as a one-layer grid.  Writing a shape to a folder
(a path ending in ``/``) gives ``z00.png``, ``z01.png``...: each voxel in its colour
(black for an uncoloured shape) on a transparent ground, which reads back the same.
"""

from __future__ import annotations

import re
import struct
from io import BytesIO
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from voxfab._shared.numbers import is_digits
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError, VoxfabError

from ._registry import ReadResult, register

if TYPE_CHECKING:
    from voxfab.shape import VoxelColours

__all__ = ["read_png_stack", "read_png", "write_png_stack", "natural_key", "DEFAULT_THRESHOLD"]

#: Grey level below which a pixel is a filled voxel.
DEFAULT_THRESHOLD = 128

_DIGITS = re.compile(r"(\d+)")
_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_IEND = b"\x00\x00\x00\x00IEND\xaeB`\x82"


def natural_key(name: str) -> tuple[tuple[int, int | str], ...]:
    """Sort key putting ``z2`` before ``z10``: digit runs compare as numbers."""
    return tuple(
        (1, int(part)) if is_digits(part) else (0, part.lower())
        for part in _DIGITS.split(name)
        if part
    )


def _check_threshold(threshold: int) -> int:
    ok = isinstance(threshold, (int, np.integer)) and not isinstance(threshold, bool)
    if not ok or not 1 <= threshold <= 256:
        raise InvalidShapeError(f"threshold: expected an integer grey level in 1..256, got {threshold!r}")
    return int(threshold)


def _layer(path: Path) -> np.ndarray:
    """Read one image as an ``(X, Y, 4)`` RGBA layer, ``[x, y]`` with y up (16-bit grey scaled to 8)."""
    from PIL import Image  # lazy: pillow is only needed here

    with open(path, "rb") as fh:
        data = fh.read()
    if data[:8] != _SIGNATURE:
        raise FormatError(f"{path}: not a PNG image (the PNG signature is missing)")
    if _IEND not in data[-64:]:
        # Pillow decodes an image whose end is cut off without complaint.
        raise FormatError(f"{path}: truncated PNG image (no IEND chunk at its end)")
    if data[12:16] == b"IHDR":
        # The size from the header, before Pillow's own bomb check raises on it.
        w, h = struct.unpack(">II", data[16:24])
        if w > MAX_SIDE or h > MAX_SIDE:
            raise InvalidShapeError(f"{path}: image {w}x{h} is over the limit of {MAX_SIDE} voxels per side")
    try:
        with Image.open(BytesIO(data)) as im:
            if im.format != "PNG":
                raise FormatError(f"{path}: not a PNG image (found {im.format})")
            w, h = im.size
            if w > MAX_SIDE or h > MAX_SIDE:
                raise InvalidShapeError(
                    f"{path}: image {w}x{h} is over the limit of {MAX_SIDE} voxels per side"
                )
            im.load()
            if im.mode.startswith("I"):
                # 16-bit grey: Pillow's conversion to 8 bits clips instead of scaling.
                grey = (np.asarray(im).astype(np.int64) >> 8).clip(0, 255).astype(np.uint8)
                rgba = np.dstack([grey, grey, grey, np.full_like(grey, 255)])
            else:
                rgba = np.asarray(im.convert("RGBA"))
    except VoxfabError:
        raise
    except Exception as exc:  # noqa: BLE001
        # Pillow reports corrupt data in many ways (UnidentifiedImageError, OSError,
        # SyntaxError, EOFError, zlib and struct errors): all mean "not a readable PNG".
        raise FormatError(f"{path}: not a readable PNG image ({exc})") from None
    # rgba[row, column]: row 0 is the top of the picture, the highest y.
    return np.ascontiguousarray(rgba.transpose(1, 0, 2)[:, ::-1])


def _voxels(layers: np.ndarray, threshold: int) -> tuple[BoolGrid, VoxelColours | None]:
    """The filled voxels and their colours of RGBA layers ``(X, Y, Z, 4)`` (see the module description)."""
    from voxfab.shape import VoxelColours

    rgb = layers[..., :3].astype(np.int64)
    alpha = layers[..., 3]
    if (alpha < 128).any():
        filled = alpha >= 128
    else:
        # Grey after compositing on white, as the stack was always read.
        a = alpha[..., None].astype(np.int64)
        on_white = (rgb * a + 255 * (255 - a)) // 255
        grey = (on_white @ np.array([299, 587, 114])) // 1000
        filled = grey < threshold
    coloured = bool(filled.any()) and bool((rgb[filled].max(axis=1) != rgb[filled].min(axis=1)).any())
    if not coloured:
        return filled, None
    opaque = layers.copy()
    opaque[..., 3] = 255
    try:
        return filled, VoxelColours.from_rgba(filled, np.where(filled[..., None], opaque, 0))
    except InvalidShapeError as exc:
        raise InvalidShapeError(f"the slices use too many colours for a voxel palette: {exc}") from None


def read_png_stack(path: PathLike, *, threshold: int = DEFAULT_THRESHOLD) -> ReadResult:
    """Read a folder of PNG slices as a grid ``[x, y, z]``.

    Parameters
    ----------
    path : path
        A folder holding one ``.png`` per z layer.
    threshold : int
        Pixels with a grey level below this are filled (default 128).

    Raises
    ------
    FormatError
        No PNG in the folder, a file that is not a PNG, or images of different sizes.
    InvalidShapeError
        More than 256 layers or an image over 256 pixels on a side.
    """
    t = _check_threshold(threshold)
    folder = Path(path)
    files = sorted(
        (p for p in folder.iterdir() if p.suffix.lower() == ".png" and p.is_file()),
        key=lambda p: natural_key(p.name),
    )
    if not files:
        raise FormatError(f"{path}: the folder holds no .png slice")
    if len(files) > MAX_SIDE:
        raise InvalidShapeError(
            f"{path}: {len(files)} slices is over the limit of {MAX_SIDE} voxels per side"
        )
    layers = []
    for f in files:
        layer = _layer(f)
        if layers and layer.shape != layers[0].shape:
            w0, h0 = layers[0].shape[:2]
            w, h = layer.shape[:2]
            raise FormatError(f"{f}: image is {w}x{h} pixels, the first slice {files[0].name} is {w0}x{h0}")
        layers.append(layer)
    try:
        grid, colours = _voxels(np.stack(layers, axis=2), t)
    except InvalidShapeError as exc:
        raise InvalidShapeError(f"{path}: {exc}") from None
    return ReadResult(grid, None, (), colours)


def read_png(path: PathLike, *, threshold: int = DEFAULT_THRESHOLD) -> ReadResult:
    """Read one PNG image as a grid one layer thick (``z = 0``)."""
    grid, colours = _voxels(_layer(Path(path))[:, :, None], _check_threshold(threshold))
    note = "read one PNG image as a single z layer; pass its folder to read a slice stack"
    return ReadResult(np.ascontiguousarray(grid), None, (note,), colours)


def write_png_stack(grid: BoolGrid, path: PathLike, *, colours: VoxelColours | None = None) -> None:
    """Write a folder of RGBA slices ``z00.png``...: each voxel in its colour (black when uncoloured) on a
    transparent ground; the folder is replaced only when every slice is written."""
    from PIL import Image

    from voxfab._shared.atomic import atomic_dir

    g = np.asarray(grid, dtype=bool)
    rgba = (colours.rgba.copy() if colours is not None
            else np.where(g[..., None], np.array([0, 0, 0, 255], np.uint8), np.uint8(0)).astype(np.uint8))
    rgba[~g] = 0
    digits = max(2, len(str(g.shape[2] - 1)))
    with atomic_dir(path) as tmp:
        for z in range(g.shape[2]):
            # Column x, row 0 the highest y: the reader's own layout.
            image = np.ascontiguousarray(rgba[:, ::-1, z].transpose(1, 0, 2))
            Image.fromarray(image, "RGBA").save(tmp / f"z{z:0{digits}d}.png", optimize=False)


register("/", reader=read_png_stack, writer=write_png_stack)
register(".png", reader=read_png)
