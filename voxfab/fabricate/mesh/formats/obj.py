"""Wavefront OBJ: indexed vertices in mm, one ``o`` group per part.

A coloured mesh comes with a material library beside it (``NAME.mtl``, named by
``mtllib``): one material per filament colour (``Kd``, its diffuse colour), and
each part's faces grouped by colour after ``usemtl``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError

from .._data import MeshData
from ._text import format_rows

EXTENSION = ".obj"
DESCRIPTION = "indexed mesh for 3D software and slicers (OBJ, mm)"
#: The material library written beside a coloured OBJ.
MATERIAL_EXTENSION = ".mtl"
MATERIAL_DESCRIPTION = "the OBJ's colours: one material per filament colour (MTL)"


def _material_names(mesh: MeshData) -> list[str]:
    from .._colours import colour_hexes

    assert mesh.palette is not None
    return [f"colour_{k + 1}_{h[1:]}" for k, h in enumerate(colour_hexes(mesh.palette))]


def material_bytes(mesh: MeshData) -> bytes:
    """The MTL text of a coloured mesh: a material per colour of its palette."""
    from .._colours import material_labels

    assert mesh.palette is not None
    out = ["# voxfab materials: one per filament colour\n"]
    for name, label, c in zip(_material_names(mesh), material_labels(mesh.palette), mesh.palette):
        r, g, b = (int(x) / 255.0 for x in c[:3])
        out.append(f"\n# {label}\nnewmtl {name}\nKa 0 0 0\nKd {r:.6g} {g:.6g} {b:.6g}\nKs 0 0 0\nd 1\nillum 1\n")
    return "".join(out).encode("utf-8")


def to_bytes(mesh: MeshData, *, name: str, materials: str | None = None) -> bytes:
    """OBJ text: the vertices of each part followed by its faces (1-based).

    ``materials``, the file name of the mesh's material library, is required for
    a coloured mesh: its faces then follow ``usemtl`` lines, colour by colour.
    """
    safe = "_".join(name.split()) or "shape"
    out = [f"# voxfab mesh of {safe}, millimetres\n"]
    names: list[str] = []
    if mesh.coloured:
        if materials is None:
            raise ValueError("a coloured OBJ needs the name of its material library")
        out.append(f"mtllib {materials}\n")
        names = _material_names(mesh)
    base = 0
    for p in range(mesh.part_count):
        v, t = mesh.part_mesh(p)
        out.append(f"o {safe}_{p + 1}\n")
        out.append(format_rows(v, "v %.9g %.9g %.9g\n"))
        if mesh.colour is None:
            out.append(format_rows(t + base + 1, "f %d %d %d\n"))
        else:
            colour = mesh.colour[mesh.part == p]
            for k in np.unique(colour):
                out.append(f"usemtl {names[k]}\n")
                out.append(format_rows(t[colour == k] + base + 1, "f %d %d %d\n"))
        base += len(v)
    return "".join(out).encode("utf-8")


def _read_materials(path: Path) -> dict[str, tuple[int, int, int, int]]:
    """``newmtl`` name -> RGBA from ``Kd`` of a material library."""
    found: dict[str, tuple[int, int, int, int]] = {}
    current = None
    for line in path.read_text(encoding="utf-8").splitlines():
        f = line.split()
        if len(f) >= 2 and f[0] == "newmtl":
            current = f[1]
            found[current] = (255, 255, 255, 255)
        elif len(f) >= 4 and f[0] == "Kd" and current is not None:
            r, g, b = (min(max(round(float(x) * 255), 0), 255) for x in f[1:4])
            found[current] = (r, g, b, 255)
    return found


def read(path: PathLike) -> MeshData:
    """Read ``v``, ``f``, ``o`` lines (triangles only), and ``usemtl`` colours from the ``mtllib`` beside it."""
    verts: list[list[float]] = []
    tris: list[list[int]] = []
    parts: list[int] = []
    colour: list[int] = []
    used: list[str] = []
    library = None
    part = -1
    current = -1
    try:
        text = Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise FormatError(f"{path}: not a text OBJ file ({exc.reason} at byte {exc.start})") from None
    for lineno, line in enumerate(text.splitlines(), 1):
        f = line.split()
        if not f or f[0].startswith("#"):
            continue
        try:
            if f[0] == "v":
                if len(f) < 4:
                    raise FormatError(f"{path}:{lineno}: a vertex needs three coordinates")
                verts.append([float(x) for x in f[1:4]])
            elif f[0] == "f":
                if len(f) != 4:
                    raise FormatError(f"{path}:{lineno}: only triangles are supported")
                tris.append([int(x.split("/")[0]) - 1 for x in f[1:4]])
                parts.append(max(part, 0))
                colour.append(current)
            elif f[0] == "o":
                part += 1
            elif f[0] == "mtllib" and len(f) == 2:
                library = Path(path).parent / f[1]
            elif f[0] == "usemtl" and len(f) == 2:
                if f[1] not in used:
                    used.append(f[1])
                current = used.index(f[1])
        except ValueError as exc:
            raise FormatError(f"{path}:{lineno}: bad number ({exc})") from exc
    if not tris:
        raise FormatError(f"{path}: no faces")
    mesh = MeshData(vertices=np.array(verts), triangles=np.array(tris), part=np.array(parts))
    if library is None or not used:
        return mesh
    try:
        known = _read_materials(library)
    except (OSError, ValueError) as exc:  # UnicodeDecodeError is a ValueError
        raise FormatError(f"{path}: its material library {library.name} is not readable ({exc})") from None
    missing = [m for m in used if m not in known]
    if missing or min(colour) < 0:
        raise FormatError(f"{path}: faces without a material of {library.name} ({', '.join(missing) or 'none named'})")
    palette = np.array([known[m] for m in used], dtype=np.uint8)
    return MeshData(vertices=mesh.vertices, triangles=mesh.triangles, part=mesh.part,
                    colour=np.array(colour, dtype=np.int64), palette=palette)
