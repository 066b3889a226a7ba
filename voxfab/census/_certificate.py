"""Re-check a "no edge-unzipping" certificate from a polycube's cells alone.

This module shares no code with the search (:mod:`._unzip`, the surface graph,
the net engine): it recounts the surface's vertices from the cubes, rebuilds the
squares and their shared edges from coordinates, and develops fold paths into
the plane by itself.

* ``colours``: every lattice point on the surface is counted by colour (``x + y
  + z`` even or odd, cells translated to the origin) and by kind (flat when four
  squares meet there).  A cut path alternates colours and holds every corner, so
  if one colour's corners outnumber all vertices of the other colour by more than
  one, no unzipping exists.
* ``solver``: each overlap no-good is a chain of squares, each sharing an edge
  with the next, that develops its last square onto its first one's cell; each
  slit no-good a chain that develops two squares side by side across their shared
  edge.  Both are re-derived here, then a path model is solved again from
  scratch (vertices from the cubes, a circuit through every corner, flat
  vertices optional, the no-goods as clauses) and must be infeasible.
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np

__all__ = ["check_certificate"]

_DIRS = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]


def _cells(cells: Any) -> set[tuple[int, int, int]]:
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 3)
    c = c - c.min(axis=0)
    return {tuple(int(v) for v in p) for p in c}


def _squares_at(filled: set, p: tuple[int, int, int]) -> int:
    """Squares of the surface meeting at lattice point p: face-adjacent octant pairs of unlike filling."""
    octs = [(p[0] - 1 + a, p[1] - 1 + b, p[2] - 1 + c) for a, b, c in itertools.product((0, 1), repeat=3)]
    count = 0
    for i, j in itertools.combinations(range(8), 2):
        if sum(abs(u - v) for u, v in zip(octs[i], octs[j])) == 1:
            count += (octs[i] in filled) != (octs[j] in filled)
    return count


def _vertices(filled: set) -> dict[tuple[int, int, int], int]:
    """Every lattice point on the surface with the number of squares meeting there."""
    points = {(x + a, y + b, z + c) for x, y, z in filled for a, b, c in itertools.product((0, 1), repeat=3)}
    out = {}
    for p in points:
        k = _squares_at(filled, p)
        if k:
            out[p] = k
    return out


def _square(face: list[int]) -> list[tuple[int, int, int]]:
    """The 4 corners of face ``[x, y, z, d]`` (cube and direction +x, -x, +y, -y, +z, -z)."""
    x, y, z, d = face
    axis, positive = d // 2, d % 2 == 0
    base = [x, y, z]
    if positive:
        base[axis] += 1
    others = [a for a in range(3) if a != axis]
    out = []
    for da, db in ((0, 0), (1, 0), (1, 1), (0, 1)):
        q = list(base)
        q[others[0]] += da
        q[others[1]] += db
        out.append(tuple(q))
    return out


def _develop(chain: list[list[int]]) -> list[dict[tuple, tuple[int, int]]]:
    """2D positions of each square's corners along a chain of squares, each sharing an edge with the next.

    The first square is laid on the unit cell at the origin; each next one is the
    previous one's square reflected across their shared edge (the edge's two
    corners keep their places, the other two step across it).
    """
    first = _square(chain[0])
    placed = [dict(zip(first, [(0, 0), (1, 0), (1, 1), (0, 1)]))]
    for face in chain[1:]:
        prev = placed[-1]
        mine = _square(face)
        shared = [p for p in mine if p in prev]
        if len(shared) != 2:
            raise ValueError(f"squares {chain} do not form a chain across shared edges")
        pos = {p: prev[p] for p in shared}
        for p in shared:
            q = next(r for r in mine if r not in shared and sum(abs(a - b) for a, b in zip(r, p)) == 1)
            t = next(r for r in prev if r not in shared and prev[r] != prev[p]
                     and abs(prev[r][0] - prev[p][0]) + abs(prev[r][1] - prev[p][1]) == 1)
            pos[q] = (2 * prev[p][0] - prev[t][0], 2 * prev[p][1] - prev[t][1])
        placed.append(pos)
    return placed


def _cell(pos: dict[tuple, tuple[int, int]]) -> tuple[int, int]:
    return (min(v[0] for v in pos.values()), min(v[1] for v in pos.values()))


def _chain(pairs: list[list[int]], faces: list[list[int]]) -> list[list[int]]:
    """The squares of a no-good's edges (pairs of face indices) in path order, from one end to the other."""
    adj: dict[int, list[int]] = {}
    for a, b in pairs:
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, []).append(a)
    ends = [v for v, n in adj.items() if len(n) == 1]
    if len(ends) != 2 or any(len(n) > 2 for n in adj.values()):
        raise ValueError("a no-good's folds do not form one path of squares")
    order, prev = [min(ends)], None
    while len(order) < len(adj):
        nxt = [v for v in adj[order[-1]] if v != prev]
        prev = order[-1]
        order.append(nxt[0])
    return [faces[i] for i in order]


def _neighbours_by_rule(filled: set, face: list[int]) -> None:
    """Refuse a face that is not on the surface (its cube filled, the cube beyond it empty)."""
    x, y, z, d = face
    step = _DIRS[d]
    if (x, y, z) not in filled or (x + step[0], y + step[1], z + step[2]) in filled:
        raise ValueError(f"face {face} is not a face of the polycube's surface")


def check_certificate(cells: Any, certificate: dict[str, Any]) -> str:
    """Re-check that a polycube has no edge-unzipping; return the reason in words.

    Raises
    ------
    ValueError
        The certificate does not prove it.
    """
    filled = _cells(cells)
    kind = certificate.get("kind")
    verts = _vertices(filled)
    corners = [0, 0]
    flats = [0, 0]
    for p, k in verts.items():
        (flats if k == 4 else corners)[sum(p) % 2] += 1
    if kind == "colours":
        if [corners, flats] != [list(certificate["corners"]), list(certificate["flats"])]:
            raise ValueError(f"the counts are corners {corners} and flats {flats}, not those of the certificate")
        for a in (0, 1):
            if corners[a] > corners[1 - a] + flats[1 - a] + 1:
                return (f"{corners[a]} corners of one colour, {corners[1 - a] + flats[1 - a]} vertices of the "
                        "other: no alternating path holds every corner")
        raise ValueError(f"corners {corners} and flats {flats} leave room for a path through every corner")
    if kind != "solver":
        raise ValueError(f"unknown certificate kind {kind!r}")
    faces = [list(f) for f in certificate["faces"]]
    for f in faces:
        _neighbours_by_rule(filled, f)
    surface = sum(1 for c in filled for s in _DIRS if (c[0] + s[0], c[1] + s[1], c[2] + s[2]) not in filled)
    if len(faces) != surface or len({tuple(f) for f in faces}) != surface:
        raise ValueError("the certificate's squares are not the polycube's surface")
    clauses = []
    for pairs in certificate["overlaps"]:
        chain = _chain(pairs, faces)
        placed = _develop(chain)
        if _cell(placed[0]) != _cell(placed[-1]):
            raise ValueError(f"overlap no-good {pairs} does not develop its end squares onto one cell")
        clauses.append(([tuple(sorted(p)) for p in pairs], None))
    for pairs, edge in certificate["slits"]:
        chain = _chain(pairs, faces)
        placed = _develop(chain)
        shared = [p for p in _square(chain[0]) if p in placed[-1]]
        if len(shared) != 2 or any(placed[0][p] != placed[-1][p] for p in shared) or \
                sorted((faces.index(chain[0]), faces.index(chain[-1]))) != sorted(edge):
            raise ValueError(f"slit no-good {pairs} does not develop its end squares side by side across their edge")
        clauses.append(([tuple(sorted(p)) for p in pairs], tuple(sorted(edge))))
    if _path_exists(faces, verts, clauses):
        raise ValueError("a cut path through every corner avoids every no-good: the certificate proves nothing")
    return (f"no cut path through the {sum(corners)} corners avoids the {len(clauses)} no-goods, each re-derived "
            "by developing its squares")


def _path_exists(faces: list[list[int]], verts: dict, clauses: list) -> bool:
    """Whether a path through every corner vertex (flat ones optional) cuts an edge of every no-good."""
    from ortools.sat.python import cp_model

    index = {p: i for i, p in enumerate(sorted(verts))}
    edges: dict[tuple[int, int], tuple] = {}  # square pair -> its shared 3D edge
    by_edge: dict[frozenset, list[int]] = {}
    for i, face in enumerate(faces):
        ring = _square(face)
        for k in range(4):
            by_edge.setdefault(frozenset((ring[k], ring[(k + 1) % 4])), []).append(i)
    m = cp_model.CpModel()
    arcs = []
    cut_of_edge: dict[frozenset, Any] = {}
    for e, owners in sorted(by_edge.items(), key=lambda kv: sorted(kv[0])):
        if len(owners) != 2:
            raise ValueError("the surface is not a 2-manifold")
        p, q = sorted(e)
        uv, vu = m.NewBoolVar(""), m.NewBoolVar("")
        arcs += [(index[p], index[q], uv), (index[q], index[p], vu)]
        c = m.NewBoolVar("")
        m.AddBoolOr([uv, vu]).OnlyEnforceIf(c)
        m.AddImplication(uv, c)
        m.AddImplication(vu, c)
        cut_of_edge[e] = c
        edges[tuple(sorted(owners))] = e
    dummy = len(index)
    for p, i in index.items():
        if verts[p] == 4:
            arcs.append((i, i, m.NewBoolVar("")))
        else:
            arcs += [(dummy, i, m.NewBoolVar("")), (i, dummy, m.NewBoolVar(""))]
    m.AddCircuit(arcs)
    for pairs, slit in clauses:
        lits = [cut_of_edge[edges[p]] for p in pairs]
        if slit is not None:
            lits.append(cut_of_edge[edges[slit]].Not())
        m.AddBoolOr(lits)
    from voxfab.unfold._cpsat import one_worker_solver, solve

    solver = one_worker_solver()  # CP-SAT's own Ctrl-C handler off, the search stopped by Ctrl-C
    solver.parameters.max_time_in_seconds = 600.0
    status = solve(solver, m)
    if status == cp_model.INFEASIBLE:
        return False
    if status in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        return True
    raise ValueError("the re-check ran out of time")
