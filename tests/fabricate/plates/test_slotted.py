"""Interlocked and radial plates, checked from the written files.

Each case writes the plates of one shape, style and material thickness, then
reads ``assembly.3mf`` back with trimesh, the sheets with ezdxf and
``plates.json``, and checks the construction with manifold3d against the
voxel solid meshed by the print pipeline.
"""

from __future__ import annotations

import json

import ezdxf
import manifold3d
import numpy as np
import pytest
import shapely
import trimesh

from voxfab.errors import FabricationError
from voxfab.fabricate.mesh import build_mesh
from voxfab.fabricate.plates import PlateOptions, fabricate_plates, make_interlocked, make_radial
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import VoxelShape, examples


def _overhang() -> np.ndarray:
    """A mushroom: a stem under a cap that overhangs it on every side."""
    g = np.zeros((15, 15, 16), bool)
    g[5:10, 5:10, :10] = True
    g[:, :, 10:16] = True
    g[:4, :4, 10:16] = False
    return g


@pytest.fixture(scope="module")
def shapes() -> dict[str, VoxelShape]:
    return {
        "ball": VoxelShape(examples.ball(8), 4.0),
        "torus": VoxelShape(examples.torus(8, 3), 4.0),
        "overhang": VoxelShape(_overhang(), 4.0),
        "queen": make_shape(load_recipe("recipes/chess/queen.toml")),
        "vase": make_shape(load_recipe("recipes/vase.toml")),
    }


def _manifold(mesh: trimesh.Trimesh) -> manifold3d.Manifold:
    m = manifold3d.Mesh(vert_properties=np.asarray(mesh.vertices, np.float32),
                        tri_verts=np.asarray(mesh.faces, np.uint32))
    return manifold3d.Manifold(m)


def _solid(shape: VoxelShape) -> manifold3d.Manifold:
    """The voxel solid exactly (split contacts, no bridges), in the print frame."""
    mesh = build_mesh(shape, contacts="split").mesh
    return manifold3d.Manifold(manifold3d.Mesh(vert_properties=np.asarray(mesh.vertices, np.float32),
                                               tri_verts=np.asarray(mesh.triangles, np.uint32)))


def _dxf_parts(path) -> tuple[list[float], np.ndarray]:
    """Areas of the parts cut on one DXF sheet (outer rings minus the rings inside them) and all cut points."""
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    rings = [shapely.Polygon([tuple(v.dxf.location)[:2] for v in e.vertices])
             for e in doc.modelspace().query("POLYLINE") if e.dxf.layer == "CUT"]
    points = np.concatenate([np.asarray(r.exterior.coords) for r in rings])
    rings.sort(key=lambda r: -r.area)
    outer: list[shapely.Polygon] = []
    areas: list[float] = []
    for r in rings:
        host = [i for i, o in enumerate(outer) if o.contains(r)]
        depth = len(host)
        if depth % 2 == 0:
            outer.append(r)
            areas.append(r.area)
        else:
            areas[host[-1]] -= r.area
            outer.append(r)
            areas.append(0.0)
    return [a for a in areas if a > 0], points


def _check(folder, shape: VoxelShape, thickness: float, kerf: float) -> dict:
    report = json.loads((folder / "plates.json").read_text())
    scene = trimesh.load(folder / "assembly.3mf", process=False, force="scene")
    meshes = {name: m for name, m in scene.geometry.items()}
    plates = report["plates_list"]
    labels = [p["label"] for p in plates]
    assert sorted(meshes) == sorted(labels) and len(meshes) == report["plates"] > 1
    # one scale: the assembly fills the print's box (origin at the shape's minimum corner, z up)
    size = np.array(report["size"])
    bounds = np.array([m.bounds for m in meshes.values()])
    assert np.all(bounds[:, 0] >= -1e-4) and np.all(bounds[:, 1] <= size + 1e-4)
    solid = _solid(shape)
    solids = {}
    for p in plates:
        mesh = meshes[p["label"]]
        assert mesh.is_watertight
        # flat and one material thickness thick: every vertex on one of two parallel planes
        normal = np.cross(p["u"], p["v"])
        depth = np.asarray(mesh.vertices) @ normal
        assert np.ptp(depth) == pytest.approx(thickness, abs=1e-4)
        assert np.all(np.isclose(depth, depth.min(), atol=1e-4) | np.isclose(depth, depth.max(), atol=1e-4))
        assert mesh.volume == pytest.approx(p["area"] * thickness, rel=1e-4)
        m = _manifold(mesh)
        solids[p["label"]] = m
        # inside the voxel solid, within one kerf (and float32 rounding)
        outside = (m - solid).volume()
        assert outside <= max(kerf, 1e-3) * p["area"] * 0.01 + 1e-3, (p["label"], outside)
    # no two plates share volume
    names = sorted(solids)
    boxes = {n: meshes[n].bounds for n in names}
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if np.any(boxes[a][1] < boxes[b][0]) or np.any(boxes[b][1] < boxes[a][0]):
                continue
            assert (solids[a] ^ solids[b]).volume() < 1e-3, (a, b)
    # the crossing graph, from the slots' partner labels, is one piece; partners touch in 3D
    parent = {n: n for n in labels}

    def find(x):
        while parent[x] != x:
            x = parent[x]
        return x

    for p in plates:
        assert p["slots"], p["label"]
        for s in p["slots"]:
            assert s["partner"] in parent
            assert s["depth"] > 0
            # partners meet at the slot's end or, at most, across the fit clearance of the slot's sides
            assert solids[p["label"]].min_gap(solids[s["partner"]], 1.0) <= report["clearance"] + 1e-3
            parent[find(p["label"])] = find(s["partner"])
    assert len({find(n) for n in labels}) == 1
    # the sheets cut the plates of the assembly: same count, same areas
    areas: list[float] = []
    width, height = report["sheet_width"], report["sheet_height"]
    for k in range(1, report["sheets"] + 1):
        a, points = _dxf_parts(folder / f"sheet-{k:02d}.dxf")
        areas += a
        assert points.min() >= 0 and points[:, 0].max() <= width and points[:, 1].max() <= height
    assert len(areas) == len(plates)
    if kerf == 0:
        assert sorted(areas) == pytest.approx(sorted(p["area"] for p in plates), rel=0.01)
    return report


CASES = [(name, style, t) for name in ("ball", "torus", "overhang", "queen", "vase")
         for style in ("interlocked", "radial") for t in (3.0, 6.0) if not (name == "torus" and style == "radial")]


@pytest.mark.parametrize(("name", "style", "thickness"), CASES)
def test_written_construction_is_flat_disjoint_inside_connected_and_cut(shapes, tmp_path, name, style,
                                                                        thickness) -> None:
    shape = shapes[name]
    sheet = "1300x900" if name == "vase" else "600x400"
    options = PlateOptions(style=style, thickness=thickness, sheet=sheet, count=4 if name == "vase" else 0)
    made = fabricate_plates(shape, options, tmp_path / "slices", name=name)
    assert {"assembly.3mf", "assembly.pdf", "plates.json"} <= {f.path for f in made.files}
    report = _check(tmp_path / "slices", shape, thickness, 0.0)
    assert report["style"] == style and report["thickness"] == thickness
    for p in report["plates_list"]:
        assert p["style"] == style
        assert ("angle" in p["plane"]) == (style == "radial")


def test_torus_has_no_hub_for_radial_plates(shapes, tmp_path) -> None:
    with pytest.raises(FabricationError, match="runs through no solid"):
        fabricate_plates(shapes["torus"], PlateOptions(style="radial"), tmp_path / "s", name="torus")
    assert not (tmp_path / "s").exists()


def test_slots_are_thickness_plus_clearance_and_kerf_true_on_the_sheet(shapes, tmp_path) -> None:
    shape = shapes["queen"]
    options = PlateOptions(style="interlocked", thickness=3.0, clearance=0.2, kerf=0.15)
    fabricate_plates(shape, options, tmp_path / "s", name="queen")
    report = _check(tmp_path / "s", shape, 3.0, 0.15)
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
    probe = shapely.LineString(part.place([[slot.position - 3, v], [slot.position + 3, v]]))
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


@pytest.mark.parametrize("style", ["interlocked", "radial"])
def test_assembly_order_lowers_every_plate_onto_plates_already_in_place(shapes, tmp_path, style) -> None:
    """The steps name every plate once; a plate's lower slots hold plates of earlier steps only."""
    import re

    fabricate_plates(shapes["queen"], PlateOptions(style=style), tmp_path / "s", name="queen")
    report = json.loads((tmp_path / "s" / "plates.json").read_text())
    step_of: dict[str, int] = {}
    for k, step in enumerate(report["steps"]):
        for label in re.findall(r"\b[ABR]\d+(?:-\d+)?\b", step.split(":")[0]):
            step_of.setdefault(label, k)
    assert sorted(step_of) == sorted(p["label"] for p in report["plates_list"])
    for p in report["plates_list"]:
        for s in p["slots"]:
            # a slot from the bottom goes over a plate already standing, one from the top takes a later one
            if s["side"] == "bottom":
                assert step_of[s["partner"]] < step_of[p["label"]]
            else:
                assert step_of[s["partner"]] > step_of[p["label"]]
    pdf = (tmp_path / "s" / "assembly.pdf").read_bytes()
    assert pdf.startswith(b"%PDF") and pdf.count(b"/Type /Page") - pdf.count(b"/Type /Pages") == 1


def test_stacked_style_writes_its_assembly_too(shapes, tmp_path) -> None:
    shape = shapes["overhang"]
    fabricate_plates(shape, PlateOptions(thickness=4.0), tmp_path / "s", name="o")
    report = json.loads((tmp_path / "s" / "plates.json").read_text())
    scene = trimesh.load(tmp_path / "s" / "assembly.3mf", process=False, force="scene")
    assert sorted(scene.geometry) == sorted(p["label"] for p in report["plates_list"])
    solid = _solid(shape)
    for p in report["plates_list"]:
        mesh = scene.geometry[p["label"]]
        z = np.asarray(mesh.vertices)[:, 2]
        assert (z.min(), z.max()) == pytest.approx((p["z"], p["z"] + 4.0))
        # dowel holes are 64-gons in the solid and exact circles in the report
        assert mesh.volume == pytest.approx(p["area"] * 4.0, rel=2e-3)
        assert (_manifold(mesh) - solid).volume() < 1e-3


@pytest.mark.parametrize("axes", ["yz", "zx"])
def test_other_axes_cross_along_the_third(shapes, tmp_path, axes) -> None:
    shape = shapes["queen"]
    fabricate_plates(shape, PlateOptions(style="interlocked", axes=axes, count=4), tmp_path / "s", name="q")
    report = _check(tmp_path / "s", shape, 3.0, 0.0)
    assert {p["plane"]["axis"] for p in report["plates_list"]} == set(axes)
    third = ({"x", "y", "z"} - set(axes)).pop()
    assert f"+{third}" in report["steps"][0]
