"""The exact strategy: a complete search for a one-piece net inside a box, on CP-SAT.

Every face gets a cell ``(x, y)`` of the ``W x H`` box and a rotation ``r``;
every surface edge may be a fold.  The folds must form a spanning tree of the
face graph (each face but the root has exactly one parent, and depths grow
along the tree, so there is no cycle), a fold forces the child's cell and
rotation from its parent's (the rule of :func:`._constraints._groups`), and no
two faces share a cell.  The solver either finds such an assignment, which is
a net, or proves that none exists.

The model is built in a fixed order and solved by one worker with a fixed
seed, so the same shape and box give the same net on every run.

Finding a net is where the model alone is weakest (a roomy box leaves the
solver little to propagate), and where growth is strongest, so the caller may
pass a growth net in the box as a hint: checked with every variable fixed, it
is confirmed in a fraction of a second.  Proofs that no net exists get no help
from it; they are what limits the size of surface this strategy decides.
"""

from __future__ import annotations

import time
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from voxfab.errors import NoNetExistsError, UnfoldError
from voxfab.shape import SurfaceGraph

from ._constraints import _SIDE_STEP, CUT, KEEP, Resolved
from ._cpsat import cp_model, one_worker_solver, solve

__all__ = ["ExactLayout", "any_box", "exact_layout", "min_box_layout"]


class ExactLayout(NamedTuple):
    """A net's layout over a surface's faces: cell (x, y), rotation and fold-tree parent (-1 root)."""

    cell: npt.NDArray[np.int64]
    rot: npt.NDArray[np.int64]
    parent: npt.NDArray[np.int64]
    box: tuple[int, int]


class Undecided(UnfoldError):
    """The budget ran out before the solver found a net or proved that none exists."""


def any_box(faces: int) -> tuple[int, int]:
    """A box that holds every one-piece net of ``faces`` faces, turned if need be: the exact strategy's default.

    A net is a connected set of cells, so its bounding box ``w x h`` has
    ``w + h - 1 <= faces``: turned to ``w <= h``, ``w <= (faces + 1) // 2`` and
    ``h <= faces``.  In this box a one-piece net always exists, so the exact
    strategy asked for no box in particular finds one (the growth hint, checked
    by the solver) and never has to prove anything: the same net on every run.
    """
    return ((faces + 1) // 2, faces)


def _arcs(sg: SurfaceGraph, faces: npt.NDArray[np.int64]) -> list[tuple[int, int, int, int]]:
    """Every half-edge ``(a, k, b, kb)`` between two faces of ``faces``: face a's edge k is face b's edge kb."""
    inside = np.zeros(sg.face_count, dtype=bool)
    inside[faces] = True
    out = []
    for a in faces.tolist():
        for k in range(4):
            b = int(sg.neighbor[a, k])
            if b >= 0 and inside[b]:
                out.append((a, k, b, int(sg.neighbor_edge[a, k])))
    return out


def exact_layout(sg: SurfaceGraph, faces: npt.NDArray[np.int64], resolved: Resolved | None,
                 box: tuple[int, int], deadline: float, zipper: bool = False,
                 hint: ExactLayout | None = None) -> ExactLayout:
    """Lay ``faces`` out as one net inside ``box``, or prove that no such net exists.

    Parameters
    ----------
    sg : SurfaceGraph
    faces : (P,) int ndarray
        The faces of one connected surface part, increasing.
    resolved : Resolved or None
        Edge constraints: cut edges are never folds (nor meet in the plane, which
        would make them folds), kept edges always are.
    box : (int, int)
        ``W x H`` cells.  A net turned by a quarter turn is still a net, so this
        also decides the ``H x W`` box.
    deadline : float
        ``time.monotonic()`` at which the solver gives up.
    zipper : bool
        The cut edges must form one path (an unzipping).  The cut edges of a
        net of a closed surface are connected and reach every vertex, so at
        most two cut edges per vertex makes them one path (and rules out every
        net of a surface with a handle, whose cut edges hold a cycle).
    hint : ExactLayout, optional
        A net in the box found by a heuristic (the growth search, with a fixed
        seed), given to the solver as a starting point: it is checked first, so
        a net is confirmed in a fraction of the time a search from scratch
        takes; a hint the model refuses is simply dropped.

    Raises
    ------
    NoNetExistsError
        The solver proved that no one-piece net fits the box.
    Undecided
        The deadline came first.
    """
    w, h = box
    n = int(faces.size)
    kind = "zipper net" if zipper else "one-piece net"
    if w * h < n:  # no model needed: the faces outnumber the cells
        raise NoNetExistsError(w, h, kind=kind)
    sat = cp_model()
    m = sat.CpModel()
    local = {f: i for i, f in enumerate(faces.tolist())}
    x = [m.NewIntVar(0, w - 1, f"x{i}") for i in range(n)]
    y = [m.NewIntVar(0, h - 1, f"y{i}") for i in range(n)]
    rot = [[m.NewBoolVar(f"r{i}_{r}") for r in range(4)] for i in range(n)]
    for i in range(n):
        m.AddExactlyOne(rot[i])
    cell = [m.NewIntVar(0, w * h - 1, f"c{i}") for i in range(n)]
    for i in range(n):
        m.Add(cell[i] == x[i] * h + y[i])
    m.AddAllDifferent(cell)

    # Symmetry: turning a whole net by a half turn (a quarter turn in a square
    # box) keeps it in the box, so the root's rotation may be pinned.
    # (Not with a hint, which may be turned any way.)
    root = 0
    if hint is None:
        for r in (range(1, 4) if w == h else range(2, 4)):
            m.Add(rot[root][r] == 0)

    arcs = _arcs(sg, faces)
    par = {}  # (a, k) -> literal "a is the parent of its neighbour across edge k"
    depth = [m.NewIntVar(0, n - 1, f"d{i}") for i in range(n)]
    m.Add(depth[root] == 0)
    incoming: list[list] = [[] for _ in range(n)]
    edge = resolved.edge if resolved is not None else None
    for a, k, b, kb in arcs:
        ia, ib = local[a], local[b]
        p = m.NewBoolVar(f"p{ia}_{k}")
        par[(a, k)] = p
        incoming[ib].append(p)
        if edge is not None and edge[a, k] == CUT:
            m.Add(p == 0)
        m.Add(depth[ib] == depth[ia] + 1).OnlyEnforceIf(p)
        for r in range(4):
            s = (k + r) % 4  # the side of a's cell that edge k lies on
            dx, dy = _SIDE_STEP[s]
            m.Add(x[ib] == x[ia] + dx).OnlyEnforceIf([p, rot[ia][r]])
            m.Add(y[ib] == y[ia] + dy).OnlyEnforceIf([p, rot[ia][r]])
            m.AddBoolOr([p.Not(), rot[ia][r].Not(), rot[ib][(s + 2 - kb) % 4]])
    for i in range(n):
        if i == root:
            m.Add(sum(incoming[i]) == 0)
        else:
            m.AddExactlyOne(incoming[i])
    for a, k, b, kb in arcs:
        if a > b:
            continue
        fold = [par[(a, k)], par[(b, kb)]]
        if edge is not None and edge[a, k] == KEEP:
            m.AddBoolOr(fold)
        elif edge is not None and edge[a, k] == CUT:
            _forbid_meeting(m, x, y, rot, local[a], k, local[b], kb)
    m.Add(sum(par.values()) == n - 1)  # implied by the tree; it helps propagation
    if zipper:
        _one_cut_path(m, sg, arcs, par)

    solver = one_worker_solver()
    prm = solver.parameters
    status = None
    if hint is not None:
        _add_hint(m, hint, faces, sg, (x, y, cell, rot, depth, par), h)
        # First the hint alone: a check in well under a second.  A refusal says
        # nothing about the box, so the full search follows.
        prm.fix_variables_to_their_hinted_value = True
        prm.max_time_in_seconds = max(deadline - time.monotonic(), 0.01)
        status = solve(solver, m)
        if status == sat.UNKNOWN and resolved is None:
            # Out of time before the check ended: without edge constraints a
            # growth net in the box is a net the check would confirm (every
            # variable fixed), and the caller refolds it anyway, so a slow run
            # gives the same net as a fast one.
            return hint
        prm.fix_variables_to_their_hinted_value = False
    if status not in (sat.OPTIMAL, sat.FEASIBLE):
        prm.max_time_in_seconds = max(deadline - time.monotonic(), 0.01)
        status = solve(solver, m)
    if status == sat.INFEASIBLE:
        raise NoNetExistsError(w, h, kind=kind)
    if status not in (sat.OPTIMAL, sat.FEASIBLE):
        raise Undecided(
            f"undecided: the exact search ran out of time before it found a one-piece net of the "
            f"{n}-face surface that fits {w}x{h} faces or proved that none exists; raise the timeout")
    f = sg.face_count
    cells = np.zeros((f, 2), dtype=np.int64)
    rots = np.zeros(f, dtype=np.int64)
    parent = np.full(f, -1, dtype=np.int64)
    for i, face in enumerate(faces.tolist()):
        cells[face] = (solver.Value(x[i]), solver.Value(y[i]))
        rots[face] = next(r for r in range(4) if solver.BooleanValue(rot[i][r]))
    for (a, k), p in par.items():
        if solver.BooleanValue(p):
            parent[int(sg.neighbor[a, k])] = a
    return ExactLayout(cells, rots, parent, (w, h))


def _one_cut_path(m, sg: SurfaceGraph, arcs: list, par: dict) -> None:  # noqa: ANN001
    """At most two cut edges at every vertex of the surface (an edge is cut when neither side is the parent)."""
    at: dict[int, list] = {}
    for a, k, b, kb in arcs:
        if a > b or (a == b and k > kb):
            continue
        cut = m.NewBoolVar("")
        m.Add(par[(a, k)] + par[(b, kb)] + cut == 1)
        for v in (int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])):
            at.setdefault(v, []).append(cut)
    for v in sorted(at):
        m.Add(sum(at[v]) <= 2)


def _add_hint(m, hint: ExactLayout, faces: npt.NDArray[np.int64], sg: SurfaceGraph, var: tuple,  # noqa: ANN001
              h: int) -> None:
    """Give the solver a whole assignment: cells, rotations, parents and depths of ``hint``."""
    x, y, cell, rot, depth, par = var
    up = hint.parent
    root = int(faces[0])
    # The model's tree hangs from faces[0]: turn the hint's tree to hang from it too.
    adj: dict[int, list[int]] = {}
    for f in faces.tolist():
        if up[f] >= 0:
            adj.setdefault(f, []).append(int(up[f]))
            adj.setdefault(int(up[f]), []).append(f)
    parent = {root: -1}
    level = {root: 0}
    queue = [root]
    for a in queue:
        for c in adj.get(a, ()):
            if c not in parent:
                parent[c], level[c] = a, level[a] + 1
                queue.append(c)
    for i, f in enumerate(faces.tolist()):
        cx, cy = (int(v) for v in hint.cell[f])
        m.AddHint(x[i], cx)
        m.AddHint(y[i], cy)
        m.AddHint(cell[i], cx * h + cy)
        m.AddHint(depth[i], level.get(f, 0))
        for r in range(4):
            m.AddHint(rot[i][r], int(hint.rot[f]) == r)
    for (a, k), p in par.items():
        m.AddHint(p, parent.get(int(sg.neighbor[a, k])) == a)


def _forbid_meeting(m, x, y, rot, ia: int, k: int, ib: int, kb: int) -> None:  # noqa: ANN001
    """Keep the two sides of a cut edge from meeting in the plane (the cut would be a slit, i.e. a fold)."""
    for r in range(4):
        s = (k + r) % 4
        dx, dy = _SIDE_STEP[s]
        # Where b must not be: the cell across side s, turned so that the edge lines up.
        ex, ey = m.NewBoolVar(""), m.NewBoolVar("")
        m.Add(x[ib] == x[ia] + dx).OnlyEnforceIf(ex)
        m.Add(x[ib] != x[ia] + dx).OnlyEnforceIf(ex.Not())
        m.Add(y[ib] == y[ia] + dy).OnlyEnforceIf(ey)
        m.Add(y[ib] != y[ia] + dy).OnlyEnforceIf(ey.Not())
        m.AddBoolOr([rot[ia][r].Not(), ex.Not(), ey.Not(), rot[ib][(s + 2 - kb) % 4].Not()])


def min_box_layout(sg: SurfaceGraph, faces: npt.NDArray[np.int64], resolved: Resolved | None,
                   deadline: float, zipper: bool = False) -> ExactLayout:
    """The net whose bounding box has the least area, that area proved minimal.

    Areas are tried from the face count upwards, each as every ``w x h`` with
    ``w <= h``, the shorter longer side first: the first box that has a net is
    the least, since every smaller one was proved to have none.  Past ``n x n``
    no larger box can help (a net of n faces spans at most n x n).

    Raises
    ------
    Undecided
        The deadline came before an area was decided.
    """
    n = int(faces.size)
    area = n
    while area <= n * n:
        for w in range(int(area ** 0.5), 0, -1):
            if area % w:
                continue
            try:
                return exact_layout(sg, faces, resolved, (w, area // w), deadline, zipper)
            except NoNetExistsError:
                continue
            except Undecided:
                raise Undecided(
                    f"undecided: the exact search ran out of time at the {w}x{area // w} box; "
                    f"no box of fewer than {area} cells holds a one-piece net of the {n}-face "
                    "surface (proved); raise the timeout") from None
        area += 1
    raise NoNetExistsError(n, n, kind="zipper net" if zipper else "one-piece net")
