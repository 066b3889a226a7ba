"""Wavefront OBJ: indexed vertices in mm, one ``o`` group per part."""

from __future__ import annotations

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError

from .._data import MeshData
from ._text import format_rows

EXTENSION = ".obj"
DESCRIPTION = "indexed mesh for 3D software and slicers (OBJ, mm)"


def to_bytes(mesh: MeshData, *, name: str) -> bytes:
    """OBJ text: the vertices of each part followed by its faces (1-based)."""
    safe = "_".join(name.split()) or "shape"
    out = [f"# voxfab mesh of {safe}, millimetres\n"]
    base = 0
    for p in range(mesh.part_count):
        v, t = mesh.part_mesh(p)
        out.append(f"o {safe}_{p + 1}\n")
        out.append(format_rows(v, "v %.9g %.9g %.9g\n"))
        out.append(format_rows(t + base + 1, "f %d %d %d\n"))
        base += len(v)
    return "".join(out).encode("utf-8")


def read(path: PathLike) -> MeshData:
    """Read ``v``, ``f`` and ``o`` lines (triangles only)."""
    verts: list[list[float]] = []
    tris: list[list[int]] = []
    parts: list[int] = []
    part = -1
    with open(path, encoding="utf-8") as fh:
        for lineno, line in enumerate(fh, 1):
            f = line.split()
            if not f or f[0].startswith("#"):
                continue
            try:
                if f[0] == "v":
                    verts.append([float(x) for x in f[1:4]])
                elif f[0] == "f":
                    if len(f) != 4:
                        raise FormatError(f"{path}:{lineno}: only triangles are supported")
                    tris.append([int(x.split("/")[0]) - 1 for x in f[1:4]])
                    parts.append(max(part, 0))
                elif f[0] == "o":
                    part += 1
            except ValueError as exc:
                raise FormatError(f"{path}:{lineno}: bad number ({exc})") from exc
    if not tris:
        raise FormatError(f"{path}: no faces")
    return MeshData(vertices=np.array(verts), triangles=np.array(tris), part=np.array(parts))
