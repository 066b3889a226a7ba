"""Slotted constructions: interlocked (waffle) and radial plates that slide into each other.

Every plate is the exact section of the voxel solid across its thickness: the
solid swept by the plate holds the whole plate, so no plate sticks out of the
shape.  Plates meet at *crossings*, where each gets a slot from opposite edges
(half-lap): the plate slotted from the top keeps its material below the slot
end, its partner slotted from the bottom keeps its material above, so the two
never share volume and slide together along the crossing line.

Radial constructions are :mod:`._radial`'s; the plates, slots and joints
they share are here.

Geometry is in mm.  A plate's drawing frame ``(u, v)`` maps to the assembly
frame (origin at the shape's minimum corner, z up, as the print mesh) by
``origin + u·U + v·V``; the plate spans ``±thickness / 2`` along ``N = U × V``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid, check_positive
from voxfab.errors import FabricationError, InvalidShapeError
from voxfab.shape import crop, fill_cavities

from ._labels import full_height, place_label
from ._outline import cells_outline, label_layer, scaled
from ._stack import Plate

#: Most plates a slotted construction may have (each is a laser job and a slotting step).
MAX_SLOTTED_PLATES = 400
#: Most plates of a radial construction (at 36 the hub slot is 11.5 plate thicknesses wide).
MAX_RADIAL_PLATES = 36
_AXES = "xyz"


@dataclasses.dataclass(frozen=True)
class Slot:
    """One half-lap slot of a plate, in the plate's frame (mm).

    Attributes
    ----------
    position : float
        ``u`` of the slot's centre line.
    width : float
        Slot width as cut (material thickness plus fit clearance, or the hub width).
    edge, end : float
        ``v`` where the slot opens (the plate's edge) and where it ends.
    depth : float
        ``|edge - end|``.
    side : str
        ``"top"`` (opens upwards, towards +v) or ``"bottom"``.
    partner : str
        Label of the plate that slides into this slot.
    moved : bool
        Whether the slot end left the crossing's middle to keep a plate whole.
    runs : str
        The frame axis the slot runs along (``"v"``, or ``"u"`` when the crossing axis is the plate's u),
        or ``"radial"`` for a ring's slot: it runs from ``centre`` at ``position`` degrees, ``edge``
        and ``end`` being signed distances from ``centre`` along that direction.
    """

    position: float
    width: float
    edge: float
    end: float
    depth: float
    side: str
    partner: str
    moved: bool = False
    runs: str = "v"
    centre: tuple[float, float] = (0.0, 0.0)

    def box(self) -> object:
        """The slot as a shapely polygon in the plate's frame."""
        if self.runs == "radial":
            return radial_box(self.centre, self.position, self.width, self.edge, self.end)
        return slot_box(0 if self.runs == "v" else 1, self.position, self.width, self.edge, self.end)


@dataclasses.dataclass(frozen=True, eq=False)
class SlottedPlate(Plate):
    """A plate of a slotted construction: its plane, its frame in the assembly and its slots.

    ``outline`` is the section with the slots cut.  ``layer`` is the family
    (1 = A, 2 = B; radial plates: 1), ``piece`` the plate's index in it.
    """

    style: str = "interlocked"
    family: str = "A"
    axis: str = "x"
    offset: float = 0.0
    angle: float = 0.0
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    u_dir: tuple[float, float, float] = (1.0, 0.0, 0.0)
    v_dir: tuple[float, float, float] = (0.0, 0.0, 1.0)
    slots: tuple[Slot, ...] = ()
    text: str = ""
    #: Partners whose labels found no room for a whole label beside their slots (none is clipped).
    marks_left_off: tuple[str, ...] = ()

    @property
    def id(self) -> str:
        """The plate's label."""
        return self.text

    @property
    def normal(self) -> npt.NDArray[np.float64]:
        """``U × V``: the direction of the plate's thickness."""
        return np.cross(self.u_dir, self.v_dir)

    def to_assembly(self, uv: npt.ArrayLike, s: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Map plate points ``(n, 2)`` and offsets ``s`` along the normal to assembly mm ``(n, 3)``."""
        uv = np.asarray(uv, dtype=np.float64).reshape(-1, 2)
        s = np.broadcast_to(np.asarray(s, dtype=np.float64), (len(uv),))
        return (np.asarray(self.origin) + uv[:, :1] * np.asarray(self.u_dir) + uv[:, 1:] * np.asarray(self.v_dir)
                + s[:, None] * self.normal)


@dataclasses.dataclass(frozen=True, eq=False)
class Construction:
    """The plates of an interlocked or radial construction and what was found while making them.

    Attributes
    ----------
    style : str
    pitch, thickness, clearance : float
    plates : tuple of SlottedPlate
        In assembly order.
    crossings : tuple of (str, str)
        Plate label pairs joined by slots (top-slotted plate first).
    moved : tuple of str
        ``"label/partner"`` of slots moved or shortened to keep a plate whole.
    left_out : tuple of str
        Sections left out: they cross no plate of the construction (they would be loose).
    trimmed : tuple of str
        Plates that lost a part a slot cut off, although the slot was moved.
    size : (float, float, float)
        The shape's extents in mm.
    steps : tuple of str
        The assembly order, one instruction each.
    weak : tuple of str
        ``"label/partner"`` crossings dropped because the plates would engage there over
        less than half the height of the shorter one (a joint that does not hold).
    advice : tuple of str
        What went wrong with the options asked for, and the ways out (a radial hub
        slot wider than the solid's neck: fewer or thinner plates).
    filled : int
        Voxels of the shape's closed cavities, which the plates run through (see :func:`solid_grid`).
    """

    style: str
    pitch: float
    thickness: float
    clearance: float
    plates: tuple[SlottedPlate, ...]
    crossings: tuple[tuple[str, str], ...]
    moved: tuple[str, ...]
    left_out: tuple[str, ...]
    trimmed: tuple[str, ...]
    size: tuple[float, float, float]
    steps: tuple[str, ...]
    weak: tuple[str, ...] = ()
    advice: tuple[str, ...] = ()
    filled: int = 0


def solid_grid(grid: npt.ArrayLike) -> tuple[npt.NDArray[np.bool_], int]:
    """The shape cropped with its closed cavities filled, and how many voxels that filled.

    A section through a closed cavity (a hollow vase) would be a plate with a hole, whose
    scrap the laser cuts out: a loose piece the assembly does not use.  The cavity is out of
    sight inside the shell, so the plates run through it whole: what is cut is what is assembled.
    """
    g = as_grid(grid, name="shape")
    full = fill_cavities(g)
    return crop(full), int(full.sum() - g.sum())


def _unit(axis: int) -> tuple[float, float, float]:
    e = [0.0, 0.0, 0.0]
    e[axis] = 1.0
    return (e[0], e[1], e[2])


def plane_layers(layers: int, count: int, pitch: float, interval: float, thickness: float = 0.0) -> list[int]:
    """Voxel layers (0-based) whose middles carry a family's plates, spread evenly.

    ``count`` plates, or when 0 one per ``interval`` mm of the shape's extent
    (at least one).  Planes sit at layer middles, so a plate no thicker than a
    voxel lies inside one voxel layer; a plane nearer than ``thickness`` to the
    one before is dropped, so plates of a family never overlap.
    """
    n = count if count > 0 else max(1, int(math.floor(layers * pitch / interval + 1e-9)))
    n = min(n, layers)
    picks = np.round((np.arange(n) + 0.5) * layers / n - 0.5).astype(int)
    kept: list[int] = []
    for i in sorted(set(int(i) for i in np.clip(picks, 0, layers - 1))):
        if not kept or (i - kept[-1]) * pitch > thickness + 1e-9:
            kept.append(i)
    return kept


def slab_section(grid: npt.NDArray[np.bool_], axis: int, centre: float, pitch: float,
                 thickness: float) -> npt.NDArray[np.bool_]:
    """Cells (of the two other axes, in order) filled in every voxel layer the plate's slab meets.

    A plate of ``thickness`` centred at ``centre`` mm along ``axis`` covers those
    cells inside the solid; a slab that leaves the grid has no section.
    """
    lo = int(math.floor((centre - thickness / 2) / pitch + 1e-9))
    hi = int(math.ceil((centre + thickness / 2) / pitch - 1e-9)) - 1
    if lo < 0 or hi >= grid.shape[axis]:
        return np.zeros([grid.shape[a] for a in range(3) if a != axis], dtype=bool)
    return np.take(grid, range(lo, hi + 1), axis=axis).all(axis=axis)


def largest_part(geometry: object) -> tuple[object, bool]:
    """The largest polygon of ``geometry`` and whether anything else was dropped."""
    parts = [g for g in getattr(geometry, "geoms", [geometry]) if g.geom_type == "Polygon" and not g.is_empty]
    if not parts:
        return geometry, True
    best = max(parts, key=lambda g: g.area)
    return best, len(parts) > 1


def is_whole(geometry: object) -> bool:
    return geometry.geom_type == "Polygon" and not geometry.is_empty


@dataclasses.dataclass
class Draft:
    """A plate under construction (mutable while slots are cut)."""

    text: str
    family: str
    axis: int
    offset: float
    angle: float
    origin: tuple[float, float, float]
    u_dir: tuple[float, float, float]
    v_dir: tuple[float, float, float]
    body: object
    cells: int
    slots: list[Slot] = dataclasses.field(default_factory=list)
    trimmed: bool = False


def _interlocked_drafts(grid: npt.NDArray[np.bool_], axes: str, pitch: float, thickness: float, count: int,
                        interval: float) -> tuple[list[Draft], list[Draft]]:
    """The sections of both families, one draft per 4-connected piece of each plane."""
    import shapely

    fams: list[list[Draft]] = [[], []]
    for f, name in enumerate("AB"):
        a = _AXES.index(axes[f])
        others = [k for k in range(3) if k != a]
        layers = plane_layers(grid.shape[a], count, pitch, interval, thickness)
        for n, i in enumerate(layers, start=1):
            centre = (i + 0.5) * pitch
            section = slab_section(grid, a, centre, pitch, thickness)
            labels, pieces = label_layer(section)
            for k in range(1, pieces + 1):
                mask = labels == k
                text = f"{name}{n}" if pieces == 1 else f"{name}{n}-{k}"
                outline = scaled(cells_outline(np.argwhere(mask)), pitch)
                origin = [0.0, 0.0, 0.0]
                origin[a] = centre
                fams[f].append(Draft(text, name, a, centre, 0.0, (origin[0], origin[1], origin[2]),
                                      _unit(others[0]), _unit(others[1]), shapely.orient_polygons(outline),
                                      int(mask.sum())))
    return fams[0], fams[1]


def band_span(geometry: object, along: int, lo: float, hi: float) -> tuple[float, float] | None:
    """Extent along the other frame axis of ``geometry`` inside the band ``lo..hi`` of frame axis ``along``."""
    import shapely

    x0, y0, x1, y1 = geometry.bounds
    box = shapely.box(lo, y0 - 1, hi, y1 + 1) if along == 0 else shapely.box(x0 - 1, lo, x1 + 1, hi)
    part = shapely.intersection(geometry, box)
    if part.is_empty or part.area <= 0:
        return None
    b = part.bounds
    return (b[1], b[3]) if along == 0 else (b[0], b[2])


def full_width(geometry: object, along: int, lo: float, hi: float) -> list[tuple[float, float]]:
    """Intervals of the other frame axis over which ``geometry`` fills the whole band ``lo..hi`` of axis ``along``.

    A slot holds its partner only where the plate has material on both sides of it
    across the partner's whole thickness; a plate that merely reaches into the band
    (a corner, a strip beside a voxel step) holds nothing there.
    """
    import shapely

    x0, y0, x1, y1 = geometry.bounds
    column = shapely.box(lo, y0, hi, y1) if along == 0 else shapely.box(x0, lo, x1, hi)
    inside = shapely.intersection(geometry, column)
    if inside.is_empty or inside.area <= 0:
        return []
    b = inside.bounds
    span = (b[1], b[3]) if along == 0 else (b[0], b[2])
    gaps = shapely.difference(shapely.box(lo, span[0], hi, span[1]) if along == 0 else
                              shapely.box(span[0], lo, span[1], hi), geometry)
    cuts = sorted(((g.bounds[1], g.bounds[3]) if along == 0 else (g.bounds[0], g.bounds[2]))
                  for g in getattr(gaps, "geoms", [gaps]) if not g.is_empty and g.area > 1e-9)
    out, at = [], span[0]
    for a, b_ in cuts:
        if a > at + 1e-9:
            out.append((at, a))
        at = max(at, b_)
    if span[1] > at + 1e-9:
        out.append((at, span[1]))
    return out


def engaged(lower: list[tuple[float, float]], upper: list[tuple[float, float]]) -> tuple[float, float] | None:
    """The longest interval where both plates fill the crossing's column, or None."""
    best = None
    for a0, a1 in lower:
        for b0, b1 in upper:
            lo, hi = max(a0, b0), min(a1, b1)
            if hi - lo > 1e-9 and (best is None or hi - lo > best[1] - best[0]):
                best = (lo, hi)
    return best


def engagement(first: Draft, first_along: int, first_at: float, second: Draft, second_along: int,
               second_at: float, width: float, margin: float) -> tuple[float, float] | None:
    """The longest stretch where two crossing plates both fill the band of the crossing, or None.

    Each plate runs through a band ``width`` wide about the other's plane (``first_at`` along
    ``first_along`` of the first plate's frame, and so on); it holds its partner only where it
    fills that band and ``margin`` beside it.
    """
    return engaged(full_width(first.body, first_along, first_at - width / 2 - margin, first_at + width / 2 + margin),
                   full_width(second.body, second_along, second_at - width / 2 - margin,
                              second_at + width / 2 + margin))


def holds(held: tuple[float, float] | None, first: tuple[float, float], second: tuple[float, float]) -> bool:
    """Whether plates spanning ``first`` and ``second`` at a crossing, engaged over ``held``, make a joint.

    They must engage over half the shorter one's height at least, or they touch without holding.
    """
    return held is not None and held[1] - held[0] >= 0.5 * min(first[1] - first[0], second[1] - second[0]) - 1e-6


def give_way(sides: list[tuple[Draft, object]]) -> Draft | None:
    """At a crossing that does not hold, cut its band out of the plate with less material in it; that plate.

    ``sides`` pairs each plate with its band (a shapely polygon in its frame).  A plate
    lying wholly in its band keeps it: the other gives way.  The plate keeps its largest
    part, so the two never share volume.
    """
    import shapely

    for plate, band in sorted(sides, key=lambda c: shapely.intersection(c[0].body, c[1]).area):
        rest = shapely.difference(plate.body, band)
        if not rest.is_empty and rest.area > 0:
            plate.body, lost = largest_part(rest)
            plate.trimmed |= lost
            return plate
    return None


def slot_box(along: int, centre: float, width: float, a: float, b: float) -> object:
    import shapely

    lo, hi = sorted((a, b))
    if along == 0:
        return shapely.box(centre - width / 2, lo, centre + width / 2, hi)
    return shapely.box(lo, centre - width / 2, hi, centre + width / 2)


def _height(d: Draft, w: int) -> float:
    """Centre of a plate's section along the crossing axis ``w``."""
    c = d.body.centroid
    return float((c.x, c.y)[[k for k in range(3) if k != d.axis].index(w)])


def radial_box(centre: tuple[float, float], angle: float, width: float, a: float, b: float) -> object:
    """Rectangle ``width`` wide along the direction ``angle`` (degrees) from ``centre``, at distances ``a..b``."""
    import shapely

    t = math.radians(angle)
    d = np.array([math.cos(t), math.sin(t)])
    n = np.array([-d[1], d[0]]) * width / 2
    c = np.asarray(centre, dtype=np.float64)
    lo, hi = sorted((a, b))
    return shapely.Polygon([c + d * lo - n, c + d * hi - n, c + d * hi + n, c + d * lo + n])


def _join_interlocked(fam_a: list[Draft], fam_b: list[Draft], width: float, pitch: float,
                      moved: list[str], weak: list[str] | None = None,
                      margin: float = 0.0) -> tuple[list[tuple[Draft, Draft, float, float]],
                                                    dict[str, tuple[float, int, int]]]:
    """Cut the half-lap slots of every crossing that engages.

    A crossing engages where both plates fill the partner's whole thickness (and
    ``margin`` beside it); that stretch must be at least half the height of the
    shorter plate at the crossing, or the pair would touch without holding: such a
    crossing gets no slots and is listed in ``weak``.

    Plates go in one after another, each lowered along the crossing axis onto
    those already in place, lower sections first (family A first among equals):
    at a crossing the earlier plate is slotted from the top, the later one from
    the bottom.  Ordering by one key keeps the order free of cycles, and a low
    piece (the foot of a section) goes in under a tall plate, a high one (a
    rim) over it, so neither slot has to run the full height of the tall plate.

    Returns
    -------
    crossings : list of (lower, upper, slot end height, crossing position)
        Earlier plate first.
    keys : dict
        Plate label → its place in the assembly order.
    """

    w = 3 - fam_a[0].axis - fam_b[0].axis if fam_a and fam_b else 2
    keys = {d.text: (round(_height(d, w), 6), f, i) for f, fam in enumerate((fam_a, fam_b)) for i, d in enumerate(fam)}
    crossings = []
    for pa in fam_a:
        for pb in fam_b:
            lower, upper = (pa, pb) if keys[pa.text] < keys[pb.text] else (pb, pa)
            # the frame axis of each plate that runs along the other's normal
            lo_along = [k for k in range(3) if k != lower.axis].index(upper.axis)
            up_along = [k for k in range(3) if k != upper.axis].index(lower.axis)
            zl = band_span(lower.body, lo_along, upper.offset - width / 2, upper.offset + width / 2)
            zu = band_span(upper.body, up_along, lower.offset - width / 2, lower.offset + width / 2)
            if zl is None or zu is None:
                continue
            z0, z1 = max(zl[0], zu[0]), min(zl[1], zu[1])
            if z1 - z0 <= 1e-9:
                continue
            held = engagement(lower, lo_along, upper.offset, upper, up_along, lower.offset, width, margin)
            if not holds(held, zl, zu):
                # No joint here; the plate with less material in the crossing gives way (its part
                # in the partner's slot is cut away), so the two never share volume.
                if weak is not None:
                    weak.append(f"{lower.text}/{upper.text}")
                give_way([(lower, slot_box(lo_along, upper.offset, width, -1e9, 1e9)),
                          (upper, slot_box(up_along, lower.offset, width, -1e9, 1e9))])
                continue
            z0, z1 = held
            # The slots' boxes for a slot end (called by slot_end at once, so the loop's names hold).
            lower_slot = lambda z: slot_box(lo_along, upper.offset, width, z, zl[1])  # noqa: B023, E731
            upper_slot = lambda z: slot_box(up_along, lower.offset, width, zu[0], z)  # noqa: B023, E731
            zm, is_moved = slot_end(lower, lower_slot, upper, upper_slot, z0, z1, pitch)
            if is_moved:
                moved.append(f"{lower.text}/{upper.text}")
            # the slot runs along the crossing axis, the frame axis other than ``along``
            lower.slots.append(Slot(upper.offset, width, zl[1], zm, zl[1] - zm, "top", upper.text, is_moved,
                                    "uv"[1 - lo_along]))
            upper.slots.append(Slot(lower.offset, width, zu[0], zm, zm - zu[0], "bottom", lower.text, is_moved,
                                    "uv"[1 - up_along]))
            crossings.append((lower, upper, zm, upper.offset))
    return crossings, keys


def slot_end(first: Draft, first_slot: Callable[[float], object], second: Draft,
             second_slot: Callable[[float], object], lo: float, hi: float, pitch: float) -> tuple[float, bool]:
    """Cut a half-lap's two slots, ending where the plates meet between ``lo`` and ``hi``; the end and whether it moved.

    ``first_slot(end)`` and ``second_slot(end)`` are the slots' boxes for an end.
    The end is the middle of the stretch, or else the nearest half-voxel step
    outwards inside it that leaves both plates whole; when none does, the
    middle, each plate keeping its largest part (and marked trimmed).
    """
    import shapely

    middle = (lo + hi) / 2
    steps = np.arange(1, int((hi - lo) / pitch * 2) + 1) * pitch / 2
    for end in [middle] + [middle + s * d for s in steps for d in (1, -1) if lo < middle + s * d < hi]:
        cut_first = shapely.difference(first.body, first_slot(end))
        cut_second = shapely.difference(second.body, second_slot(end))
        if is_whole(cut_first) and is_whole(cut_second):
            first.body, second.body = cut_first, cut_second
            return end, bool(abs(end - middle) > 1e-9)
    first.body, lost_first = largest_part(shapely.difference(first.body, first_slot(middle)))
    second.body, lost_second = largest_part(shapely.difference(second.body, second_slot(middle)))
    first.trimmed |= lost_first
    second.trimmed |= lost_second
    return middle, False


def _waves(order: list[str], crossings: list[tuple[str, str]]) -> list[list[str]]:
    """Plates grouped by when they can go in: each wave slides onto the waves before it."""
    wave: dict[str, int] = {}
    below: dict[str, list[str]] = {}
    for a, b in crossings:
        below.setdefault(b, []).append(a)
    for t in order:  # the order puts every plate after those it is lowered onto
        wave[t] = 1 + max((wave[a] for a in below.get(t, []) if a in wave), default=-1)
    groups: list[list[str]] = [[] for _ in range(max(wave.values(), default=-1) + 1)]
    for t in order:
        groups[wave[t]].append(t)
    return groups


def connected_plates(drafts: list[Draft], crossings: list[tuple[str, str]]) -> tuple[list[Draft], list[str]]:
    """The largest connected group of plates (by material area); the others are reported as left out."""
    parent = {d.text: d.text for d in drafts}

    def find(x: str) -> str:
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b in crossings:
        parent[find(a)] = find(b)
    area: dict[str, float] = {}
    for d in drafts:
        area[find(d.text)] = area.get(find(d.text), 0.0) + d.body.area
    if not area:
        return [], []
    best = max(sorted(area), key=lambda r: area[r])
    keep = [d for d in drafts if find(d.text) == best]
    return keep, [d.text for d in drafts if find(d.text) != best]


def open_narrow(d: Draft, width: float) -> None:
    """Remove the strips narrower than ``width`` that slots leave beside a voxel step.

    An opening by a square keeps every part of a rectilinear outline at least
    ``width`` wide as it is; a plate it cuts in two keeps its largest part.
    """
    import shapely

    if width <= 0:
        return
    opened = d.body.buffer(-width / 2, join_style="mitre").buffer(width / 2, join_style="mitre")
    if opened.is_empty or d.body.difference(opened).area <= 1e-9 * d.body.area:
        return
    # the opening is inside the body up to rounding: clip it, so no plate grows
    body, lost = largest_part(shapely.intersection(d.body, opened))
    d.body = shapely.simplify(body, 0.0)
    d.trimmed |= lost


def still_joined(drafts: list[Draft], joints: list[tuple[Draft, Draft, float, float]], width: float,
                  min_width: float) -> list[tuple[str, str]]:
    """Open every plate (:func:`open_narrow`), then the crossings whose plates still meet at the slot end.

    ``joints`` holds ``(lower, upper, height of the slot ends, position of the crossing)``; a
    crossing holds while the lower plate reaches up to the slot end inside the crossing and
    the upper one down to it.  The slots of a crossing that no longer holds are dropped.
    """
    for d in drafts:
        open_narrow(d, min_width)
    held = []
    for lower, upper, zm, _ in joints:
        lo_along = [k for k in range(3) if k != lower.axis].index(upper.axis) if lower.axis != upper.axis else 0
        up_along = [k for k in range(3) if k != upper.axis].index(lower.axis) if lower.axis != upper.axis else 0
        zl = band_span(lower.body, lo_along, upper.offset - width / 2, upper.offset + width / 2)
        zu = band_span(upper.body, up_along, lower.offset - width / 2, lower.offset + width / 2)
        if zl is not None and zu is not None and zl[1] >= zm - 1e-6 and zu[0] <= zm + 1e-6:
            held.append((lower.text, upper.text))
        else:
            lower.slots = [sl for sl in lower.slots if sl.partner != upper.text]
            upper.slots = [sl for sl in upper.slots if sl.partner != lower.text]
    return held


def finish_plate(d: Draft, number: int, style: str, thickness: float, pitch: float, kept: set[str]) -> SlottedPlate:
    """Freeze a draft into a plate with its label and its partners' labels engraved."""
    import shapely


    clearance = max(0.1 * pitch, 0.2)
    slots = tuple(s for s in d.slots if s.partner in kept)
    label = place_label(d.text, d.body, shapely.Polygon(), pitch=pitch, clearance=clearance)
    strokes = list(label.strokes)
    taken = shapely.union_all([shapely.box(*shapely.LineString(s).bounds).buffer(clearance) for s in strokes
                               if len(s) > 1]) if strokes else shapely.Polygon()
    left_off = []
    full = (full_height(pitch),)
    for s in slots:
        # The partner's label, in parentheses so it never reads as this plate's own: beside the slot, at
        # full size and the right way up; else elsewhere on the plate so; only then turned or smaller.
        text = f"({s.partner})"
        near = s.box().buffer(2.0 * pitch, join_style="mitre")
        region = shapely.difference(shapely.intersection(d.body, near), taken)
        free = shapely.difference(d.body, taken)
        mark = None
        for where in (region, free):
            if mark is None and not where.is_empty and where.area > 0:
                mark = place_label(text, where, shapely.Polygon(), pitch=pitch, clearance=clearance,
                                   sizes=full, upright=True, fallback=False)
        if mark is None and not region.is_empty and region.area > 0:
            mark = place_label(text, largest_part(region)[0], shapely.Polygon(), pitch=pitch, clearance=clearance,
                               fallback=False)
        if mark is None:
            left_off.append(s.partner)  # no room for it whole: the slot goes unlabelled, and the report says so
            continue
        strokes.extend(mark.strokes)
        if mark.strokes:
            taken = shapely.union(taken, shapely.box(*shapely.MultiLineString(
                [m for m in mark.strokes if len(m) > 1]).bounds).buffer(clearance))
    label = dataclasses.replace(label, strokes=tuple(strokes))
    return SlottedPlate(
        number=number, layer=1 if d.family in ("A", "R") else 2, piece=number, copy=1,
        outline=shapely.orient_polygons(d.body), holes=np.zeros((0, 2)), hole_diameter=0.0, z=0.0,
        thickness=thickness, label=label, score=(), cells=d.cells, style=style, family=d.family,
        axis=_AXES[d.axis], offset=d.offset, angle=d.angle, origin=d.origin, u_dir=d.u_dir, v_dir=d.v_dir,
        slots=slots, text=d.text, marks_left_off=tuple(left_off),
    )


def make_interlocked(grid: npt.ArrayLike, *, pitch: float, thickness: float = 3.0, axes: str = "xy",
                     count: int = 5, interval: float = 12.0, clearance: float = 0.1,
                     min_width: float = 1.0) -> Construction:
    """Two families of plates slotted into each other at right angles (a waffle, or sliceform).

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
    pitch : float
        Voxel edge in mm.
    thickness : float
        Measured material thickness in mm.
    axes : str
        Normals of family A and family B, e.g. ``"xy"``: A plates are
        perpendicular to x, B plates to y, and they cross along the third axis.
    count : int
        Plates per family; 0 for one every ``interval`` mm.
    interval : float
        Distance in mm between the plates of a family when ``count`` is 0.
    clearance : float
        Slot width beyond the thickness, for the fit, in mm.
    min_width : float
        Narrowest strip in mm kept beside a slot; narrower ones are cut away.

    Returns
    -------
    Construction
        Family A stands; family B slides down onto it (B's slots open downwards).
    """
    pitch = check_positive(pitch, name="pitch")
    thickness = check_positive(thickness, name="thickness")
    if len(axes) != 2 or axes[0] == axes[1] or any(a not in _AXES for a in axes):
        raise InvalidShapeError(f"axes: expected two different axes of x, y, z such as 'xy', got {axes!r}")
    g, filled = solid_grid(grid)
    fam_a, fam_b = _interlocked_drafts(g, axes, pitch, thickness, count, interval)
    if len(fam_a) + len(fam_b) > MAX_SLOTTED_PLATES:
        raise InvalidShapeError(f"count: {len(fam_a) + len(fam_b)} plates, over the limit of {MAX_SLOTTED_PLATES}; "
                                "use fewer plates per family or a larger interval")
    moved: list[str] = []
    weak: list[str] = []
    width = thickness + clearance
    joints, keys = _join_interlocked(fam_a, fam_b, width, pitch, moved, weak, min_width)
    crossings = still_joined(fam_a + fam_b, joints, width, min_width)
    keep, left_out = connected_plates(fam_a + fam_b, crossings)
    if not keep or not crossings:
        raise FabricationError("interlocked: no two plates cross; use more plates per family or other axes")
    kept = {d.text for d in keep}
    ordered = sorted(keep, key=lambda d: keys[d.text])
    plates = tuple(finish_plate(d, n, "interlocked", thickness, pitch, kept) for n, d in enumerate(ordered, start=1))
    w = _AXES[3 - _AXES.index(axes[0]) - _AXES.index(axes[1])]
    kept_crossings = tuple((a, b) for a, b in crossings if a in kept and b in kept)
    waves = _waves([p.text for p in plates], list(kept_crossings))
    steps = (f"stand {' '.join(waves[0])} upright (normals along {axes[0]} and {axes[1]}) with their slots "
             f"open towards +{w}",
             *(f"lower {' '.join(group)} along -{w} onto the plates in place: each lower slot onto the plate "
               "whose label it carries" for group in waves[1:]))
    return Construction("interlocked", pitch, thickness, clearance, plates, kept_crossings,
                        tuple(m for m in moved if set(m.split("/")) <= kept), tuple(left_out),
                        tuple(d.text for d in keep if d.trimmed), tuple(float(s * pitch) for s in g.shape), steps,
                        tuple(weak), filled=filled)
