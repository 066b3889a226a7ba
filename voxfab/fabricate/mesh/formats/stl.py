"""Binary STL: a triangle soup in mm (no units in the file, no vertex identity)."""

from __future__ import annotations

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError

from .._data import MeshData

EXTENSION = ".stl"
DESCRIPTION = "solid for any slicer (binary STL, mm, no units stored)"

_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def to_bytes(mesh: MeshData, *, name: str) -> bytes:
    """Binary STL bytes: an 80-byte header, the count, and 50 bytes per triangle."""
    tri = mesh.vertices[mesh.triangles]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    rec = np.zeros(tri.shape[0], dtype=_RECORD)
    rec["normal"] = n
    rec["v"] = tri
    # A header starting with "solid" makes some readers take the file for ASCII STL.
    header = f"voxfab binary STL, millimetres: {name}".encode("ascii", "replace")[:80].ljust(80, b" ")
    return header + np.uint32(tri.shape[0]).tobytes() + rec.tobytes()


def read(path: PathLike) -> MeshData:
    """Read a binary STL; each triangle gets its own three vertices, all in part 0."""
    with open(path, "rb") as fh:
        data = fh.read()
    if len(data) < 84:
        raise FormatError(f"{path}: too short for a binary STL ({len(data)} bytes)")
    count = int(np.frombuffer(data, "<u4", 1, 80)[0])
    if len(data) != 84 + 50 * count:
        raise FormatError(f"{path}: binary STL header says {count} triangles but the size is {len(data)} bytes")
    rec = np.frombuffer(data, _RECORD, count, 84)
    v = rec["v"].reshape(-1, 3).astype(np.float64)
    return MeshData(vertices=v, triangles=np.arange(3 * count).reshape(-1, 3), part=np.zeros(count, dtype=np.int64))
