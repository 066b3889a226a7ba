"""File formats: one module per format, found through a registry by extension.

Readers return a :class:`ReadResult` (grid, pitch, notes, colours); :func:`write` takes
a shape (or a bool grid ``[x, y, z]``) and a path and writes atomically, keeping the
pitch and the colours where the format can (:func:`carries`).
"""

from ._registry import (
    ReadResult,
    carries,
    read,
    readable_formats,
    register,
    writable_formats,
    write,
    writer_for,
)

__all__ = ["ReadResult", "carries", "read", "write", "register", "readable_formats", "writable_formats", "writer_for"]
