"""Folding a net up: flat at the start, the surface at the end, every hinge held, folds turning the right way."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from voxfab.cli import main
from voxfab.errors import InvalidShapeError
from voxfab.recipe import load_recipe
from voxfab.recipe._build import make_shape
from voxfab.render import fold_angles, fold_frames, save_fold_animation
from voxfab.shape import examples
from voxfab.unfold import unfold

RECIPES = Path(__file__).resolve().parents[2] / "recipes"
OUT = Path(__file__).resolve().parents[2] / "output" / "test-pictures"


@pytest.fixture(scope="module")
def queen_net():
    grid = make_shape(load_recipe(RECIPES / "chess" / "queen.toml")).grid
    return unfold(grid, rng=1)


@pytest.mark.parametrize("which", ["queen", "tunnel"])
def test_the_net_folds_from_the_sheet_to_the_surface(queen_net, which):
    net = queen_net if which == "queen" else unfold(examples.tunnel_cube(5), rng=2)
    frames = fold_frames(net, steps=7)
    # Folded: the faces are the surface, corner for corner.
    assert np.abs(frames[-1] - net.corners3d).max() < 1e-9
    # Flat: one plane, and every face where the sheet has it (distances as in the 2D net).
    first = frames[0].reshape(-1, 3)
    centred = first - first.mean(axis=0)
    assert np.linalg.svd(centred, compute_uv=False)[-1] < 1e-6
    c2 = net.corners2d.reshape(-1, 2).astype(float)
    pick = np.random.default_rng(0).choice(len(first), size=(400, 2))
    d3 = np.linalg.norm(first[pick[:, 0]] - first[pick[:, 1]], axis=1)
    d2 = np.linalg.norm(c2[pick[:, 0]] - c2[pick[:, 1]], axis=1)
    assert np.allclose(d3, d2, atol=1e-6)
    # Every frame: each face stays a unit square and every fold of the tree stays a shared edge.
    root, parent, order, _ = fold_angles(net)
    for corners in frames:
        sides = np.linalg.norm(np.roll(corners, -1, axis=1) - corners, axis=2)
        assert np.allclose(sides, 1.0)
        for c in order[1:]:
            p = int(parent[c])
            close = np.linalg.norm(corners[c][:, None] - corners[p][None], axis=2) < 1e-6
            assert close.sum() == 2, (c, p)


def test_mountain_and_valley_folds_turn_opposite_ways(queen_net):
    """The hinge angle's sign against an independent test of the surface: is the child behind its parent?"""
    net = queen_net
    root, parent, order, angles = fold_angles(net)
    centre = net.corners3d.mean(axis=1)
    counts = {"mountain": set(), "valley": set(), "flat": 0}
    for c in order[1:]:
        p = int(parent[c])
        behind = float((centre[c] - centre[p]) @ net.normal[p])
        if abs(behind) < 1e-9:
            counts["flat"] += 1
            assert abs(angles[c]) < 1e-9
        else:
            kind = "mountain" if behind < 0 else "valley"  # convex edge: the child drops behind
            assert abs(abs(angles[c]) - np.pi / 2) < 1e-9
            counts[kind].add(int(np.sign(angles[c])))
    # A mountain fold turns the child away from the viewer, a valley fold towards.
    assert counts["mountain"] == {-1} and counts["valley"] == {1}


def test_fold_gif_from_the_cli(queen_net, tmp_path, capsys):
    path = tmp_path / "queen.json"
    path.write_text(queen_net.to_json())
    out = tmp_path / "fold.gif"
    assert main(["render", "--fold", str(path), "-o", str(out), "--steps", "12", "--size", "240"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["kind"] == "fold" and report["faces"] == queen_net.face_count
    with Image.open(out) as im:
        assert im.size == (240, 240) and im.n_frames == report["frames"] == 12
        im.seek(im.n_frames - 1)
        last = np.asarray(im.convert("RGB"))
    assert (last.sum(axis=2) < 700).mean() > 0.02  # the folded queen is drawn, not a blank frame
    OUT.mkdir(parents=True, exist_ok=True)
    save_fold_animation(queen_net, OUT / "queen-fold.gif", steps=24, size=320)  # for a person to look at


def test_fold_refusals(queen_net, tmp_path, capsys):
    path = tmp_path / "queen.json"
    path.write_text(queen_net.to_json())
    with pytest.raises(InvalidShapeError, match="steps"):
        fold_frames(queen_net, steps=1)
    assert main(["render", "--fold", str(path), "-o", str(tmp_path / "f.png")]) != 0
    assert main(["render", "x.npy", "--fold", str(path), "-o", str(tmp_path / "f.gif")]) != 0
    assert main(["render", "--fold", str(path), "-o", str(tmp_path / "f.gif"), "--steps", "1000"]) != 0
    err = capsys.readouterr().err
    assert err.count("voxfab: error:") == 3 and "Traceback" not in err
    assert not list(tmp_path.glob("f.*"))
