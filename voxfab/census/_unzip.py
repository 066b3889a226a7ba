"""Edge-unzipping in the model of Demaine, Demaine, Eppstein and O'Rourke (CCCG 2020), on CP-SAT.

An *unzipping* cuts the surface along one path of cube edges that visits every
*corner* vertex (three, five or six squares round it).  It may pass through a
*flat* vertex (four squares, 360 degrees) or leave it uncut, so squares round a
flat vertex may stay joined: the folds then hold cycles, and the net is the
development of the disk the cut leaves.  This is weaker than the unit-square
zipper of :mod:`voxfab.unfold._zipper` (``voxfab net --zipper``), whose path
visits every vertex: the 2 x 2 x 2 cube has no unit-square zipper, yet it unzips
here.

The search is the zipper search's, with flat vertices optional:

0. the short fold paths whose end faces develop onto one cell are ruled out
   first (one of their edges is cut);
1. solve for a path (``AddCircuit`` with a dummy node, a self-loop on each flat
   vertex for "not on the path"), ending at corner vertices: a path ending at a
   flat vertex closes up again there, so its last edge is no cut;
2. develop the uncut edges (a breadth-first tree of them fixes the layout; the
   others close round flat vertices and agree with it);
3. two faces on one cell: one edge of the tree path between them is cut (a
   no-good valid for every cut); a cut edge whose two sides develop side by
   side closes up (a slit, not a cut): it is left uncut or the tree path between
   its faces is cut.  Back to 1.  (The paper allows such a slit, as boundary
   edges that touch; a net file keeps it as a fold, which breaks the cut path.
   So a proof that leaned on a slit rule is no proof in the paper's model: the
   outcome is then ``undecided``.)

Without a path the search is a proof that none exists.  The cheap proof comes
first, as in the paper: the vertex graph is bipartite (lattice colour ``x + y +
z`` even or odd), a path alternates colours, so when one colour's corners
outnumber every vertex of the other colour (corner or flat) by more than one,
no path holds them all.  Each "none" carries a certificate that
:func:`voxfab.census.check_certificate` re-checks from the cells alone.
"""

from __future__ import annotations

import dataclasses
import time
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from voxfab.errors import UnfoldError

if TYPE_CHECKING:  # the net engine loads numba: imported where a search runs, not by the CLI's parser
    from voxfab.unfold import Net

__all__ = ["UNZIP_OUTCOMES", "Unzipping", "unzip"]

#: What an unzipping search finds: a net, a proof that none exists, or neither within its time.
UNZIP_OUTCOMES = ("found", "none", "undecided")

#: Fold paths of up to this many folds are checked for overlaps before the search (five squares round a
#: vertex need four; longer overlaps come as no-goods, measured 17 % faster than six on the 7-cube polycubes).
_SHORT_PATH = 4


@dataclasses.dataclass(frozen=True, eq=False)
class Unzipping:
    """The outcome of :func:`unzip` on one polycube.

    Attributes
    ----------
    outcome : str
        One of :data:`UNZIP_OUTCOMES`.
    net : Net or None
        The net (``found``): its folds are the uncut edges, the cut edges form one path.
    path : tuple of (int, int, int)
        The cut path's lattice points in order (``found``).
    certificate : dict or None
        Why none exists (``none``): see :func:`voxfab.census.check_certificate`.
    why : str
        The search's own words for ``none`` and ``undecided``.
    """

    outcome: str
    net: Net | None
    path: tuple[tuple[int, int, int], ...]
    certificate: dict[str, Any] | None
    why: str


def _face_key(sg: Any, f: int) -> list[int]:
    """A face as ``[x, y, z, d]``: its cube and its direction (+x, -x, +y, -y, +z, -z)."""
    return [*sg.voxel[f].tolist(), int(sg.direction[f])]


def unzip(grid: npt.ArrayLike, *, timeout: float = 10.0) -> Unzipping:
    """Search an edge-unzipping of a polycube whose surface is a 2-manifold of genus 0.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The polycube; its surface must be a manifold of genus 0 (see :func:`voxfab.census.topology`).
    timeout : float
        Seconds for the search; when they run out the outcome is ``undecided``.

    Returns
    -------
    Unzipping

    Raises
    ------
    UnfoldError
        The surface is not a manifold of genus 0.
    """
    from voxfab.shape import surface_graph
    from voxfab.unfold._exact import _cp_model, one_worker_solver
    from voxfab.unfold._layout import build_net, count_without_tab_room
    from voxfab.unfold._validate import validate
    from voxfab.unfold._zipper import _edges, _fold_flat, _short_overlaps, _tree_path

    from ._topology import topology

    g = np.asarray(grid, dtype=bool)
    topo = topology(g)
    if topo.kind != "manifold":
        raise UnfoldError(f"the unzipping model takes polycubes whose surface is a 2-manifold of genus 0, "
                          f"not one with {'a ' + topo.kind if topo.kind != 'handle' else 'handles'}")
    deadline = time.monotonic() + timeout
    (ce, co), (fe, fo) = topo.corners, topo.flats
    for big, small, name in ((ce, co + fo, "even"), (co, ce + fe, "odd")):
        if big > small + 1:
            other = "odd" if name == "even" else "even"
            return Unzipping("none", None, (), {
                "kind": "colours", "corners": [ce, co], "flats": [fe, fo]},
                f"{big} corner vertices are {name} (x + y + z) and only {small} vertices are {other}: a cut "
                "path alternates colours, so none holds every corner")
    sg = surface_graph(g)
    f = sg.face_count
    faces = np.arange(f, dtype=np.int64)
    edges = _edges(sg, faces)
    verts = np.unique(sg.vertex)
    degree = np.bincount(sg.vertex.ravel(), minlength=verts.size)  # squares round each vertex
    corner = degree != 4
    cp_model = _cp_model()
    m = cp_model.CpModel()
    dummy = int(verts.size)
    arcs: list[tuple[int, int, Any]] = []
    cut = []
    for i, (a, k, _, _) in enumerate(edges):
        u, v = int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])
        uv, vu = m.new_bool_var(f"u{i}"), m.new_bool_var(f"v{i}")
        arcs += [(u, v, uv), (v, u, vu)]
        cut.append((uv, vu))
    starts, ends = [], []
    for v in range(dummy):
        if corner[v]:  # the path's ends, joined through the dummy node into one circuit
            s, t = m.new_bool_var(f"s{v}"), m.new_bool_var(f"t{v}")
            arcs += [(dummy, v, s), (v, dummy, t)]
            starts.append(s)
            ends.append(t)
        else:  # a flat vertex may stay off the path
            arcs.append((v, v, m.new_bool_var(f"skip{v}")))
    m.add_circuit(arcs)
    # A path and its reverse are one cut: the end at the lower corner is its start.
    for j in range(len(starts)):
        m.add(sum(ends[: j + 1]) >= 1).only_enforce_if(starts[j])
    nogoods: list[list[int]] = []
    for path in _short_overlaps(sg, faces, edges, _SHORT_PATH, deadline):
        m.add_bool_or([lit for i in path for lit in cut[i]])
        nogoods.append(list(path))
    solver = one_worker_solver()
    prm = solver.parameters
    prm.cp_model_presolve = False  # re-solved after each round of no-goods, as the zipper search
    slit_rules: list[tuple[list[int], int]] = []
    rounds = 0
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            break
        prm.max_time_in_seconds = left
        status = solver.solve(m)
        if status == cp_model.INFEASIBLE and slit_rules:
            # The paper allows a net whose boundary edges touch, so a cut edge that closes up again (a
            # slit) is allowed there; a net file keeps it as a fold, which breaks the path.  Without a
            # slit-free path the question stays open here.
            return Unzipping("undecided", None, (), None,
                             f"undecided: no unzipping of the {f}-square surface without a slit exists (proved), "
                             "and one whose cut path closes up along an edge was not ruled out")
        if status == cp_model.INFEASIBLE:
            return Unzipping("none", None, (), {
                "kind": "solver", "faces": [_face_key(sg, a) for a in range(f)],
                "overlaps": [[list(edges[i][::2]) for i in ng] for ng in nogoods],
                "slits": [[[list(edges[i][::2]) for i in p], list(edges[e][::2])] for p, e in slit_rules]},
                f"no unzipping of the {f}-square surface exists (proved: every cut path through its "
                f"{int(corner.sum())} corner vertices folds into an overlap; {rounds} rounds of overlaps ruled out)")
        if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            break
        # Each literal read once: the solver's per-literal reads dominate small models otherwise.
        forward = [solver.boolean_value(uv) for uv, _ in cut]
        backward = [solver.boolean_value(vu) for _, vu in cut]
        is_cut = [a or b for a, b in zip(forward, backward)]
        fold_ids = [i for i, c in enumerate(is_cut) if not c]
        folds = [edges[i] for i in fold_ids]
        cell, rot, parent, via = _fold_flat(faces, folds, f)
        owner: dict[tuple[int, int], int] = {}
        clashes = []
        for a in range(f):
            c = (int(cell[a, 0]), int(cell[a, 1]))
            if c in owner:
                clashes.append((owner[c], a))
            else:
                owner[c] = a
        slits = [] if clashes else _slits(sg, edges, is_cut, cell, rot)
        if not clashes and not slits:
            net = build_net(sg, faces, cell, rot, parent, seed=0, strategy="unzip")
            net = dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(g, net))
            # The independent refold: a net the model let through but the validator refuses is a bug here.
            validate(g, net, strict=True)
            if net.folds.shape[0] != len(fold_ids):
                raise UnfoldError("unzip: the developed net does not keep every uncut edge as a fold")
            return Unzipping("found", net, _path_points(sg, edges, forward, backward), None, "")
        for u, v in clashes:
            tree = [fold_ids[i] for i in _tree_path(u, v, parent, via)]
            m.add_bool_or([lit for i in tree for lit in cut[i]])
            nogoods.append(tree)
        for e in slits:
            a, _, b, _ = edges[e]
            tree = [fold_ids[i] for i in _tree_path(a, b, parent, via)]
            lits = [lit for i in tree for lit in cut[i]]
            for lit in cut[e]:  # the edge stays uncut, or the tree path between its squares is cut
                m.add_bool_or([*lits, ~lit])
            slit_rules.append((tree, e))
        rounds += 1
        m.clear_hints()
        for (uv, vu), a, b in zip(cut, forward, backward):
            m.add_hint(uv, a)
            m.add_hint(vu, b)
    return Unzipping("undecided", None, (), None,
                     f"undecided: the unzipping search ran out of time on the {f}-square surface "
                     f"({rounds} rounds of overlaps ruled out); raise the timeout")


def _slits(sg: Any, edges: list, is_cut: list[bool], cell: npt.NDArray[np.int64],
           rot: npt.NDArray[np.int64]) -> list[int]:
    """Cut edges whose two squares develop side by side across that edge: the cut would close up."""
    from voxfab.unfold._layout import SIDE_STEP

    out = []
    for e, (a, k, b, kb) in enumerate(edges):
        if not is_cut[e]:
            continue
        s = (k + int(rot[a])) % 4
        if ((cell[a] + SIDE_STEP[s] == cell[b]).all() and int(rot[b]) == (s + 2 - kb) % 4):
            out.append(e)
    return out


def _path_points(sg: Any, edges: list, forward: list[bool],
                 backward: list[bool]) -> tuple[tuple[int, int, int], ...]:
    """The cut path's lattice points from its start, from each edge's arc taken forward or backward."""
    step: dict[int, int] = {}
    into: set[int] = set()
    for (a, k, _, _), uv, vu in zip(edges, forward, backward):
        u, v = int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])
        if uv:
            step[u] = v
            into.add(v)
        elif vu:
            step[v] = u
            into.add(u)
    start = next(v for v in step if v not in into)
    points = [start]
    while points[-1] in step:
        points.append(step[points[-1]])
    pos = sg.vertex_position
    return tuple(tuple(int(c) for c in pos[v]) for v in points)
