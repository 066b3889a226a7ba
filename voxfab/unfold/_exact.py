"""The exact unfolder: a CP-SAT model that finds a one-piece net or proves that none exists.

The model (OR-Tools CP-SAT, imported only here):

- every face but a fixed root picks one parent across one of its edges; a
  depth per face, larger than its parent's, forbids cycles, so the parent
  choices form a spanning tree of the face graph (the folds);
- every face gets a cell ``(x, y)`` inside the box and one of 4 rotations; a
  fold puts the child on the cell across the parent's edge, turned so that the
  shared edge coincides (the rule of :func:`voxfab.unfold._layout.build_net`);
- no two faces share a cell (all different);
- kept edges must meet in the plane, cut edges must not be folds and must not
  close up in the plane;
- a zipper: every vertex has at most two cut edges.  The cut edges of a net of
  a closed surface are connected and reach every vertex, so this makes them one
  path (and there is none when the surface has a handle).

The solver runs with one worker and a fixed seed, so the same input gives the
same net on every run.  INFEASIBLE is a proof that no net exists; a time-out
is undecided, never reported as "none".
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import numpy.typing as npt

from voxfab.errors import NoNetError, UnfoldError
from voxfab.shape import SurfaceGraph

from ._constraints import CUT, KEEP, Resolved
from ._layout import SIDE_STEP, build_net
from ._net import Net

__all__ = ["ExactOutcome", "decide", "smallest_box", "cut_edges_form_path"]

#: Statuses of :class:`ExactOutcome`.
FOUND, NONE, UNDECIDED = "found", "none", "undecided"


@dataclasses.dataclass(frozen=True)
class ExactOutcome:
    """What the exact search decided for one box.

    ``status`` is ``"found"`` (``net`` holds the net), ``"none"`` (proved: no
    net exists under the constraints) or ``"undecided"`` (the time ran out).
    """

    status: str
    net: Net | None
    box: tuple[int, int] | None
    seconds: float


def _vertex_edges(sg: SurfaceGraph) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """Each undirected surface edge once: its half (face, edge), and its two vertex ids."""
    f = sg.face_count
    a = np.repeat(np.arange(f), 4)
    k = np.tile(np.arange(4), f)
    b = sg.neighbor[a, k]
    kb = sg.neighbor_edge[a, k]
    first = (a < b) | ((a == b) & (k < kb))
    a, k = a[first], k[first]
    va = sg.vertex[a, k]
    vb = sg.vertex[a, (k + 1) % 4]
    return np.stack([a, k], axis=1), va, vb


def cut_edges_form_path(sg: SurfaceGraph, net: Net) -> bool:
    """Whether the cut edges of a one-piece net (surface edges that are not folds) form one simple path."""
    halves, va, vb = _vertex_edges(sg)
    folded = {(min(i, j), max(i, j)) for i, j in net.folds.tolist()}
    cut = [t for t, (a, k) in enumerate(halves.tolist())
           if (min(a, int(sg.neighbor[a, k])), max(a, int(sg.neighbor[a, k]))) not in folded]
    if not cut:
        return False
    u, v = va[cut], vb[cut]
    if (u == v).any():
        return False
    nodes, inv = np.unique(np.concatenate([u, v]), return_inverse=True)
    deg = np.bincount(inv, minlength=nodes.size)
    if deg.max() > 2 or len(cut) != nodes.size - 1:
        return False
    # A forest with one edge fewer than its vertices is one tree: check it is connected.
    label = np.arange(nodes.size)
    iu, iv = inv[: len(cut)], inv[len(cut):]
    for _ in range(nodes.size):
        low = np.minimum(label[iu], label[iv])
        new = label.copy()
        np.minimum.at(new, iu, low)
        np.minimum.at(new, iv, low)
        if np.array_equal(new, label):
            break
        label = new
    return bool((label == label[0]).all())


def _solve(sg: SurfaceGraph, box: tuple[int, int], resolved: Resolved | None, zipper: bool,
           deadline: float, banned: list[npt.NDArray[np.int64]]) -> tuple[str, dict | None]:
    """One CP-SAT run for one box; the layout of the net found, if any.

    ``banned`` lists fold trees ruled out, as the parent edge of each face (-1 for the root).
    """
    from ortools.sat.python import cp_model

    f = sg.face_count
    w, h = box
    nb, ne = sg.neighbor, sg.neighbor_edge
    m = cp_model.CpModel()
    x = [m.NewIntVar(0, w - 1, f"x{i}") for i in range(f)]
    y = [m.NewIntVar(0, h - 1, f"y{i}") for i in range(f)]
    rot = [[m.NewBoolVar(f"r{i}_{r}") for r in range(4)] for i in range(f)]
    for i in range(f):
        m.AddExactlyOne(rot[i])
    depth = [m.NewIntVar(0, f - 1, f"d{i}") for i in range(f)]
    # Rotating a whole net keeps it a net: the root's turn is fixed up to the
    # box's own symmetries (a half turn keeps W x H, a quarter turn only a square).
    m.Add(depth[0] == 0)
    m.AddBoolOr([rot[0][0]] if w == h else [rot[0][0], rot[0][1]])
    edge = resolved.edge if resolved is not None else np.zeros((f, 4), dtype=np.int8)
    parent = [[None] * 4 for _ in range(f)]
    for i in range(1, f):
        lits = []
        for k in range(4):
            p = int(nb[i, k])
            if p == i or edge[i, k] == CUT:
                continue
            q = m.NewBoolVar(f"p{i}_{k}")
            parent[i][k] = q
            lits.append(q)
            m.Add(depth[i] >= depth[p] + 1).OnlyEnforceIf(q)
        m.AddExactlyOne(lits)

    def meets(child: int, k: int, lit_list: list) -> None:
        """Under ``lit_list``, face ``child`` lies across its edge ``k`` from its neighbour, edge to edge."""
        p, kk = int(nb[child, k]), int(ne[child, k])
        turn = (kk + 2 - k) % 4
        for r in range(4):
            s = (kk + r) % 4
            on = [*lit_list, rot[p][r]]
            m.Add(x[child] == x[p] + int(SIDE_STEP[s, 0])).OnlyEnforceIf(on)
            m.Add(y[child] == y[p] + int(SIDE_STEP[s, 1])).OnlyEnforceIf(on)
            m.AddImplication(rot[p][r], rot[child][(r + turn) % 4]).OnlyEnforceIf(lit_list)

    for i in range(1, f):
        for k in range(4):
            if parent[i][k] is not None:
                meets(i, k, [parent[i][k]])
    halves, va, vb = _vertex_edges(sg)
    cut_lit = []
    for a, k in halves.tolist():
        b, kb = int(nb[a, k]), int(ne[a, k])
        folds = [lit for lit in (parent[a][k], parent[b][kb]) if lit is not None]
        if edge[a, k] == KEEP:
            meets(b, kb, [])
        elif edge[a, k] == CUT:
            _never_meets(m, x, y, rot, a, k, b, kb)
        cut = m.NewBoolVar(f"c{a}_{k}")
        m.Add(sum(folds) + cut == 1)
        cut_lit.append(cut)
    if zipper:
        for v in np.unique(np.concatenate([va, vb])).tolist():
            around = [c for c, p, q in zip(cut_lit, va.tolist(), vb.tolist()) if p == v or q == v]
            twice = [c for c, p, q in zip(cut_lit, va.tolist(), vb.tolist()) if p == v and q == v]
            m.Add(sum(around) + sum(twice) <= 2)
    m.AddAllDifferent([x[i] * h + y[i] for i in range(f)])
    for par in banned:
        m.AddBoolOr([parent[i][k].Not() for i in range(1, f) for k in range(4)
                     if k == int(par[i])])
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = 1
    solver.parameters.random_seed = 0
    solver.parameters.max_time_in_seconds = max(deadline - time.monotonic(), 0.01)
    status = solver.Solve(m)
    if status == cp_model.INFEASIBLE:
        return NONE, None
    if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        return UNDECIDED, None
    cell = np.array([[solver.Value(x[i]), solver.Value(y[i])] for i in range(f)], dtype=np.int64)
    r = np.array([next(t for t in range(4) if solver.Value(rot[i][t])) for i in range(f)], dtype=np.int64)
    par = np.full(f, -1, dtype=np.int64)
    via = np.full(f, -1, dtype=np.int64)
    for i in range(1, f):
        for k in range(4):
            if parent[i][k] is not None and solver.Value(parent[i][k]):
                par[i], via[i] = nb[i, k], k
    return FOUND, {"cell": cell, "rot": r, "par": par, "via": via}


def _never_meets(m, x, y, rot, a: int, k: int, b: int, kb: int) -> None:  # noqa: ANN001
    """A cut edge must not close up in the plane (a slit), or the net would fold it."""
    turn = (k + 2 - kb) % 4
    for r in range(4):
        s = (k + r) % 4
        dx, dy = int(SIDE_STEP[s, 0]), int(SIDE_STEP[s, 1])
        off_x, off_y = m.NewBoolVar(""), m.NewBoolVar("")
        m.Add(x[b] != x[a] + dx).OnlyEnforceIf(off_x)
        m.Add(y[b] != y[a] + dy).OnlyEnforceIf(off_y)
        m.AddBoolOr([off_x, off_y, rot[a][r].Not(), rot[b][(r + turn) % 4].Not()])


def decide(sg: SurfaceGraph, box: tuple[int, int], resolved: Resolved | None, *, zipper: bool,
           timeout: float) -> ExactOutcome:
    """Find a net of the whole surface ``sg`` inside ``box`` (either way round), or prove there is none.

    A net that fits ``W x H`` turned a quarter fits ``H x W``, so one
    orientation is searched.  With ``zipper`` a layout whose cut edges are
    not one path once slits close up is ruled out and the search goes on, so
    the answer stays exact.
    """
    start = time.monotonic()
    deadline = start + timeout
    w, h = box
    if w * h < sg.face_count:
        return ExactOutcome(NONE, None, box, 0.0)
    banned: list[npt.NDArray[np.int64]] = []
    while True:
        status, found = _solve(sg, (w, h), resolved, zipper, deadline, banned)
        if status != FOUND:
            return ExactOutcome(status, None, box, time.monotonic() - start)
        net = build_net(sg, np.arange(sg.face_count), found["cell"], found["rot"], found["par"], seed=0,
                        strategy="exact")
        if not zipper or cut_edges_form_path(sg, net):
            return ExactOutcome(FOUND, net, box, time.monotonic() - start)
        banned.append(found["via"])


def free_box(sg: SurfaceGraph) -> tuple[int, int]:
    """A box that holds every net of the surface: a net of F cells spans at most F x F."""
    return sg.face_count, sg.face_count


def boxes_by_size(faces: int, limit: int) -> list[tuple[int, int]]:
    """Boxes ``(w, h)``, ``w <= h``, of ``faces`` to ``limit`` cells, smallest area first, then shorter longer side."""
    out = [(w, a // w) for a in range(faces, limit + 1) for w in range(1, int(a ** 0.5) + 1) if a % w == 0]
    return sorted(out, key=lambda b: (b[0] * b[1], b[1]))


@dataclasses.dataclass(frozen=True)
class SmallestBox:
    """The smallest box holding a one-piece net, and the smaller boxes proved empty."""

    net: Net
    box: tuple[int, int]
    proved_empty: tuple[tuple[int, int], ...]


def smallest_box(sg: SurfaceGraph, resolved: Resolved | None, *, zipper: bool, timeout: float) -> SmallestBox:
    """Try boxes in order of area, then longer side, until one holds a net.

    Raises NoNetError when no box at all holds one (the free search is
    infeasible), UnfoldError when the time runs out before an answer.
    """
    deadline = time.monotonic() + timeout
    f = sg.face_count
    empty: list[tuple[int, int]] = []
    for box in boxes_by_size(f, f * f):
        left = deadline - time.monotonic()
        if left <= 0:
            break
        out = decide(sg, box, resolved, zipper=zipper, timeout=left)
        if out.status == FOUND:
            return SmallestBox(out.net, box, tuple(empty))
        if out.status == UNDECIDED:
            break
        empty.append(box)
        if box[0] == f:
            raise NoNetError(f"no one-piece net of the {f}-face surface exists (proved)")
    done = f", {len(empty)} smaller boxes proved empty" if empty else ""
    raise UnfoldError(f"undecided: the smallest box of the {f}-face surface was not found in {timeout:g} s{done}; "
                      "raise the timeout")
