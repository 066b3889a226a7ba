"""Print-ready solids: manifold meshes from voxels, contact bridges, CAD parts, 3MF/STL/OBJ/GLB/PLY, in colour.

>>> from voxfab.shape import examples
>>> result = build_mesh(examples.tunnel_cube(5), pitch=2.0)
>>> result.report.bodies, round(result.report.volume, 6)
(1, 648.0)
"""

from __future__ import annotations

import dataclasses
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
from ._colours import MAX_FILAMENTS, Filament, Filaments, assign_filaments, filaments_line
from ._contacts import Contacts, bridge_boxes, find_contacts
from ._data import MeshData
from ._faces import voxel_mesh
from ._mass import (
    DEFAULT_INFILL,
    PLA_DENSITY,
    MassProperties,
    PrintEstimate,
    PrintProfile,
    SpinReport,
    estimate_print,
    format_duration,
    mass_properties,
    overhang_area,
    spin_report,
)
from ._options import MeshOptions
from .formats import format_for, mesh_extensions, read_mesh, write_mesh

__all__ = [
    "BRIDGE_WIDTH",
    "ENGRAVE_DEPTH",
    "DEFAULT_INFILL",
    "MAX_FACES",
    "PLA_DENSITY",
    "MIN_WALL",
    "ContactMode",
    "Contacts",
    "Filament",
    "Filaments",
    "MAX_FILAMENTS",
    "MeshData",
    "MeshOptions",
    "MeshReport",
    "MeshResult",
    "MassProperties",
    "PrintEstimate",
    "PrintProfile",
    "SpinReport",
    "assign_filaments",
    "bridge_boxes",
    "build_mesh",
    "fabricate_mesh",
    "filaments_line",
    "check_mesh",
    "estimate_line",
    "estimate_print",
    "format_duration",
    "mass_properties",
    "overhang_area",
    "spin_report",
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


def _rounded(values: object, digits: int = 6) -> object:
    """Plain floats rounded to ``digits`` decimals (nested lists kept)."""
    import numpy as np

    return np.round(np.asarray(values, dtype=np.float64), digits).tolist()


def report_dict(result: MeshResult, *, name: str, infill: float = DEFAULT_INFILL,
                spin: bool = False) -> dict[str, object]:
    """The figures of a mesh result as plain JSON values.

    Besides counts and sizes: the centre of mass and the principal moments of
    inertia of the solid (uniform, at the print's average density), the PLA mass
    and print time at ``infill`` percent, and with ``spin`` the top's spin report.
    """
    import numpy as np

    r = result.report
    props = mass_properties(result.mesh)
    estimate = estimate_print(result.mesh, props.volume, infill=infill)
    density = estimate.mass_g / props.volume  # g/mm³, averaged over walls and infill
    moments, axes = np.linalg.eigh(props.inertia * density)
    warnings = list(result.warnings)
    ledges, lowest = overhang_area(result.mesh)
    figures: dict[str, object] = {
        "center_of_mass_mm": _rounded(props.center),
        "inertia_tensor_g_mm2": _rounded(props.inertia * density),
        "principal_moments": _rounded(moments),
        "principal_axes": _rounded(axes.T),
        "moments_unit": "g mm^2, about the centre of mass, print frame (z up)",
        "infill_percent": infill,
        "filament_mm3": round(estimate.filament_mm3, 6),
        "mass_g": round(estimate.mass_g, 9),
        "print_time_s": round(estimate.time_s),
        "print_time": format_duration(estimate.time_s),
        # voxel steps are horizontal ledges: what a slicer's automatic supports go under
        "support_area_mm2": round(ledges, 6),
        "support_lowest_mm": None if lowest is None else round(lowest, 6),
    }
    if spin:
        top = spin_report(result.mesh, props, pitch=result.pitch)
        figures["spin"] = {
            "tip_mm": _rounded(top.tip),
            "tip_width_mm": round(top.tip_width, 6),
            "tip_patches": top.tip_patches,
            "axis_offset_mm": round(top.axis_offset, 6),
            "center_height_mm": round(top.height, 6),
            "moment_ratio": round(top.moment_ratio, 6),
            "center_moment_ratio": round(top.center_ratio, 6),
            "sleep_rpm": round(top.sleep_rpm, 1),
            "spins": not top.warnings,
        }
        warnings += top.warnings
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
        **figures,
        "warnings": warnings,
    }


def estimate_line(report: dict[str, object]) -> str:
    """One line a maker reads before printing: size, PLA mass and print time (and the top's spin check)."""
    size = " x ".join(f"{s:g}" for s in report["size_mm"])  # type: ignore[attr-defined]
    line = (f"{size} mm, {report['mass_g']:.1f} g of PLA at {report['infill_percent']:g} % infill, "
            f"about {report['print_time']}")
    if report.get("support_lowest_mm") is not None:
        line += (f"; needs support under {report['support_area_mm2']:.0f} mm² of voxel ledges (the lowest "
                 f"{report['support_lowest_mm']:g} mm up)")
    else:
        line += "; no support needed (every layer stands on the one below)"
    spin = report.get("spin")
    if isinstance(spin, dict):
        verdict = "spins" if spin["spins"] else "wobbles"
        line += (f"; as a top it {verdict} (centre of mass {spin['axis_offset_mm']:.2f} mm off the tip's axis, "
                 f"moment ratio {spin['moment_ratio']:.2f} at the tip; upright above {spin['sleep_rpm']:.0f} rpm)")
    return line


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
        The mesh file to write (.3mf, .stl, .obj, .glb or .ply).  A coloured
        shape's colours go into every format but STL (a note says so); a 3MF holds
        at most :data:`MAX_FILAMENTS` of them (more are merged, with a warning).
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
    coloured = shape.colours is not None
    notes: list[str] = []
    if coloured and module.EXTENSION == ".stl":
        notes.append("STL holds no colour: the print is written in one (write .3mf to print its colours, "
                     ".glb, .obj or .ply to view them)")
        shape, coloured = shape.with_colours(None), False
    limit = options.colours
    if coloured and limit is None and module.EXTENSION == ".3mf":
        limit = MAX_FILAMENTS  # a printer holds no more: merge rather than write a file no printer prints
    elif not coloured and options.colours is not None:
        notes.append(f"colours = {options.colours}: the shape has no colours, so there is nothing to merge")
    result = build_mesh(
        shape, size=options.size, contacts=options.contacts, bridge_width=options.bridge_width,
        fill=options.solid, hollow=options.hollow, label=label, engrave_depth=options.engrave_depth,
        base=options.base, magnet=options.magnet, merge=options.merge, name=name, colours=limit,
    )
    if options.colours is None and limit is not None and result.filaments.visible > MAX_FILAMENTS:
        merged = (f"the shape shows {result.filaments.visible} colours, more than the {MAX_FILAMENTS} filaments a "
                  f"printer holds: merged to {MAX_FILAMENTS} (set colours, --colours N, to choose how many)")
        result = dataclasses.replace(result, warnings=(*result.warnings, merged))
    written = write_mesh(target, result.mesh, name=name)
    report = report_dict(result, name=name, infill=options.infill, spin=options.spin)
    if result.filaments is not None:
        report["colours"] = result.filaments.as_dict()
    if notes:
        report["notes"] = notes
    files = [OutputFile(target.name, module.DESCRIPTION)]
    files += [OutputFile(p.name, module.MATERIAL_DESCRIPTION) for p in written[1:]]
    if report_path is not None:
        rp = Path(report_path)
        write_text(rp, json.dumps(report, indent=2, sort_keys=True) + "\n")
        files.append(OutputFile(rp.relative_to(target.parent).as_posix(),
                                "size, volume, part count, mass, print time, centre of mass, moments and printability warnings of the mesh (JSON)"))
    return Artefact(tuple(files), tuple(report["warnings"]), report)  # type: ignore[arg-type]
