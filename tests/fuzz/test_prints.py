"""Hardening 3, class 1: valid hollow prints are made, keep their footprint, and measure as their voxels.

A drain hole once took the one voxel a spinning top stands on, and the mesh check then
refused the print against the box it had before.  Each case here builds the mesh, reads
the written file back with trimesh (an independent reader), and measures it in mm.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, run_cli
from hypothesis import given
from hypothesis import strategies as st

from voxfab.errors import InvalidShapeError
from voxfab.fabricate.mesh import build_mesh, hollow_out
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import cavity_count, component_count, crop

RECIPES = Path(__file__).parents[2] / "recipes"


def _shape(name: str):
    return make_shape(load_recipe(RECIPES / f"{name}.toml"))


def _measured(path: Path) -> tuple[np.ndarray, float, bool]:
    import trimesh

    mesh = trimesh.load(path, force="mesh", process=False)
    return np.asarray(mesh.bounds), float(mesh.volume), bool(mesh.is_watertight)


@pytest.mark.parametrize("wall", [1, 2, 3])
def test_the_spinning_top_hollowed_through_the_cli_keeps_its_tip(tmp_path: Path, wall: int) -> None:
    top = _shape("spinning_top")
    np.save(tmp_path / "top.npy", top.grid)
    assert crop(top.grid)[:, :, 0].sum() == 1  # it stands on one voxel
    out = tmp_path / "top.3mf"
    o = check_outcome(run_cli(["mesh", tmp_path / "top.npy", "--hollow", wall, "--pitch", 2.4, "-o", out]))
    assert o.code == 0, o.err
    bounds, volume, watertight = _measured(out)
    g = crop(top.grid)
    assert watertight
    assert np.allclose(bounds, [[0, 0, 0], np.array(g.shape) * 2.4], atol=1e-3)
    hollow = hollow_out(g, wall)
    assert hollow[:, :, 0].sum() == 1 and hollow[:, :, 0].tolist() == g[:, :, 0].tolist()  # the tip stays
    # the voxels, plus the small bridges over edge contacts that the thin inner wall leaves
    assert hollow.sum() * 2.4**3 * (1 - 1e-9) <= volume <= hollow.sum() * 2.4**3 * 1.002
    assert cavity_count(hollow) == 0 and component_count(hollow) == 1


@pytest.mark.parametrize("name", ["chess/pawn", "chess/queen", "egg", "vase"])
def test_bundled_shapes_hollow_with_their_footprint(name: str) -> None:
    g = crop(_shape(name).grid)
    h = hollow_out(g, 2)
    if h.sum() == g.sum():  # walls of 2 leave no cavity (the vase's are thinner): refused, changing nothing
        with pytest.raises(InvalidShapeError, match="hollow: walls of 2 voxels leave no cavity"):
            build_mesh(g, pitch=1.0, hollow=2)
        return
    r = build_mesh(g, pitch=1.0, hollow=2)
    assert np.allclose(r.report.bounds, [[0, 0, 0], g.shape])
    assert h[:, :, 0].any() and cavity_count(h) == 0
    assert h.sum() * (1 - 1e-9) <= r.report.volume <= h.sum() * 1.002


@st.composite
def standing_on_one_voxel(draw: st.DrawFn) -> np.ndarray:
    """A solid of revolution-like stack of squares and discs, on a one-voxel foot somewhere under it."""
    side = draw(st.integers(5, 11))
    height = draw(st.integers(4, 10))
    g = np.zeros((side, side, height + 1), bool)
    yy, xx = np.mgrid[:side, :side]
    c = (side - 1) / 2
    for z in range(1, height + 1):
        r = draw(st.floats(1.0, side / 2))
        if draw(st.booleans()):
            g[:, :, z] = np.hypot(xx - c, yy - c) <= r
        else:
            g[:, :, z] = np.maximum(abs(xx - c), abs(yy - c)) <= r
        if not g[:, :, z].any():
            g[int(c), int(c), z] = True
    # the foot: one voxel under a voxel of the first layer
    under = np.argwhere(g[:, :, 1])
    fx, fy = under[draw(st.integers(0, len(under) - 1))]
    g[fx, fy, 0] = True
    return g


@given(standing_on_one_voxel(), st.integers(1, 3))
def test_any_print_on_one_voxel_hollows_and_checks(g: np.ndarray, wall: int) -> None:
    if component_count(g) != 1:
        return  # layers that do not touch: not one print
    h = crop(hollow_out(g, wall))
    if h.sum() == g.sum():  # no voxel deeper than the walls: the option would change nothing, so it is refused
        with pytest.raises(InvalidShapeError, match="hollow: "):
            build_mesh(g, pitch=1.5, hollow=wall)
        return
    r = build_mesh(g, pitch=1.5, hollow=wall)
    assert cavity_count(h) == 0
    assert np.allclose(r.report.bounds, [[0, 0, 0], np.array(h.shape) * 1.5])
    assert h.sum() * 1.5**3 * (1 - 1e-9) <= r.report.volume <= h.sum() * 1.5**3 * 1.05  # contact bridges
    if h.shape == crop(g).shape:
        assert h[:, :, 0].sum() == 1  # the foot is kept whenever another drain exists
    else:
        assert any("stood on" in w for w in r.warnings)


def test_a_cavity_straight_above_its_only_foot_drains_through_it_and_says_so() -> None:
    g = np.zeros((3, 3, 6), bool)
    g[:, :, 1:] = True  # a 3x3 prism with a one-column cavity inside (wall 1)
    g[1, 1, 0] = True  # standing on one voxel right under the cavity
    r = build_mesh(g, pitch=2.0, hollow=1)
    assert any("stood on" in w for w in r.warnings)
    assert np.allclose(r.report.bounds, [[0, 0, 0], [6, 6, 10]])
    assert r.report.volume == pytest.approx((45 - 3 - 1) * 8.0)


@pytest.mark.parametrize(("base", "magnet", "cut_off"), [(3, "6x3", True), (3, "6x4", True), (2, "8x2.5", True),
                                                         (3, "6x2", False), (4, "6x3", False)])
def test_a_magnet_that_cuts_the_ball_off_its_base_is_named(tmp_path: Path, base: float, magnet: str,
                                                            cut_off: bool) -> None:
    from _fuzz import refused

    from voxfab.shape import examples

    np.save(tmp_path / "ball.npy", examples.ball(6))  # stands on one voxel
    argv = ["mesh", tmp_path / "ball.npy", "--base", base, "--magnet", magnet, "-o", tmp_path / "b.3mf"]
    if cut_off:
        line = refused(argv)
        assert f"a magnet pocket {magnet.split('x')[0]} mm wide" in line and "cuts the print off its" in line
        assert not (tmp_path / "b.3mf").exists()
    else:
        assert check_outcome(run_cli(argv)).code == 0
        bounds, _, watertight = _measured(tmp_path / "b.3mf")
        assert watertight and bounds[1][2] == pytest.approx(13 + base, abs=1e-3)
