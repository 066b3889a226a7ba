"""Zipper nets in any box: the cut edges as one Hamiltonian path, overlaps refused lazily, on CP-SAT.

A zipper net's cut edges form one path through every vertex of the surface
(they are connected and reach every vertex, and no vertex has three).  On a
surface of genus 0 the edges left uncut are then a spanning tree of the faces
(Euler: ``F - 1 = E - (V - 1)``), so a zipper net *is* a Hamiltonian path of
the vertex graph whose complement folds flat without overlap.  The model is
that path alone, one ``AddCircuit`` over the vertices and a dummy node (a far
stronger propagator than a tree encoded by depths), with no cells at all:

0. the short paths whose ends fold onto one cell (five faces round a vertex
   span 450 degrees, a path round a notch doubles back) are found by a
   bounded enumeration and ruled out first: one of their edges is cut;
1. solve for a Hamiltonian path;
2. fold its complement flat (the layout of a tree is fixed by its folds);
3. two faces on one cell are an overlap that every tree holding the tree path
   between them repeats, so "one of these edges is cut" is added (a no-good),
   and the search goes on from 1 (:func:`._cpsat.solve_with_nogoods`).

The loop ends with a net, with a proof that none exists (the path model
with its no-goods, each of them valid, is infeasible), or at the deadline.
A surface with a handle has no zipper net (its cut edges hold a cycle), which
the Euler count shows with no search; nor has a surface whose vertices of the
two lattice colours (``x + y + z`` even or odd) differ by more than one, since
every edge joins two colours (the 2x2x2 cube: 14 and 12).  One worker and a fixed seed make every
step, and so the net, the same on every run.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from voxfab.errors import NoNetExistsError, UnfoldError
from voxfab.shape import SurfaceGraph

from ._constraints import _SIDE_STEP
from ._cpsat import solve_with_nogoods
from ._cutpath import Edge, cell_clashes, fold_flat, path_model, short_overlaps, surface_edges, tree_path
from ._exact import ExactLayout, Undecided

__all__ = ["zipper_layout"]

#: Paths of up to this many folds that overlap are ruled out before the search (the common,
#: local overlaps); longer ones as the search meets them.
_SHORT_PATH = 6


def _slits(sg: SurfaceGraph, edges: list[Edge], is_cut: list[bool], cell: npt.NDArray[np.int64],
           rot: npt.NDArray[np.int64]) -> list[tuple[int, int]]:
    """The two faces of each cut edge inside the path whose sides meet in the plane anyway.

    Such an edge closes up (the net keeps it as a fold), which splits the cut
    path in two: not a zipper.  At an end of the path it only shortens the path.
    """
    ends: dict[int, int] = {}
    cuts = []
    for (a, k, b, kb), c in zip(edges, is_cut):
        if c:
            cuts.append((a, k, b, kb))
            for v in (int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])):
                ends[v] = ends.get(v, 0) + 1
    out = []
    for a, k, b, kb in cuts:
        if ends[int(sg.vertex[a, k])] == 1 or ends[int(sg.vertex[a, (k + 1) % 4])] == 1:
            continue
        s = (k + int(rot[a])) % 4
        if (tuple(cell[b]) == (int(cell[a, 0]) + _SIDE_STEP[s][0], int(cell[a, 1]) + _SIDE_STEP[s][1])
                and int(rot[b]) == (s + 2 - kb) % 4):
            out.append((a, b))
    return out


def zipper_layout(sg: SurfaceGraph, faces: npt.NDArray[np.int64], deadline: float) -> ExactLayout:
    """A zipper net of the surface part ``faces`` in any box, or a proof that none exists.

    Parameters
    ----------
    sg : SurfaceGraph
    faces : (P,) int ndarray
        The faces of one connected surface part, increasing.
    deadline : float
        ``time.monotonic()`` at which the search gives up.

    Returns
    -------
    ExactLayout
        Cells (from 0), rotations and fold-tree parents; ``box`` is the net's extent.

    Raises
    ------
    NoNetExistsError
        No zipper net exists (proved), ``why`` says how.
    Undecided
        The deadline came first.
    """
    f = sg.face_count
    n = int(faces.size)
    edges = surface_edges(sg, faces)
    verts = np.unique(sg.vertex[faces])
    genus2 = 2 - (verts.size - len(edges) + n)  # twice the genus, by Euler
    if genus2 < 0:
        raise UnfoldError(f"the {n}-face surface is not one closed surface (Euler characteristic {2 - genus2})")
    if genus2 > 0:
        raise NoNetExistsError(None, None, kind="zipper net", why=(
            f"the {n}-face surface has a handle (Euler characteristic {2 - genus2}), so the cut edges of any "
            "of its nets hold a cycle, never one path"))
    # Vertices of the voxel lattice take two colours (x + y + z even or odd) and every edge joins
    # two colours, so a path through all of them has as many of each, give or take one.
    colour = sg.vertex_position[verts].sum(axis=1) % 2
    even, odd = int((colour == 0).sum()), int((colour == 1).sum())
    if abs(even - odd) > 1:
        raise NoNetExistsError(None, None, kind="zipper net", why=(
            f"the {n}-face surface has {even} vertices of one colour and {odd} of the other (x + y + z even "
            "or odd), and a cut path alternates colours"))
    m, cut = path_model(sg, faces, edges)
    for path in short_overlaps(sg, faces, edges, _SHORT_PATH, deadline):
        m.add_bool_or([lit for i in path for lit in cut[i]])

    def refuse(values: list[bool]) -> list[list]:
        """No-goods for a path whose uncut edges fold into an overlap, or whose cut closes up inside."""
        is_cut = [uv or vu for uv, vu in zip(values[0::2], values[1::2])]
        fold_ids = [i for i, c in enumerate(is_cut) if not c]
        cell, rot, parent, via = fold_flat(faces, [edges[i] for i in fold_ids], f)
        clashes = cell_clashes(faces, cell) or _slits(sg, edges, is_cut, cell, rot)
        # Every tree holding these folds lays u and v on one cell (or side by side across their
        # cut edge): one of them must be cut.
        return [[lit for i in tree_path(u, v, parent, via) for lit in cut[fold_ids[i]]] for u, v in clashes]

    search = solve_with_nogoods(m, [lit for pair in cut for lit in pair], refuse, deadline=deadline)
    if search.status == "infeasible":
        raise NoNetExistsError(None, None, kind="zipper net", why=(
            f"every path through the {verts.size} vertices of the {n}-face surface folds into an overlap "
            f"({search.rounds} overlaps ruled out)"))
    if search.status == "timeout":
        raise Undecided(
            f"undecided: the zipper search ran out of time before it found a zipper net of the {n}-face "
            f"surface or proved that none exists ({search.rounds} overlaps ruled out); raise the timeout")
    is_cut = [uv or vu for uv, vu in zip(search.values[0::2], search.values[1::2])]
    cell, rot, parent, _ = fold_flat(faces, [e for e, c in zip(edges, is_cut) if not c], f)
    xy = cell[faces]
    lo = xy.min(axis=0)
    w, h = (xy.max(axis=0) - lo + 1).tolist()
    return ExactLayout(cell - lo, rot, parent, (int(w), int(h)))
