"""Interlocked and radial plates, checked from the written files (see ``_plate_checks``).

Each case writes the plates of one shape, style and material thickness, then
reads ``assembly.3mf``, the sheets and ``plates.json`` back.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from _plate_checks import check_written, construction_shapes

from voxfab.fabricate.plates import PlateOptions, fabricate_plates, make_interlocked, make_radial


@pytest.fixture(scope="module")
def shapes():
    return construction_shapes()


# Four radial plates of 6 mm need a 14.6 mm hub slot, wider than the queen's neck: no two of them hold
# (tests/cli/test_slices_cli.py checks the refusal and its ways out).
CASES = [(name, style, t) for name in ("ball", "torus", "overhang", "queen", "vase")
         for style in ("interlocked", "radial") for t in (3.0, 6.0) if (name, style, t) != ("queen", "radial", 6.0)]


@pytest.mark.parametrize(("name", "style", "thickness"), CASES)
def test_written_construction_is_flat_disjoint_inside_connected_and_cut(shapes, tmp_path, name, style,
                                                                        thickness) -> None:
    shape = shapes[name]
    sheet = "1300x900" if name == "vase" else "600x400"
    family = {"count": 4 if name == "vase" else 0} if style == "interlocked" else {}  # radial has no count
    options = PlateOptions(style=style, thickness=thickness, sheet=sheet, **family)
    made = fabricate_plates(shape, options, tmp_path / "slices", name=name)
    assert {"assembly.3mf", "assembly.pdf", "plates.json"} <= {f.path for f in made.files}
    report = check_written(tmp_path / "slices", shape, thickness, 0.0)
    assert report["style"] == style and report["thickness"] == thickness
    for p in report["plates_list"]:
        assert p["style"] == style
        assert {"family", "plane", "label", "sheet", "turns", "offset", "slots"} <= set(p)
        assert all({"position", "width", "depth", "partner"} <= set(sl) for sl in p["slots"])
        assert ("angle" in p["plane"]) == (style == "radial" and p["family"] == "R")


def test_torus_radial_pieces_are_locked_by_a_flat_ring(shapes) -> None:
    """No solid on the axis: a ring at the fullest layer takes every radial piece, slotted from outside."""
    c = make_radial(shapes["torus"].grid, pitch=4.0, thickness=3.0, count=4)
    ring, *pieces = c.plates
    assert ring.text == "H1" and ring.family == "H" and ring.axis == "z"
    assert len(pieces) == 8 and all(p.family == "R" for p in pieces)
    assert c.crossings == tuple(("H1", p.text) for p in pieces)
    assert sorted(s.partner for s in ring.slots) == sorted(p.text for p in pieces)
    for p in pieces:
        (slot,) = p.slots
        # the piece's slot opens towards the axis, the ring's away from it, and they meet
        ring_slot = next(s for s in ring.slots if s.partner == p.text)
        assert abs(slot.end) == pytest.approx(abs(ring_slot.end))
        assert abs(slot.edge) < abs(slot.end) < abs(ring_slot.edge)
    bars = np.zeros((9, 9, 3), bool)
    bars[0, :, 0] = bars[8, :, 2] = True  # two bars at different heights: the ring is the lower one
    two = make_radial(bars, pitch=4.0, thickness=3.0, count=2)
    assert [p.text for p in two.plates] == ["H1", "R1-1"] and two.left_out == ("R1-2",)


def test_slots_are_thickness_plus_clearance_and_kerf_true_on_the_sheet(shapes, tmp_path) -> None:
    shape = shapes["queen"]
    options = PlateOptions(style="interlocked", thickness=3.0, clearance=0.2, kerf=0.15)
    fabricate_plates(shape, options, tmp_path / "s", name="queen")
    report = check_written(tmp_path / "s", shape, 3.0, 0.15)
    assert report["slot_width"] == pytest.approx(3.2)
    construction = make_interlocked(shape.grid, pitch=shape.pitch, thickness=3.0, clearance=0.2)
    for plate in construction.plates:
        for slot in plate.slots:
            assert slot.width == pytest.approx(3.2)
            # the slot is cut out of the plate: its box holds no material
            assert slot.box().area == pytest.approx(3.2 * slot.depth)
            assert shapely.intersection(plate.outline, slot.box()).area == pytest.approx(0.0, abs=1e-9)
    # crossing pairs: the depths of a pair meet at one height, and add up to the crossing's height
    by = {p.text: p for p in construction.plates}
    for a, b in construction.crossings:
        sa = next(s for s in by[a].slots if s.partner == b)
        sb = next(s for s in by[b].slots if s.partner == a)
        assert (sa.side, sb.side) == ("top", "bottom")
        assert sa.end == pytest.approx(sb.end)
        assert sa.depth + sb.depth == pytest.approx(sa.edge - sb.edge)
    # on the sheet the slot is drawn one kerf narrower: the laser's kerf brings it back to 3.2 mm
    from voxfab.fabricate.plates import nest_plates

    sheets = nest_plates(construction.plates, sheet="600x400", kerf=0.15)
    part, slot = next((pt, sl) for sh in sheets for pt in sh.parts for sl in pt.plate.slots if sl.depth > 2)
    drawn = shapely.Polygon(part.cut[0], part.cut[1:])
    v = slot.end + 0.5 if slot.side == "top" else slot.end - 0.5  # just inside the slot
    # a crossing holds only where the plate has at least min_width (1 mm) beside the slot: probe within that
    reach = slot.width / 2 + 0.9
    probe = shapely.LineString(part.place([[slot.position - reach, v], [slot.position + reach, v]]))
    centre = shapely.Point(part.place([[slot.position, v]])[0])
    gap = probe.difference(drawn)
    pieces = [g for g in getattr(gap, "geoms", [gap]) if shapely.distance(g, centre) < 1e-9]
    assert pieces and pieces[0].length == pytest.approx(3.2 - 0.15, abs=1e-6)


def test_radial_hub_tiers_stack_bottom_up(shapes) -> None:
    shape = shapes["queen"]
    c = make_radial(shape.grid, pitch=shape.pitch, thickness=3.0, count=4)
    assert [p.angle for p in c.plates] == [0.0, 45.0, 90.0, 135.0]
    assert c.crossings == (("R1", "R2"), ("R2", "R3"), ("R3", "R4"))
    ends = [sorted(s.end for s in p.slots) for p in c.plates]
    # plate k keeps the tier between its bottom slot's end and its top slot's end
    assert ends[0][0] == pytest.approx(ends[1][0]) and ends[1][1] == pytest.approx(ends[2][0])
    width = 3.0 / np.tan(np.pi / 8) + 0.1
    assert all(s.width == pytest.approx(width) for p in c.plates for s in p.slots)
    two = make_radial(shape.grid, pitch=shape.pitch, thickness=3.0, count=2)
    (top,), (bottom,) = (p.slots for p in two.plates)
    assert (top.side, bottom.side, top.width) == ("top", "bottom", pytest.approx(3.1))
    assert top.end == pytest.approx(bottom.end)


def test_same_inputs_same_bytes(shapes, tmp_path) -> None:
    shape = shapes["overhang"]
    for style in ("interlocked", "radial"):
        a = fabricate_plates(shape, PlateOptions(style=style), tmp_path / f"a{style}", name="o")
        fabricate_plates(shape, PlateOptions(style=style), tmp_path / f"b{style}", name="o")
        for f in a.files:
            assert (tmp_path / f"a{style}" / f.path).read_bytes() == (tmp_path / f"b{style}" / f.path).read_bytes()


@pytest.mark.parametrize("axes", ["yz", "zx"])
def test_other_axes_cross_along_the_third(shapes, tmp_path, axes) -> None:
    shape = shapes["queen"]
    fabricate_plates(shape, PlateOptions(style="interlocked", axes=axes, count=4), tmp_path / "s", name="q")
    report = check_written(tmp_path / "s", shape, 3.0, 0.0)
    assert {p["plane"]["axis"] for p in report["plates_list"]} == set(axes)
    third = ({"x", "y", "z"} - set(axes)).pop()
    assert f"+{third}" in report["steps"][0]


def _box(lo: np.ndarray, hi: np.ndarray):
    import manifold3d

    return manifold3d.Manifold.cube(tuple(hi - lo)).translate(tuple(lo))


def _slab(axis: str, lo: float, hi: float, size: np.ndarray):
    """The part ``lo <= axis <= hi`` of a box around the whole assembly."""
    k = "xyz".index(axis)
    a, b = np.full(3, -1.0), size + 1.0
    a[k], b[k] = lo, hi
    return _box(a, b)


def test_knight_crossings_engage_half_the_shorter_plate_and_hold_every_plate(tmp_path) -> None:
    """The knight at 2.8 mm, measured in assembly.3mf: at each kept crossing both plates run through the
    partner's whole thickness (material on both sides of each slot) and engage over at least half the
    shorter plate's height; crossings that would not are dropped with a warning; every plate has a joint."""
    import json

    import trimesh
    from _plate_checks import manifold_of

    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import VoxelShape

    knight = VoxelShape(make_shape(load_recipe("recipes/chess/knight.toml")).grid, 2.8)
    made = fabricate_plates(knight, PlateOptions(style="interlocked"), tmp_path / "s", name="knight")
    report = json.loads((tmp_path / "s" / "plates.json").read_text())
    assert report["weak"], "the knight's corner crossings barely touch: they are dropped"
    assert any("crossing(s) dropped" in w and report["weak"][0] in w for w in made.warnings)
    scene = trimesh.load(tmp_path / "s" / "assembly.3mf", process=False, force="scene")
    solids = {name: manifold_of(m) for name, m in scene.geometry.items()}
    plates = {p["label"]: p for p in report["plates_list"]}
    size, t, side = np.array(report["size"]), report["thickness"], 0.5
    pairs = 0
    for label, p in plates.items():
        assert p["slots"], f"{label} is held by no joint"
        for s in p["slots"]:
            q = plates[s["partner"]]
            qa, qo = q["plane"]["axis"], q["plane"]["offset"]
            pa, po = p["plane"]["axis"], p["plane"]["offset"]
            w = "xyz".replace(pa, "").replace(qa, "")
            heights = {}
            k = "xyz".index(w)
            for name, mine, mine_off, other, o_off in ((label, pa, po, s["partner"], (qa, qo)),
                                                       (s["partner"], qa, qo, label, (pa, po))):
                axis_o, off_o = o_off
                inside = solids[name] ^ _slab(axis_o, off_o - t / 2, off_o + t / 2, size)
                heights[name] = inside.volume() / t**2
                # where the partner sits in this plate's slot: its part inside this plate's slab, along w
                held = (solids[other] ^ _slab(mine, mine_off - t / 2, mine_off + t / 2, size)).bounding_box()
                own = solids[name].bounding_box()
                w0, w1 = max(held[k], own[k]), min(held[3 + k], own[3 + k])
                assert w1 - w0 > 0.5, (name, "holds nothing of", other)
                # material on both sides of the partner over at least half that stretch: a slot, not a notch
                for a, b in ((off_o - t / 2 - side, off_o - t / 2), (off_o + t / 2, off_o + t / 2 + side)):
                    beside = solids[name] ^ _slab(axis_o, a, b, size) ^ _slab(w, w0, w1, size)
                    assert beside.volume() >= 0.5 * side * t * (w1 - w0), (name, "beside", other)
            h_p, h_q = heights[label], heights[s["partner"]]
            partner_slot = next(x for x in q["slots"] if x["partner"] == label)
            shorter = min(h_p + s["depth"], h_q + partner_slot["depth"])
            assert h_p + h_q >= 0.5 * shorter - 1e-3, (label, s["partner"], h_p, h_q, shorter)
            pairs += 1
    assert pairs == 2 * len(report["crossings"]) > 0


def test_partner_labels_without_room_are_listed_in_plates_json(tmp_path) -> None:
    """The queen at 2 mm: a slot's partner label that has no room whole is left off, listed and warned about."""
    import json

    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import VoxelShape

    queen = VoxelShape(make_shape(load_recipe("recipes/chess/queen.toml")).grid, 2.0)
    made = fabricate_plates(queen, PlateOptions(style="interlocked"), tmp_path / "s", name="queen")
    report = json.loads((tmp_path / "s" / "plates.json").read_text())
    construction = make_interlocked(queen.grid, pitch=2.0)
    left_off = [f"{p.text}/{m}" for p in construction.plates for m in p.marks_left_off]
    assert report["marks_left_off"] == left_off and len(left_off) >= 1
    assert any(f"{len(left_off)} slot(s) without their partner's label" in w for w in made.warnings)


def _hollow_vase() -> np.ndarray:
    """A closed vase of revolution, hollow: a seven-lobed shell around one cavity."""
    from pathlib import Path

    from voxfab.digitize._recipes import make_revolution

    return make_revolution(base_dir=Path("."), curve="sqrt(x^2 + y^2) - 1 - 0.1972*cos(7*atan2(y, x))",
                           generatrix="max(x - (0.4378 + 0.0948*sin(2.8641*y + 1.9493)), abs(y) - 1.5231)",
                           mode="surface")


@pytest.mark.parametrize("style", ["interlocked", "radial"])
def test_the_sheets_cut_exactly_the_plates_assembled(tmp_path, style) -> None:
    """A hollow vase at 8 mm in 3 mm plates: each part cut on the sheets, holes and all, is a plate of
    assembly.3mf; no ring cuts out scrap the assembly does not use (the closed cavity is filled)."""
    import json

    import ezdxf
    import shapely
    import trimesh
    from _dxf_read import closed_rings

    from voxfab.shape import VoxelShape, cavity_count

    grid = _hollow_vase()
    assert cavity_count(grid) == 1
    fabricate_plates(VoxelShape(grid, 8.0), PlateOptions(style=style, thickness=3.0), tmp_path / style, name="vase")
    report = json.loads((tmp_path / style / "plates.json").read_text())
    # what the laser frees: each region inside a cut ring, whatever is inside it
    freed = []
    for k in range(1, report["sheets"] + 1):
        rings = [shapely.Polygon(r) for r in closed_rings(ezdxf.readfile(tmp_path / style / f"sheet-{k:02d}.dxf"))]
        freed += [r.area for r in rings if not any(o.contains(r) for o in rings if o is not r)]
        inner = [r for r in rings if any(o.contains(r) for o in rings if o is not r)]
        assert not inner, f"{len(inner)} ring(s) cut inside a part on sheet {k}"
    scene = trimesh.load(tmp_path / style / "assembly.3mf", force="scene")
    assembled = [m.volume / report["thickness"] for m in scene.geometry.values()]
    assert len(freed) == len(assembled) == report["plates"] > 1
    assert sorted(freed) == pytest.approx(sorted(assembled), rel=1e-4)
    assert report["filled_voxels"] > 0
