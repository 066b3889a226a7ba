"""Editing a net one edge at a time: the result validates and refolds, only a local part moves, errors are one line."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.recipe import load_recipe
from voxfab.recipe._build import make_shape
from voxfab.render import fold_frames
from voxfab.shape import examples
from voxfab.unfold import EdgeConstraints, Net, cut_edge, join_edge, seam_pairs, unfold, validate

RECIPES = Path(__file__).resolve().parents[2] / "recipes"
_NORMALS = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y", (0, 0, 1): "+z", (0, 0, -1): "-z"}


@pytest.fixture(scope="module")
def queen():
    grid = make_shape(load_recipe(RECIPES / "chess" / "queen.toml")).grid
    return grid, unfold(grid, rng=1)


@pytest.fixture(scope="module")
def ball():
    grid = examples.ball(3)
    return grid, unfold(grid, rng=5, timeout=30)


def name(net: Net, i: int) -> tuple:
    return (*net.voxel[i].tolist(), _NORMALS[tuple(net.normal[i].tolist())])


def cells(net: Net) -> dict:
    """Each face's (cell, corner 0) in the sheet, by its name."""
    lo = net.corners2d.min(axis=1)
    return {name(net, i): (tuple(lo[i].tolist()), tuple(net.corners2d[i, 0].tolist())) for i in range(net.face_count)}


def moved_faces(before: Net, after: Net) -> int:
    """Faces not where the rest of the net puts them: the most common shift of the sheet is 'not moved'."""
    a, b = cells(before), cells(after)
    shifts = {}
    for f, ((x0, y0), (p0, q0)) in a.items():
        (x1, y1), (p1, q1) = b[f]
        shift = (x1 - x0, y1 - y0)
        same_turn = (p1 - x1, q1 - y1) == (p0 - x0, q0 - y0)
        shifts[f] = shift if same_turn else None
    values = [s for s in shifts.values() if s is not None]
    common = max(set(values), key=values.count)
    return sum(1 for s in shifts.values() if s != common)


def folds_by_name(net: Net) -> set:
    return {frozenset((name(net, i), name(net, j))) for i, j in net.folds.tolist()}


def check(grid, result, marks=None) -> None:
    """The edited net is a valid unfolding keeping the marks, and it folds up onto the surface."""
    assert validate(grid, list(result.pieces), strict=False, constraints=marks or result.marks).ok
    for piece in result.pieces:
        if piece.face_count > 1:
            assert np.abs(fold_frames(piece, steps=2)[-1] - piece.corners3d).max() < 1e-9


@pytest.mark.parametrize("which", ["queen", "ball"])
def test_cut_opens_the_fold_and_moves_only_a_local_part(which, queen, ball):
    grid, net = queen if which == "queen" else ball
    # a fold near the edge of the layout: a few faces hang on it
    moved_counts = []
    for t in (len(net.folds) // 3, len(net.folds) // 2, 2 * len(net.folds) // 3):
        i, j = net.folds[t].tolist()
        r = cut_edge(grid, net, name(net, i), name(net, j))
        check(grid, r)
        assert len(r.pieces) == 1 and r.net.face_count == net.face_count
        edge = frozenset((name(net, i), name(net, j)))
        assert edge not in folds_by_name(r.net)
        assert {frozenset(e) for e in r.marks.cut} == {edge}
        assert edge in {frozenset(e) for e in r.cut}
        # Only the side that was cut off moved; the rest kept its place in the sheet.
        assert moved_faces(net, r.net) == r.moved <= net.face_count // 2
        moved_counts.append(r.moved)
    assert min(moved_counts) < net.face_count // 10


@pytest.mark.parametrize("which", ["queen", "ball"])
def test_join_folds_the_seam_and_moves_only_a_local_part(which, queen, ball):
    grid, net = queen if which == "queen" else ball
    seams = seam_pairs(grid, net)
    done = 0
    for s in seams[:: max(1, len(seams) // 6)][:6]:
        a, b = name(net, int(s[0, 0])), name(net, int(s[1, 0]))
        try:
            r = join_edge(grid, net, a, b)
        except UnfoldError as exc:
            assert "\n" not in str(exc) and str(exc).startswith("no room to join")
            continue
        check(grid, r)
        assert frozenset((a, b)) in folds_by_name(r.net)
        assert {frozenset(e) for e in r.marks.keep} == {frozenset((a, b))}
        # one fold on the loop it closed was opened instead
        assert len(r.cut) >= 1 and frozenset((a, b)) in {frozenset(e) for e in r.joined}
        assert moved_faces(net, r.net) == r.moved <= net.face_count // 2
        done += 1
    assert done >= 3


def test_marks_persist_over_a_run_of_edits(queen):
    grid, net = queen
    rng = np.random.default_rng(7)
    marks, cuts, edits = None, 0, 0
    for _ in range(6):
        i, j = net.folds[rng.integers(len(net.folds))].tolist()
        try:
            r = cut_edge(grid, net, name(net, i), name(net, j), constraints=marks)
        except UnfoldError as exc:  # a side with no free place to go: the net and marks stay as they were
            assert str(exc).startswith("no room to re-attach")
            continue
        net, marks = r.net, r.marks
        cuts += 1
        seams = seam_pairs(grid, net)
        s = seams[rng.integers(len(seams))]
        try:
            r = join_edge(grid, net, name(net, int(s[0, 0])), name(net, int(s[1, 0])), constraints=marks)
        except UnfoldError:
            continue
        net, marks = r.net, r.marks
        edits += 1
    assert cuts >= 3 and edits >= 2
    assert len(marks.cut) == cuts and len(marks.keep) == edits
    # every mark made along the way still holds in the last net
    assert validate(grid, net, constraints=marks).ok


def test_edits_are_deterministic(ball):
    grid, net = ball
    i, j = net.folds[10].tolist()
    one = cut_edge(grid, net, name(net, i), name(net, j)).net.to_json()
    two = cut_edge(grid, net, name(net, i), name(net, j)).net.to_json()
    assert one == two


def test_pieces_split_off_and_join_back(ball):
    grid, net = ball
    i, j = net.folds[len(net.folds) // 2].tolist()
    a, b = name(net, i), name(net, j)
    r = cut_edge(grid, net, a, b, split=True)
    assert len(r.pieces) == 2 and sum(p.face_count for p in r.pieces) == net.face_count
    check(grid, r)
    # joining the seam between the two pieces makes them one again, with that edge a fold
    back = join_edge(grid, list(r.pieces), a, b)
    assert len(back.pieces) == 1
    check(grid, back)
    assert frozenset((a, b)) in folds_by_name(back.net)
    # and a cut inside a net of several pieces splits by default
    k, m = r.pieces[0].folds[0].tolist()
    more = cut_edge(grid, list(r.pieces), name(r.pieces[0], k), name(r.pieces[0], m))
    assert len(more.pieces) == 3
    check(grid, more)


def test_errors_are_one_line(ball):
    grid, net = ball
    i, j = net.folds[0].tolist()
    seam = seam_pairs(grid, net)[0]
    s, t = name(net, int(seam[0, 0])), name(net, int(seam[1, 0]))
    cases = [
        (UnfoldError, "already cut", lambda: cut_edge(grid, net, s, t)),
        (UnfoldError, "already a fold", lambda: join_edge(grid, net, name(net, i), name(net, j))),
        (InvalidShapeError, "not an exposed face", lambda: cut_edge(grid, net, (90, 0, 0, "+z"), name(net, j))),
        (InvalidShapeError, "do not meet", lambda: cut_edge(grid, net, name(net, 0), name(net, net.face_count - 1))),
        (InvalidShapeError, "normal", lambda: cut_edge(grid, net, (0, 0, 0, "up"), name(net, j))),
    ]
    for kind, words, call in cases:
        with pytest.raises(kind) as info:
            call()
        assert words in str(info.value) and "\n" not in str(info.value)


def test_a_side_with_every_way_back_cut_has_no_room(ball):
    grid, net = ball
    # a face hanging on one fold, every other edge of it marked cut: cutting the fold leaves it nowhere to go
    degree = np.bincount(net.folds.reshape(-1), minlength=net.face_count)
    leaf = int(np.flatnonzero(degree == 1)[0])
    (pair,) = [p for p in net.folds.tolist() if leaf in p]
    other = pair[0] if pair[1] == leaf else pair[1]
    c3 = {tuple(c) for c in net.corners3d[leaf].tolist()}
    around = [g for g in range(net.face_count)
              if g not in (leaf, other) and len(c3 & {tuple(c) for c in net.corners3d[g].tolist()}) == 2]
    # only the edge neighbours of the face (two shared corners) are its edges; keep the ones the surface joins
    marks = EdgeConstraints(cut=[(name(net, leaf), name(net, g)) for g in around
                                 if validate(grid, net, strict=False, constraints=EdgeConstraints(
                                     cut=[(name(net, leaf), name(net, g))])).ok])
    assert len(marks.cut) == 3
    with pytest.raises(UnfoldError, match="no room to re-attach the 1 faces") as info:
        cut_edge(grid, net, name(net, leaf), name(net, other), constraints=marks)
    assert "\n" not in str(info.value)


def test_joining_a_loop_of_kept_folds_is_refused(ball):
    grid, net = ball
    seam = seam_pairs(grid, net)[0]
    a, b = int(seam[0, 0]), int(seam[1, 0])
    # keep every fold of the net: no fold on the loop may open
    marks = EdgeConstraints(keep=[(name(net, i), name(net, j)) for i, j in net.folds.tolist()])
    with pytest.raises(UnfoldError, match="would close a loop of kept folds"):
        join_edge(grid, net, name(net, a), name(net, b), constraints=marks)


def test_most_cuts_of_the_queen_find_room(queen):
    """Cuts spread over the net: the side goes back whole, piece by piece, or after lifting branches in its way."""
    grid, net = queen
    done = 0
    picks = net.folds[np.linspace(0, len(net.folds) - 1, 12).astype(int)]
    for i, j in picks.tolist():
        try:
            r = cut_edge(grid, net, name(net, i), name(net, j))
        except UnfoldError as exc:
            assert str(exc).startswith("no room to re-attach") and "\n" not in str(exc)
            continue
        assert validate(grid, r.net, strict=False, constraints=r.marks).ok
        assert moved_faces(net, r.net) == r.moved <= net.face_count // 2
        done += 1
    assert done >= 9


def test_an_edit_of_a_net_in_pieces_counts_tab_room_only_on_pieces_it_changed(monkeypatch):
    """Cuts of a net in pieces count the seams without tab room of each piece once: a second cut
    counts only the pieces it made, and every count is that of the piece as it is."""
    import voxfab.unfold._edit as edit
    from voxfab.unfold._layout import count_without_tab_room

    grid = examples.ball(4)
    pieces = list(unfold(grid, rng=0, fit=(6, 6), pieces="flat", timeout=60))
    assert len(pieces) >= 4
    counted: list[int] = []
    real = edit.count_without_tab_room
    monkeypatch.setattr(edit, "count_without_tab_room", lambda g, n: counted.append(1) or real(g, n))
    edit._UNTABBED.clear()
    big = max(pieces, key=lambda n: n.face_count)
    names = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y", (0, 0, 1): "+z", (0, 0, -1): "-z"}

    def face(i: int) -> tuple:
        return (*big.voxel[i].tolist(), names[tuple(big.normal[i].tolist())])

    results = []
    for t in range(2):
        i, j = big.folds[t * 3].tolist()
        counted.clear()
        results.append(cut_edge(grid, pieces, face(i), face(j), split=True))
        assert len(counted) == (len(pieces) + 1 if t == 0 else 2)
    for piece in results[1].pieces:
        assert piece.seams_without_tab_room == count_without_tab_room(grid, piece)
