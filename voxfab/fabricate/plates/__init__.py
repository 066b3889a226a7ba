"""Slice plates: a voxel shape as a stack of laser-cut plates, nested on sheets.

Pipeline: :func:`make_plates` slices the shape along an axis into exact voxel
outlines (one polygon with holes per 4-connected piece, numbered
``layer-piece``), gives each piece as many plates as the measured thickness
asks, drills dowel holes through the overlap of consecutive layers, engraves
single-stroke labels where the next plate hides them and scores the next
layer's outline.  :func:`nest_plates` packs the plates onto sheets, and the
writers make one DXF (R2000 in mm, or R12) and one SVG per sheet, an assembly PDF and,
optionally, STEP and STL of the plate stack.  :func:`make_slices` runs it all
and :func:`write_slices` writes the files with ``plates.json`` and
``assembly.3mf`` (the plates as assembled, in the print mesh's frame).

Two slotted styles need no glue: ``interlocked`` (two families of plates
half-lapped into each other, :func:`make_interlocked`) and ``radial`` (plates
fanned about the vertical axis and joined at a tiered hub, :func:`make_radial`).
They are nested, labelled and written by the same steps.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import PathLike
from voxfab.drawing.dxf import DEFAULT_DXF_VERSION
from voxfab.fabricate._outputs import Artefact, OutputFile
from voxfab.shape import VoxelShape

from ._assembly import assembly_3mf, write_assembly_3mf
from ._colour import PlateColour, construction_colours, nest_by_colour, stack_colours
from ._dowels import Dowel, Joint, find_joints
from ._labels import Label, text_strokes
from ._nest import PlacedPart, PlateSheet, nest_plates
from ._options import PlateOptions
from ._order import construction_pdf, write_construction_pdf
from ._outline import Axis, Piece, slice_layers
from ._radial import make_radial
from ._report import (
    ConstructionReport,
    PlatesReport,
    construction_warnings,
    make_construction_report,
    make_report,
    plate_warnings,
)
from ._slotted import Construction, Slot, SlottedPlate, make_interlocked
from ._stack import Plate, PlateStack, make_plates
from ._step import stack_compound, step_bytes, write_step, write_stl
from .dxf import sheet_dxf, write_dxf
from .pdf import assembly_pdf, write_assembly_pdf
from .svg import sheet_svg, write_svg

__all__ = [
    "Axis",
    "Construction",
    "ConstructionReport",
    "Slot",
    "SlottedPlate",
    "assembly_3mf",
    "construction_pdf",
    "construction_warnings",
    "make_construction_report",
    "make_construction",
    "make_interlocked",
    "make_radial",
    "write_assembly_3mf",
    "write_construction_pdf",
    "Dowel",
    "Joint",
    "Label",
    "PlateColour",
    "Piece",
    "PlacedPart",
    "Plate",
    "PlateOptions",
    "PlateStack",
    "PlatesReport",
    "PlateSheet",
    "Slices",
    "assembly_pdf",
    "fabricate_plates",
    "find_joints",
    "make_plates",
    "make_report",
    "make_slices",
    "nest_plates",
    "plate_warnings",
    "sheet_dxf",
    "sheet_stem",
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
    """A plate stack or a slotted construction, its sheets and its report.

    ``stack`` is set for the stacked style, ``construction`` for the others;
    ``colours`` holds the main colour of each plate (in plate order) when the shape has colours.
    """

    stack: PlateStack | None
    sheets: tuple[PlateSheet, ...]
    report: PlatesReport | ConstructionReport
    construction: Construction | None = None
    colours: tuple[PlateColour | None, ...] | None = None

    @property
    def plates(self) -> tuple[Plate, ...]:
        """Every plate to cut."""
        return self.stack.plates if self.stack is not None else self.construction.plates

    @property
    def style(self) -> str:
        """``"stacked"``, ``"interlocked"`` or ``"radial"``."""
        return "stacked" if self.stack is not None else self.construction.style


#: The defaults of :func:`make_slices`, the recipe's and the CLI's: one declaration.
_DEFAULTS = PlateOptions()


def make_slices(
    shape: VoxelShape | npt.ArrayLike,
    *,
    pitch: float | None = None,
    axis: str | Axis = _DEFAULTS.axis,
    thickness: float = _DEFAULTS.thickness,
    sheet: str | tuple[float, float] = _DEFAULTS.sheet,
    margin: float = _DEFAULTS.margin,
    spacing: float = _DEFAULTS.spacing,
    kerf: float = _DEFAULTS.kerf,
    dowel: float = _DEFAULTS.dowel,
    dowel_margin: float = _DEFAULTS.dowel_margin,
    dowels_per_joint: int = _DEFAULTS.dowels_per_joint,
    score: bool = _DEFAULTS.score,
    min_width: float = _DEFAULTS.min_width,
    style: str = _DEFAULTS.style,
    axes: str = _DEFAULTS.axes,
    count: int = _DEFAULTS.count,
    interval: float = _DEFAULTS.interval,
    radial_plates: int = _DEFAULTS.radial_plates,
    clearance: float = _DEFAULTS.clearance,
    by_colour: bool = _DEFAULTS.by_colour,
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
    style : {'stacked', 'interlocked', 'radial'}
        The construction.
    axes, count, interval, clearance
        Interlocked plates, see :func:`make_interlocked`.
    radial_plates, clearance
        Radial plates, see :func:`make_radial`.
    by_colour : bool
        Nest the plates of each main colour on sheets of their own (a shape with colours).

    Returns
    -------
    Slices
    """
    if isinstance(shape, VoxelShape):
        grid, default_pitch, colours = shape.grid, shape.pitch, shape.colours
    else:
        grid, default_pitch, colours = np.asarray(shape), 1.0, None
    nest = {"sheet": sheet, "margin": margin, "spacing": spacing, "kerf": kerf}
    pitch = default_pitch if pitch is None else pitch
    if style in ("interlocked", "radial"):
        construction = make_construction(grid, pitch=pitch, style=style, thickness=thickness, axes=axes, count=count,
                                         interval=interval, radial_plates=radial_plates, clearance=clearance,
                                         min_width=min_width, kerf=kerf)
        plate_colours = construction_colours(construction, colours) if colours is not None else None
        sheets = _nest(construction.plates, plate_colours, by_colour, nest)
        report = make_construction_report(construction, sheets, kerf=kerf, min_width=min_width)
        return Slices(None, sheets, report, construction, plate_colours)
    if style != "stacked":
        from voxfab.errors import InvalidShapeError

        raise InvalidShapeError(f"style: expected stacked, interlocked or radial, got {style!r}")
    stack = make_plates(
        grid,
        pitch=pitch,
        axis=axis,
        thickness=thickness,
        dowel=dowel,
        dowel_margin=dowel_margin,
        dowels_per_joint=dowels_per_joint,
        score=score,
        min_width=min_width,
        kerf=kerf,
    )
    plate_colours = stack_colours(stack, colours) if colours is not None else None
    sheets = _nest(stack.plates, plate_colours, by_colour, nest)
    return Slices(stack, sheets, make_report(stack, sheets, kerf=kerf), colours=plate_colours)


def _nest(plates: tuple[Plate, ...], plate_colours: tuple[PlateColour | None, ...] | None, by_colour: bool,
          nest: dict) -> tuple[PlateSheet, ...]:
    if by_colour and plate_colours is not None:
        return nest_by_colour(plates, plate_colours, **nest)
    return nest_plates(plates, **nest)


def make_construction(grid: npt.ArrayLike, *, pitch: float, style: str, thickness: float, axes: str, count: int,
                      interval: float, radial_plates: int, clearance: float, min_width: float,
                      kerf: float) -> Construction:
    """The interlocked or radial construction of :func:`make_slices` (strips under ``min_width`` or two kerfs go)."""
    width = max(min_width, 2.0 * kerf)
    if style == "interlocked":
        return make_interlocked(grid, pitch=pitch, thickness=thickness, axes=axes, count=count, interval=interval,
                                clearance=clearance, min_width=width)
    return make_radial(grid, pitch=pitch, thickness=thickness, count=radial_plates, clearance=clearance,
                       min_width=width)


def _r(v: float) -> float:
    return round(float(v), 4) + 0.0


def _slotted_json(result: Slices, name: str) -> dict:
    """The report plus, per plate, its plane, where it is cut and its slots."""
    where = {part.plate.number: (sheet.index, part) for sheet in result.sheets for part in sheet.parts}
    plates = []
    for p in result.construction.plates:
        sheet_index, part = where[p.number]
        flat = p.style != "radial" or p.family == "H"  # a radial construction's ring lies flat
        plane = {"axis": p.axis, "offset": _r(p.offset)} if flat else {"angle": _r(p.angle)}
        plates.append({
            "number": p.number,
            "style": p.style,
            "family": p.family,
            "plane": plane,
            "label": p.label.text,
            "area": _r(p.area),
            "origin": [_r(v) for v in p.origin],
            "u": [_r(v) for v in p.u_dir],
            "v": [_r(v) for v in p.v_dir],
            "sheet": sheet_index,
            "turns": part.turns,
            "inside": part.host,
            "offset": [_r(v) for v in part.offset],
            "slots": [{"position": _r(s.position), "width": _r(s.width), "depth": _r(s.depth),
                       "edge": _r(s.edge), "end": _r(s.end), "side": s.side, "runs": s.runs,
                       "partner": s.partner, "moved": s.moved} for s in p.slots],
        })
    return {**result.report.to_json(), "name": name, "plates_list": plates,
            "crossings": [list(c) for c in result.construction.crossings]}


def sheet_stem(sheet: PlateSheet, count: int) -> str:
    """File name stem of a sheet among ``count``: ``sheet-01``, or ``sheet-01-c83232`` for a sheet of one colour."""
    stem = f"sheet-{sheet.index:0{max(2, len(str(count)))}d}"
    return f"{stem}-{sheet.colour.lstrip('#')}" if sheet.colour else stem


def _colours_json(result: Slices, data: dict) -> dict:
    """Each plate's main colour, the plates and sheets of each colour, and each sheet's colour and file."""
    if result.colours is None:
        return data
    for record, colour in zip(data["plates_list"], result.colours):
        record["colour"] = colour.to_json() if colour is not None else None
    sheet_of = {part.plate.number: sheet.index for sheet in result.sheets for part in sheet.parts}
    groups: dict[str, list[Plate]] = {}
    for p, colour in zip(result.plates, result.colours):
        groups.setdefault(colour.hex if colour is not None else "", []).append(p)
    data["colours"] = [{"colour": hex_ or None, "plates": [p.number for p in group],
                        "area": _r(sum(p.area for p in group)),
                        "sheets": sorted({sheet_of[p.number] for p in group})} for hex_, group in groups.items()]
    data["by_colour"] = any(sheet.colour for sheet in result.sheets)
    data["sheets_list"] = [{"index": sheet.index, "colour": sheet.colour or None,
                            "file": sheet_stem(sheet, len(result.sheets)) + ".dxf",
                            "plates": [part.plate.number for part in sheet.parts]} for sheet in result.sheets]
    return data


def plates_json(result: Slices, *, name: str = "") -> dict:
    """The report plus one record per plate (where it is cut) and per dowel (stacked) or slot.

    For a shape with colours, also each plate's main colour, the plates and sheets of each colour
    and each sheet's colour.
    """
    if result.stack is None:
        return _colours_json(result, _slotted_json(result, name))
    where = {part.plate.number: (sheet.index, part) for sheet in result.sheets for part in sheet.parts}
    plates = []
    for p in result.stack.plates:
        sheet_index, part = where[p.number]
        plates.append({
            "number": p.number,
            "style": "stacked",
            "family": "",
            "plane": {"axis": result.stack.axis, "offset": _r(p.z + p.thickness / 2)},
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
    return _colours_json(result, {**result.report.to_json(), "name": name, "plates_list": plates,
                                  "dowels_list": dowels})


def write_slices(result: Slices, folder: PathLike, *, name: str = "", step: bool = False,
                 dxf_version: str = DEFAULT_DXF_VERSION.value) -> list[OutputFile]:
    """Write sheets (DXF + SVG), ``assembly.pdf``, ``plates.json`` and optionally STEP/STL.

    Returns
    -------
    files : list of OutputFile
        Paths relative to ``folder``.
    """
    folder = Path(folder)
    files: list[OutputFile] = []
    for sheet in result.sheets:
        stem = sheet_stem(sheet, len(result.sheets))
        material = f", material {sheet.colour}" if sheet.colour else ""
        write_dxf(sheet, folder / f"{stem}.dxf", version=dxf_version)
        files.append(OutputFile(f"{stem}.dxf", f"sheet {sheet.index} for laser cutting (DXF {dxf_version}, mm: "
                                               f"CUT, SCORE, LABEL{material})"))
        write_svg(sheet, folder / f"{stem}.svg")
        files.append(OutputFile(f"{stem}.svg", f"sheet {sheet.index} for laser cutting (SVG, mm{material})"))
    if result.stack is not None:
        write_assembly_pdf(result.stack, folder / "assembly.pdf", title=name)
        files.append(OutputFile("assembly.pdf", "assembly instructions: stack order as a grid of layers"))
        axis = result.stack.axis
    else:
        write_construction_pdf(result.construction, folder / "assembly.pdf", title=name)
        files.append(OutputFile("assembly.pdf", "assembly instructions: the order of slotting and a plan view"))
        axis = "z"
    write_assembly_3mf(result.plates, folder / "assembly.3mf", axis=axis, name=name)
    files.append(OutputFile("assembly.3mf", "the plates as assembled, one object per plate label (3MF, mm, "
                                            "the print mesh's frame)"))
    if step and result.stack is not None:
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
    if options.step and options.style == "stacked":
        from voxfab._shared.deps import require_extra  # refuse before any work

        require_extra("cad", "step (STEP and STL of the plate stack)")
    result = make_slices(
        shape, axis=options.axis, thickness=options.thickness, sheet=options.sheet, margin=options.margin,
        spacing=options.spacing, kerf=options.kerf, dowel=options.dowel, dowel_margin=options.dowel_margin,
        dowels_per_joint=options.dowels_per_joint, score=options.score, min_width=options.min_width,
        style=options.style, axes=options.axes, count=options.count, interval=options.interval,
        radial_plates=options.radial_plates, clearance=options.clearance, by_colour=options.by_colour,
    )
    if result.construction is not None and result.construction.left_out:
        from ._ways import ways_to_keep

        ways, tried = ways_to_keep(shape.grid, shape.pitch, options)
        result = dataclasses.replace(result, report=dataclasses.replace(
            result.report, ways_to_keep=tuple(str(w) for w in ways), ways_tried=tried))
    with atomic_dir(folder, marker="plates.json") as tmp:
        files = write_slices(result, tmp, name=name, step=options.step, dxf_version=options.dxf_version)
    warnings = plate_warnings(result.report) if result.stack is not None else construction_warnings(result.report)
    if options.by_colour and shape.colours is None:
        warnings.append("by_colour: the shape has no colours; the plates are nested together")
    return Artefact(tuple(files), tuple(warnings), result.report.to_json())
