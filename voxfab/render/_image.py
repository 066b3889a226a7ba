"""Deterministic PNG, PDF and GIF bytes from Pillow images (no dates, no varying metadata)."""

from __future__ import annotations

import io
import zlib
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.errors import InvalidShapeError, UnknownFormatError

if TYPE_CHECKING:
    from PIL import Image

__all__ = ["png_bytes", "pdf_bytes", "gif_bytes", "save_picture", "font"]


def font(size: int):  # noqa: ANN201 - a PIL font object
    """Pillow's built-in scalable font at ``size`` pixels (the same glyphs everywhere)."""
    from PIL import ImageFont

    return ImageFont.load_default(size=max(6, int(size)))


def png_bytes(image: Image.Image) -> bytes:
    """PNG bytes of ``image`` with no text or time chunks."""
    buf = io.BytesIO()
    image.save(buf, format="PNG", optimize=False, compress_level=6)
    return buf.getvalue()


def _pdf_string(text: str) -> bytes:
    escaped = text.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)")
    return b"(" + escaped.encode("latin-1", "replace") + b")"


def pdf_bytes(image: Image.Image, *, title: str = "", dpi: float = 150.0) -> bytes:
    """A one-page PDF showing ``image`` at ``dpi``, losslessly (Flate), with no dates.

    Pillow's own PDF writer stores creation dates and JPEG-compresses RGB images,
    so the few objects are written here directly.
    """
    rgb = image.convert("RGB")
    w, h = rgb.size
    pw, ph = w * 72.0 / dpi, h * 72.0 / dpi
    data = zlib.compress(rgb.tobytes(), 6)
    content = f"q {pw:.4f} 0 0 {ph:.4f} 0 0 cm /Im0 Do Q\n".encode("ascii")
    objects = [
        b"<< /Type /Catalog /Pages 2 0 R >>",
        b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        (
            f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {pw:.4f} {ph:.4f}] "
            f"/Resources << /XObject << /Im0 5 0 R >> >> /Contents 4 0 R >>"
        ).encode("ascii"),
        b"<< /Length %d >>\nstream\n" % len(content) + content + b"\nendstream",
        (
            f"<< /Type /XObject /Subtype /Image /Width {w} /Height {h} /ColorSpace /DeviceRGB "
            f"/BitsPerComponent 8 /Filter /FlateDecode /Length {len(data)} >>\nstream\n"
        ).encode("ascii")
        + data
        + b"\nendstream",
        b"<< /Title " + _pdf_string(title) + b" /Producer (voxfab) >>",
    ]
    out = bytearray(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
    offsets = []
    for i, body in enumerate(objects, start=1):
        offsets.append(len(out))
        out += b"%d 0 obj\n" % i + body + b"\nendobj\n"
    xref = len(out)
    out += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
    for off in offsets:
        out += b"%010d 00000 n \n" % off
    out += b"trailer\n<< /Size %d /Root 1 0 R /Info %d 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (
        len(objects) + 1,
        len(objects),
        xref,
    )
    return bytes(out)


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
