"""PNG slice stacks (read): a folder of images, one per z layer from the bottom.

The files ``*.png`` of the folder are sorted naturally by name (``z2`` before
``z10``); file k is layer ``z = k``.  In each image a pixel darker than
``threshold`` (grey level 0..255, after compositing any transparency on white)
is a filled voxel; column ``i`` is ``x = i`` and image row 0 is the highest ``y``,
as a map is drawn.  A single ``.png`` file reads as a one-layer grid.
"""

from __future__ import annotations

import re
import struct
from io import BytesIO
from pathlib import Path

import numpy as np

from voxfab._shared.numbers import is_digits
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError, VoxfabError

from ._registry import ReadResult, register

__all__ = ["read_png_stack", "read_png", "natural_key", "DEFAULT_THRESHOLD"]

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


def _layer(path: Path, threshold: int) -> BoolGrid:
    """Read one image as a ``(X, Y)`` bool layer, ``[x, y]`` with y up."""
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
            if im.mode in ("RGBA", "LA", "PA") or (im.mode == "P" and "transparency" in im.info):
                rgba = im.convert("RGBA")
                white = Image.new("RGBA", rgba.size, (255, 255, 255, 255))
                im = Image.alpha_composite(white, rgba)
            if im.mode.startswith("I"):
                # 16-bit grey: Pillow's conversion to 8 bits clips instead of scaling.
                grey = (np.asarray(im).astype(np.int64) >> 8).clip(0, 255)
            else:
                grey = np.asarray(im.convert("L"))
    except VoxfabError:
        raise
    except Exception as exc:  # noqa: BLE001
        # Pillow reports corrupt data in many ways (UnidentifiedImageError, OSError,
        # SyntaxError, EOFError, zlib and struct errors): all mean "not a readable PNG".
        raise FormatError(f"{path}: not a readable PNG image ({exc})") from None
    # grey[row, column]: row 0 is the top of the picture, the highest y.
    return (grey < threshold).T[:, ::-1]


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
        layer = _layer(f, t)
        if layers and layer.shape != layers[0].shape:
            w0, h0 = layers[0].shape
            w, h = layer.shape
            raise FormatError(f"{f}: image is {w}x{h} pixels, the first slice {files[0].name} is {w0}x{h0}")
        layers.append(layer)
    return ReadResult(np.stack(layers, axis=2))


def read_png(path: PathLike, *, threshold: int = DEFAULT_THRESHOLD) -> ReadResult:
    """Read one PNG image as a grid one layer thick (``z = 0``)."""
    grid = np.ascontiguousarray(_layer(Path(path), _check_threshold(threshold))[:, :, None])
    note = "read one PNG image as a single z layer; pass its folder to read a slice stack"
    return ReadResult(grid, None, (note,))


register("/", reader=read_png_stack)
register(".png", reader=read_png)
