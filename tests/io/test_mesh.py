"""Meshes voxelized: volumes against analytic solids, voxels against analytic inside tests."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from voxfab import io
from voxfab._shared.progress import Meter
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.io.mesh import _crossings, mesh_grid, voxelize
from voxfab.shape import component_count, well_formed_reasons

MESH_FORMATS = ["stl", "obj", "ply", "3mf"]

R_SPHERE = 5.0
R_MAJOR, R_MINOR = 4.0, 1.5


def sphere() -> trimesh.Trimesh:
    return trimesh.creation.icosphere(subdivisions=4, radius=R_SPHERE)


def torus() -> trimesh.Trimesh:
    return trimesh.creation.torus(major_radius=R_MAJOR, minor_radius=R_MINOR, major_sections=96, minor_sections=48)


def box() -> trimesh.Trimesh:
    return trimesh.creation.box(extents=(10.0, 6.0, 4.0))


# name -> (mesh, analytic volume, analytic area, analytic inside test on points (N, 3))
SOLIDS = {
    "box": (box, 240.0, 2 * (60 + 40 + 24),
            lambda p: (np.abs(p) < np.array([5.0, 3.0, 2.0])).all(axis=1)),
    "sphere": (sphere, 4 / 3 * math.pi * R_SPHERE**3, 4 * math.pi * R_SPHERE**2,
               lambda p: np.linalg.norm(p, axis=1) < R_SPHERE),
    "torus": (torus, 2 * math.pi**2 * R_MAJOR * R_MINOR**2, 4 * math.pi**2 * R_MAJOR * R_MINOR,
              lambda p: (np.hypot(p[:, 0], p[:, 1]) - R_MAJOR) ** 2 + p[:, 2] ** 2 < R_MINOR**2),
}
# Distance from the analytic surface within which the faceted mesh may disagree with it.
FACET_MARGIN = {"box": 1e-9, "sphere": 0.02, "torus": 0.02}


def centres(shape, pitch, origin) -> np.ndarray:
    idx = np.indices(shape).reshape(3, -1).T
    return origin + (idx + 0.5) * pitch


@pytest.mark.parametrize("fmt", MESH_FORMATS)
@pytest.mark.parametrize("name", sorted(SOLIDS))
def test_volume_matches_analytic_solid(tmp_path, name, fmt):
    make, volume, area, _ = SOLIDS[name]
    path = tmp_path / f"{name}.{fmt}"
    make().export(path)
    result = io.read(path)
    pitch = result.pitch
    assert pitch == pytest.approx(max(make().extents) / 25)
    assert max(result.grid.shape) == 25
    measured = result.grid.sum() * pitch**3
    # A voxel is wrong only where the surface passes within a voxel of its centre,
    # and such errors mostly cancel: a tenth of a voxel layer over the surface.
    assert abs(measured - volume) <= 0.1 * area * pitch, (measured, volume)
    assert component_count(result.grid) == 1
    assert result.notes[0].endswith(", watertight")


@pytest.mark.parametrize("name", sorted(SOLIDS))
def test_voxels_match_analytic_inside_test_away_from_surface(tmp_path, name):
    make, _, _, inside = SOLIDS[name]
    mesh = make()
    grid, pitch, origin = voxelize(mesh.vertices, mesh.faces, resolution=25)
    pts = centres(grid.shape, pitch, origin)
    expected = inside(pts)
    # points clearly off the analytic surface (by the facet error) must agree exactly
    near = inside(pts * (1 + FACET_MARGIN[name] / 3)) != inside(pts * (1 - FACET_MARGIN[name] / 3))
    got = grid.reshape(-1)
    assert np.array_equal(got[~near], expected[~near])
    assert near.sum() < 0.05 * len(pts)
    # and the file reader gives this very grid (no cavity or extra piece here)
    mesh.export(tmp_path / "m.ply")
    assert np.array_equal(io.read(tmp_path / "m.ply").grid, grid)


@pytest.mark.parametrize("name", sorted(SOLIDS))
def test_three_ray_directions_agree_on_watertight_meshes(name):
    mesh = SOLIDS[name][0]()
    grid, pitch, origin = voxelize(mesh.vertices, mesh.faces, resolution=30)
    tri = (mesh.vertices[mesh.faces] - origin) / pitch - 0.5
    bar = Meter(None, "")
    votes = [_crossings(tri, axis, grid.shape, bar) for axis in range(3)]
    assert np.array_equal(votes[0], votes[1]) and np.array_equal(votes[1], votes[2])
    assert bar.done == 3 * len(tri)  # every batch of every ray direction counted


def test_box_aligned_with_the_grid_is_exact(tmp_path):
    # Faces on voxel boundaries and diagonals through voxel centres: the worst case for rays.
    path = tmp_path / "box.stl"
    box().export(path)
    result = io.read(path, resolution=50)
    assert result.grid.shape == (50, 30, 20) and result.grid.all()
    assert result.pitch == pytest.approx(0.2)


def test_hand_written_ascii_stl_and_obj(tmp_path):
    mesh = sphere()
    tris = mesh.vertices[mesh.faces].tolist()
    stl = ["solid s"]
    for t in tris:
        stl += ["facet normal 0 0 0", "outer loop", *(f"vertex {x!r} {y!r} {z!r}" for x, y, z in t), "endloop", "endfacet"]
    stl.append("endsolid s")
    (tmp_path / "s.stl").write_text("\n".join(stl) + "\n")
    obj = [f"v {x!r} {y!r} {z!r}" for x, y, z in mesh.vertices.tolist()]
    obj += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in mesh.faces.tolist()]
    (tmp_path / "s.obj").write_text("\n".join(obj) + "\n")
    expected, _, _ = voxelize(mesh.vertices, mesh.faces, resolution=25)
    for name in ("s.stl", "s.obj"):
        result = io.read(tmp_path / name)
        assert np.array_equal(result.grid, expected), name
        assert result.notes[0] == f"mesh of {len(mesh.faces)} triangles, watertight"


def test_mesh_with_holes_is_still_solid(tmp_path):
    mesh = sphere()
    whole, _, _ = voxelize(mesh.vertices, mesh.faces, resolution=25)
    rng = np.random.default_rng(7)
    keep = np.ones(len(mesh.faces), dtype=bool)
    keep[rng.choice(len(mesh.faces), size=40, replace=False)] = False
    holed = trimesh.Trimesh(mesh.vertices, mesh.faces[keep], process=False)
    assert not holed.is_watertight
    holed.export(tmp_path / "holed.stl")
    result = io.read(tmp_path / "holed.stl")
    assert result.grid.shape == whole.shape
    assert np.count_nonzero(result.grid != whole) <= 0.01 * whole.sum()
    assert "NOT watertight" in result.notes[0]
    assert any("open or non-manifold edges" in n for n in result.notes)


def test_separate_pieces_are_dropped_with_a_note(tmp_path):
    big = trimesh.creation.box(extents=(16, 10, 10))
    big.apply_translation((8, 5, 5))  # x 0..16
    small = trimesh.creation.box(extents=(4, 4, 4))
    small.apply_translation((23, 2, 2))  # x 21..25: longest side 25, pitch 1
    scene = trimesh.Scene([big, small])
    scene.export(tmp_path / "two.3mf")
    trimesh.util.concatenate([big, small]).export(tmp_path / "two.stl")
    for name in ("two.3mf", "two.stl"):
        result = io.read(tmp_path / name)
        assert "kept the largest 6-connected piece (1600 voxels); dropped 1 other piece (64 voxels)" in result.notes
        # The kept box is voxelized again on its own: 16 mm over 25 voxels, a well-formed shape.
        assert result.pitch == pytest.approx(16 / 25)
        assert result.grid.shape == (25, 16, 16) and result.grid.all(), name
        assert well_formed_reasons(result.grid) == []
        assert any("voxelized the kept piece again at 25 voxels" in n for n in result.notes)


def test_a_stray_piece_does_not_shrink_a_curved_shape(tmp_path):
    ball = trimesh.creation.icosphere(subdivisions=3, radius=10.0)
    speck = trimesh.creation.box(extents=(1, 1, 1))
    speck.apply_translation((30, 0, 0))  # far off: alone it would make the ball 13 voxels wide
    trimesh.util.concatenate([ball, speck]).export(tmp_path / "ball.stl")
    ball.export(tmp_path / "alone.stl")
    with_speck, alone = io.read(tmp_path / "ball.stl"), io.read(tmp_path / "alone.stl")
    assert np.array_equal(with_speck.grid, alone.grid) and with_speck.pitch == pytest.approx(alone.pitch)
    assert max(with_speck.grid.shape) == 25 and well_formed_reasons(with_speck.grid) == []


def test_enclosed_cavity_is_filled_with_a_note(tmp_path):
    outer = sphere()
    inner = trimesh.creation.icosphere(subdivisions=3, radius=2.5)
    inner.invert()
    hollow = trimesh.util.concatenate([outer, inner])
    hollow.export(tmp_path / "hollow.obj")
    full, _, _ = voxelize(outer.vertices, outer.faces, resolution=25)
    shell, pitch, origin = voxelize(hollow.vertices, hollow.faces, resolution=25)
    cavity = np.linalg.norm(centres(shell.shape, pitch, origin), axis=1).reshape(shell.shape) < 2.4
    assert not shell[cavity].any() and full[cavity].all()
    result = io.read(tmp_path / "hollow.obj")
    assert np.array_equal(result.grid, full)
    added = int(full.sum() - shell.sum())
    assert f"filled 1 enclosed cavity ({added} voxels)" in result.notes


def test_mesh_grid_notes_resolution():
    mesh = box()
    grid, pitch, notes = mesh_grid(mesh.vertices, mesh.faces, resolution=10)
    assert grid.shape == (10, 6, 4) and pitch == pytest.approx(1.0)
    assert notes == ["voxelized at 10 voxels along the longest side (1 mesh units per voxel)"]


@pytest.mark.parametrize("bad", [0, 257, 2.5, 25.0, True, -3, "25", None])
def test_bad_resolution(tmp_path, bad):
    box().export(tmp_path / "b.stl")
    with pytest.raises(InvalidShapeError, match="resolution"):
        io.read(tmp_path / "b.stl", resolution=bad)


def test_open_surface_has_nothing_inside(tmp_path):
    square = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])
    square.export(tmp_path / "square.stl")
    with pytest.raises(InvalidShapeError, match=r"square.stl: no voxel centre lies inside"):
        io.read(tmp_path / "square.stl")


def test_point_cloud_ply_is_not_a_mesh(tmp_path):
    trimesh.PointCloud(np.random.default_rng(0).random((20, 3))).export(tmp_path / "cloud.ply")
    with pytest.raises(FormatError, match="cloud.ply: the file holds no triangle"):
        io.read(tmp_path / "cloud.ply")


def test_non_finite_vertices(tmp_path):
    (tmp_path / "nan.obj").write_text("v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    with pytest.raises(FormatError, match="non-finite"):
        io.read(tmp_path / "nan.obj")


def test_batches_give_the_same_grid(monkeypatch):
    import voxfab.io.mesh as mesh_module

    mesh = torus()
    whole, _, _ = voxelize(mesh.vertices, mesh.faces, resolution=20)
    monkeypatch.setattr(mesh_module, "_PAIRS_PER_BATCH", 50)
    batched, _, _ = voxelize(mesh.vertices, mesh.faces, resolution=20)
    assert np.array_equal(whole, batched)


@pytest.mark.parametrize("seed", range(6))
def test_random_convex_solids_match_their_half_spaces(seed):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(30, 3)) * rng.uniform(0.5, 3.0, size=3)
    hull = trimesh.convex.convex_hull(points)
    hull.apply_transform(trimesh.transformations.random_rotation_matrix(rng.random(3)))
    assert hull.is_watertight
    grid, pitch, origin = voxelize(hull.vertices, hull.faces, resolution=18)
    # independent inside test: signed distances to the facet planes
    pts = centres(grid.shape, pitch, origin)
    normals, offsets = hull.face_normals, np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0])
    signed = (pts @ normals.T - offsets).max(axis=1)
    clear = np.abs(signed) > 1e-7 * pitch
    assert np.array_equal(grid.reshape(-1)[clear], (signed < 0)[clear])
    assert grid.sum() * pitch**3 == pytest.approx(hull.volume, rel=0.25)
