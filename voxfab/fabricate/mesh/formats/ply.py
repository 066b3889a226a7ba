"""PLY (Stanford polygon file), binary little-endian: vertices in mm, triangles, and a colour per face.

A coloured mesh gives each face ``red``, ``green`` and ``blue`` properties (the
face colours MeshLab, Blender and trimesh show).  PLY has no groups, so the
parts are found again from the shells when it is read.
"""

from __future__ import annotations

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError

from .._data import MeshData, parts_from_shells

EXTENSION = ".ply"
DESCRIPTION = "mesh with face colours for viewers and 3D software (binary PLY, mm)"

_VERTEX = np.dtype([("x", "<f8"), ("y", "<f8"), ("z", "<f8")])
_FACE = np.dtype([("n", "u1"), ("v", "<i4", (3,))])
_COLOURED_FACE = np.dtype([("n", "u1"), ("v", "<i4", (3,)), ("rgb", "u1", (3,))])


def to_bytes(mesh: MeshData, *, name: str) -> bytes:
    """PLY bytes: an ASCII header, then the vertex and face records."""
    coloured = mesh.colour is not None and mesh.palette is not None
    safe = " ".join(name.split()) or "shape"
    header = [
        "ply", "format binary_little_endian 1.0", f"comment voxfab mesh of {safe}, millimetres",
        f"element vertex {len(mesh.vertices)}", "property double x", "property double y", "property double z",
        f"element face {len(mesh.triangles)}", "property list uchar int vertex_indices",
    ]
    if coloured:
        header += ["property uchar red", "property uchar green", "property uchar blue"]
    header.append("end_header")
    verts = np.zeros(len(mesh.vertices), dtype=_VERTEX)
    for a, key in enumerate("xyz"):
        verts[key] = mesh.vertices[:, a]
    faces = np.zeros(len(mesh.triangles), dtype=_COLOURED_FACE if coloured else _FACE)
    faces["n"] = 3
    faces["v"] = mesh.triangles
    if coloured:
        assert mesh.palette is not None and mesh.colour is not None
        faces["rgb"] = mesh.palette[mesh.colour, :3]
    return ("\n".join(header) + "\n").encode("ascii") + verts.tobytes() + faces.tobytes()


def read(path: PathLike) -> MeshData:
    """Read a PLY written by :func:`to_bytes` (face colours become the mesh's colours)."""
    with open(path, "rb") as fh:
        data = fh.read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        raise FormatError(f"{path}: not a PLY file")
    lines = data[:end].decode("ascii", "replace").splitlines()
    if "format binary_little_endian 1.0" not in lines:
        raise FormatError(f"{path}: only binary little-endian PLY is read")
    counts = {f[1]: int(f[2]) for f in (line.split() for line in lines) if len(f) == 3 and f[0] == "element"}
    coloured = "property uchar red" in lines
    body = data[end + len(b"end_header\n"):]
    face_type = _COLOURED_FACE if coloured else _FACE
    nv, nf = counts.get("vertex", 0), counts.get("face", 0)
    if len(body) != nv * _VERTEX.itemsize + nf * face_type.itemsize:
        raise FormatError(f"{path}: the PLY header says {nv} vertices and {nf} faces but the size differs")
    verts = np.frombuffer(body, _VERTEX, nv)
    faces = np.frombuffer(body, face_type, nf, nv * _VERTEX.itemsize)
    v = np.column_stack([verts["x"], verts["y"], verts["z"]]).astype(np.float64)
    t = faces["v"].astype(np.int64)
    colour, palette = None, None
    if coloured:
        rgb = faces["rgb"]
        palette3, colour = np.unique(rgb, axis=0, return_inverse=True)
        palette = np.concatenate([palette3, np.full((len(palette3), 1), 255, np.uint8)], axis=1)
        colour = colour.reshape(-1).astype(np.int64)
    return MeshData(vertices=v, triangles=t, part=parts_from_shells(v, t), colour=colour, palette=palette)
