"""Colour through a recipe: paint operations, the build's shape files, and the scale kept for every command."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from _voxart import read_vox_independently

from voxfab import io
from voxfab.cli import main
from voxfab.errors import RecipeError
from voxfab.recipe import build, load_recipe, make_shape

RECIPE = """
name = "ball"
pitch = 3.4
[source]
maker = "implicit"
expression = "x^2 + y^2 + z^2 - 1"
size = 15
[[operations]]
op = "paint"
colour = "blue"
[[operations]]
op = "paint"
colour = "#c03020"
where = "7 - z"
[[operations]]
op = "rotate"
axis = "x"
turns = 1
"""


@pytest.fixture
def recipe(tmp_path):
    path = tmp_path / "ball.toml"
    path.write_text(RECIPE)
    return path


def test_paint_colours_by_an_expression_and_moves_with_the_shape(recipe):
    shape = make_shape(load_recipe(recipe))
    assert shape.colours.count == 2
    red = np.all(shape.colours.rgba[..., :3] == (0xC0, 0x30, 0x20), axis=-1)
    blue = np.all(shape.colours.rgba[..., :3] == (0x30, 0x60, 0xD0), axis=-1)
    assert np.array_equal(red | blue, shape.grid) and red.any() and blue.any()
    # Painted where 7 - z < 0 (z > 7), then turned a quarter about x: the colours turned with the voxels,
    # so the red part is now the part at y < 7, and the blue the rest.
    assert np.nonzero(red)[1].max() < 7 <= np.nonzero(blue)[1].min()


@pytest.mark.parametrize("op, message", [
    ('op = "paint"', "needs 'colour"),
    ('op = "paint"\ncolour = "#12"', "operations\\[0\\].colour"),
    ('op = "paint"\ncolour = "red"\nwhere = "z +* 2"', "operations\\[0\\].where"),
    # Paint of alpha 00 is no paint: the voxel would read back as empty from every RGBA file.
    ('op = "paint"\ncolour = "#ff000000"', "operations\\[0\\].colour: .*transparent"),
])
def test_bad_paint_is_refused_by_key(tmp_path, op, message):
    path = tmp_path / "bad.toml"
    path.write_text(RECIPE.split("[[operations]]")[0] + "[[operations]]\n" + op + "\n")
    with pytest.raises(RecipeError, match=message):
        load_recipe(path)


def test_build_writes_the_shape_with_its_pitch_and_colours(recipe, tmp_path, capsys):
    folder = build(load_recipe(recipe), tmp_path / "out")
    kept = io.read(folder / "shape.npz")
    assert kept.pitch == 3.4 and kept.colours.count == 2
    size, voxels = read_vox_independently(folder / "shape.vox")
    assert len(voxels) == kept.grid.sum() and len(set(voxels.values())) == 2
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["shape"]["colours"] == 2
    assert "shape.npz" in {f["path"] for f in manifest["files"]}
    assert main(["info", str(folder / "shape.npz")]) == 0
    assert "colours        2" in capsys.readouterr().out


def test_every_command_reads_the_builds_scale(recipe, tmp_path):
    folder = build(load_recipe(recipe), tmp_path / "out")
    run = [sys.executable, "-m", "voxfab", "mesh"]
    kept = subprocess.run([*run, str(folder / "shape.npz"), "-o", str(tmp_path / "a.stl"), "--json"],
                          capture_output=True, text=True, timeout=120)
    assert kept.returncode == 0 and "no scale" not in kept.stderr
    assert json.loads(kept.stdout)["size_mm"][2] == pytest.approx(15 * 3.4)
    lost = subprocess.run([*run, str(folder / "shape.npy"), "-o", str(tmp_path / "b.stl"), "--json"],
                          capture_output=True, text=True, timeout=120)
    assert lost.returncode == 0 and json.loads(lost.stdout)["size_mm"][2] == pytest.approx(15)
    note = [line for line in lost.stderr.splitlines() if "no scale" in line]
    assert len(note) == 1 and "--pitch" in note[0]
