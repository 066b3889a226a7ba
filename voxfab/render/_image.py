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

__all__ = ["pdf_bytes", "gif_bytes", "save_picture", "font", "shared_palette"]


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


def shared_palette(frames: Sequence[object], bases: object = None) -> list[Image.Image]:
    """RGB frames (``(H, W, 3)`` uint8 arrays or images) as palette images on one palette made for them all.

    A GIF frame holds 256 colours.  When the frames use no more, the palette is exactly
    their colours (sorted, so the same frames give the same bytes).  Else it holds ramps
    of shades of each of ``bases`` (the voxels' colours, ``(n, 3)``), so that a colour
    only a few pixels show (an eye, a button) is kept, and the median cut of all frames
    together for the rest (the background, blends at edges).  Every frame maps onto the
    one palette, so a colour does not flicker from frame to frame.
    """
    import numpy as np
    from PIL import Image

    rgb = [np.asarray(f, dtype=np.uint8)[..., :3] for f in frames]
    keys = [(a[..., 0].astype(np.int32) << 16) | (a[..., 1].astype(np.int32) << 8) | a[..., 2] for a in rgb]
    used = np.unique(np.concatenate([k.ravel() for k in keys]))
    if len(used) <= 256:
        palette = np.stack([used >> 16, (used >> 8) & 255, used & 255], axis=1).astype(np.uint8)
        out = []
        for k in keys:
            im = Image.frombytes("P", (k.shape[1], k.shape[0]), np.searchsorted(used, k).astype(np.uint8).tobytes())
            im.putpalette(palette.ravel().tolist())
            out.append(im)
        return out
    base = np.unique(np.asarray(bases if bases is not None else np.zeros((0, 3)), dtype=np.float64).reshape(-1, 3),
                     axis=0)
    levels = 192 // len(base) if len(base) else 0  # a quarter of the palette is left for the rest
    ramps = (np.rint(base[:, None, :] * np.linspace(0.25, 1.0, levels)[None, :, None]).reshape(-1, 3)
             if levels >= 2 else np.zeros((0, 3)))
    rest = Image.fromarray(np.concatenate(rgb, axis=0)).quantize(256 - len(ramps), method=Image.Quantize.MEDIANCUT,
                                                                 dither=Image.Dither.NONE)
    extra = np.asarray(rest.getpalette()[: 3 * (256 - len(ramps))], dtype=np.float64).reshape(-1, 3)
    target = Image.new("P", (1, 1))
    target.putpalette(np.concatenate([extra, ramps]).astype(np.uint8).ravel().tolist())
    return [Image.fromarray(a).quantize(palette=target, dither=Image.Dither.NONE) for a in rgb]


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
