"""Slice plates: a voxel shape as a stack of laser-cut plates, nested on sheets.

Pipeline: :func:`make_plates` slices the shape along an axis into exact voxel
outlines (one polygon with holes per 4-connected piece, numbered
``layer-piece``), gives each piece as many plates as the measured thickness
asks, drills dowel holes through the overlap of consecutive layers, engraves
single-stroke labels where the next plate hides them and scores the next
layer's outline.  :func:`nest_plates` packs the plates onto sheets, and the
writers make one DXF (R12) and one SVG per sheet, an assembly PDF and,
optionally, STEP and STL of the plate stack.  :func:`make_slices` runs it all
and :func:`write_slices` writes the files with ``plates.json``.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import PathLike
from voxfab.fabricate._outputs import Artefact, OutputFile
from voxfab.shape import VoxelShape

from ._dowels import Dowel, Joint, find_joints
from ._labels import Label, text_strokes
from ._nest import PlacedPart, Sheet, nest_plates, parse_sheet
from ._options import PlateOptions
from ._outline import Axis, Piece, slice_layers
from ._report import PlatesReport, make_report, plate_warnings
from ._stack import Plate, PlateStack, make_plates
from ._step import stack_compound, step_bytes, write_step, write_stl
from .dxf import sheet_dxf, write_dxf
from .pdf import assembly_pdf, write_assembly_pdf
from .svg import sheet_svg, write_svg

__all__ = [
    "Axis",
    "Dowel",
    "Joint",
    "Label",
    "Piece",
    "PlacedPart",
    "Plate",
    "PlateOptions",
    "PlateStack",
    "PlatesReport",
    "Sheet",
    "Slices",
    "assembly_pdf",
    "fabricate_plates",
    "find_joints",
    "make_plates",
    "make_report",
    "make_slices",
    "nest_plates",
    "parse_sheet",
    "plate_warnings",
    "sheet_dxf",
    "sheet_svg",
    "slice_layers",
    "stack_compound",
    "step_bytes",
    "text_strokes",
    "write_assembly_pdf",
    "write_dxf",
    "write_slices",
    "write_step",
    "write_stl",
    "write_svg",
]


@dataclasses.dataclass(frozen=True, eq=False)
class Slices:
    """A plate stack, its sheets and its report."""

    stack: PlateStack
    sheets: tuple[Sheet, ...]
    report: PlatesReport


def make_slices(
    shape: VoxelShape | npt.ArrayLike,
    *,
    pitch: float | None = None,
    axis: str | Axis = "z",
    thickness: float = 3.0,
    sheet: str | tuple[float, float] = "600x400",
    margin: float = 5.0,
    spacing: float = 2.0,
    kerf: float = 0.0,
    dowel: float = 3.0,
    dowel_margin: float = 1.0,
    dowels_per_joint: int = 2,
    score: bool = True,
    min_width: float = 1.0,
) -> Slices:
    """Slice a shape into plates and nest them onto sheets.

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
    pitch : float or None
        Voxel edge in mm; ``None`` takes the shape's pitch (1.0 for an array).
    axis, thickness, dowel, dowel_margin, dowels_per_joint, score, min_width
        See :func:`make_plates`.
    sheet, margin, spacing, kerf
        See :func:`nest_plates`.

    Returns
    -------
    Slices
    """
    if isinstance(shape, VoxelShape):
        grid, default_pitch = shape.grid, shape.pitch
    else:
        grid, default_pitch = np.asarray(shape), 1.0
    stack = make_plates(
        grid,
        pitch=default_pitch if pitch is None else pitch,
        axis=axis,
        thickness=thickness,
        dowel=dowel,
        dowel_margin=dowel_margin,
        dowels_per_joint=dowels_per_joint,
        score=score,
        min_width=min_width,
        kerf=kerf,
    )
    sheets = nest_plates(stack.plates, sheet=sheet, margin=margin, spacing=spacing, kerf=kerf)
    return Slices(stack, sheets, make_report(stack, sheets, kerf=kerf))


def _r(v: float) -> float:
    return round(float(v), 4) + 0.0


def plates_json(result: Slices, *, name: str = "") -> dict:
    """The report plus one record per plate (where it is cut) and per dowel."""
    where = {part.plate.number: (sheet.index, part) for sheet in result.sheets for part in sheet.parts}
    plates = []
    for p in result.stack.plates:
        sheet_index, part = where[p.number]
        plates.append({
            "number": p.number,
            "label": p.label.text,
            "layer": p.layer,
            "voxel_layer": result.stack.sources[p.layer - 1],
            "piece": p.piece,
            "copy": p.copy,
            "z": _r(p.z),
            "voxels": p.cells,
            "area": _r(p.area),
            "holes": [[_r(x), _r(y)] for x, y in p.holes],
            "label_hidden": p.label.hidden,
            "sheet": sheet_index,
            "turns": part.turns,
            "inside": part.host,
            "offset": [_r(v) for v in part.offset],
        })
    dowels = [
        {"x": _r(d.x), "y": _r(d.y), "lower": d.lower, "upper": d.upper, "clearance": _r(d.clearance)}
        for d in result.stack.dowels
    ]
    return {**result.report.to_json(), "name": name, "plates_list": plates, "dowels_list": dowels}


def write_slices(result: Slices, folder: PathLike, *, name: str = "", step: bool = False) -> list[OutputFile]:
    """Write sheets (DXF + SVG), ``assembly.pdf``, ``plates.json`` and optionally STEP/STL.

    Returns
    -------
    files : list of OutputFile
        Paths relative to ``folder``.
    """
    folder = Path(folder)
    files: list[OutputFile] = []
    digits = max(2, len(str(len(result.sheets))))
    for sheet in result.sheets:
        stem = f"sheet-{sheet.index:0{digits}d}"
        write_dxf(sheet, folder / f"{stem}.dxf")
        files.append(OutputFile(f"{stem}.dxf", f"sheet {sheet.index} for laser cutting (DXF R12: CUT, SCORE, LABEL)"))
        write_svg(sheet, folder / f"{stem}.svg")
        files.append(OutputFile(f"{stem}.svg", f"sheet {sheet.index} for laser cutting (SVG, mm)"))
    write_assembly_pdf(result.stack, folder / "assembly.pdf", title=name)
    files.append(OutputFile("assembly.pdf", "assembly instructions: stack order as a grid of layers"))
    if step:
        compound = stack_compound(result.stack)
        write_step(result.stack, folder / "plates.step", compound=compound)
        files.append(OutputFile("plates.step", "3D plate stack (STEP, mm)"))
        write_stl(result.stack, folder / "plates.stl", compound=compound)
        files.append(OutputFile("plates.stl", "3D plate stack (binary STL, mm)"))
    write_text(folder / "plates.json", json.dumps(plates_json(result, name=name), indent=2, sort_keys=True) + "\n")
    files.append(OutputFile("plates.json", "plate report: counts, material, stack height drift, warnings"))
    return files


def fabricate_plates(shape: VoxelShape, options: PlateOptions, folder: PathLike, *, name: str) -> Artefact:
    """The plates pipeline: slice, nest and write the sheets, the assembly PDF and ``plates.json``.

    The CLI (``voxfab slices``), recipes (output ``slices``), the studio and batch
    runs all call this.  The folder is assembled under a temporary name and
    replaces ``folder`` whole, so no stale sheet of an earlier run remains.

    Parameters
    ----------
    shape : VoxelShape
        The shape; ``shape.pitch`` is the mm per voxel.
    options : PlateOptions
        Checked options.
    folder : path-like
        Output folder: new, empty, or an earlier plates output (replaced).
    name : str
        The shape's name, in the assembly PDF and the report.

    Returns
    -------
    Artefact
        Files relative to ``folder``, the maker's warnings, and the report.
    """
    from voxfab._shared.atomic import atomic_dir, check_output

    folder = Path(folder)
    check_output(folder, folder=True, parents=True, marker="plates.json")  # before any work
    if options.step:
        from voxfab._shared.deps import require_extra  # refuse before any work

        require_extra("cad", "step (STEP and STL of the plate stack)")
    result = make_slices(
        shape, axis=options.axis, thickness=options.thickness, sheet=options.sheet, margin=options.margin,
        spacing=options.spacing, kerf=options.kerf, dowel=options.dowel, dowel_margin=options.dowel_margin,
        dowels_per_joint=options.dowels_per_joint, score=options.score, min_width=options.min_width,
    )
    with atomic_dir(folder, marker="plates.json") as tmp:
        files = write_slices(result, tmp, name=name, step=options.step)
    return Artefact(tuple(files), tuple(plate_warnings(result.report)), result.report.to_json())
