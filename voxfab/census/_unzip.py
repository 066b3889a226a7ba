"""Edge-unzipping in the model of Demaine, Demaine, Eppstein and O'Rourke (CCCG 2020), on CP-SAT.

An *unzipping* cuts the surface along one path of cube edges that visits every
*corner* vertex (three, five or six squares round it).  It may pass through a
*flat* vertex (four squares, 360 degrees) or leave it uncut, so squares round a
flat vertex may stay joined: the folds then hold cycles, and the net is the
development of the disk the cut leaves.  This is weaker than the unit-square
zipper of :mod:`voxfab.unfold._zipper` (``voxfab net --zipper``), whose path
visits every vertex: the 2 x 2 x 2 cube has no unit-square zipper, yet it unzips
here.

The search is the zipper search's (:mod:`voxfab.unfold._cutpath`), with flat vertices optional:

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
   its faces is cut.  Back to 1 (:func:`voxfab.unfold.solve_with_nogoods`).
   (The paper allows such a slit, as boundary edges that touch; a net file
   keeps it as a fold, which breaks the cut path.  So a proof that leaned on a
   slit rule is no proof in the paper's model: the outcome is then
   ``undecided``.)

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
    from voxfab.unfold import solve_with_nogoods, validate
    from voxfab.unfold._cutpath import (
        cell_clashes,
        fold_flat,
        path_model,
        short_overlaps,
        surface_edges,
        tree_path,
    )
    from voxfab.unfold._exact import Undecided
    from voxfab.unfold._layout import build_net, count_without_tab_room

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
    edges = surface_edges(sg, faces)
    corner = np.bincount(sg.vertex.ravel()) != 4  # squares round each vertex: 4 at a flat one
    m, cut = path_model(sg, faces, edges, optional=~corner)  # the path ends at corners, may pass flat vertices
    nogoods: list[list[int]] = []
    try:
        for path in short_overlaps(sg, faces, edges, _SHORT_PATH, deadline):
            m.add_bool_or([lit for i in path for lit in cut[i]])
            nogoods.append(list(path))
    except Undecided:  # the time ran out before the search began: undecided, like any search out of time
        return Unzipping("undecided", None, (), None,
                         f"undecided: the unzipping search ran out of time while it ruled out the short overlaps "
                         f"of the {f}-square surface; raise the timeout")
    slit_rules: list[tuple[list[int], int]] = []

    def refuse(values: list[bool]) -> list[list]:
        """No-goods for a cut whose uncut edges develop into an overlap, or whose cut closes up."""
        is_cut = [uv or vu for uv, vu in zip(values[0::2], values[1::2])]
        fold_ids = [i for i, c in enumerate(is_cut) if not c]
        cell, rot, parent, via = fold_flat(faces, [edges[i] for i in fold_ids], f)
        out = []
        for u, v in cell_clashes(faces, cell):
            tree = [fold_ids[i] for i in tree_path(u, v, parent, via)]
            out.append([lit for i in tree for lit in cut[i]])
            nogoods.append(tree)
        if out:
            return out
        for e in _slits(sg, edges, is_cut, cell, rot):
            a, _, b, _ = edges[e]
            tree = [fold_ids[i] for i in tree_path(a, b, parent, via)]
            lits = [lit for i in tree for lit in cut[i]]
            # The edge stays uncut, or the tree path between its squares is cut.
            out += [[*lits, ~lit] for lit in cut[e]]
            slit_rules.append((tree, e))
        return out

    search = solve_with_nogoods(m, [lit for pair in cut for lit in pair], refuse, deadline=deadline)
    if search.status == "infeasible" and slit_rules:
        # The paper allows a net whose boundary edges touch, so a cut edge that closes up again (a
        # slit) is allowed there; a net file keeps it as a fold, which breaks the path.  Without a
        # slit-free path the question stays open here.
        return Unzipping("undecided", None, (), None,
                         f"undecided: no unzipping of the {f}-square surface without a slit exists (proved), "
                         "and one whose cut path closes up along an edge was not ruled out")
    if search.status == "infeasible":
        return Unzipping("none", None, (), {
            "kind": "solver", "faces": [_face_key(sg, a) for a in range(f)],
            "overlaps": [[list(edges[i][::2]) for i in ng] for ng in nogoods],
            "slits": [[[list(edges[i][::2]) for i in p], list(edges[e][::2])] for p, e in slit_rules]},
            f"no unzipping of the {f}-square surface exists (proved: every cut path through its "
            f"{int(corner.sum())} corner vertices folds into an overlap; {search.rounds} rounds of overlaps "
            "ruled out)")
    if search.status == "timeout":
        return Unzipping("undecided", None, (), None,
                         f"undecided: the unzipping search ran out of time on the {f}-square surface "
                         f"({search.rounds} rounds of overlaps ruled out); raise the timeout")
    forward, backward = search.values[0::2], search.values[1::2]
    fold_ids = [i for i, (uv, vu) in enumerate(zip(forward, backward)) if not (uv or vu)]
    cell, rot, parent, _ = fold_flat(faces, [edges[i] for i in fold_ids], f)
    net = build_net(sg, faces, cell, rot, parent, seed=0, strategy="unzip")
    net = dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(g, net))
    # The independent refold: a net the model let through but the validator refuses is a bug here.
    validate(g, net, strict=True)
    if net.folds.shape[0] != len(fold_ids):
        raise UnfoldError("unzip: the developed net does not keep every uncut edge as a fold")
    return Unzipping("found", net, _path_points(sg, edges, forward, backward), None, "")


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
