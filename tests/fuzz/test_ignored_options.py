"""An option either acts or is refused by its flag: none is taken and silently ignored.

On the bundled queen; the outputs that are made are read back (trimesh, ezdxf) to
show the option's effect.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, refused, run_cli

from voxfab.recipe import load_recipe, make_shape

RECIPES = Path(__file__).resolve().parents[2] / "recipes"


@pytest.fixture(scope="module")
def queen(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("queen") / "queen.npy"
    np.save(path, make_shape(load_recipe(RECIPES / "chess" / "queen.toml")).grid)
    return path


@pytest.mark.parametrize("outputs, flags, words", [
    (["n.svg"], ["--dxf-version", "R12"], "--dxf-version: for .dxf drawings"),
    (["n.svg", "n.pdf"], ["--dxf-version", "R12"], "--dxf-version: for .dxf drawings"),
    (["n.dxf"], ["--svg-lines", "preview"], "--svg-lines: for .svg drawings"),
    (["n.json"], ["--tab-width", "7"], "--tab-width: for drawings"),
    (["n.json"], ["--sheet", "A3"], "--sheet: for drawings"),
    (["n.json"], ["--no-tabs"], "--tabs: for drawings"),
])
def test_a_drawing_option_no_output_reads_is_refused_by_its_flag(tmp_path, queen, outputs, flags, words):
    argv = ["net", queen, *[x for o in outputs for x in ("-o", tmp_path / o)], *flags]
    assert words in refused(argv)
    assert list(tmp_path.iterdir()) == []


def test_the_dxf_version_acts_on_a_dxf_beside_an_svg(tmp_path, queen):
    import ezdxf

    o = check_outcome(run_cli(["net", queen, "-o", tmp_path / "n.svg", "-o", tmp_path / "n.dxf", "--dxf-version",
                               "R12", "--face-size", "10", "--sheet", "A0"]))
    assert o.code == 0, o.err
    assert ezdxf.readfile(tmp_path / "n.dxf").dxfversion == "AC1009"  # R12


@pytest.mark.parametrize("flags, words", [
    (["--radial-plates", "6"], "--radial-plates: for the radial style, not stacked"),
    (["--style", "interlocked", "--radial-plates", "6"], "--radial-plates: for the radial style, not interlocked"),
    (["--style", "radial", "--count", "3"], "--count: for the interlocked style, not radial"),
    (["--style", "radial", "--dowel", "4"], "--dowel: for the stacked style, not radial"),
    (["--clearance", "0.3"], "--clearance: for the interlocked and radial styles, not stacked"),
    (["--style", "interlocked", "--axis", "x"], "--axis: for the stacked style, not interlocked"),
])
def test_a_plate_option_of_another_style_is_refused_by_its_flag(tmp_path, queen, flags, words):
    out = tmp_path / "plates"
    assert words in refused(["slices", queen, "-o", out, *flags])
    assert not out.exists()


def test_radial_plates_act_on_the_radial_style(tmp_path):
    import json

    top = tmp_path / "top.npy"
    np.save(top, make_shape(load_recipe(RECIPES / "spinning_top.toml")).grid)
    for n in (4, 6):
        out = tmp_path / f"radial-{n}"
        o = check_outcome(run_cli(["slices", top, "-o", out, "--style", "radial", "--radial-plates", n]))
        assert o.code == 0, o.err
        report = json.loads((out / "plates.json").read_text())
        assert report["style"] == "radial" and report["plates"] + len(report["left_out"]) == n, report


def test_hollow_walls_that_leave_no_cavity_are_refused(tmp_path, queen):
    line = refused(["mesh", queen, "-o", tmp_path / "q.stl", "--hollow", "128"])
    assert "hollow: walls of 128 voxels leave no cavity" in line and "at most 2" in line
    assert list(tmp_path.iterdir()) == []


def test_the_thickest_hollow_that_leaves_a_cavity_acts(tmp_path, queen):
    import trimesh

    volumes = {}
    for wall in (0, 2):
        o = check_outcome(run_cli(["mesh", queen, "-o", tmp_path / f"q{wall}.stl", "--hollow", wall]))
        assert o.code == 0, o.err
        mesh = trimesh.load(tmp_path / f"q{wall}.stl")
        assert mesh.is_watertight
        volumes[wall] = mesh.volume
    assert volumes[2] < volumes[0]
