"""Deterministic PNG, PDF and GIF bytes from Pillow images (no dates, no varying metadata).

PNG and PDF go through the drawing backends (:mod:`voxfab.drawing`), so every
PDF voxfab writes comes from one writer.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.drawing.png import png_bytes
from voxfab.errors import InvalidShapeError, UnknownFormatError

if TYPE_CHECKING:
    from PIL import Image

__all__ = ["pdf_bytes", "gif_bytes", "save_picture", "font"]


def font(size: int):  # noqa: ANN201 - a PIL font object
    """Pillow's built-in scalable font at ``size`` pixels (the same glyphs everywhere)."""
    from PIL import ImageFont

    return ImageFont.load_default(size=max(6, int(size)))


def pdf_bytes(image: Image.Image, *, title: str = "", dpi: float = 150.0) -> bytes:
    """A one-page PDF showing ``image`` at ``dpi``, losslessly, with no dates.

    The page is a drawing holding the picture as one placed image, written by the
    one PDF backend (:mod:`voxfab.drawing.pdf`); Pillow's own PDF writer would
    store creation dates and JPEG-compress RGB images.
    """
    from voxfab.drawing import Drawing, Page, PlacedImage
    from voxfab.drawing.pdf import pdf_document

    if not dpi > 0:
        raise InvalidShapeError(f"dpi: expected a positive number, got {dpi!r}")
    w, h = image.size
    width, height = w * 25.4 / dpi, h * 25.4 / dpi
    page = Page(width, height, layers={}, images=(PlacedImage.of(image, x=0.0, y=0.0, width=width, height=height),),
                title=title)
    return pdf_document(Drawing((page,), title=title))


def gif_bytes(frames: Sequence[Image.Image], *, duration_ms: int = 80, loop: int = 0) -> bytes:
    """An animated GIF of palette images ``frames`` (all with the same palette).

    Pillow merges a frame identical to the one before into it (adding its
    duration), so the frame count is the number of changes.
    """
    if not frames:
        raise InvalidShapeError("frames: an animation needs at least one frame")
    if duration_ms <= 0:
        raise InvalidShapeError(f"duration_ms: expected a positive integer, got {duration_ms}")
    buf = io.BytesIO()
    first, rest = frames[0], list(frames[1:])
    first.save(
        buf,
        format="GIF",
        save_all=True,
        append_images=rest,
        duration=int(duration_ms),
        loop=int(loop),
        optimize=False,
        disposal=1,
    )
    return buf.getvalue()


def save_picture(image: Image.Image, path: PathLike, *, title: str = "") -> Path:
    """Write ``image`` atomically as PNG or PDF, chosen by the file extension."""
    p = Path(path)
    ext = p.suffix.lower()
    if ext == ".png":
        write_bytes(p, png_bytes(image))
    elif ext == ".pdf":
        write_bytes(p, pdf_bytes(image, title=title))
    else:
        raise UnknownFormatError(f"{p}: unknown picture extension {ext!r}; expected .png or .pdf")
    return p
