"""Binary glTF 2.0 (GLB): one mesh node per part.

glTF measures in metres, so the positions stay in mm (exact float32 values) and
a root node scales the scene by 0.001.  glTF is Y-up (+Z towards the viewer), so
voxfab's ``(x, y, z)`` with z up is written as ``(x, z, -y)``: a rotation, which
keeps the triangles' winding.

A coloured mesh has one material per filament colour (its ``baseColorFactor``,
linear as glTF wants it, and the ``#rrggbb`` in the material's extras) and, per
part, one primitive per colour sharing the part's vertices.
"""

from __future__ import annotations

import json
import struct

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError
from voxfab.io.mesh import from_y_up, to_y_up

from .._data import MeshData

EXTENSION = ".glb"
DESCRIPTION = "mesh for viewers, web pages and game engines (glTF binary, scaled to metres)"

_ARRAY_BUFFER = 34962
_ELEMENT_ARRAY_BUFFER = 34963
_FLOAT = 5126
_UINT = 5125


def _pad(b: bytes, fill: bytes) -> bytes:
    return b + fill * (-len(b) % 4)


def srgb_to_linear(rgb: np.ndarray) -> np.ndarray:
    """Linear-light values 0..1 of sRGB values 0..255 (glTF's colour factors are linear)."""
    c = np.asarray(rgb, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(linear: np.ndarray) -> np.ndarray:
    """sRGB values 0..255 (rounded) of linear-light values 0..1, the inverse of :func:`srgb_to_linear`."""
    c = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    s = np.where(c <= 0.0031308, c * 12.92, 1.055 * c ** (1 / 2.4) - 0.055)
    return np.round(s * 255.0).astype(np.int64)


def _materials(mesh: MeshData) -> list[dict[str, object]]:
    from .._colours import colour_hexes, material_labels

    assert mesh.palette is not None
    return [
        {"name": label, "extras": {"colour": hexed},
         "pbrMetallicRoughness": {"baseColorFactor": [*(round(float(x), 9) for x in srgb_to_linear(c[:3])), 1.0],
                                  "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        for label, hexed, c in zip(material_labels(mesh.palette), colour_hexes(mesh.palette), mesh.palette)
    ]


def to_bytes(mesh: MeshData, *, name: str) -> bytes:
    """GLB bytes: a JSON chunk and a binary chunk."""
    blobs: list[bytes] = []
    views, accessors, meshes, nodes = [], [], [], []
    offset = 0

    def add(data: bytes, target: int) -> None:
        nonlocal offset
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
        blobs.append(_pad(data, b"\0"))
        offset += len(blobs[-1])

    for p in range(mesh.part_count):
        v, t = mesh.part_mesh(p)
        pos = np.ascontiguousarray(to_y_up(v), dtype="<f4")
        add(pos.tobytes(), _ARRAY_BUFFER)
        accessors.append({
            "bufferView": len(views) - 1, "componentType": _FLOAT, "count": int(len(pos)), "type": "VEC3",
            "min": [float(x) for x in pos.min(axis=0)], "max": [float(x) for x in pos.max(axis=0)],
        })
        position = len(accessors) - 1
        if mesh.colour is None:
            groups = [(None, t)]
        else:
            colour = mesh.colour[mesh.part == p]
            groups = [(int(k), t[colour == k]) for k in np.unique(colour)]
        primitives = []
        for material, tris in groups:
            idx = np.ascontiguousarray(tris, dtype="<u4")
            add(idx.tobytes(), _ELEMENT_ARRAY_BUFFER)
            accessors.append({"bufferView": len(views) - 1, "componentType": _UINT, "count": int(idx.size),
                              "type": "SCALAR"})
            primitive: dict[str, object] = {"attributes": {"POSITION": position}, "indices": len(accessors) - 1,
                                            "mode": 4}
            if material is not None:
                primitive["material"] = material
            primitives.append(primitive)
        meshes.append({"name": f"{name} part {p + 1}", "primitives": primitives})
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
    if mesh.coloured:
        doc["materials"] = _materials(mesh)
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

    verts, tris, parts, colours = [], [], [], []
    base = 0
    for p, m in enumerate(doc["meshes"]):
        prims = m["primitives"]
        v = from_y_up(array(prims[0]["attributes"]["POSITION"], "<f4", 3).astype(np.float64))
        for prim in prims:  # the primitives of one part share its vertices
            t = array(prim["indices"], "<u4", 3).astype(np.int64)
            tris.append(t + base)
            parts.append(np.full(len(t), p))
            colours.append(np.full(len(t), prim.get("material", -1)))
        verts.append(v)
        base += len(v)
    colour, palette = None, None
    if "materials" in doc:
        colour = np.concatenate(colours)
        factors = np.array([mat["pbrMetallicRoughness"]["baseColorFactor"][:3] for mat in doc["materials"]])
        palette = np.full((len(factors), 4), 255, dtype=np.uint8)
        palette[:, :3] = linear_to_srgb(factors)
    return MeshData(vertices=np.concatenate(verts), triangles=np.concatenate(tris), part=np.concatenate(parts),
                    colour=colour, palette=palette)
