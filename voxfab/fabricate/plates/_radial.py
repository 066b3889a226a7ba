"""Radial constructions: plates fanned about the axis through the middle of the footprint, or locked by a ring.

The plates, slots and joints are those of :mod:`._slotted`; geometry is in mm.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import check_positive
from voxfab.errors import FabricationError, InvalidShapeError

from ._outline import cells_outline, label_layer, scaled
from ._slotted import (
    MAX_RADIAL_PLATES,
    Construction,
    Draft,
    Slot,
    band_span,
    connected_plates,
    engagement,
    finish_plate,
    give_way,
    holds,
    largest_part,
    open_narrow,
    radial_box,
    slab_section,
    slot_box,
    slot_end,
    solid_grid,
    still_joined,
)


def radial_section(layers: list[object | None], centre: tuple[float, float], angle: float, reach: float,
                   thickness: float, pitch: float) -> object:
    """Exact section of the voxel solid by a vertical plate through ``centre`` at ``angle`` degrees.

    In the plate's frame ``(r, z)``, ``r`` along ``(cos a, sin a)`` from the
    axis: per voxel layer, the ``r`` where the plate's whole thickness lies
    inside the layer.  The part of the plate's strip outside a layer is a set
    of connected polygons; each one rules out the ``r`` of its projection.
    """
    import shapely

    a = math.radians(angle)
    d = np.array([math.cos(a), math.sin(a)])
    n = np.array([math.sin(a), -math.cos(a)])
    c = np.asarray(centre, dtype=np.float64)
    corners = np.array([c - d * reach - n * thickness / 2, c + d * reach - n * thickness / 2,
                        c + d * reach + n * thickness / 2, c - d * reach + n * thickness / 2])
    strip = shapely.Polygon(corners)
    boxes = []
    for k, layer in enumerate(layers):
        if layer is None:
            continue
        outside = shapely.difference(strip, layer)
        bad = []
        for part in getattr(outside, "geoms", [outside]):
            if part.is_empty or part.area <= 0:
                continue
            r = (shapely.get_coordinates(part) - c) @ d
            bad.append((float(r.min()), float(r.max())))
        bad.sort()
        start = -reach
        for lo, hi in bad + [(reach, reach)]:
            if lo > start + 1e-9:
                boxes.append(shapely.box(start, k * pitch, lo, (k + 1) * pitch))
            start = max(start, hi)
    if not boxes:
        return shapely.Polygon()
    return shapely.simplify(shapely.union_all(boxes), 0.0)


def make_radial(grid: npt.ArrayLike, *, pitch: float, thickness: float = 3.0, count: int = 4,
                clearance: float = 0.1, min_width: float = 1.0) -> Construction:
    """``count`` vertical plates fanned at equal angles about the axis through the middle of the footprint.

    The plates meet at the hub, the column where they all cross.  The hub's
    height is split into ``count`` tiers, one per plate from the bottom up:
    each plate keeps its tier and is slotted from the top above it and from
    the bottom below it, so plate 1 stands and every next plate drops onto the
    one before from above, no plate passing through another.  Two plates make
    a plain half-lap (one slotted from the top, one from the bottom).  The
    hub slot is as wide as two plates at the smallest angle need:
    ``thickness / 2 · cot(90° / count)`` each side, plus half the clearance.
    Strips narrower than ``min_width`` mm beside a slot are cut away.

    Returns
    -------
    Construction
    """
    import shapely

    pitch = check_positive(pitch, name="pitch")
    thickness = check_positive(thickness, name="thickness")
    if int(count) != count or not 2 <= count <= MAX_RADIAL_PLATES:
        raise InvalidShapeError(f"radial_plates: expected an integer from 2 to {MAX_RADIAL_PLATES}, got {count!r}")
    g, filled = solid_grid(grid)
    nx, ny, nz = g.shape
    centre = (nx * pitch / 2, ny * pitch / 2)
    reach = math.hypot(nx, ny) * pitch / 2 + pitch
    layers = [scaled(cells_outline(np.argwhere(g[:, :, k])), pitch) if g[:, :, k].any() else None
              for k in range(nz)]
    half = thickness / 2 / math.tan(math.pi / (2 * count)) + clearance / 2
    drafts: list[Draft] = []
    left_out: list[str] = []
    sections = [radial_section(layers, centre, 180.0 * k / count, reach, thickness, pitch) for k in range(count)]
    hub_box = shapely.box(-half, -1.0, half, nz * pitch + 1.0)
    if not any(p.intersects(hub_box) for sec in sections for p in getattr(sec, "geoms", [sec]) if not p.is_empty):
        # the axis runs through no solid (a ring, a torus): a flat ring plate locks the radial pieces
        return _ring_radial(g, filled, sections, centre, reach, pitch=pitch, thickness=thickness, clearance=clearance,
                            min_width=min_width)
    for k, section in enumerate(sections):
        angle = 180.0 * k / count
        text = f"R{k + 1}"
        hub = [p for p in getattr(section, "geoms", [section]) if not p.is_empty and p.intersects(hub_box)]
        others = [p for p in getattr(section, "geoms", [section]) if not p.is_empty and p not in hub]
        left_out.extend(f"{text} piece at r = {p.bounds[0]:.1f}..{p.bounds[2]:.1f} mm" for p in others)
        if len(hub) != 1:
            raise FabricationError(
                f"radial: plate {text} misses the hub" if not hub
                else f"radial: plate {text} meets the axis in {len(hub)} separate parts")
        a = math.radians(angle)
        drafts.append(Draft(text, "R", 2, 0.0, angle, (centre[0], centre[1], 0.0),
                             (math.cos(a), math.sin(a), 0.0), (0.0, 0.0, 1.0),
                             shapely.orient_polygons(hub[0]), int(round(hub[0].area / pitch ** 2))))
    spans = [band_span(d.body, 0, -half, half) for d in drafts]
    if any(s is None for s in spans):
        raise FabricationError("radial: the axis through the middle of the footprint runs through no solid")
    width = 2 * half
    z0, z1 = max(s[0] for s in spans), min(s[1] for s in spans)
    if z1 - z0 <= 1e-9:
        raise FabricationError("radial: the plates share no stretch of the axis to join at")
    advice = _hub_advice(drafts, z0, z1, pitch, thickness, clearance, min_width, count, width)
    weak: list[str] = []
    hub = _holding(drafts, spans, width, min_width, weak)
    if len(hub) < 2:
        raise FabricationError("radial: no two plates hold each other at the hub (they engage over less than half "
                               f"their height); {advice[0] if advice else 'use fewer or thinner plates'}")
    spans = [band_span(d.body, 0, -half, half) for d in hub]
    z0, z1 = max(s[0] for s in spans), min(s[1] for s in spans)
    n = len(hub)
    tiers = np.linspace(z0, z1, n + 1)
    for k, (d, (lo, hi)) in enumerate(zip(hub, spans)):
        if k < n - 1:
            d.body = shapely.difference(d.body, slot_box(0, 0.0, width, float(tiers[k + 1]), hi))
            d.slots.append(Slot(0.0, width, hi, float(tiers[k + 1]), hi - float(tiers[k + 1]), "top",
                                hub[k + 1].text))
        if k > 0:
            d.body = shapely.difference(d.body, slot_box(0, 0.0, width, lo, float(tiers[k])))
            d.slots.append(Slot(0.0, width, lo, float(tiers[k]), float(tiers[k]) - lo, "bottom",
                                hub[k - 1].text))
        d.body, lost = largest_part(d.body)
        d.trimmed |= lost
    joints = [(hub[k], hub[k + 1], float(tiers[k + 1]), 0.0) for k in range(n - 1)]
    held = still_joined(drafts, joints, width, min_width)
    keep, dropped = connected_plates(drafts, held)
    if len(keep) < 2:
        raise FabricationError("radial: the hub is too thin to join the plates; use fewer or thinner plates")
    left_out.extend(dropped)
    kept = {d.text for d in keep}
    plates = tuple(finish_plate(d, n, "radial", thickness, pitch, kept) for n, d in enumerate(keep, start=1))
    labels = [p.text for p in plates]
    steps = (f"stand {labels[0]} upright with its hub slot open at the top",
             *(f"drop {b} from above onto {a} at the hub: the lower slot of {b} over {a}"
               for a, b in zip(labels, labels[1:])))
    crossings = tuple((a, b) for a, b in held if a in kept and b in kept)
    return Construction("radial", pitch, thickness, clearance, plates, crossings, (), tuple(left_out),
                        tuple(d.text for d in keep if d.trimmed), tuple(float(s * pitch) for s in g.shape), steps,
                        weak=tuple(weak), advice=advice, filled=filled)


def _holding(drafts: list[Draft], spans: list[tuple[float, float]], width: float, margin: float,
             weak: list[str]) -> list[Draft]:
    """The plates that join at the hub: every two of them engage over half the shorter one's height.

    Every two plates cross in the hub, each through the other's slot, so the interlocked
    rule holds for every pair: where a pair engages less, the plate with less material in
    the hub gives way (its hub column is cut out: it joins nothing, and is left out) and
    the pair is listed in ``weak``.
    """
    column = slot_box(0, 0.0, width, -1e9, 1e9)
    # every pair is judged on the plates as sectioned, before any gives way
    failing = [(a, b) for i, (a, sa) in enumerate(zip(drafts, spans)) for b, sb in zip(drafts[i + 1:], spans[i + 1:])
               if not holds(engagement(a, 0, 0.0, b, 0, 0.0, width, margin), sa, sb)]
    out = set()
    for a, b in failing:
        weak.append(f"{a.text}/{b.text}")
        if a.text not in out and b.text not in out:
            cut = give_way([(a, column), (b, column)])
            out.add(cut.text if cut is not None else b.text)
    return [d for d in drafts if d.text not in out]


def hub_slot_width(count: int, thickness: float, clearance: float) -> float:
    """Width of the radial hub slot: two plates at the smallest angle, ``thickness / 2 · cot(90° / count)`` each
    side of the axis, plus the clearance."""
    return thickness / math.tan(math.pi / (2 * count)) + clearance


def _hub_advice(drafts: list[Draft], z0: float, z1: float, pitch: float, thickness: float, clearance: float,
                min_width: float, count: int, width: float) -> tuple[str, ...]:
    """When the hub slot is wider than the solid's narrowest section along the hub (its neck), the ways out.

    Every height of the hub but a plate's own tier is slotted, so a slot as wide as
    the neck cuts the plate there in two (it loses its top, or is left out).  A
    hub fits when the slot leaves ``min_width`` of material on each side of it.
    """
    import shapely

    neck = math.inf
    for d in drafts:
        for k in range(int(math.floor(z0 / pitch + 1e-9)), int(math.ceil(z1 / pitch - 1e-9))):
            row = shapely.intersection(d.body, shapely.box(-1e9, (k + 0.25) * pitch, 1e9, (k + 0.75) * pitch))
            parts = [q for q in getattr(row, "geoms", [row]) if not q.is_empty and q.bounds[0] <= 0 <= q.bounds[2]]
            if parts:
                neck = min(neck, parts[0].bounds[2] - parts[0].bounds[0])
    room = neck - 2 * min_width
    if not math.isfinite(neck) or width <= room + 1e-9:
        return ()
    ways = []
    fewer = next((n for n in range(count - 1, 1, -1) if hub_slot_width(n, thickness, clearance) <= room), None)
    if fewer is not None:
        ways.append(f"fewer plates (--radial-plates {fewer})")
    thinner = math.floor((room - clearance) * math.tan(math.pi / (2 * count)) * 10) / 10
    if thinner >= 0.1:
        ways.append(f"thinner plates (--thickness {thinner:g}, with {count} plates)")
    ways.append("a larger pitch (a wider neck)")
    return (f"the radial hub slot ({width:.1f} mm for {count} plates of {thickness:g} mm) is wider than the "
            f"solid's neck along the hub ({neck:.1f} mm, less {min_width:g} mm each side): plates lose parts or "
            f"are left out; use {', or '.join(ways)}",)


def _ring_radial(g: npt.NDArray[np.bool_], filled: int, sections: list[object], centre: tuple[float, float], reach: float, *,
                 pitch: float, thickness: float, clearance: float, min_width: float) -> Construction:
    """Radial pieces locked by a flat ring, for a shape with no solid on its axis.

    The ring ``H1`` is the section of the solid at the voxel layer with the
    most cells.  Each radial piece meets it along a line pointing away from
    the axis, and the pair is half-lapped across that line: the piece is
    slotted from its edge nearer the axis, the ring from its outer edge, each
    to the middle of the stretch they share.  Lay the ring flat, then slide
    every piece onto it towards the axis; pieces never meet one another.
    """
    import shapely

    counts = g.sum(axis=(0, 1))
    layer = int(np.argmax(counts))
    zc = (layer + 0.5) * pitch
    cells = slab_section(g, 2, zc, pitch, thickness)
    labels, n = label_layer(cells)
    if n == 0:
        raise FabricationError("radial: the axis runs through no solid, and no layer can carry a ring to join at")
    sizes = np.bincount(labels.ravel())[1:]
    ring = scaled(cells_outline(np.argwhere(labels == int(np.argmax(sizes)) + 1)), pitch)
    ring_draft = Draft("H1", "H", 2, zc, 0.0, (0.0, 0.0, zc), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0),
                        shapely.orient_polygons(ring), int(sizes.max()))
    width = thickness + clearance
    pieces: list[Draft] = []
    joints: list[tuple[Draft, float, float, float]] = []  # piece, side, slot end (distance), angle
    left_out: list[str] = [f"H1 piece {k}" for k in range(2, n + 1)] if n > 1 else []
    moved: list[str] = []
    for k, section in enumerate(sections):
        angle = 180.0 * k / len(sections)
        a = math.radians(angle)
        parts = sorted((p for p in getattr(section, "geoms", [section]) if not p.is_empty),
                       key=lambda p: (p.centroid.x, p.centroid.y))
        for j, part in enumerate(parts, start=1):
            pieces.append(Draft(f"R{k + 1}-{j}", "R", 2, 0.0, angle, (centre[0], centre[1], 0.0),
                                 (math.cos(a), math.sin(a), 0.0), (0.0, 0.0, 1.0), shapely.orient_polygons(part),
                                 int(round(part.area / pitch ** 2))))
    for d in pieces:
        side = 1.0 if d.body.centroid.x > 0 else -1.0
        band = band_span(d.body, 1, zc - width / 2, zc + width / 2)
        strip = radial_box(centre, d.angle, width, 0.0, side * reach)
        on_ring = shapely.intersection(ring_draft.body, strip)
        if band is None or on_ring.is_empty or on_ring.area <= 0:
            continue
        rho = (shapely.get_coordinates(on_ring) - np.asarray(centre)) @ np.array(d.u_dir[:2]) * side
        p0, p1 = sorted((band[0] * side, band[1] * side))
        q0, q1 = float(rho.min()), float(rho.max())
        lo, hi = max(p0, q0), min(p1, q1)
        if hi - lo <= 1e-9:
            continue
        # The slots' boxes for a slot end (called by slot_end at once, so the loop's names hold).
        piece_slot = lambda r: slot_box(1, zc, width, side * p0, side * r)  # noqa: B023, E731
        ring_slot = lambda r: radial_box(centre, d.angle, width, side * r, side * q1)  # noqa: B023, E731
        m, is_moved = slot_end(d, piece_slot, ring_draft, ring_slot, lo, hi, pitch)
        if is_moved:
            moved.append(f"H1/{d.text}")
        d.slots.append(Slot(zc, width, side * p0, side * m, m - p0, "inner", "H1", is_moved, "u"))
        ring_draft.slots.append(Slot(d.angle, width, side * q1, side * m, q1 - m, "outer", d.text, is_moved,
                                     "radial", centre))
        joints.append((d, side, m, d.angle))
    for d in [ring_draft, *pieces]:
        open_narrow(d, min_width)
    held = []
    for d, side, m, angle in joints:
        band = band_span(d.body, 1, zc - width / 2, zc + width / 2)
        on_ring = shapely.intersection(ring_draft.body, radial_box(centre, angle, width, 0.0, side * reach))
        ok = band is not None and not on_ring.is_empty and on_ring.area > 0
        if ok:
            rho = (shapely.get_coordinates(on_ring) - np.asarray(centre)) @ np.array(d.u_dir[:2]) * side
            ok = min(band[0] * side, band[1] * side) <= m + 1e-6 and float(rho.max()) >= m - 1e-6
        if ok:
            held.append(("H1", d.text))
        else:
            d.slots = [sl for sl in d.slots if sl.partner != "H1"]
            ring_draft.slots = [sl for sl in ring_draft.slots if sl.partner != d.text]
    keep, dropped = connected_plates([ring_draft, *pieces], held)
    if ring_draft not in keep or len(keep) < 2:
        raise FabricationError("radial: the axis runs through no solid, and no radial piece crosses a ring")
    left_out.extend(dropped)
    kept = {d.text for d in keep}
    plates = tuple(finish_plate(d, i, "radial", thickness, pitch, kept) for i, d in enumerate(keep, start=1))
    labels = [p.text for p in plates if p.text != "H1"]
    steps = ("lay the ring H1 flat with its slots open towards the outside",
             f"slide {' '.join(labels)} onto H1 towards the axis: the slot of each piece over the ring "
             "at the ring slot engraved with its label")
    return Construction("radial", pitch, thickness, clearance, plates, tuple(held), tuple(moved), tuple(left_out),
                        tuple(d.text for d in keep if d.trimmed), tuple(float(v * pitch) for v in g.shape), steps,
                        filled=filled)
