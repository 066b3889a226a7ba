"""File formats: one module per format, found through a registry by extension.

Readers return a :class:`ReadResult` (grid, pitch, notes); writers take a bool grid
``[x, y, z]`` and a path and write atomically.
"""

from ._registry import (
    ReadResult,
    read,
    readable_formats,
    register,
    writable_formats,
    write,
)

__all__ = ["ReadResult", "read", "write", "register", "readable_formats", "writable_formats"]
