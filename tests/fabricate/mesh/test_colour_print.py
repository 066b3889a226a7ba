"""Coloured prints, checked from the files alone: every triangle's colour against the voxel it lies on.

The 3MF is read with zipfile and xml.etree, GLB, OBJ and PLY with trimesh; the
voxel under a triangle is found here from its points and normal, by plain
arithmetic, and PrusaSlicer's painting codes are derived here from its bit layout.
"""

from __future__ import annotations

import json
import subprocess
import sys
import zipfile

import numpy as np
import pytest
from _colourcheck import (
    check_triangle_colours,
    edges_closed,
    hexed,
    painting_code,
    printed_as_map,
    read_3mf,
    voxel_colours,
)
from _voxart import CHARACTER_COLOURS, character, character_rgba

from voxfab.fabricate.mesh import MeshOptions, build_mesh, check_mesh, fabricate_mesh, read_mesh
from voxfab.shape import VoxelColours, VoxelShape


def test_painting_codes_match_the_ones_checked_by_slicing():
    from voxfab.fabricate.mesh.formats.threemf import paint_code

    assert [painting_code(e) for e in range(1, 6)] == ["4", "8", "0C", "1C", "2C"]
    assert [paint_code(e) for e in range(1, 17)] == [painting_code(e) for e in range(1, 17)]
    with pytest.raises(ValueError):
        paint_code(17)


@pytest.fixture(scope="module")
def char_rgba():
    return character_rgba()


def _print(tmp_path, shape, fmt="3mf", **options):
    made = fabricate_mesh(shape, MeshOptions(format=fmt, **options), tmp_path / f"mesh.{fmt}", name="char",
                          report_path=tmp_path / "mesh.json")
    return made, json.loads((tmp_path / "mesh.json").read_text())


@pytest.mark.parametrize("colours", [None, 3])
def test_every_3mf_triangle_has_its_voxels_colour_three_ways(tmp_path, char_rgba, colours):
    made, report = _print(tmp_path, character(), colours=colours)
    filaments = report["colours"]["filaments"]
    assert len(filaments) == (12 if colours is None else 3)
    assert [f["extruder"] for f in filaments] == list(range(1, len(filaments) + 1))
    extruder = {f["colour"]: f["extruder"] for f in filaments}
    filled, hexes = voxel_colours(char_rgba)
    printed_as = printed_as_map(report)
    # Every colour of the character is printed with exactly one filament, and merged colours go to filaments.
    assert set(printed_as) == {hexed(c) for c in CHARACTER_COLOURS.values()}
    assert set(printed_as.values()) == set(extruder)
    (v, t, colour, mmu, bambu), = read_3mf(tmp_path / "mesh.3mf")
    assert edges_closed(t)
    on, off = check_triangle_colours(v, t, colour, hexes, filled, 2.0, printed_as)
    assert on > 300 and off > 0  # triangles on the four bridges (sword, feather, arms) lie partly off voxels
    assert mmu == bambu == [painting_code(extruder[c]) for c in colour]
    # The areas of mesh.json are those of the triangles of each colour; the voxels those of its colours.
    area = np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1) / 2
    for f in filaments:
        assert f["area_mm2"] == pytest.approx(area[np.array(colour) == f["colour"]].sum())
        assert f["voxels"] == sum(1 for h in hexes[filled] if printed_as[h] == f["colour"])
    # Extruder 1 holds the colour most of the print shows.
    assert [f["area_mm2"] for f in filaments] == sorted((f["area_mm2"] for f in filaments), reverse=True)
    assert check_mesh(read_mesh(tmp_path / "mesh.3mf")).triangles == len(t)


def test_split_parts_lie_on_voxel_faces_only(tmp_path, char_rgba):
    _, report = _print(tmp_path, character(), contacts="split")
    filled, hexes = voxel_colours(char_rgba)
    objects = read_3mf(tmp_path / "mesh.3mf")
    assert len(objects) == 5
    extruder = {f["colour"]: f["extruder"] for f in report["colours"]["filaments"]}
    for v, t, colour, mmu, _ in objects:
        assert edges_closed(t)
        on, off = check_triangle_colours(v, t, colour, hexes, filled, 2.0, printed_as_map(report))
        assert off == 0 and on == len(t)
        assert mmu == [painting_code(extruder[c]) for c in colour]


def _slabs(colours, widths):
    """Slabs of 4 x 4 voxels along x, each ``widths[i]`` thick in ``colours[i]``."""
    g = np.ones((sum(widths), 4, 4), bool)
    rgba = np.zeros((*g.shape, 4), np.uint8)
    x = 0
    for c, w in zip(colours, widths):
        rgba[x:x + w] = (*c, 255)
        x += w
    return VoxelShape(g, 2.0, VoxelColours.from_rgba(g, rgba))


def _groups(report):
    return sorted(sorted([f["colour"], *f["merged"]]) for f in report["colours"]["filaments"])


def test_merging_is_perceptual(tmp_path):
    red, red2, blue, cyan = (200, 30, 30), (210, 40, 35), (30, 60, 200), (40, 170, 200)
    shape = _slabs([red, red2, blue, cyan], [4, 4, 4, 4])
    _, three = _print(tmp_path / "a", shape, colours=3)
    assert _groups(three) == [["#1e3cc8"], ["#28aac8"], ["#c81e1e", "#d22823"]]  # the two reds share one
    _, two = _print(tmp_path / "b", shape, colours=2)
    assert _groups(two) == [["#1e3cc8", "#28aac8"], ["#c81e1e", "#d22823"]]
    # A group prints in its largest member's colour, one of the model's.
    assert {f["colour"] for f in two["colours"]["filaments"]} <= {"#c81e1e", "#d22823", "#1e3cc8", "#28aac8"}


def test_merging_is_weighted_by_visible_area(tmp_path):
    # Two large reds 20 apart in CIELAB, and one green voxel over 100 from both: by colour alone the reds
    # are the closest pair, but the green voxel is the least of the print to change colour.
    g = np.ones((20, 6, 6), bool)
    rgba = np.zeros((*g.shape, 4), np.uint8)
    rgba[:10] = (200, 30, 30, 255)
    rgba[10:] = (220, 90, 40, 255)
    rgba[19, 5, 5] = (40, 180, 60, 255)
    shape = VoxelShape(g, 2.0, VoxelColours.from_rgba(g, rgba))
    _, two = _print(tmp_path, shape, colours=2)
    assert _groups(two) == [["#28b43c", "#dc5a28"], ["#c81e1e"]]  # the green goes with the nearer orange


def test_the_same_shape_gives_the_same_bytes(tmp_path):
    for sub in ("a", "b"):
        _print(tmp_path / sub, character(), colours=5)
    for name in ("mesh.3mf", "mesh.json"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_more_than_16_colours_in_a_3mf_are_merged_with_a_warning(tmp_path):
    g = np.ones((20, 3, 3), bool)
    rgba = np.zeros((*g.shape, 4), np.uint8)
    for i in range(20):  # 20 slabs around the hue circle
        angle = 2 * np.pi * i / 20
        rgba[i] = (128 + 120 * np.cos(angle), 128 + 120 * np.cos(angle - 2.1), 128 + 120 * np.cos(angle + 2.1), 255)
    shape = VoxelShape(g, 2.0, VoxelColours.from_rgba(g, rgba))
    made, report = _print(tmp_path / "a", shape)
    assert len(report["colours"]["filaments"]) == 16 and report["colours"]["visible_colours"] == 20
    assert [w for w in made.warnings if "20 colours" in w and "16" in w]
    (v, t, colour, mmu, _), = read_3mf(tmp_path / "a" / "mesh.3mf")
    assert len(set(colour)) == 16 and set(mmu) == {painting_code(e) for e in range(1, 17)}
    # A viewer's file keeps every colour; asking for 16 is no warning.
    glb_made, glb = _print(tmp_path / "b", shape, fmt="glb")
    assert len(glb["colours"]["filaments"]) == 20
    assert not [w for w in glb_made.warnings if "merged" in w]  # nothing was merged, so nothing says so
    made16, _ = _print(tmp_path / "c", shape, colours=16)
    assert not [w for w in made16.warnings if "colours" in w]


def test_colours_through_the_cad_kernel_and_a_hollowed_print(tmp_path, char_rgba):
    made, report = _print(tmp_path, character(), colours=4, base=2.0, magnet="4x1")
    filled, hexes = voxel_colours(char_rgba)
    (v, t, colour, mmu, _), = read_3mf(tmp_path / "mesh.3mf")
    assert edges_closed(t)
    printed_as = printed_as_map(report)
    # The base plate and the pocket take the colours of the voxels above them.
    _, off = check_triangle_colours(v, t, colour, hexes, filled, 2.0, printed_as, z0=2.0)
    assert off > 0 and len(set(colour)) == 4
    # A hollowed painted ball: the walls of the cavity and of the drain in their voxels' colours.
    c = np.arange(12) - 5.5
    ball = (c[:, None, None] ** 2 + c[None, :, None] ** 2 + c[None, None, :] ** 2) <= 36
    rgba = np.zeros((*ball.shape, 4), np.uint8)
    rgba[ball] = (230, 230, 230, 255)
    rgba[ball & (c[None, None, :] > 1)] = (200, 40, 40, 255)
    rgba[ball & (c[:, None, None] > 2)] = (40, 40, 200, 255)
    shape = VoxelShape(ball, 2.0, VoxelColours.from_rgba(ball, rgba))
    made, report = _print(tmp_path / "h", shape, hollow=2)
    assert report["volume_mm3"] <= (ball.sum() - 8) * 8.0  # hollow, opened by its drain
    filled, hexes = voxel_colours(rgba)
    (v, t, colour, _, _), = read_3mf(tmp_path / "h" / "mesh.3mf")
    assert edges_closed(t)
    # Point by point against the solid ball's colours (the hollow print's voxels are some of its voxels):
    # the walls of the cavity and of the drain too lie on voxel faces, in their voxels' colours.
    on, off = check_triangle_colours(v, t, colour, hexes, filled, 2.0, printed_as_map(report))
    assert off == 0 and on == len(t) and len(set(colour)) == 3


def _trimesh_faces(path):
    """``(vertices mm z-up, faces, face colours uint8 RGB as trimesh gives them)`` of a mesh file."""
    import trimesh

    loaded = trimesh.load(path, process=False)
    if isinstance(loaded, trimesh.Trimesh):
        return [(loaded.vertices, loaded.faces, loaded.visual.face_colors[:, :3])]
    out = []
    for node in loaded.graph.nodes_geometry:
        transform, name = loaded.graph[node]
        geom = loaded.geometry[name].copy()
        geom.apply_transform(transform)
        material = geom.visual.material
        colour = getattr(material, "baseColorFactor", None)
        colour = material.diffuse if colour is None else colour
        v = np.asarray(geom.vertices)
        if path.suffix == ".glb":  # metres, y up -> mm, z up
            v = np.column_stack([v[:, 0], -v[:, 2], v[:, 1]]) * 1000.0
        out.append((v, np.asarray(geom.faces), np.tile(np.asarray(colour)[:3], (len(geom.faces), 1))))
    return out


def linear_byte(hex_colour: str) -> tuple[int, ...]:
    """glTF's linear colour factor of an sRGB colour, as trimesh keeps it (0..255)."""
    c = np.array([int(hex_colour[i:i + 2], 16) for i in (1, 3, 5)]) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return tuple(int(x) for x in np.round(lin * 255))


@pytest.mark.parametrize("fmt", ["glb", "obj", "ply"])
def test_viewer_formats_carry_each_triangles_colour(tmp_path, char_rgba, fmt):
    made, report = _print(tmp_path, character(), fmt=fmt)
    if fmt == "obj":
        assert [f.path for f in made.files] == ["mesh.obj", "mesh.mtl", "mesh.json"]
        assert (tmp_path / "mesh.obj").read_text().startswith("# voxfab mesh of char, millimetres\nmtllib mesh.mtl\n")
    filled, hexes = voxel_colours(char_rgba)
    printed_as = printed_as_map(report)
    if fmt == "glb":  # compare in the file's own terms: linear factors
        printed_as = {k: hexed(linear_byte(h)) for k, h in printed_as.items()}
    total = 0
    for v, f, rgb in _trimesh_faces(tmp_path / f"mesh.{fmt}"):
        colour = [hexed(c) for c in rgb]
        check_triangle_colours(v, f, colour, hexes, filled, 2.0, printed_as)
        total += len(f)
    assert total == report["triangles"]
    back = read_mesh(tmp_path / f"mesh.{fmt}")
    assert back.coloured and len(back.palette) == 12
    check_mesh(back)  # still closed, edge by edge


def test_stl_is_one_colour_and_says_so_once(tmp_path):
    from voxfab import io

    io.write(character(), tmp_path / "char.npz")
    io.write(character().with_colours(None), tmp_path / "plain.npz")
    run = [sys.executable, "-m", "voxfab", "mesh"]
    coloured = subprocess.run([*run, str(tmp_path / "char.npz"), "-o", str(tmp_path / "c.stl")],
                              capture_output=True, text=True, timeout=300)
    plain = subprocess.run([*run, str(tmp_path / "plain.npz"), "-o", str(tmp_path / "p.stl")],
                           capture_output=True, text=True, timeout=300)
    assert coloured.returncode == plain.returncode == 0
    notes = [line for line in coloured.stderr.splitlines() if "STL" in line]
    assert len(notes) == 1 and "one" in notes[0] and not [ln for ln in plain.stderr.splitlines() if "STL" in ln]
    assert (tmp_path / "c.stl").read_bytes()[84:] == (tmp_path / "p.stl").read_bytes()[84:]
    assert "colours:" not in coloured.stdout


def test_cli_reports_the_extruders_and_refuses_a_bad_count(tmp_path):
    from voxfab import io

    io.write(character(), tmp_path / "char.npz")
    run = [sys.executable, "-m", "voxfab", "mesh", str(tmp_path / "char.npz"), "-o", str(tmp_path / "c.3mf")]
    ok = subprocess.run([*run, "--colours", "3"], capture_output=True, text=True, timeout=300)
    assert ok.returncode == 0, ok.stderr
    line = next(ln for ln in ok.stdout.splitlines() if ln.strip().startswith("colours:"))
    assert "12 colours merged into 3 filament(s)" in line and line.count("(with ") >= 2
    for bad in ("0", "17", "two"):
        refused = subprocess.run([*run, "--colours", bad], capture_output=True, text=True, timeout=300)
        assert refused.returncode != 0 and "Traceback" not in refused.stderr
        assert len(refused.stderr.strip().splitlines()) == 1 and "--colours" in refused.stderr


def test_uncoloured_shapes_keep_their_files(tmp_path):
    g = character().grid
    plain = build_mesh(VoxelShape(g, 2.0))
    one = build_mesh(VoxelShape(g, 2.0, VoxelColours.uniform(g, (200, 40, 40, 255))))
    # One colour merges faces exactly as no colour does.
    assert np.array_equal(plain.mesh.triangles, one.mesh.triangles) and plain.mesh.colour is None
    made, report = _print(tmp_path, VoxelShape(g, 2.0), colours=3)
    text = zipfile.ZipFile(tmp_path / "mesh.3mf").read("3D/3dmodel.model").decode()
    assert "basematerials" not in text and "mmu_segmentation" not in text and "colours" not in report
    assert report["notes"] == ["colours = 3: the shape has no colours, so there is nothing to merge"]


RECIPE = """
name = "capped"
pitch = 3.0
[source]
maker = "implicit"
expression = "x^2 + y^2 + z^2 - 1"
size = 9
[[operations]]
op = "paint"
colour = "#3060d0"
[[operations]]
op = "paint"
colour = "#c03020"
where = "5 - z"
[[operations]]
op = "paint"
colour = "#d04030"
where = "(x - 4)^2 + (y - 4)^2 - 2"
[outputs.mesh]
colours = COLOURS
"""


def test_recipe_key_and_studio_options_are_the_same_declaration(tmp_path, capsys):
    from voxfab.errors import RecipeError
    from voxfab.fabricate import outputs
    from voxfab.recipe import build, load_recipe

    path = tmp_path / "capped.toml"
    path.write_text(RECIPE.replace("COLOURS", "0"))
    with pytest.raises(RecipeError, match=r"outputs\.mesh\.colours"):
        load_recipe(path)
    path.write_text(RECIPE.replace("COLOURS", "2"))
    folder = build(load_recipe(path), tmp_path / "out")
    report = json.loads((folder / "mesh.json").read_text())
    assert _groups(report) == [["#3060d0"], ["#c03020", "#d04030"]]  # the two reds print as one
    (_, _, colour, _, _), = read_3mf(folder / "mesh.3mf")
    assert set(colour) == {"#3060d0", "#c03020"}
    # voxfab build says which filament goes in which extruder.
    from voxfab.cli import main

    assert main(["build", str(path), "-o", str(tmp_path / "cli")]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if ln.strip().startswith("colours:"))
    assert "3 colours merged into 2 filament(s), by extruder: 1 #" in line and "(with #d04030)" in line
    # The studio reads a download's options through the same table.
    row = outputs()["mesh"]
    assert row.settings(row.download_table("mesh.3mf", {"colours": 4})).colours == 4
    with pytest.raises(Exception, match="colours: expected an integer number of filaments from 1 to 16"):
        row.settings(row.download_table("mesh.3mf", {"colours": 17}))


def test_a_colour_only_inside_takes_the_nearest_filament(tmp_path):
    g = np.ones((3, 3, 3), bool)
    rgba = np.zeros((3, 3, 3, 4), np.uint8)
    rgba[...] = (200, 30, 30, 255)
    rgba[1, 1, 1] = (30, 60, 200, 255)  # hidden: no face of it shows
    _, report = _print(tmp_path, VoxelShape(g, 2.0, VoxelColours.from_rgba(g, rgba)))
    (only,) = report["colours"]["filaments"]
    assert only["colour"] == "#c81e1e" and only["merged"] == ["#1e3cc8"] and only["voxels"] == 27
    assert report["colours"]["shape_colours"] == 2 and report["colours"]["visible_colours"] == 1


def test_bridges_take_the_same_colours_whatever_the_palette_order():
    # The sword's hilt touches the hand at one corner: its bridge ties between two colours, and the tie goes
    # by colour, not by where the palette happens to list them (a .vox and the repository order them apart).
    c = character()
    used = np.unique(c.colours.index[c.grid])
    new_of_old = np.zeros(256, np.int64)
    new_of_old[used] = np.arange(len(used), 0, -1)  # the palette reversed
    palette = np.zeros((len(used) + 1, 4), np.uint8)
    palette[new_of_old[used]] = c.colours.palette[used]
    reordered = VoxelShape(c.grid, c.pitch, VoxelColours(new_of_old[c.colours.index], palette))
    assert reordered.colours == c.colours
    meshes = [build_mesh(s, colours=None).mesh for s in (c, reordered)]
    assert np.array_equal(meshes[0].vertices, meshes[1].vertices)
    assert np.array_equal(meshes[0].triangles, meshes[1].triangles)
    hexes = [[tuple(m.palette[k][:3]) for k in m.colour] for m in meshes]
    assert hexes[0] == hexes[1]
