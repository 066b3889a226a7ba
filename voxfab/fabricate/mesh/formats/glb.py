"""Binary glTF 2.0 (GLB): one mesh node per part.

glTF measures in metres, so the positions stay in mm (exact float32 values) and
a root node scales the scene by 0.001.  glTF is Y-up (+Z towards the viewer), so
voxfab's ``(x, y, z)`` with z up is written as ``(x, z, -y)``: a rotation, which
keeps the triangles' winding.
"""

from __future__ import annotations

import json
import struct

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError

from .._data import MeshData

EXTENSION = ".glb"
DESCRIPTION = "mesh for viewers, web pages and game engines (glTF binary, scaled to metres)"

_ARRAY_BUFFER = 34962
_ELEMENT_ARRAY_BUFFER = 34963
_FLOAT = 5126
_UINT = 5125


def _pad(b: bytes, fill: bytes) -> bytes:
    return b + fill * (-len(b) % 4)


def to_y_up(v: np.ndarray) -> np.ndarray:
    """``(x, y, z)`` z-up → glTF's ``(x, z, -y)`` y-up (a quarter turn about x)."""
    return np.column_stack([v[:, 0], v[:, 2], -v[:, 1]])


def from_y_up(v: np.ndarray) -> np.ndarray:
    """glTF's ``(X, Y, Z)`` y-up → ``(X, -Z, Y)`` z-up, the inverse of :func:`to_y_up`."""
    return np.column_stack([v[:, 0], -v[:, 2], v[:, 1]])


def to_bytes(mesh: MeshData, *, name: str) -> bytes:
    """GLB bytes: a JSON chunk and a binary chunk."""
    blobs: list[bytes] = []
    views, accessors, meshes, nodes = [], [], [], []
    offset = 0
    for p in range(mesh.part_count):
        v, t = mesh.part_mesh(p)
        pos = np.ascontiguousarray(to_y_up(v), dtype="<f4")
        idx = np.ascontiguousarray(t, dtype="<u4")
        for data, target in ((pos.tobytes(), _ARRAY_BUFFER), (idx.tobytes(), _ELEMENT_ARRAY_BUFFER)):
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
            blobs.append(_pad(data, b"\0"))
            offset += len(blobs[-1])
        accessors.append({
            "bufferView": len(views) - 2, "componentType": _FLOAT, "count": int(len(pos)), "type": "VEC3",
            "min": [float(x) for x in pos.min(axis=0)], "max": [float(x) for x in pos.max(axis=0)],
        })
        accessors.append({"bufferView": len(views) - 1, "componentType": _UINT, "count": int(idx.size), "type": "SCALAR"})
        meshes.append({"name": f"{name} part {p + 1}", "primitives": [
            {"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1, "mode": 4}]})
        nodes.append({"name": f"{name} part {p + 1}", "mesh": p})
    n_parts = len(meshes)
    nodes.append({"name": name, "scale": [0.001, 0.001, 0.001], "children": list(range(n_parts))})
    doc = {
        "asset": {"version": "2.0", "generator": "voxfab", "extras": {"source_unit": "millimeter"}},
        "scene": 0,
        "scenes": [{"name": name, "nodes": [n_parts]}],
        "nodes": nodes,
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": offset}],
    }
    js = _pad(json.dumps(doc, sort_keys=True, separators=(",", ":")).encode("utf-8"), b" ")
    binary = b"".join(blobs)
    total = 12 + 8 + len(js) + 8 + len(binary)
    return (
        struct.pack("<4sII", b"glTF", 2, total)
        + struct.pack("<I4s", len(js), b"JSON") + js
        + struct.pack("<I4s", len(binary), b"BIN\0") + binary
    )


def read(path: PathLike) -> MeshData:
    """Read a GLB written by :func:`to_bytes`; positions in mm, z up (the root scale is not applied)."""
    with open(path, "rb") as fh:
        data = fh.read()
    try:
        magic, version, total = struct.unpack_from("<4sII", data, 0)
        if magic != b"glTF" or version != 2 or total != len(data):
            raise FormatError(f"{path}: not a glTF 2.0 binary file")
        jlen, jtype = struct.unpack_from("<I4s", data, 12)
        doc = json.loads(data[20 : 20 + jlen])
        blen, btype = struct.unpack_from("<I4s", data, 20 + jlen)
        binary = data[28 + jlen : 28 + jlen + blen]
    except (struct.error, json.JSONDecodeError) as exc:
        raise FormatError(f"{path}: corrupt GLB ({exc})") from exc
    if jtype != b"JSON" or btype != b"BIN\0":
        raise FormatError(f"{path}: unexpected GLB chunks {jtype!r}, {btype!r}")

    def array(acc_index: int, dtype: str, width: int) -> np.ndarray:
        acc = doc["accessors"][acc_index]
        view = doc["bufferViews"][acc["bufferView"]]
        start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        per = {"SCALAR": 1, "VEC3": 3}[acc["type"]]
        return np.frombuffer(binary, dtype, acc["count"] * per, start).reshape(-1, width)

    verts, tris, parts = [], [], []
    base = 0
    for p, m in enumerate(doc["meshes"]):
        prim = m["primitives"][0]
        v = from_y_up(array(prim["attributes"]["POSITION"], "<f4", 3).astype(np.float64))
        t = array(prim["indices"], "<u4", 3).astype(np.int64)
        verts.append(v)
        tris.append(t + base)
        parts.append(np.full(len(t), p))
        base += len(v)
    return MeshData(vertices=np.concatenate(verts), triangles=np.concatenate(tris), part=np.concatenate(parts))
