"""The exact strategy against proofs by hand and an exhaustive enumeration of spanning trees."""

from __future__ import annotations

import itertools
import pickle
import subprocess
import sys

import numpy as np
import pytest
from _zipper_checks import cuts_form_one_path

pytest.importorskip("ortools")

from voxfab.errors import EXIT_CODES, InvalidShapeError, NoNetExistsError, UnfoldError  # noqa: E402
from voxfab.shape import surface_graph  # noqa: E402
from voxfab.unfold import EdgeConstraints, unfold, validate  # noqa: E402
from voxfab.unfold._constraints import face_of  # noqa: E402

CUBE = np.ones((1, 1, 1), dtype=bool)
DOMINO = np.ones((2, 1, 1), dtype=bool)
#: Cell offset across each cell side (bottom, right, top, left), y up: the net format's convention.
STEP = ((0, -1), (1, 0), (0, 1), (-1, 0))


def _edges(sg) -> list[tuple[int, int, int, int]]:
    """Each surface edge once, as (a, k, b, kb)."""
    out = []
    for a in range(sg.face_count):
        for k in range(4):
            b, kb = int(sg.neighbor[a, k]), int(sg.neighbor_edge[a, k])
            if (a, k) < (b, kb):
                out.append((a, k, b, kb))
    return out


def _layout(sg, tree: list[tuple[int, int, int, int]]) -> dict[int, tuple[int, int]] | None:
    """Cells of the faces when the tree's edges are folded (face 0 at the origin, unturned); None on overlap."""
    adj: dict[int, list[tuple[int, int, int]]] = {}
    for a, k, b, kb in tree:
        adj.setdefault(a, []).append((k, b, kb))
        adj.setdefault(b, []).append((kb, a, k))
    cell, rot = {0: (0, 0)}, {0: 0}
    todo = [0]
    while todo:
        a = todo.pop()
        for k, b, kb in adj.get(a, ()):
            if b in cell:
                continue
            s = (k + rot[a]) % 4
            cell[b] = (cell[a][0] + STEP[s][0], cell[a][1] + STEP[s][1])
            rot[b] = (s + 2 - kb) % 4
            todo.append(b)
    return cell if len(set(cell.values())) == len(cell) else None


def _cut_path(sg, tree: list) -> bool:
    """Whether the edges left out of the tree form one simple path on the surface's vertices."""
    kept = {(a, k) for a, k, _, _ in tree}
    cut = [(int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])) for a, k, _, _ in _edges(sg) if (a, k) not in kept]
    deg: dict[int, int] = {}
    for u, v in cut:
        deg[u], deg[v] = deg.get(u, 0) + 1, deg.get(v, 0) + 1
    return max(deg.values()) <= 2 and len(cut) == len(deg) - 1  # connected: a tree has V - 1 edges


def _find(root: list[int], i: int) -> int:
    """The representative of ``i`` in a union-find forest."""
    while root[i] != i:
        i = root[i]
    return i


def _nets(grid: np.ndarray) -> list[tuple[tuple[int, int], bool]]:
    """Every spanning tree of the face graph that lays out without overlap: (box w <= h, cuts form a path)."""
    sg = surface_graph(grid)
    edges = _edges(sg)
    f = sg.face_count
    out = []
    for tree in itertools.combinations(edges, f - 1):
        root = list(range(f))
        ok = True
        for a, _, b, _ in tree:
            ra, rb = _find(root, a), _find(root, b)
            if ra == rb:
                ok = False
                break
            root[ra] = rb
        if not ok:
            continue
        cell = _layout(sg, list(tree))
        if cell is None:
            continue
        xs, ys = [c[0] for c in cell.values()], [c[1] for c in cell.values()]
        w, h = max(xs) - min(xs) + 1, max(ys) - min(ys) + 1
        out.append(((min(w, h), max(w, h)), _cut_path(sg, list(tree))))
    return out


def _fits(nets: list, box: tuple[int, int], zipper: bool = False) -> bool:
    lo, hi = sorted(box)
    return any(w <= lo and h <= hi and (path or not zipper) for (w, h), path in nets)


def _exact(grid: np.ndarray, box: tuple[int, int], **kw):
    try:
        net = unfold(grid, rng=0, strategy="exact", fit=box, timeout=30, **kw)
    except NoNetExistsError:
        return None
    assert validate(grid, net).ok, box
    return net


def test_cube_has_no_net_in_3x3_and_one_in_2x5_and_3x4():
    with pytest.raises(NoNetExistsError, match=r"^no one-piece net of this shape fits 3x3 faces \(proved\)$"):
        unfold(CUBE, rng=0, strategy="exact", fit=(3, 3), timeout=30)
    for box in ((2, 5), (5, 2), (3, 4), (4, 3)):
        net = _exact(CUBE, box)
        xmin, ymin, xmax, ymax = net.bounds()
        w, h = xmax - xmin, ymax - ymin
        assert (w <= box[0] and h <= box[1]) or (w <= box[1] and h <= box[0]), box
        assert net.strategy == "exact"


def _recipe_grid(name: str) -> np.ndarray:
    from pathlib import Path

    from voxfab.recipe import load_recipe, make_shape

    return make_shape(load_recipe(Path(__file__).parents[2] / "recipes" / f"{name}.toml")).grid


@pytest.mark.parametrize("name", ["chess/queen", "egg"])
def test_no_box_searches_the_box_that_holds_any_net(name):
    """The library itself (no front end) gives the exact strategy with no box the box of any_box.

    The whole shape: the growth hint in that roomy box is confirmed by the solver
    in about a second of CPU (queen 862 faces, egg 2398), so no slice is needed.
    """
    from voxfab.unfold._exact import any_box

    grid = _recipe_grid(name)
    faces = surface_graph(grid).face_count
    net = unfold(grid, rng=0, strategy="exact", timeout=120)
    assert net.strategy == "exact" and len(net.voxel) == faces
    report = validate(grid, net)  # refolded onto the shape: every face once, no overlap on the sheet
    assert report.ok, report
    xmin, ymin, xmax, ymax = net.bounds()
    w, h = sorted((xmax - xmin, ymax - ymin))
    assert w <= any_box(faces)[0] and h <= any_box(faces)[1]
    # The same net whatever the seed, and the same as asking for that box by hand.
    assert unfold(grid, rng=9, strategy="exact", timeout=120).to_json() == net.to_json()
    assert unfold(grid, rng=0, strategy="exact", fit=any_box(faces), timeout=120).to_json() == net.to_json()


def test_no_box_and_no_net_is_proved_for_any_box():
    """Constraints that cut a face off all round: no net in any box, and the message does not name one."""
    sg = surface_graph(DOMINO)
    ring = [(face_of(sg, 0), face_of(sg, int(sg.neighbor[0, k]))) for k in range(4)]
    with pytest.raises(NoNetExistsError, match=r"in any box \(proved\): .*cut off") as info:
        unfold(DOMINO, rng=0, strategy="exact", constraints=EdgeConstraints(cut=ring), timeout=30)
    assert info.value.box is None


def test_cube_min_box_is_2x5():
    net = unfold(CUBE, rng=0, strategy="exact", min_box=True, timeout=30)
    assert validate(CUBE, net).ok
    xmin, ymin, xmax, ymax = net.bounds()
    assert sorted((xmax - xmin, ymax - ymin)) == [2, 5]


@pytest.mark.parametrize("grid", [CUBE, DOMINO], ids=["cube", "domino"])
def test_boxes_agree_with_every_spanning_tree(grid):
    nets = _nets(grid)
    if grid is CUBE:
        assert len(nets) == 384  # the cube's spanning trees that are nets (11 up to symmetry)
    f = surface_graph(grid).face_count
    boxes = [(w, h) for w in range(1, 6) for h in range(w, 8) if w * h >= f]
    for box in boxes:
        assert (_exact(grid, box) is not None) == _fits(nets, box), box
    for box in [(2, 5), (3, 4), (3, 5), (2, 7), (4, 4)]:
        assert (_exact(grid, box, zipper=True) is not None) == _fits(nets, box, zipper=True), box


def test_zipper_net_cuts_form_one_path():
    grid = np.zeros((3, 2, 2), dtype=bool)
    grid[:, 0, 0] = grid[0, :, 0] = grid[0, 0, :] = True  # three arms from a corner
    net = unfold(grid, rng=0, strategy="exact", fit=(20, 20), zipper=True, timeout=30)
    assert validate(grid, net).ok
    assert cuts_form_one_path(grid, net)


@pytest.mark.parametrize("grid", [CUBE, DOMINO], ids=["cube", "domino"])
def test_zipper_in_any_box_agrees_with_every_spanning_tree(grid):
    """Without a box the zipper search answers "is there any zipper net": as the enumeration does."""
    expected = any(path for _, path in _nets(grid))
    try:
        net = unfold(grid, rng=0, strategy="exact", zipper=True, timeout=30)
    except NoNetExistsError:
        net = None
    assert expected and net is not None  # the cube and the domino both have zipper nets
    assert validate(grid, net).ok and cuts_form_one_path(grid, net)


def test_torus_has_no_zipper_net():
    # A ring has a handle: the cut edges of any of its nets hold a cycle.
    ring = np.ones((3, 3, 1), dtype=bool)
    ring[1, 1, 0] = False
    with pytest.raises(NoNetExistsError):
        unfold(ring, rng=0, strategy="exact", fit=(32, 32), zipper=True, timeout=30)
    with pytest.raises(NoNetExistsError, match="has a handle"):
        unfold(ring, rng=0, strategy="exact", zipper=True, timeout=30)


def _cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "voxfab", "net", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=120)


def test_same_net_json_twice_on_a_ball(tmp_path):
    from voxfab.shape import examples

    shape = examples.ball(3)
    assert 150 <= surface_graph(shape).face_count <= 260
    np.save(tmp_path / "ball.npy", shape)
    texts = []
    for name, seed in (("a.json", 0), ("b.json", 7)):  # the seed is not used
        r = _cli("ball.npy", "-o", name, "--strategy", "exact", "--box", "30x30", "--seed", seed,
                 "--timeout", 60, cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        texts.append((tmp_path / name).read_bytes())
    assert texts[0] == texts[1]
    from voxfab.unfold import Net

    assert validate(shape, Net.from_json(texts[0].decode())).ok


def test_cli_proved_none_has_its_own_exit_status_and_writes_nothing(tmp_path):
    np.save(tmp_path / "cube.npy", CUBE)
    r = _cli("cube.npy", "-o", "net.json", "--strategy", "exact", "--box", "3x3", cwd=tmp_path)
    assert r.returncode == EXIT_CODES[NoNetExistsError] and r.returncode not in (0, 1, 2)
    assert r.returncode != EXIT_CODES[UnfoldError]
    assert r.stderr.strip() == "voxfab: error: no one-piece net of this shape fits 3x3 faces (proved)"
    assert not (tmp_path / "net.json").exists()
    r = _cli("cube.npy", "-o", "net.json", "--strategy", "exact", "--box", "2x2", "--face-size", "10",
             cwd=tmp_path)  # a box in mm that holds no face: bad input, not a proof
    assert r.returncode == EXIT_CODES[InvalidShapeError], r.stderr
    assert r.stderr.startswith("voxfab: error: ") and "Traceback" not in r.stderr


def test_a_slow_run_gives_the_same_net():
    from voxfab.shape import examples

    shape = examples.ball(2)
    fast = unfold(shape, rng=0, strategy="exact", fit=(12, 12), timeout=60)
    # Out of time before the solver checked the growth net: the same net all the same.
    slow = unfold(shape, rng=0, strategy="exact", fit=(12, 12), timeout=1e-6)
    assert slow.to_json() == fast.to_json()


def test_time_out_is_undecided_not_none():
    grid = np.ones((3, 3, 6), dtype=bool)
    with pytest.raises(UnfoldError, match="^undecided") as info:
        unfold(grid, rng=0, strategy="exact", fit=(10, 9), timeout=0.05)
    assert not isinstance(info.value, NoNetExistsError)


def test_edge_constraints_are_obeyed_or_proved_impossible():
    sg = surface_graph(CUBE)
    top = next(i for i in range(sg.face_count) if face_of(sg, i)[3] == "+z")
    ring = [(face_of(sg, top), face_of(sg, int(sg.neighbor[top, k]))) for k in range(4)]
    cut = EdgeConstraints(cut=ring[:3])  # the top hangs by its fourth edge
    assert validate(CUBE, _exact(CUBE, (2, 5), constraints=cut), constraints=cut).ok
    keep = EdgeConstraints(keep=ring)  # a plus sign of five faces: the sixth has no room in 3x3
    with pytest.raises(NoNetExistsError):
        unfold(CUBE, rng=0, strategy="exact", fit=(3, 3), constraints=keep, timeout=30)
    assert validate(CUBE, _exact(CUBE, (3, 4), constraints=keep), constraints=keep).ok
    # Proved without a search: the plus sign spans 3x3, wider than 2x5; a face cut off all round.
    with pytest.raises(NoNetExistsError, match=r"fits 2x5 faces \(proved\): .*span 3x3") as info:
        unfold(CUBE, rng=0, strategy="exact", fit=(2, 5), constraints=keep, timeout=30)
    again = pickle.loads(pickle.dumps(info.value))
    assert str(again) == str(info.value) and again.box == (2, 5)
    with pytest.raises(NoNetExistsError, match="cut off"):
        unfold(CUBE, rng=0, strategy="exact", fit=(3, 4), constraints=EdgeConstraints(cut=ring), timeout=30)


def test_bad_options_are_refused():
    with pytest.raises(InvalidShapeError, match="one-piece"):
        unfold(CUBE, rng=0, strategy="exact", fit=(3, 4), pieces="auto")
    with pytest.raises(InvalidShapeError, match="needs strategy 'exact'"):
        unfold(CUBE, rng=0, min_box=True)


def test_zipper_needs_exact():
    with pytest.raises(InvalidShapeError, match="exact"):
        unfold(CUBE, rng=0, zipper=True)
