"""Editing a net one edge at a time: cut a fold or join a seam, and repair the layout around it.

A net is a layout of unit cells, each face on one cell with one of four
rotations, held together by its folds.  Cutting a fold splits the fold tree in
two; the smaller side is lifted off and hung again, rigidly, across another
edge to the rest at the nearest place where its cells are free; where it fits
whole nowhere, its subtrees go back one by one, and failing that the small
branches of the rest in its way are lifted and hung again after it (in a net of
several pieces, or with ``split``, it is left as a piece of its own instead).  Joining a seam makes it a fold:
inside one piece that would close a loop, so a fold on the tree path between
the two faces is cut and the smaller side swings round to meet across the
joined edge; between two pieces the smaller piece moves to meet the other.
Everything else keeps its place in the sheet, so an edit is a local repair and
never a new search.

The marks gathered so far (:class:`EdgeConstraints`) are kept: a cut edge never
becomes a fold again, a kept edge is never cut, and each edit adds its own edge
to them (a cut to ``cut``, a join to ``keep``).  Every result is checked by
:func:`voxfab.unfold.validate` before it is returned.
"""

from __future__ import annotations

import dataclasses
import hashlib
import threading
from collections import deque
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid
from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.shape import SurfaceGraph, fill_cavities, surface_graph

from ._constraints import NORMALS, Edge, EdgeConstraints, Face, face_index, face_of
from ._layout import SIDE_STEP, build_net, count_without_tab_room
from ._net import Net
from ._validate import validate

__all__ = ["EditResult", "cut_edge", "join_edge"]

#: Places one edit may try for the faces it lifts (a bound on the time an edit takes when room is scarce).
MAX_TRIES = 3000

#: Rotation of a face from where its corner 0 sits in its cell (dx + 2 dy of CELL_CORNER).
_ROT_OF_CORNER = {0: 0, 1: 1, 3: 2, 2: 3}


@dataclasses.dataclass(frozen=True)
class EditResult:
    """The net after one edit.

    Attributes
    ----------
    pieces : tuple of Net
        The edited net: one Net for a one-piece net, else its pieces.
    marks : EdgeConstraints
        The marks gathered so far, with this edit's edge added.
    moved : int
        Faces that moved in the sheet (relative to the rest of their piece).
    cut : tuple of Edge
        Edges that were folds and are now cut (the edited edge, and any fold the
        repair had to open).
    joined : tuple of Edge
        Edges that were cut and are now folds.
    """

    pieces: tuple[Net, ...]
    marks: EdgeConstraints
    moved: int
    cut: tuple[Edge, ...]
    joined: tuple[Edge, ...]

    @property
    def net(self) -> Net:
        """The one-piece net (raises when the edit left several pieces)."""
        if len(self.pieces) != 1:
            raise UnfoldError(f"the edited net is in {len(self.pieces)} pieces, not one")
        return self.pieces[0]


@dataclasses.dataclass
class _Layout:
    """A net (or its pieces) as arrays over the surface graph's faces."""

    sg: SurfaceGraph
    grid: npt.NDArray[np.bool_]
    cell: npt.NDArray[np.int64]   # (F, 2) cell of each face, in its piece's frame
    rot: npt.NDArray[np.int64]    # (F,) rotation
    piece: npt.NDArray[np.int64]  # (F,) piece of each face
    fold: set[tuple[int, int]]    # folded face pairs (i < j), surface-graph indices
    nets: list[Net]


def _pair(i: int, j: int) -> tuple[int, int]:
    return (i, j) if i < j else (j, i)


def _load(grid: npt.ArrayLike, net: Net | Sequence[Net]) -> _Layout:
    nets = [net] if isinstance(net, Net) else list(net)
    if not nets:
        raise InvalidShapeError("net: no pieces to edit")
    g = as_grid(grid)
    if nets[0].filled:
        g = fill_cavities(g)
    sg = surface_graph(g)
    f = sg.face_count
    cell = np.zeros((f, 2), dtype=np.int64)
    rot = np.zeros(f, dtype=np.int64)
    piece = np.full(f, -1, dtype=np.int64)
    fold: set[tuple[int, int]] = set()
    for p, piece_net in enumerate(nets):
        names = [(int(v[0]), int(v[1]), int(v[2]), NORMALS[_direction(n)])
                 for v, n in zip(piece_net.voxel.tolist(), piece_net.normal.tolist())]
        ids = face_index(sg, names)
        if (ids < 0).any() or (piece[ids] >= 0).any():
            raise InvalidShapeError("net: its faces are not the faces of this shape (was it made for another one?)")
        c2 = piece_net.corners2d
        lo = c2.min(axis=1)
        off = c2[:, 0] - lo
        cell[ids] = lo
        rot[ids] = [_ROT_OF_CORNER[int(dx + 2 * dy)] for dx, dy in off.tolist()]
        piece[ids] = p
        for i, j in piece_net.folds.tolist():
            fold.add(_pair(int(ids[i]), int(ids[j])))
    if (piece < 0).any():
        raise InvalidShapeError(f"net: {int((piece < 0).sum())} faces of the shape are in no piece")
    return _Layout(sg, g, cell, rot, piece, fold, nets)


def _direction(n: list[int]) -> int:
    axis = int(np.flatnonzero(n)[0])
    return 2 * axis + (0 if n[axis] > 0 else 1)


def _edge_of(lay: _Layout, face_a: Face, face_b: Face) -> tuple[int, int, Edge]:
    """Surface-graph indices of the two faces of an edge, checked to meet along it."""
    edge = EdgeConstraints(cut=[(face_a, face_b)])
    e = next(iter(edge.cut))
    a, b = (int(i) for i in face_index(lay.sg, list(e)))
    for name, i in zip(e, (a, b)):
        if i < 0:
            raise InvalidShapeError(f"edge: face {list(name)} is not an exposed face of the shape")
    if not (lay.sg.neighbor[a] == b).any():
        raise InvalidShapeError(f"edge: faces {list(e[0])} and {list(e[1])} do not meet along an edge")
    return a, b, e


def _marked(lay: _Layout, marks: EdgeConstraints | None) -> tuple[set[tuple[int, int]], set[tuple[int, int]]]:
    """The cut and kept face pairs of ``marks`` as surface-graph indices (faces not on the surface ignored)."""
    out: list[set[tuple[int, int]]] = [set(), set()]
    if marks:
        for t, name in enumerate(("cut", "keep")):
            edges = sorted(getattr(marks, name))
            ids = face_index(lay.sg, [face for e in edges for face in e]).reshape(-1, 2)
            out[t] = {_pair(int(i), int(j)) for i, j in ids.tolist() if i >= 0 and j >= 0}
    return out[0], out[1]


def _tree(lay: _Layout, members: npt.NDArray[np.int64], first: list[tuple[int, int]],
          keep: set[tuple[int, int]]) -> dict[int, list[int]]:
    """A spanning tree of one piece's folds: kept folds first, then ``first``, then breadth first.

    Kept folds are in the tree so that no side a cut lifts off ever splits a kept
    edge; the root is the face nearest the middle of the piece, so the sides the
    tree cuts off lie towards the outside, as the fold-up hinges them.
    """
    inside = set(members.tolist())
    adj: dict[int, list[int]] = {i: [] for i in inside}
    for i, j in sorted(lay.fold):
        if i in inside and j in inside:
            adj[i].append(j)
            adj[j].append(i)
    centre = lay.cell[members].mean(axis=0)
    root = int(members[np.argmin(((lay.cell[members] - centre) ** 2).sum(axis=1))])
    order = {root: 0}
    queue = deque([root])
    while queue:
        i = queue.popleft()
        for j in adj[i]:
            if j not in order:
                order[j] = len(order)
                queue.append(j)
    edges = sorted((p for p in lay.fold if p[0] in inside and p[1] in inside),
                   key=lambda p: (max(order.get(p[0], 0), order.get(p[1], 0)), p))
    head = {i: i for i in inside}

    def find(i: int) -> int:
        while head[i] != i:
            head[i] = head[head[i]]
            i = head[i]
        return i

    tree: dict[int, list[int]] = {i: [] for i in inside}
    for i, j in [p for p in edges if p in keep] + first + edges:
        ri, rj = find(i), find(j)
        if ri != rj:
            head[ri] = rj
            tree[i].append(j)
            tree[j].append(i)
    return tree


def _side(tree: dict[int, list[int]], start: int, without: tuple[int, int]) -> npt.NDArray[np.int64]:
    """Faces reached from ``start`` in the tree without crossing the edge ``without``."""
    seen = {start}
    queue = [start]
    for i in queue:
        for j in tree[i]:
            if j not in seen and _pair(i, j) != without:
                seen.add(j)
                queue.append(j)
    return np.array(sorted(seen), dtype=np.int64)


def _keys(cells: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    # cells stay within a few thousand of the origin, so one int64 holds both coordinates
    return (cells[:, 0] + (1 << 20)) * (1 << 21) + (cells[:, 1] + (1 << 20))


def _turn(v: npt.NDArray[np.int64], quarter: int) -> npt.NDArray[np.int64]:
    """Cell offsets turned ``quarter`` quarter turns counter-clockwise."""
    x, y = v[..., 0], v[..., 1]
    for _ in range(quarter % 4):
        x, y = -y, x
    return np.stack([x, y], axis=-1)


@dataclasses.dataclass(frozen=True)
class _Move:
    moved: npt.NDArray[np.int64]
    cell: npt.NDArray[np.int64]  # new cells of the moved faces
    rot: npt.NDArray[np.int64]


def _hinge_move(lay: _Layout, moved: npt.NDArray[np.int64], u: int, k: int) -> _Move:
    """The rigid move of ``moved`` that puts face ``u`` across its edge ``k`` from the face there."""
    sg = lay.sg
    v = int(sg.neighbor[u, k])
    kv = int(sg.neighbor_edge[u, k])
    side = (kv + lay.rot[v]) % 4
    new_cell = lay.cell[v] + SIDE_STEP[side]
    new_rot = (side + 2 - k) % 4
    turn = int((new_rot - lay.rot[u]) % 4)
    cells = new_cell + _turn(lay.cell[moved] - lay.cell[u], turn)
    return _Move(moved, cells, (lay.rot[moved] + turn) % 4)


class _Hanger:
    """Hangs faces of a lifted side back onto the placed ones, keeping as much of the side rigid as fits.

    The whole side is tried first across each free edge, nearest first; when it
    fits nowhere, its root face goes alone to the nearest free place and each of
    its subtrees in turn hangs on its parent again (the old fold), or failing that
    across the nearest free edge, and so on down.  A place is free when no cell is
    taken twice, no cut edge closes up and no kept edge opens.
    """

    def __init__(self, lay: _Layout, placed: npt.NDArray[np.bool_], cut: set[tuple[int, int]],
                 keep: set[tuple[int, int]], tries: list[int]) -> None:
        self.lay, self.placed, self.cut, self.keep = lay, placed.copy(), cut, keep
        self.tries = tries  # places left to try, shared by the hangers of one edit
        self.keys = set(_keys(lay.cell[placed]).tolist())
        self.saved = (lay.cell.copy(), lay.rot.copy())
        self.log: list[tuple[_Move, npt.NDArray[np.int64], npt.NDArray[np.int64]]] = []

    def undo(self) -> None:
        self.lay.cell[:], self.lay.rot[:] = self.saved

    def moved(self) -> int:
        """Faces whose cell or turn the hanger changed."""
        cell, rot = self.saved
        return int(((self.lay.cell != cell).any(axis=1) | (self.lay.rot != rot)).sum())

    def back_to(self, mark: int) -> None:
        """Take back the moves committed since ``len(self.log)`` was ``mark``."""
        while len(self.log) > mark:
            mv, cell, rot = self.log.pop()
            self.lay.cell[mv.moved], self.lay.rot[mv.moved] = cell, rot
            self.placed[mv.moved] = False
            self.keys.difference_update(_keys(mv.cell).tolist())

    def fits(self, mv: _Move) -> bool:
        self.tries[0] -= 1
        if self.tries[0] < 0:
            return False
        if any(k in self.keys for k in _keys(mv.cell).tolist()):
            return False
        lay = self.lay
        w, k, y, pos = _boundary(lay, mv.moved, self.placed)
        if not w.size:
            return True
        side = (k + mv.rot[pos]) % 4
        meets = (mv.cell[pos] + SIDE_STEP[side] == lay.cell[y]).all(axis=1) & (
            lay.rot[y] == (side + 2 - lay.sg.neighbor_edge[w, k]) % 4)
        for i, j, m in zip(w.tolist(), y.tolist(), meets.tolist()):
            pair = _pair(i, j)
            if (m and pair in self.cut) or (not m and pair in self.keep):
                return False
        return True

    def commit(self, mv: _Move) -> None:
        self.log.append((mv, self.lay.cell[mv.moved].copy(), self.lay.rot[mv.moved].copy()))
        self.lay.cell[mv.moved] = mv.cell
        self.lay.rot[mv.moved] = mv.rot
        self.placed[mv.moved] = True
        self.keys.update(_keys(mv.cell).tolist())

    def nearest(self, side: npt.NDArray[np.int64]) -> list[_Move]:
        """Moves hanging ``side`` across each uncut edge to a placed face, nearest to where it was first."""
        w, k, y, _ = _boundary(self.lay, side, self.placed)
        centre = self.lay.cell[side].mean(axis=0)
        moves = []
        for t, (u, kk, v) in enumerate(zip(w.tolist(), k.tolist(), y.tolist())):
            if _pair(u, v) in self.cut:
                continue
            mv = _hinge_move(self.lay, side, u, kk)
            turned = int((mv.rot[0] - self.lay.rot[side[0]]) % 4) != 0
            moves.append((float(np.abs(mv.cell.mean(axis=0) - centre).sum()), turned, t, mv))
        moves.sort(key=lambda m: m[:3])
        return [m[3] for m in moves]

    def first(self, moves: list[_Move]) -> bool:
        for mv in moves:
            if self.fits(mv):
                self.commit(mv)
                return True
        return False

    def hang(self, tree: dict[int, list[int]], side: npt.NDArray[np.int64], root: int,
             hinge: tuple[int, int] | None = None) -> bool:
        """Place ``side`` (the tree below ``root``, not yet placed); ``hinge`` (face, edge) fixes the root's place."""
        children: dict[int, list[int]] = {}
        inside = set(side.tolist())
        order, up = [root], {root: -1}
        for i in order:
            children[i] = [j for j in tree[i] if j in inside and j not in up]
            for j in children[i]:
                up[j] = i
                order.append(j)
        below: dict[int, list[int]] = {}
        for i in reversed(order):
            below[i] = [i] + [f for c in children[i] for f in below[c]]
        mark = len(self.log)
        if self._hang(children, below, root, hinge):
            return True
        self.back_to(mark)
        return False

    def _hang(self, children: dict[int, list[int]], below: dict[int, list[int]], s: int,
              hinge: tuple[int, ...] | None) -> bool:
        """Hang the subtree below ``s``; ``hinge`` is (face, edge) or (face, edge, True) for a kept fold."""
        lay = self.lay
        sub = np.array(sorted(below[s]), dtype=np.int64)
        if hinge is not None:
            if self.first([_hinge_move(lay, sub, hinge[0], hinge[1])]):
                return True
            if len(hinge) == 3:
                return False
        elif self.first(self.nearest(sub)):
            return True
        alone = np.array([s], dtype=np.int64)
        if not self.first([_hinge_move(lay, alone, hinge[0], hinge[1])] if hinge is not None else self.nearest(alone)):
            return False
        for c in children[s]:
            k = int(np.flatnonzero(lay.sg.neighbor[c] == s)[0])
            kept = _pair(c, s) in self.keep
            mark = len(self.log)
            # back on its old fold first; a kept fold may not open at all
            if self._hang(children, below, c, (c, k, True) if kept else (c, k)):
                continue
            self.back_to(mark)
            if kept or not self._hang(children, below, c, None):
                return False
        return True


def _boundary(lay: _Layout, moved: npt.NDArray[np.int64], rest_mask: npt.NDArray[np.bool_]
              ) -> tuple[npt.NDArray[np.int64], ...]:
    w = np.repeat(moved, 4)
    k = np.tile(np.arange(4), moved.size)
    y = lay.sg.neighbor[w, k]
    keep = (y >= 0) & rest_mask[np.maximum(y, 0)]
    pos = np.repeat(np.arange(moved.size), 4)
    return w[keep], k[keep], y[keep], pos[keep]


def _rebuild(lay: _Layout, marks: EdgeConstraints, before: set[tuple[int, int]], *, moved: int,
             piece_of: npt.NDArray[np.int64]) -> EditResult:
    """Nets from the arrays (folds: every edge that meets in the plane), validated with the marks.

    ``before`` are the folded pairs before the edit, to tell which edges it cut and joined.
    """
    sg = lay.sg
    f = sg.face_count
    pieces = []
    template = lay.nets[0]
    parent = np.full(f, -1, dtype=np.int64)
    for p in range(int(piece_of.max()) + 1):
        faces = np.flatnonzero(piece_of == p)
        net = build_net(sg, faces, lay.cell, lay.rot, parent, seed=template.seed, strategy=template.strategy)
        net = dataclasses.replace(net, filled=template.filled)
        pieces.append(dataclasses.replace(net, seams_without_tab_room=_untabbed(lay.grid, net)))
    report = validate(lay.grid, pieces, strict=False, constraints=marks)
    if not report.ok:
        raise UnfoldError(f"the repaired net is not valid: {report.problems[0]}")
    return _with_changes(EditResult(tuple(pieces), marks, moved, (), ()), lay, before)


#: Seams without tab room of the pieces last rebuilt, by shape and piece: an edit changes one or two
#: pieces of many, and the others are counted once (a tenth of a second on the queen's 35 pieces).
_UNTABBED: dict[bytes, int] = {}
_UNTABBED_KEPT = 256
_UNTABBED_LOCK = threading.Lock()  # studio edits run on worker threads


def _untabbed(grid: npt.NDArray[np.bool_], net: Net) -> int:
    """:func:`count_without_tab_room` of ``net``, counted once per shape and piece."""
    h = hashlib.sha256(repr((grid.shape, net.voxel.shape, net.folds.shape)).encode())
    for a in (np.packbits(grid), net.voxel, net.normal, net.corners2d, net.folds):
        h.update(np.ascontiguousarray(a).tobytes())
    key = h.digest()
    with _UNTABBED_LOCK:
        known = _UNTABBED.get(key)
    if known is not None:
        return known
    count = count_without_tab_room(grid, net)
    with _UNTABBED_LOCK:
        _UNTABBED[key] = count
        while len(_UNTABBED) > _UNTABBED_KEPT:
            del _UNTABBED[next(iter(_UNTABBED))]
    return count


def _marks_with(marks: EdgeConstraints | None, edge: Edge, name: str) -> EdgeConstraints:
    cut = set(marks.cut) if marks else set()
    keep = set(marks.keep) if marks else set()
    (cut if name == "cut" else keep).add(edge)
    (keep if name == "cut" else cut).discard(edge)
    return EdgeConstraints(cut=cut, keep=keep)


def cut_edge(grid: npt.ArrayLike, net: Net | Sequence[Net], face_a: Face, face_b: Face, *,
             constraints: EdgeConstraints | None = None, split: bool | None = None) -> EditResult:
    """Cut the fold between two faces and repair the net around it.

    The fold tree loses the edge; the smaller of its two sides is hung again
    across another free edge to the rest, at the place nearest where it was with
    no cell taken twice, no cut edge closing up and no kept edge opening.  With
    ``split`` it becomes a piece of its own instead.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape the net unfolds.
    net : Net or sequence of Net
        The net, or its pieces.
    face_a, face_b : Face
        The edge, by its two faces ``(x, y, z, "+z")``.
    constraints : EdgeConstraints, optional
        The marks so far; the result keeps them and adds this cut.
    split : bool, optional
        Make the cut-off side a new piece (default: when the net is already in
        several pieces).

    Returns
    -------
    EditResult

    Raises
    ------
    InvalidShapeError
        The faces are not two faces of the shape meeting along an edge.
    UnfoldError
        The edge is not a fold, or the cut-off side has no room anywhere (one line).
    """
    lay = _load(grid, net)
    a, b, edge = _edge_of(lay, face_a, face_b)
    marks = _marks_with(constraints, edge, "cut")
    cut_pairs, keep = _marked(lay, marks)
    if _pair(a, b) not in lay.fold:
        raise UnfoldError(f"edge {_name(edge)} is already cut")
    split = len(lay.nets) > 1 if split is None else split
    p = int(lay.piece[a])
    members = np.flatnonzero(lay.piece == p)
    tree = _tree(lay, members, [_pair(a, b)], keep)
    side_b = _side(tree, b, _pair(a, b))
    moved = side_b if 2 * side_b.size <= members.size else np.setdiff1d(members, side_b)
    piece_of = lay.piece.copy()
    before = {_pair(i, j) for i, j in lay.fold}
    if split:
        piece_of[moved] = int(lay.piece.max()) + 1
        return _rebuild(lay, marks, before, moved=0, piece_of=_renumber(piece_of))
    placed = np.zeros(lay.sg.face_count, dtype=bool)
    placed[members] = True
    placed[moved] = False
    tries = [MAX_TRIES]
    hanger = _Hanger(lay, placed, cut_pairs, keep, tries)
    root, other = (b, a) if b in set(moved.tolist()) else (a, b)
    if not hanger.hang(tree, moved, root) and not (
            hanger := _make_room(lay, tree, moved, other, np.setdiff1d(members, moved), cut_pairs, keep, tries)):
        raise UnfoldError(f"no room to re-attach the {moved.size} faces cut off by edge {_name(edge)}: "
                          "every free place overlaps the rest or closes a cut edge; cut an edge nearer the outline, "
                          "or allow several pieces")
    return _rebuild(lay, marks, before, moved=hanger.moved(), piece_of=piece_of)


#: Faces of the rest an edit may lift out of the way and hang again, and the places of the side it tries.
MAX_LIFTED = 96
_ROOM_PLACES = 24


def _make_room(lay: _Layout, tree: dict[int, list[int]], moved: npt.NDArray[np.int64], at: int,
               rest: npt.NDArray[np.int64], cut: set[tuple[int, int]], keep: set[tuple[int, int]],
               tries: list[int], moves: list[_Move] | None = None) -> _Hanger | None:
    """Hang the cut-off side where small branches of the rest are in the way, and hang those again.

    For each place of the whole side, nearest first, the faces in its way are
    found, and each with the branch below it (as the fold tree hangs from the
    face ``at`` the side was cut from, so nothing is left hanging) is lifted; the
    side takes the place, then each branch goes back on its own fold if that is
    free, else to the nearest free place, piece by piece.  Kept folds are never
    opened; at most :data:`MAX_LIFTED` faces are lifted.  ``moves`` gives the places
    to try instead (a join has one).  None when no place works.
    """
    inside = set(rest.tolist())
    up = {at: -1}
    order = [at]
    for i in order:  # breadth first: the list grows while it is read
        for j in tree[i]:
            if j in inside and j not in up:
                up[j] = i
                order.append(j)
    below: dict[int, list[int]] = {i: [] for i in order}
    for i in order[1:]:
        below[up[i]].append(i)
    owner = dict(zip(_keys(lay.cell[rest]).tolist(), rest.tolist()))
    placed = np.zeros(lay.sg.face_count, dtype=bool)
    placed[rest] = True
    if moves is None:
        moves = _Hanger(lay, placed, cut, keep, tries).nearest(moved)[:_ROOM_PLACES]
    for mv in moves:
        if tries[0] <= 0:
            break
        blockers = sorted({owner[k] for k in _keys(mv.cell).tolist() if k in owner})
        if not blockers or at in blockers:
            continue
        # the topmost blockers: a blocker under another one's branch goes with it
        lifted: dict[int, list[int]] = {}
        for z in sorted(blockers, key=order.index):
            x = z
            while x != -1 and x not in lifted:
                x = up[x]
            if x == -1:
                sub, stack = [], [z]
                while stack:
                    i = stack.pop()
                    sub.append(i)
                    stack.extend(below[i])
                lifted[z] = sub
        if sum(len(f) for f in lifted.values()) > MAX_LIFTED or any(_pair(z, up[z]) in keep for z in lifted):
            continue
        free = placed.copy()
        for sub in lifted.values():
            free[sub] = False
        hanger = _Hanger(lay, free, cut, keep, tries)
        ok = hanger.fits(mv)
        if ok:
            hanger.commit(mv)
            for z, sub in lifted.items():
                branch = np.array(sorted(sub), dtype=np.int64)
                k = int(np.flatnonzero(lay.sg.neighbor[z] == up[z])[0])
                if not (hanger.hang(tree, branch, z, (z, k)) or hanger.hang(tree, branch, z, None)):
                    ok = False
                    break
        if ok:
            return hanger
        hanger.undo()
    return None


def join_edge(grid: npt.ArrayLike, net: Net | Sequence[Net], face_a: Face, face_b: Face, *,
              constraints: EdgeConstraints | None = None) -> EditResult:
    """Make the cut edge between two faces a fold and repair the net around it.

    Inside one piece, the fold would close a loop, so the fold on the tree path
    from one face to the other that lets the smallest side swing round to meet
    across the joined edge (with no cell taken twice, no cut edge closing up and
    no kept edge opening) is cut.  Between two pieces, the smaller piece moves to
    meet the other and the two become one.

    Parameters
    ----------
    grid, net, face_a, face_b, constraints
        As :func:`cut_edge`; the result's marks keep this edge folded.

    Returns
    -------
    EditResult

    Raises
    ------
    InvalidShapeError
        The faces are not two faces of the shape meeting along an edge.
    UnfoldError
        The edge is a fold already, every fold on the loop is kept, or no side
        can swing round without overlapping (one line).
    """
    lay = _load(grid, net)
    a, b, edge = _edge_of(lay, face_a, face_b)
    marks = _marks_with(constraints, edge, "keep")
    cut_pairs, keep = _marked(lay, marks)
    if _pair(a, b) in lay.fold:
        raise UnfoldError(f"edge {_name(edge)} is already a fold")
    before = set(lay.fold)
    ka = int(np.flatnonzero(lay.sg.neighbor[a] == b)[0])
    kb = int(lay.sg.neighbor_edge[a, ka])
    pa, pb = int(lay.piece[a]), int(lay.piece[b])
    piece_of = lay.piece.copy()
    if pa != pb:
        ma, mb = np.flatnonzero(lay.piece == pa), np.flatnonzero(lay.piece == pb)
        # the smaller piece moves; the merged piece takes the lower number
        moved, u, k, fixed = (mb, b, kb, ma) if mb.size <= ma.size else (ma, a, ka, mb)
        choices = [(moved, u, k, fixed)]
    else:
        members = np.flatnonzero(lay.piece == pa)
        tree = _tree(lay, members, [], keep)
        path = _path(tree, a, b)
        choices = []
        for i, j in zip(path, path[1:]):
            if _pair(i, j) in keep:
                continue
            side = _side(tree, j, _pair(i, j))  # the side of b
            if 2 * side.size <= members.size:
                choices.append((side, b, kb, np.setdiff1d(members, side)))
            else:
                other = np.setdiff1d(members, side)
                choices.append((other, a, ka, side))
        if not choices:
            raise UnfoldError(f"joining edge {_name(edge)} would close a loop of kept folds; "
                              "unmark one of them first")
        choices.sort(key=lambda c: (c[0].size, int(c[0][0])))
    tries = [MAX_TRIES]
    for moved, u, k, fixed in choices:
        if tries[0] <= 0:
            break
        placed = np.zeros(lay.sg.face_count, dtype=bool)
        placed[fixed] = True
        hanger = _Hanger(lay, placed, cut_pairs, keep, tries)
        # inside a piece the swinging side keeps its folds where it can; a whole piece moves rigidly
        if (hanger.hang(tree, moved, u, (u, k)) if pa == pb else hanger.first([_hinge_move(lay, moved, u, k)])):
            if pa != pb:
                piece_of[moved] = min(pa, pb)
                piece_of = _renumber(piece_of)
            return _rebuild(lay, marks, before, moved=hanger.moved(), piece_of=piece_of)
        hanger.undo()
    if pa == pb:
        # no side fits as it swings: lift the small branches in the way of the smallest ones
        for moved, u, k, fixed in choices[:4]:
            v = int(lay.sg.neighbor[u, k])
            hanger = _make_room(lay, tree, moved, v, fixed, cut_pairs, keep, tries,
                                moves=[_hinge_move(lay, moved, u, k)])
            if hanger is not None:
                return _rebuild(lay, marks, before, moved=hanger.moved(), piece_of=piece_of)
    if pa != pb:
        raise UnfoldError(f"no room to join edge {_name(edge)}: the two pieces would overlap")
    raise UnfoldError(f"no room to join edge {_name(edge)}: every way to open the loop it closes makes "
                      "faces overlap or closes a cut edge")


def _path(tree: dict[int, list[int]], a: int, b: int) -> list[int]:
    """The faces on the tree path from a to b."""
    back = {a: a}
    queue = deque([a])
    while queue:
        i = queue.popleft()
        if i == b:
            break
        for j in tree[i]:
            if j not in back:
                back[j] = i
                queue.append(j)
    path = [b]
    while path[-1] != a:
        path.append(back[path[-1]])
    return path[::-1]


def _renumber(piece_of: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """Pieces numbered 0.. in the order of their first face."""
    _, first = np.unique(piece_of, return_index=True)
    order = np.argsort(first)
    new = np.empty_like(order)
    new[order] = np.arange(order.size)
    labels = np.unique(piece_of)
    return new[np.searchsorted(labels, piece_of)]


def _with_changes(result: EditResult, lay: _Layout, before: set[tuple[int, int]]) -> EditResult:
    """Record which edges changed from fold to cut and back."""
    sg = lay.sg
    after: set[tuple[int, int]] = set()
    for piece in result.pieces:
        names = [(int(v[0]), int(v[1]), int(v[2]), NORMALS[_direction(n)])
                 for v, n in zip(piece.voxel.tolist(), piece.normal.tolist())]
        ids = face_index(sg, names)
        after |= {_pair(int(ids[i]), int(ids[j])) for i, j in piece.folds.tolist()}

    def names(pairs: set[tuple[int, int]]) -> tuple[Edge, ...]:
        return tuple(sorted((face_of(sg, i), face_of(sg, j)) if face_of(sg, i) < face_of(sg, j)
                            else (face_of(sg, j), face_of(sg, i)) for i, j in pairs))

    return dataclasses.replace(result, cut=names(before - after), joined=names(after - before))


def _name(edge: Edge) -> str:
    (ax, ay, az, an), (bx, by, bz, bn) = edge
    return f"[{ax},{ay},{az},{an}]-[{bx},{by},{bz},{bn}]"

