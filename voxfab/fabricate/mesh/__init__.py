"""Print-ready solids: manifold meshes from voxels, contact bridges, CAD parts, 3MF/STL/OBJ/GLB.

>>> from voxfab.shape import examples
>>> result = build_mesh(examples.tunnel_cube(5), pitch=2.0)
>>> result.report.bodies, round(result.report.volume, 6)
(1, 648.0)
"""

from __future__ import annotations

import json
from pathlib import Path

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import PathLike
from voxfab.fabricate._outputs import Artefact, OutputFile
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
from ._options import MeshOptions
from .formats import format_for, mesh_extensions, read_mesh, write_mesh

__all__ = [
    "BRIDGE_WIDTH",
    "ENGRAVE_DEPTH",
    "MAX_FACES",
    "MIN_WALL",
    "ContactMode",
    "Contacts",
    "MeshData",
    "MeshOptions",
    "MeshReport",
    "MeshResult",
    "bridge_boxes",
    "build_mesh",
    "fabricate_mesh",
    "check_mesh",
    "find_contacts",
    "format_for",
    "hollow_out",
    "mesh_extensions",
    "parse_magnet",
    "read_mesh",
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


def fabricate_mesh(
    shape: VoxelShape,
    options: MeshOptions,
    path: PathLike,
    *,
    name: str,
    report_path: PathLike | None = None,
) -> Artefact:
    """The print pipeline: build, check and write the mesh (and its figures as JSON).

    The CLI (``voxfab mesh``), recipes (output ``mesh``), the studio and batch runs
    all call this.

    Parameters
    ----------
    shape : VoxelShape
        The shape; ``shape.pitch`` is the mm per voxel unless ``options.size`` is given.
    options : MeshOptions
        Checked options (the file format comes from ``path``'s extension).
    path : path-like
        The mesh file to write (.3mf, .stl, .obj or .glb).
    name : str
        The shape's name: file metadata, and ``{name}`` in the label.
    report_path : path-like, optional
        Also write the figures there as JSON.

    Returns
    -------
    Artefact
        Files relative to ``path``'s folder, warnings (thin walls, a print in
        several parts, an illegible label), and the figures of :func:`report_dict`.
    """
    target = Path(path)
    module = format_for(target)  # refuse an unknown extension before any work
    label = options.label.replace("{name}", name) if options.label else None
    result = build_mesh(
        shape, size=options.size, contacts=options.contacts, bridge_width=options.bridge_width,
        fill=options.solid, hollow=options.hollow, label=label, engrave_depth=options.engrave_depth,
        base=options.base, magnet=options.magnet, merge=options.merge, name=name,
    )
    write_mesh(target, result.mesh, name=name)
    report = report_dict(result, name=name)
    files = [OutputFile(target.name, module.DESCRIPTION)]
    if report_path is not None:
        rp = Path(report_path)
        write_text(rp, json.dumps(report, indent=2, sort_keys=True) + "\n")
        files.append(OutputFile(rp.relative_to(target.parent).as_posix(),
                                "size, volume, part count and printability warnings of the mesh (JSON)"))
    return Artefact(tuple(files), tuple(report["warnings"]), report)  # type: ignore[arg-type]
