"""Print-ready solids: manifold meshes from voxels, contact bridges, CAD parts, 3MF/STL/OBJ/GLB.

>>> from voxfab.shape import examples
>>> result = build_mesh(examples.tunnel_cube(5), pitch=2.0)
>>> result.report.bodies, round(result.report.volume, 6)
(1, 648.0)
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Literal

from voxfab._shared.atomic import write_text
from voxfab.fabricate._registry import OutputFile
from voxfab.shape import VoxelShape

from ._build import (
    BRIDGE_WIDTH,
    ENGRAVE_DEPTH,
    MAX_FACES,
    MIN_WALL,
    ContactMode,
    MeshResult,
    build_mesh,
    hollow_out,
    parse_magnet,
)
from ._check import MeshReport, check_mesh
from ._contacts import Contacts, bridge_boxes, find_contacts
from ._data import MeshData
from ._faces import voxel_mesh
from .formats import format_for, mesh_extensions, read_mesh, write_mesh

__all__ = [
    "BRIDGE_WIDTH",
    "ENGRAVE_DEPTH",
    "MAX_FACES",
    "MIN_WALL",
    "ContactMode",
    "Contacts",
    "MeshData",
    "MeshReport",
    "MeshResult",
    "bridge_boxes",
    "build_mesh",
    "check_mesh",
    "find_contacts",
    "format_for",
    "hollow_out",
    "mesh_extensions",
    "parse_magnet",
    "read_mesh",
    "recipe_output",
    "report_dict",
    "voxel_mesh",
    "write_mesh",
]


def report_dict(result: MeshResult, *, name: str) -> dict[str, object]:
    """The figures of a mesh result as plain JSON values."""
    r = result.report
    return {
        "name": name,
        "pitch_mm": result.pitch,
        "triangles": r.triangles,
        "vertices": r.vertices,
        "parts": r.parts,
        "bodies": r.bodies,
        "shells": r.shells,
        "volume_mm3": round(r.volume, 6),
        "size_mm": [round(hi - lo, 6) for lo, hi in zip(*r.bounds)],
        "contacts": result.contacts,
        "bridges": result.bridges,
        "warnings": list(result.warnings),
    }


def recipe_output(
    shape: VoxelShape,
    outdir: Path,
    *,
    name: str,
    seed: int,
    format: Literal["3mf", "stl", "obj", "glb"] = "3mf",
    size: float | None = None,
    contacts: Literal["bridge", "split", "error"] = "bridge",
    bridge_width: float | None = None,
    solid: bool = True,
    hollow: int = 0,
    label: str | None = None,
    base: float = 0.0,
    magnet: str | None = None,
) -> list[OutputFile]:
    """Recipe output ``mesh``: a checked print-ready mesh and its figures.

    Parameters
    ----------
    shape : VoxelShape
        The shape; ``shape.pitch`` is the mm per voxel unless ``size`` is given.
    outdir : Path
        Folder to write ``mesh.<format>`` and ``mesh.json`` into.
    name : str
        Recipe name, stored in the file's metadata; ``{name}`` in ``label`` is replaced by it.
    seed : int
        Unused (the mesh is deterministic); part of the output interface.
    format, size, contacts, bridge_width, hollow, label, base, magnet
        As :func:`build_mesh`; ``magnet`` is ``"DxH"`` in mm.
    solid : bool
        Fill enclosed cavities.
    """
    del seed
    text = label.replace("{name}", name) if label else None
    result = build_mesh(
        shape,
        size=size,
        contacts=contacts,
        bridge_width=bridge_width,
        fill=solid,
        hollow=hollow,
        label=text,
        base=base,
        magnet=magnet,
        name=name,
    )
    ext = "." + str(format).lower().lstrip(".")
    module = format_for(f"mesh{ext}")
    write_mesh(Path(outdir) / f"mesh{ext}", result.mesh, name=name)
    write_text(Path(outdir) / "mesh.json", json.dumps(report_dict(result, name=name), indent=2, sort_keys=True) + "\n")
    return [
        OutputFile(f"mesh{ext}", module.DESCRIPTION),
        OutputFile("mesh.json", "size, volume, part count and printability warnings of the mesh (JSON)"),
    ]
