"""The independent validator: it accepts real nets and catches every broken condition."""

from __future__ import annotations

import dataclasses
from collections import deque

import numpy as np
import pytest

from voxfab.errors import UnfoldError
from voxfab.shape import examples, surface_graph
from voxfab.unfold import Net, unfold, validate

# Cell corner offsets counter-clockwise and the step across each cell side, written
# out here so the fixtures do not lean on the search's own tables.
_CORNER = np.array([[0, 0], [1, 0], [1, 1], [0, 1]])
_STEP = np.array([[0, -1], [1, 0], [0, 1], [-1, 0]])


def _layout(grid, folds):
    """Lay out the tree ``folds`` of the surface of ``grid`` from face 0 (overlaps allowed)."""
    sg = surface_graph(grid)
    f = sg.face_count
    adj = {i: [] for i in range(f)}
    for a, b in folds:
        adj[a].append(b)
        adj[b].append(a)
    cell = {0: np.array([0, 0])}
    rot = {0: 0}
    queue = deque([0])
    while queue:
        i = queue.popleft()
        for j in adj[i]:
            if j in cell:
                continue
            k = int(np.flatnonzero(sg.neighbor[i] == j)[0])
            s = (k + rot[i]) % 4
            cell[j] = cell[i] + _STEP[s]
            rot[j] = (s + 2 - int(sg.neighbor_edge[i, k])) % 4
            queue.append(j)
    c2 = np.array([[cell[i] + _CORNER[(k + rot[i]) % 4] for k in range(4)] for i in range(f)])
    kinds = [int(sg.fold[a, int(np.flatnonzero(sg.neighbor[a] == b)[0])]) for a, b in folds]
    return Net(
        voxel=sg.voxel, normal=sg.normal, corners3d=sg.corners, corners2d=c2,
        folds=np.sort(np.array(folds), axis=1), seed=0, strategy="test",
        mountain=kinds.count(1), valley=kinds.count(-1), flat=kinds.count(0),
    )


@pytest.fixture(scope="module")
def ball_net():
    grid = examples.ball(3)
    return grid, unfold(grid, rng=5, timeout=30)


def _replace(net: Net, **changes) -> Net:
    return dataclasses.replace(net, **changes)


def test_real_net_is_valid(ball_net):
    grid, net = ball_net
    report = validate(grid, net)
    assert report.ok and report.faces == net.face_count == surface_graph(grid).face_count
    assert report.seams_without_tab_room == net.seams_without_tab_room


def test_unit_cube_cross_is_valid():
    # The Latin cross: -z at the centre, the four sides around, +z beyond +x's side.
    grid = examples.box(1, 1, 1)
    sg = surface_graph(grid)
    bottom = 5  # faces sorted by direction: +x -x +y -y +z -z
    folds = [(0, bottom), (1, bottom), (2, bottom), (3, bottom), (0, 4)]
    net = _layout(grid, folds)
    assert sg.face_count == 6
    assert validate(grid, net).ok


def test_catches_mirrored_face(ball_net):
    grid, net = ball_net
    c2 = net.corners2d.copy()
    c2[7] = c2[7][::-1]  # same square, clockwise
    problems = validate(grid, _replace(net, corners2d=c2), strict=False).problems
    assert any("mirrored" in p for p in problems)
    with pytest.raises(UnfoldError, match="mirrored"):
        validate(grid, _replace(net, corners2d=c2))


def test_catches_mirror_image_of_whole_net(ball_net):
    grid, net = ball_net
    c2 = net.corners2d.copy()
    c2[..., 0] *= -1  # reflect the whole sheet: every face is mirrored
    problems = validate(grid, _replace(net, corners2d=c2), strict=False).problems
    assert any("mirrored" in p for p in problems)


def test_catches_overlap(ball_net):
    grid, net = ball_net
    c2 = net.corners2d.copy()
    c2[3] = c2[3] - c2[3].min(axis=0) + c2[10].min(axis=0)
    problems = validate(grid, _replace(net, corners2d=c2), strict=False).problems
    assert any("overlap" in p for p in problems)


def test_catches_non_square_face(ball_net):
    grid, net = ball_net
    c2 = net.corners2d.copy()
    c2[4, 2] += 1
    problems = validate(grid, _replace(net, corners2d=c2), strict=False).problems
    assert any("unit square" in p for p in problems)


def test_catches_missing_face(ball_net):
    grid, net = ball_net
    keep = np.arange(net.face_count) != net.face_count - 1
    folds = net.folds[(net.folds < net.face_count - 1).all(axis=1)]
    bad = _replace(net, voxel=net.voxel[keep], normal=net.normal[keep],
                   corners3d=net.corners3d[keep], corners2d=net.corners2d[keep], folds=folds)
    problems = validate(grid, bad, strict=False).problems
    assert any("missing" in p for p in problems)


def test_catches_extra_and_repeated_face(ball_net):
    grid, net = ball_net
    far = net.corners2d[:1] + 1000
    extra = _replace(net, voxel=np.vstack([net.voxel, net.voxel[:1]]),
                     normal=np.vstack([net.normal, net.normal[:1]]),
                     corners3d=np.vstack([net.corners3d, net.corners3d[:1]]),
                     corners2d=np.vstack([net.corners2d, far]))
    problems = validate(grid, extra, strict=False).problems
    assert any("repeats" in p for p in problems)
    # A face of a voxel that is not in the shape.
    alien = _replace(extra, voxel=np.vstack([net.voxel, [[100, 100, 100]]]))
    problems = validate(grid, alien, strict=False).problems
    assert any("not an exposed face" in p for p in problems)


def test_catches_wrong_3d_corners(ball_net):
    grid, net = ball_net
    c3 = net.corners3d.copy()
    c3[2] = c3[2][::-1]  # clockwise seen from outside
    problems = validate(grid, _replace(net, corners3d=c3), strict=False).problems
    assert any("counter-clockwise" in p for p in problems)


def test_catches_broken_fold(ball_net):
    grid, net = ball_net
    # Rotate one leaf face in place: its fold edge no longer matches in 2D.
    counts = np.bincount(net.folds.ravel(), minlength=net.face_count)
    leaf = int(np.flatnonzero(counts == 1)[0])
    c2 = net.corners2d.copy()
    c2[leaf] = np.roll(c2[leaf], 1, axis=0)
    problems = validate(grid, _replace(net, corners2d=c2), strict=False).problems
    assert any("different places in 2D" in p for p in problems)


def test_catches_non_adjacent_fold(ball_net):
    grid, net = ball_net
    sg = surface_graph(grid)
    i = 0
    far = next(j for j in range(sg.face_count)
               if j not in sg.neighbor[i] and j != i and
               len({tuple(c) for c in sg.corners[i].tolist()} & {tuple(c) for c in sg.corners[j].tolist()}) == 0)
    folds = np.vstack([net.folds, [[i, far]]])
    problems = validate(grid, _replace(net, folds=folds), strict=False).problems
    assert any("share no edge" in p for p in problems)


def test_catches_fold_across_edge_contact():
    # Voxels (0,0,0) and (1,1,0) touch only along a vertical edge (joined above by
    # a bridge).  The +x face of one and the -y face of the other share that edge
    # geometrically, but by the 6-connectivity rule they are apart.
    grid = np.zeros((2, 2, 2), dtype=bool)
    grid[0, 0, 0] = grid[1, 1, 0] = True
    grid[0, 0, 1] = grid[1, 0, 1] = grid[1, 1, 1] = True
    net = unfold(grid, rng=0, timeout=10)
    assert validate(grid, net).ok
    sg = surface_graph(grid)
    a = int(np.flatnonzero((sg.voxel == [0, 0, 0]).all(1) & (sg.direction == 0))[0])
    b = int(np.flatnonzero((sg.voxel == [1, 1, 0]).all(1) & (sg.direction == 3))[0])
    assert b not in sg.neighbor[a]
    folds = np.vstack([net.folds, [[min(a, b), max(a, b)]]])
    problems = validate(grid, _replace(net, folds=folds), strict=False).problems
    assert any("not neighbours" in p for p in problems)


def test_catches_disconnected_net(ball_net):
    grid, net = ball_net
    folds = net.folds[1:]
    kinds_dropped = _replace(net, folds=folds)
    problems = validate(grid, kinds_dropped, strict=False).problems
    assert any("do not connect" in p for p in problems)


def test_catches_wrong_counts(ball_net):
    grid, net = ball_net
    problems = validate(grid, _replace(net, mountain=net.mountain + 1), strict=False).problems
    assert any("fold counts" in p for p in problems)
    problems = validate(
        grid, _replace(net, seams_without_tab_room=net.seams_without_tab_room + 1), strict=False
    ).problems
    assert any("tab room" in p for p in problems)


def test_catches_slit():
    # A 2x2 flat block of the 2x2x1 box's top with a cut ending at its centre.
    grid = examples.box(2, 2, 1)
    net = unfold(grid, rng=1, timeout=10)
    assert validate(grid, net).ok
    sg = surface_graph(grid)
    # Find a fold that is not needed for connectivity and whose faces are flat
    # neighbours: removing it leaves a cut whose sides meet in the plane.
    for t, (i, j) in enumerate(net.folds.tolist()):
        k = int(np.flatnonzero(sg.neighbor[i] == j)[0])
        if sg.fold[i, k] != 0:
            continue
        rest = np.delete(net.folds, t, axis=0)
        problems = validate(grid, _replace(net, folds=rest, flat=net.flat - 1), strict=False).problems
        if not any("do not connect" in p for p in problems):
            assert any("slit" in p for p in problems)
            return
    pytest.skip("this net has no cycle of flat folds")


# Uno (2008): the 1x1x3 box has an essentially unique overlapping edge development.
# Faces named by the z level of their voxel and their normal.
_UNO_FOLDS = [
    ((0, "+x"), (0, "-z")), ((0, "+x"), (1, "+x")), ((0, "-x"), (0, "-y")),
    ((0, "-x"), (1, "-x")), ((0, "+y"), (1, "+y")), ((0, "-y"), (0, "-z")),
    ((1, "+x"), (1, "-y")), ((1, "-x"), (2, "-x")), ((1, "+y"), (2, "+y")),
    ((2, "+x"), (2, "+y")), ((2, "+x"), (2, "-y")), ((2, "+x"), (2, "+z")),
    ((2, "-x"), (2, "-y")),
]
_NORMALS = {"+x": [1, 0, 0], "-x": [-1, 0, 0], "+y": [0, 1, 0], "-y": [0, -1, 0],
            "+z": [0, 0, 1], "-z": [0, 0, -1]}


def test_rejects_uno_overlapping_development_of_1x1x3_box():
    grid = examples.box(1, 1, 3)
    sg = surface_graph(grid)

    def face(z, n):
        hit = (sg.voxel == [0, 0, z]).all(1) & (sg.normal == _NORMALS[n]).all(1)
        return int(np.flatnonzero(hit)[0])

    folds = [(face(*a), face(*b)) for a, b in _UNO_FOLDS]
    assert len(folds) == sg.face_count - 1  # a spanning tree of the 14 faces
    net = _layout(grid, folds)
    cells = net.corners2d.min(axis=1)
    assert len({tuple(c) for c in cells.tolist()}) < sg.face_count  # it does overlap
    report = validate(grid, net, strict=False)
    assert any("overlap" in p for p in report.problems)
    # Every other condition holds: the only fault is the overlap.
    assert all("overlap" in p or "tab room" in p for p in report.problems)
    with pytest.raises(UnfoldError, match="overlap"):
        validate(grid, net)


def test_pieces_are_validated_together():
    grid = examples.box(3, 3, 3)
    grid[1, 1, 1] = False  # one cavity: two surfaces
    nets = unfold(grid, rng=2, pieces="auto", timeout=20)
    assert isinstance(nets, list) and len(nets) == 2
    assert validate(grid, nets).ok
    problems = validate(grid, nets[:1], strict=False).problems
    assert any("missing" in p for p in problems)


@pytest.mark.parametrize("tab_aware", [True, False])
def test_whole_array_and_face_by_face_checks_agree(monkeypatch, tab_aware):
    """A sound net is confirmed over whole arrays; the face-by-face check gives the same report."""
    from voxfab.unfold import _validate

    shapes = [examples.ball(4), examples.torus(6, 2)]
    nets = [(g, unfold(g, rng=s, timeout=60, tab_aware=tab_aware, pieces="auto")) for g in shapes for s in (0, 1)]
    fast = [validate(g, n, strict=False) for g, n in nets]
    assert all(r.ok for r in fast) and any(r.seams_without_tab_room for r in fast) == (not tab_aware)
    monkeypatch.setattr(_validate, "_sound_piece", lambda *a: None)
    monkeypatch.setattr(_validate, "_SOUND", {})  # no piece known sound: each checked face by face
    assert [validate(g, n, strict=False) for g, n in nets] == fast


def test_a_piece_found_sound_is_not_refolded_again_yet_any_change_to_it_is_caught(ball_net, monkeypatch):
    from voxfab.unfold import _validate

    grid, net = ball_net
    monkeypatch.setattr(_validate, "_SOUND", {})
    assert validate(grid, [net]).ok
    calls = []
    real = _validate._sound_piece
    monkeypatch.setattr(_validate, "_sound_piece", lambda *a: calls.append(1) or real(*a))
    # An edit validates many pieces it did not change: each is known sound.
    assert validate(grid, [net]).ok and calls == []
    # Any field changed is a piece of its own, checked again (and caught).
    problems = validate(grid, [_replace(net, mountain=net.mountain + 1)], strict=False).problems
    assert any("fold counts" in p for p in problems) and len(calls) == 1
    moved = _replace(net, corners2d=net.corners2d + 3)
    assert validate(grid, [moved]).ok and len(calls) == 2
    # A net given alone (a one-piece net, checked once) is neither looked up nor kept.
    assert validate(grid, moved).ok and len(calls) == 3
    # A sound piece twice: the second copy repeats the first's faces.
    problems = validate(grid, [net, net], strict=False).problems
    assert any("repeats" in p for p in problems)
