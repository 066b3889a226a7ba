"""Meshes in colour: each voxel takes the colour of the nearest surface, from face colours, vertex colours
or a texture, in PLY, GLB and OBJ with its MTL."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from PIL import Image

from voxfab import io

RED, BLUE = (220, 30, 30, 255), (40, 60, 200, 255)


def _striped_box() -> trimesh.Trimesh:
    """A 10 x 10 x 20 box, its top face red and the rest blue, one colour per triangle."""
    box = trimesh.creation.box(extents=(10, 10, 20))
    box.unmerge_vertices()  # a colour per face needs corners of its own in formats that colour vertices
    colours = np.tile(BLUE, (len(box.faces), 1)).astype(np.uint8)
    colours[box.triangles_center[:, 2] > 9.9] = RED
    box.visual.face_colors = colours
    return box


@pytest.mark.parametrize("ext", [".ply", ".glb", ".obj"])
def test_face_colours_give_each_voxel_its_nearest_face(tmp_path, ext):
    path = tmp_path / f"box{ext}"
    box = _striped_box()
    if ext == ".glb":  # glTF is y-up: the box stands on its end as a glTF viewer shows it
        box.apply_transform(trimesh.transformations.rotation_matrix(-np.pi / 2, [1, 0, 0]))
    box.export(path)
    result = io.read(path)
    assert result.colours is not None and result.colours.count == 2
    rgba = result.colours.rgba
    top = result.grid.shape[2] - 1
    # Voxels of the top layer are nearest the red top (its rim is as near a side: either will do);
    # every side voxel below is nearest a blue side.
    assert {tuple(c) for c in rgba[1:-1, 1:-1, top][result.grid[1:-1, 1:-1, top]]} == {RED}
    side = np.zeros(result.grid.shape, bool)
    side[[0, -1]] = side[:, [0, -1]] = True
    side[:, :, top - 1:] = False
    below = rgba[side & result.grid]
    assert {tuple(c) for c in below} == {BLUE}


def test_texture_through_mtl_is_sampled_where_each_voxel_is(tmp_path):
    ball = trimesh.creation.uv_sphere(radius=10, count=[32, 32])
    theta = np.arctan2(ball.vertices[:, 1], ball.vertices[:, 0])
    uv = np.stack([(theta / (2 * np.pi)) % 1.0, 0.5 + ball.vertices[:, 2] / 20.0], axis=1)
    image = np.zeros((64, 64, 4), np.uint8)
    image[:32] = RED  # the image's top half is v > 0.5: the upper hemisphere
    image[32:] = BLUE
    ball.visual = trimesh.visual.TextureVisuals(uv=uv, image=Image.fromarray(image))
    path = tmp_path / "ball.obj"
    ball.export(path)
    assert (tmp_path / "material.mtl").exists() or list(tmp_path.glob("*.mtl"))
    result = io.read(path)
    assert result.colours is not None
    z = np.argwhere(result.grid)[:, 2]
    colours = result.colours.rgba[result.grid]
    middle = (result.grid.shape[2] - 1) / 2
    upper, lower = z > middle + 1, z < middle - 1
    assert {tuple(c) for c in colours[upper]} == {RED}
    assert {tuple(c) for c in colours[lower]} == {BLUE}


def test_vertex_colours_blend_across_triangles(tmp_path):
    ball = trimesh.creation.icosphere(subdivisions=3, radius=10)
    colours = np.zeros((len(ball.vertices), 4), np.uint8)
    colours[:, 3] = 255
    colours[:, 0] = np.interp(ball.vertices[:, 2], [-10, 10], [0, 255]).round()
    ball.visual.vertex_colors = colours
    path = tmp_path / "ball.ply"
    ball.export(path)
    result = io.read(path)
    red = result.colours.rgba[..., 0].astype(float)
    z = np.indices(result.grid.shape)[2]
    # Red grows with height: the voxels' red channel follows z closely.
    assert np.corrcoef(red[result.grid], z[result.grid])[0, 1] > 0.95


def test_a_mesh_without_colours_reads_uncoloured(tmp_path):
    path = tmp_path / "plain.stl"
    trimesh.creation.box(extents=(5, 5, 5)).export(path)
    assert io.read(path).colours is None


def test_a_glb_is_read_upright_in_millimetres(tmp_path):
    # voxfab's own GLB of the character (y-up, in metres) reads back as its STL does: the same voxels, the
    # same pitch in mm, and the colours of the print.
    from _voxart import character

    from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh

    for ext in ("glb", "stl", "ply"):
        fabricate_mesh(character(pitch=2.0), MeshOptions(contacts="split"), tmp_path / f"c.{ext}", name="c")
    glb, stl = io.read(tmp_path / "c.glb"), io.read(tmp_path / "c.stl")
    assert np.array_equal(glb.grid, stl.grid) and glb.pitch == pytest.approx(stl.pitch, rel=1e-6)
    assert glb.grid.shape[2] == max(glb.grid.shape)  # the figure stands: its height is its longest side
    ply = io.read(tmp_path / "c.ply")  # the same colours, to the glTF's linear rounding
    assert np.abs(glb.colours.rgba[glb.grid].astype(int) - ply.colours.rgba[ply.grid].astype(int)).max() <= 3
