"""The slice-plate report: counts, material, stack height drift, warnings."""

from __future__ import annotations

import dataclasses
from typing import Any

from ._nest import PlateSheet
from ._stack import PlateStack

FORMAT = "voxfab-plates/1"
#: Stack height error, as a fraction of the object's height, that a maker is warned about.
DRIFT_WARNING = 0.01


@dataclasses.dataclass(frozen=True)
class PlatesReport:
    """What a plate stack takes to make, and what to watch for.

    Lengths in mm, areas in mm².

    Attributes
    ----------
    axis : str
        Slicing axis.
    pitch, thickness : float
        Voxel pitch and measured plate thickness.
    plates_per_layer : int
        Plates of every stack layer, or 0 when the layers take unequal numbers.
    voxel_layers : int
        Voxel layers of the shape along the axis.
    resampled : bool
        Whether the plate thickness resampled the layers (see :func:`layer_runs`).
    layers, pieces, plates, sheets, dowels : int
        Counts (``layers``: stack layers, each one voxel layer's outline).
    sheet_width, sheet_height : float
    material_area : float
        Area of all plates (dowel holes removed, no kerf).
    sheet_area : float
        Area of all sheets used.
    material_fraction : float
        ``material_area / sheet_area``.
    shape_height, stack_height, drift : float
        Voxel height ``voxel_layers × pitch``, plate stack height
        ``plates × thickness`` and their difference (the height error, under
        ``thickness / 2``).
    dowel_diameter, kerf, min_width : float
    dowel_length : float
        Length of one dowel: it goes through the plates of two layers.
    labels_hidden : int
        Labels placed where the next plate covers them.
    labels_on_plan : tuple of str
        Plates too small for a whole label of the smallest height: not engraved,
        named on the assembly plan instead (a label is never clipped).
    unsupported : tuple of str
        Pieces sharing no area with a neighbouring layer.
    thin : tuple of str
        Pieces with a part narrower than ``min_width``.
    undowelled : tuple of str
        Pieces with a neighbour but no room for a dowel hole.
    """

    axis: str
    pitch: float
    thickness: float
    plates_per_layer: int
    voxel_layers: int
    resampled: bool
    layers: int
    pieces: int
    plates: int
    sheets: int
    dowels: int
    sheet_width: float
    sheet_height: float
    material_area: float
    sheet_area: float
    material_fraction: float
    shape_height: float
    stack_height: float
    drift: float
    dowel_diameter: float
    dowel_length: float
    kerf: float
    min_width: float
    labels_hidden: int
    labels_on_plan: tuple[str, ...]
    unsupported: tuple[str, ...]
    thin: tuple[str, ...]
    undowelled: tuple[str, ...]

    def to_json(self) -> dict[str, Any]:
        """The report as a JSON-ready dict (with a ``format`` key)."""
        data = dataclasses.asdict(self)
        for key in ("labels_on_plan", "unsupported", "thin", "undowelled"):
            data[key] = list(data[key])
        return {"format": FORMAT, **data}


def _r(v: float) -> float:
    return round(float(v), 6) + 0.0


def _dowel_plates(counts: tuple[int, ...]) -> int:
    """Most plates one dowel goes through: those of two consecutive stack layers."""
    if len(counts) == 1:
        return 2 * counts[0]
    return max(a + b for a, b in zip(counts[:-1], counts[1:]))


def make_report(stack: PlateStack, sheets: tuple[PlateSheet, ...], *, kerf: float = 0.0) -> PlatesReport:
    """Build the report of a plate stack nested on ``sheets``."""
    material = sum(p.area for p in stack.plates)
    width = sheets[0].width if sheets else 0.0
    height = sheets[0].height if sheets else 0.0
    sheet_area = len(sheets) * width * height
    return PlatesReport(
        axis=stack.axis,
        pitch=_r(stack.pitch),
        thickness=_r(stack.thickness),
        plates_per_layer=stack.plates_per_layer,
        voxel_layers=stack.voxel_layers,
        resampled=stack.resampled,
        layers=len(stack.layers),
        pieces=sum(len(pcs) for pcs in stack.layers),
        plates=len(stack.plates),
        sheets=len(sheets),
        dowels=len(stack.dowels),
        sheet_width=_r(width),
        sheet_height=_r(height),
        material_area=_r(material),
        sheet_area=_r(sheet_area),
        material_fraction=_r(material / sheet_area) if sheet_area else 0.0,
        shape_height=_r(stack.nominal_height),
        stack_height=_r(stack.height),
        drift=_r(stack.drift),
        dowel_diameter=_r(stack.dowel_diameter),
        dowel_length=_r(_dowel_plates(stack.counts) * stack.thickness),
        kerf=_r(kerf),
        min_width=_r(stack.min_width),
        labels_hidden=sum(p.label.hidden for p in stack.plates),
        labels_on_plan=tuple(p.label.text for p in stack.plates if not p.label.complete),
        unsupported=stack.unsupported,
        thin=stack.thin,
        undowelled=stack.undowelled,
    )


def _ids(ids: tuple[str, ...], most: int = 6) -> str:
    shown = ", ".join(ids[:most])
    return shown + (f" and {len(ids) - most} more" if len(ids) > most else "")


def plate_warnings(report: PlatesReport) -> list[str]:
    """What a maker must know before cutting, one line each (empty when all is well)."""
    out = []
    if report.unsupported:
        out.append(f"{len(report.unsupported)} loose island(s) touch no plate above or below: "
                   f"{_ids(report.unsupported)}")
    if report.dowel_diameter > 0 and report.undowelled:
        out.append(f"{len(report.undowelled)} plate piece(s) without dowels (no room for a "
                   f"{report.dowel_diameter:g} mm hole): {_ids(report.undowelled)}")
    elif report.dowel_diameter == 0 and report.layers > 1:
        out.append("plates without dowels (dowel = 0): align the stack by the scored outlines")
    if abs(report.drift) > DRIFT_WARNING * report.shape_height:
        levels = round(report.stack_height / report.thickness)
        out.append(f"the stack is {report.stack_height:g} mm tall ({levels} plate layers of {report.thickness:g} mm), "
                   f"{report.drift:+g} mm from the object's {report.shape_height:g} mm")
    if report.thin:
        out.append(f"{len(report.thin)} piece(s) narrower than {report.min_width:g} mm somewhere: "
                   f"{_ids(report.thin)}")
    out += _label_warnings(report.labels_on_plan)
    return out


def _label_warnings(on_plan: tuple[str, ...], left_off: tuple[str, ...] = ()) -> list[str]:
    from ._labels import MIN_HEIGHT

    out = []
    if on_plan:
        out.append(f"{len(on_plan)} plate(s) too small for a whole {MIN_HEIGHT:g} mm label, not engraved: "
                   f"find them by the assembly plan: {_ids(on_plan)}")
    if left_off:
        out.append(f"{len(left_off)} slot(s) without their partner's label (no room for it whole): {_ids(left_off)}")
    return out


@dataclasses.dataclass(frozen=True)
class ConstructionReport:
    """What an interlocked or radial construction takes to make, and what to watch for.

    Lengths in mm, areas in mm².

    Attributes
    ----------
    style : str
        ``"interlocked"`` or ``"radial"``.
    pitch, thickness, clearance, kerf : float
    slot_width : float
        Width of the slots as cut (the hub slots of a radial construction).
    plates, crossings, sheets : int
    sheet_width, sheet_height, material_area, sheet_area, material_fraction : float
        As in :class:`PlatesReport`.
    size : tuple of float
        The shape's extents in mm, which the assembly fills.
    moved : tuple of str
        ``"plate/partner"`` crossings whose slots were moved off the middle to keep a plate whole.
    left_out : tuple of str
        Sections left out because they cross no plate of the construction.
    trimmed : tuple of str
        Plates that lost a part a slot cut off.
    thin : tuple of str
        Plates with a part narrower than ``min_width`` (a strip beside a slot, a thin wall).
    min_width : float
    labels_on_plan : tuple of str
        Plates too small for a whole label: not engraved, named on the plan.
    marks_left_off : tuple of str
        ``"plate/partner"`` slots without the partner's label, for want of room for it whole.
    steps : tuple of str
        The assembly order.
    filled_voxels : int
        Voxels of the shape's closed cavities that the plates run through, so that no plate
        has a hole whose scrap is cut but not assembled.
    ways_to_keep : tuple of str
        When sections are left out: other options (a finer pitch, thinner plates) that keep
        them all, each checked by making the construction with them.
    ways_tried : tuple of str
        The options tried for that, as ``voxfab slices`` options.
    """

    style: str
    pitch: float
    thickness: float
    clearance: float
    kerf: float
    slot_width: float
    plates: int
    crossings: int
    sheets: int
    sheet_width: float
    sheet_height: float
    material_area: float
    sheet_area: float
    material_fraction: float
    size: tuple[float, ...]
    moved: tuple[str, ...]
    left_out: tuple[str, ...]
    trimmed: tuple[str, ...]
    thin: tuple[str, ...]
    min_width: float
    labels_on_plan: tuple[str, ...]
    marks_left_off: tuple[str, ...]
    steps: tuple[str, ...]
    weak: tuple[str, ...] = ()
    advice: tuple[str, ...] = ()
    filled_voxels: int = 0
    ways_to_keep: tuple[str, ...] = ()
    ways_tried: tuple[str, ...] = ()

    def to_json(self) -> dict[str, Any]:
        """The report as a JSON-ready dict (with a ``format`` key)."""
        data = dataclasses.asdict(self)
        for key in ("size", "moved", "left_out", "trimmed", "thin", "labels_on_plan", "marks_left_off", "steps",
                    "weak", "advice", "ways_to_keep", "ways_tried"):
            data[key] = list(data[key])
        return {"format": FORMAT, **data}


def make_construction_report(construction: Any, sheets: tuple[PlateSheet, ...], *, kerf: float = 0.0,
                             min_width: float = 0.0) -> ConstructionReport:
    """Build the report of a slotted construction nested on ``sheets``.

    ``min_width`` is the narrowest cuttable feature in mm; ``2 × kerf`` is used when larger.
    """
    from ._stack import _is_thin

    narrow = max(min_width, 2.0 * kerf)
    material = sum(p.area for p in construction.plates)
    width = sheets[0].width if sheets else 0.0
    height = sheets[0].height if sheets else 0.0
    sheet_area = len(sheets) * width * height
    slot = max((s.width for p in construction.plates for s in p.slots), default=0.0)
    return ConstructionReport(
        style=construction.style,
        pitch=_r(construction.pitch),
        thickness=_r(construction.thickness),
        clearance=_r(construction.clearance),
        kerf=_r(kerf),
        slot_width=_r(slot),
        plates=len(construction.plates),
        crossings=len(construction.crossings),
        sheets=len(sheets),
        sheet_width=_r(width),
        sheet_height=_r(height),
        material_area=_r(material),
        sheet_area=_r(sheet_area),
        material_fraction=_r(material / sheet_area) if sheet_area else 0.0,
        size=tuple(_r(s) for s in construction.size),
        moved=construction.moved,
        left_out=construction.left_out,
        trimmed=construction.trimmed,
        thin=tuple(p.text for p in construction.plates if narrow > 0 and _is_thin(p.outline, narrow)),
        min_width=_r(narrow),
        # the plates' own labels and the partners' labels beside their slots
        labels_on_plan=tuple(p.label.text for p in construction.plates if not p.label.complete),
        marks_left_off=tuple(f"{p.text}/{m}" for p in construction.plates for m in p.marks_left_off),
        steps=construction.steps,
        weak=construction.weak,
        advice=construction.advice,
        filled_voxels=construction.filled,
    )


def construction_warnings(report: ConstructionReport) -> list[str]:
    """What a maker must know before cutting a slotted construction, one line each."""
    out = list(report.advice)
    if report.moved:
        out.append(f"{len(report.moved)} slot pair(s) moved off the crossing's middle to keep a plate whole: "
                   f"{_ids(report.moved)}")
    if report.trimmed:
        out.append(f"{len(report.trimmed)} plate(s) lost a part that a slot cut off: {_ids(report.trimmed)}")
    if report.weak:
        out.append(f"{len(report.weak)} crossing(s) dropped, the plates would engage over less than half their "
                   f"height there: {_ids(report.weak)}")
    if report.left_out:
        ways = (f"; to keep them: {', or '.join(report.ways_to_keep)}" if report.ways_to_keep else
                f"; no finer pitch or thinner plates tried keeps them ({'; '.join(report.ways_tried)})")
        out.append(f"{len(report.left_out)} section(s) left out, they cross no other plate: {_ids(report.left_out)}"
                   + ways)
    if report.thin:
        out.append(f"{len(report.thin)} plate(s) narrower than {report.min_width:g} mm somewhere: {_ids(report.thin)}")
    out += _label_warnings(report.labels_on_plan, report.marks_left_off)
    return out
