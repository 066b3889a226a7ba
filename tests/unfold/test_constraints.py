"""Edge constraints: cut edges are never folds, kept edges always are, on real shapes."""

from __future__ import annotations

import json
import subprocess
import sys
import time

import numpy as np
import pytest

from voxfab.errors import FormatError, InvalidShapeError, UnfoldError
from voxfab.shape import examples
from voxfab.unfold import EdgeConstraints, Net, seam_pairs, unfold, validate

_NAMES = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y",
          (0, 0, 1): "+z", (0, 0, -1): "-z"}


def _face(net: Net, i: int) -> tuple:
    return (*net.voxel[i].tolist(), _NAMES[tuple(net.normal[i].tolist())])


def _edge(net: Net, i: int, j: int) -> tuple:
    return tuple(sorted((_face(net, i), _face(net, j))))


def _folds(net: Net) -> list[tuple]:
    return [_edge(net, i, j) for i, j in net.folds.tolist()]


def _seams(grid, net: Net) -> list[tuple]:
    return [_edge(net, a, b) for (a, _), (b, _) in seam_pairs(grid, net).tolist()]


def _pick(items: list, fraction: float, seed: int) -> list:
    rng = np.random.default_rng(seed)
    return [items[t] for t in sorted(rng.choice(len(items), int(len(items) * fraction), replace=False))]


@pytest.mark.parametrize("name, grid", [("ball4", examples.ball(4)), ("tunnel5", examples.tunnel_cube(5)),
                                        ("random", examples.random_shape(2, side=10))])
def test_cut_and_keep_edges_of_another_net_are_honoured(name, grid):
    # Another net's seams and folds are a feasible set of constraints.
    other = unfold(grid, rng=1, tab_aware=False)
    cut = _pick(_seams(grid, other), 0.25, 2)
    keep = _pick(_folds(other), 0.25, 3)
    c = EdgeConstraints(cut=cut, keep=keep)
    net = unfold(grid, rng=5, constraints=c, timeout=30)
    assert validate(grid, net, constraints=c).ok  # the independent refold agrees
    folds = set(_folds(net))
    assert not folds & c.cut
    assert c.keep <= folds
    # The constraints changed the net: without them the same seed folds some cut edges.
    free = unfold(grid, rng=5, timeout=30)
    assert set(_folds(free)) & c.cut
    assert not validate(grid, free, constraints=c, strict=False).ok


def test_kept_faces_move_as_one_rigid_group():
    grid = examples.box(4, 3, 3)
    top = [(x, y, 2, "+z") for x in range(4) for y in range(3)]
    # The whole top as one kept group (a tree of keep edges across it) plus its
    # fold over the +x side: a 4x3 block with a 3-face flap lying flat.
    keep = [((x, y, 2, "+z"), (x + 1, y, 2, "+z")) for x in range(3) for y in range(3)]
    keep += [((0, y, 2, "+z"), (0, y + 1, 2, "+z")) for y in range(2)]
    keep += [((3, y, 2, "+z"), (3, y, 2, "+x")) for y in range(3)]
    c = EdgeConstraints(keep=keep)
    for seed in range(4):
        net = unfold(grid, rng=seed, constraints=c)
        assert validate(grid, net, constraints=c).ok
        faces = {_face(net, i): i for i in range(net.face_count)}
        cells = {f: tuple(net.corners2d[faces[f]].min(axis=0).tolist()) for f in top}
        xs = {cells[f][0] for f in top}
        ys = {cells[f][1] for f in top}
        assert len(xs) * len(ys) == 12  # the top lies as one flat 4x3 (or 3x4) block
        # Coplanar neighbours on the block meet in the plane, so they are folds too.
        assert ((1, 1, 2, "+z"), (1, 2, 2, "+z")) in set(_folds(net))


def test_cut_edge_never_closes_up_in_the_plane():
    # Cutting every edge between two faces of a flat top still needs them apart.
    grid = examples.box(3, 3, 3)
    cut = [((1, 1, 2, "+z"), (2, 1, 2, "+z")), ((1, 1, 2, "+z"), (1, 2, 2, "+z"))]
    c = EdgeConstraints(cut=cut)
    for seed in range(6):
        net = unfold(grid, rng=seed, constraints=c)
        assert validate(grid, net, constraints=c).ok  # slits are refused by the validator


def test_same_seed_same_net_with_constraints():
    grid = examples.ball(3)
    other = unfold(grid, rng=0, tab_aware=False)
    c = EdgeConstraints(cut=_seams(grid, other)[:10], keep=_folds(other)[:10])
    assert unfold(grid, rng=4, constraints=c).to_json() == unfold(grid, rng=4, constraints=c).to_json()


def test_impossible_keep_edges_are_refused():
    grid = examples.box(2, 2, 2)
    corner = [(1, 1, 1, "+x"), (1, 1, 1, "+y"), (1, 1, 1, "+z")]
    loop = [(corner[0], corner[1]), (corner[1], corner[2]), (corner[2], corner[0])]
    with pytest.raises(UnfoldError, match="loop that cannot lie flat"):
        unfold(grid, rng=0, constraints=EdgeConstraints(keep=loop))
    # A kept band of 8 faces around the box cannot lie in a 5x6 box.
    band = [(0, 0, 1, "+z"), (1, 0, 1, "+z"), (1, 0, 1, "+x"), (1, 0, 0, "+x"), (1, 0, 0, "-z"),
            (0, 0, 0, "-z"), (0, 0, 0, "-x"), (0, 0, 1, "-x")]
    strip = list(zip(band, band[1:]))
    with pytest.raises(UnfoldError, match="do not fit"):
        unfold(grid, rng=0, fit=(5, 6), constraints=EdgeConstraints(keep=strip))
    assert validate(grid, unfold(grid, rng=0, fit=(5, 8), constraints=EdgeConstraints(keep=strip))).ok


def test_edges_not_on_the_surface_are_refused():
    grid = examples.box(2, 2, 2)
    with pytest.raises(InvalidShapeError, match="not an exposed face"):
        unfold(grid, rng=0, constraints=EdgeConstraints(cut=[((0, 0, 0, "+x"), (0, 0, 0, "+y"))]))
    with pytest.raises(InvalidShapeError, match="do not meet along an edge"):
        unfold(grid, rng=0, constraints=EdgeConstraints(cut=[((1, 0, 0, "+x"), (0, 1, 0, "+y"))]))
    with pytest.raises(InvalidShapeError, match="constraints"):
        unfold(grid, rng=0, constraints={"cut": []})


def test_json_form_round_trips_and_bad_input_is_refused():
    c = EdgeConstraints(cut=[[[1, 0, 0, "+x"], [1, 0, 0, "+z"]]], keep=[((0, 0, 1, "+z"), (1, 0, 1, "+z"))])
    assert c.cut == {((1, 0, 0, "+x"), (1, 0, 0, "+z"))}
    again = EdgeConstraints.from_json(c.to_json())
    assert again == c and again.to_json() == c.to_json()
    assert json.loads(c.to_json()) == {"cut": [[[1, 0, 0, "+x"], [1, 0, 0, "+z"]]],
                                       "keep": [[[0, 0, 1, "+z"], [1, 0, 1, "+z"]]]}
    assert EdgeConstraints.from_json('{"keep": [[[1,0,0,"+z"],[0,0,0,"+z"]]]}').keep == {
        ((0, 0, 0, "+z"), (1, 0, 0, "+z"))}
    with pytest.raises(FormatError):
        EdgeConstraints.from_json("[1, 2")
    with pytest.raises(FormatError, match="unknown key"):
        EdgeConstraints.from_json('{"cuts": []}')
    with pytest.raises(InvalidShapeError, match="normal"):
        EdgeConstraints.from_json('{"cut": [[[0,0,0,"up"],[0,0,0,"+x"]]]}')
    with pytest.raises(InvalidShapeError, match="both cut and kept"):
        EdgeConstraints(cut=[((0, 0, 0, "+x"), (0, 0, 0, "+z"))], keep=[((0, 0, 0, "+z"), (0, 0, 0, "+x"))])
    with pytest.raises(InvalidShapeError, match="integers"):
        EdgeConstraints(cut=[((0, 0.5, 0, "+x"), (0, 0, 0, "+z"))])


def test_net_command_reads_constraints(tmp_path):
    grid = examples.ball(3)
    np.save(tmp_path / "b.npy", grid)
    other = unfold(grid, rng=2, tab_aware=False)
    c = EdgeConstraints(cut=_seams(grid, other)[:12], keep=_folds(other)[:12])
    (tmp_path / "c.json").write_text(c.to_json())
    run = [sys.executable, "-m", "voxfab", "net", str(tmp_path / "b.npy"), "-o", str(tmp_path / "n.json"),
           "--constraints"]
    done = subprocess.run(run + [str(tmp_path / "c.json")], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    net = Net.from_json((tmp_path / "n.json").read_text())
    assert validate(grid, net, constraints=c).ok
    (tmp_path / "bad.json").write_text('{"cut": [[[40,0,0,"+x"],[40,0,0,"+z"]]]}')
    done = subprocess.run(run + [str(tmp_path / "bad.json")], capture_output=True, text=True, timeout=120)
    assert done.returncode != 0
    assert done.stderr.startswith("voxfab: error:") and "not an exposed face" in done.stderr
    assert "Traceback" not in done.stderr


def _all_edges_of(grid, net: Net, face: int) -> list[tuple]:
    """Every surface edge of ``face``, from the folds and seams of a net of ``grid``."""
    named = _face(net, face)
    return [e for e in _folds(net) + _seams(grid, net) if named in e]


@pytest.mark.parametrize("name, grid", [("ball5", examples.ball(5)), ("tunnel5", examples.tunnel_cube(5))])
def test_cut_constraints_that_leave_no_one_piece_net_fail_at_once(name, grid):
    other = unfold(grid, rng=1, tab_aware=False)
    lonely = _all_edges_of(grid, other, 7)
    assert len(lonely) == 4
    t0 = time.perf_counter()
    with pytest.raises(UnfoldError, match=r"cut off from all its neighbours.*--pieces auto"):
        unfold(grid, rng=2, constraints=EdgeConstraints(cut=lonely), timeout=60)
    # A ring of cuts around a patch of two faces.
    mate = next(b if a == 7 else a for a, b in other.folds.tolist() if 7 in (a, b))
    ring = sorted(set(lonely + _all_edges_of(grid, other, mate)) - {_edge(other, 7, mate)})
    with pytest.raises(UnfoldError, match=r"separate the 2 faces"):
        unfold(grid, rng=2, constraints=EdgeConstraints(cut=ring), timeout=60)
    assert time.perf_counter() - t0 < 10  # both refused before the 60 s search
