"""Independent net validator: refold a net and compare it with the voxel surface.

Deliberately shares no code with the search: the exposed faces, their corners,
the neighbour rule across each edge and the fold kinds are recomputed here from
the grid alone, and each face's 3D placement is rebuilt by folding the 2D layout
along the net's folds.
"""

from __future__ import annotations

import dataclasses
from collections import deque
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid
from voxfab.errors import UnfoldError

from ._constraints import EdgeConstraints
from ._net import Net

__all__ = ["ValidationReport", "validate"]

_MAX_LISTED = 20


@dataclasses.dataclass(frozen=True)
class ValidationReport:
    """Outcome of :func:`validate`.

    Attributes
    ----------
    problems : tuple of str
        One line per violated condition (empty when the net is valid).
    faces : int
        Exposed faces of the shape.
    pieces : int
        Nets checked.
    seams : int
        Cut edge pairs inside the nets.
    seams_without_tab_room : int
        Seams neither of whose sides has a free cell beyond it.
    """

    problems: tuple[str, ...]
    faces: int
    pieces: int
    seams: int
    seams_without_tab_room: int

    @property
    def ok(self) -> bool:
        """Whether no problem was found."""
        return not self.problems


def _exposed(g: npt.NDArray[np.bool_]) -> dict[tuple[tuple[int, ...], tuple[int, ...]], int]:
    p = np.pad(g, 1)
    out = {}
    normals = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    for n in normals:
        shifted = np.roll(p, tuple(-c for c in n), axis=(0, 1, 2))
        for v in np.argwhere(p & ~shifted):
            out[(tuple(int(c) - 1 for c in v), n)] = len(out)
    return out


def _filled(g: npt.NDArray[np.bool_], v: npt.NDArray[np.int64]) -> bool:
    x, y, z = v.tolist()
    if not (0 <= x < g.shape[0] and 0 <= y < g.shape[1] and 0 <= z < g.shape[2]):
        return False
    return bool(g[x, y, z])


def _cross(a: npt.NDArray, b: npt.NDArray) -> npt.NDArray:
    """The cross product of two 3-vectors (np.cross costs more than the arithmetic on one pair)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def _square(v: npt.NDArray[np.int64], n: npt.NDArray[np.int64]) -> set[tuple[int, ...]]:
    """Corner points of the face of voxel v with outward normal n."""
    axis = int(np.flatnonzero(n)[0])
    others = [a for a in range(3) if a != axis]
    base = v.copy()
    if n[axis] > 0:
        base[axis] += 1
    pts = set()
    for da in (0, 1):
        for db in (0, 1):
            q = base.copy()
            q[others[0]] += da
            q[others[1]] += db
            pts.add(tuple(q.tolist()))
    return pts


def _rule_neighbour(g, v, n, u):
    """Neighbour face across the edge of face (v, n) lying towards in-plane u, and the fold kind."""
    side = v + u
    if _filled(g, side):
        if _filled(g, side + n):
            return (tuple((side + n).tolist()), tuple((-u).tolist())), -1
        return (tuple(side.tolist()), tuple(n.tolist())), 0
    return (tuple(v.tolist()), tuple(u.tolist())), 1


def validate(
    shape: object, net: Net | Sequence[Net], *, strict: bool = True,
    constraints: EdgeConstraints | None = None,
) -> ValidationReport:
    """Check that ``net`` is a valid unfolding of ``shape`` by refolding it.

    Conditions checked: every exposed face appears exactly once (no missing, no
    extra, no repeated face); each 3D face has its true corners counter-clockwise
    seen from outside; each 2D face is a unit square on the integer grid with
    counter-clockwise corners (not mirrored); no two faces share a cell; every fold
    joins two faces that are neighbours by the 6-connectivity rule along their
    shared edge, with that edge at the same place in 2D on both faces; the folds
    connect each net into one piece; no cut edge closes up in the plane (a slit);
    folding each face's 2D square along the fold tree by ±90° (mountain, valley)
    or 0° (flat) puts it on its 3D face; and the stored fold and tab-room counts
    are right.  With ``constraints``: each named edge is an edge of the surface,
    no cut edge is a fold, and every kept edge is a fold inside one net.

    Parameters
    ----------
    shape : (X, Y, Z) bool array_like or VoxelShape
    net : Net or sequence of Net
        One net, or the pieces of a several-piece unfolding.
    strict : bool
        Raise UnfoldError listing the problems instead of returning them.
    constraints : EdgeConstraints, optional
        Edges the net must cut or keep folded.

    Returns
    -------
    ValidationReport
    """
    g = as_grid(getattr(shape, "grid", shape))
    nets = [net] if isinstance(net, Net) else list(net)
    faces = _exposed(g)
    problems: list[str] = []
    owner: dict[int, tuple[int, int]] = {}
    seams = no_room = 0
    for p, piece in enumerate(nets):
        tag = f"piece {p}: " if len(nets) > 1 else ""
        s, r = _check_piece(g, faces, piece, p, owner, problems, tag)
        seams += s
        no_room += r
    missing = len(faces) - len(owner)
    if missing:
        problems.append(f"{missing} exposed face(s) missing from the net")
    if constraints:
        _check_constraints(g, faces, nets, constraints, problems)
    report = ValidationReport(tuple(problems), len(faces), len(nets), seams, no_room)
    if strict and problems:
        shown = "; ".join(problems[:5])
        more = f" (and {len(problems) - 5} more)" if len(problems) > 5 else ""
        raise UnfoldError(f"invalid net: {shown}{more}")
    return report


def _check_piece(g, faces, net: Net, p: int, owner: dict, problems: list[str], tag: str):
    nf = net.face_count
    err = problems.append
    v3 = np.asarray(net.voxel, dtype=np.int64)
    n3 = np.asarray(net.normal, dtype=np.int64)
    c3 = np.asarray(net.corners3d, dtype=np.int64)
    c2 = np.asarray(net.corners2d, dtype=np.int64)
    good = np.ones(nf, dtype=bool)  # faces whose own geometry is sound
    for i in range(nf):
        key = (tuple(v3[i].tolist()), tuple(n3[i].tolist()))
        if key not in faces:
            err(f"{tag}face {i} (voxel {key[0]}, normal {key[1]}) is not an exposed face")
            good[i] = False
            continue
        idx = faces[key]
        if idx in owner:
            err(f"{tag}face {i} repeats face {owner[idx][1]} of piece {owner[idx][0]} ({key})")
        else:
            owner[idx] = (p, i)
        want = _square(v3[i], n3[i])
        if {tuple(c) for c in c3[i].tolist()} != want:
            err(f"{tag}face {i}: corners3d are not the corners of its face")
            good[i] = False
            continue
        e1, e3 = c3[i, 1] - c3[i, 0], c3[i, 3] - c3[i, 0]
        if not np.array_equal(_cross(e1, e3), n3[i]) or not np.array_equal(
            c3[i, 2], c3[i, 1] + e3
        ):
            err(f"{tag}face {i}: corners3d are not counter-clockwise seen from outside")
            good[i] = False
        d1, d3 = c2[i, 1] - c2[i, 0], c2[i, 3] - c2[i, 0]
        if (
            abs(d1).sum() != 1
            or abs(d3).sum() != 1
            or not np.array_equal(c2[i, 2], c2[i, 1] + d3)
        ):
            err(f"{tag}face {i}: corners2d are not a unit square on the grid")
            good[i] = False
        elif d1[0] * d3[1] - d1[1] * d3[0] != 1:
            err(f"{tag}face {i} is mirrored (corners2d clockwise)")
            good[i] = False
    cells: dict[tuple[int, int], int] = {}
    lows = c2.min(axis=1).tolist() if nf else []
    for i in range(nf):
        cell = tuple(lows[i])
        if cell in cells:
            err(f"{tag}faces {cells[cell]} and {i} overlap on cell {cell}")
        else:
            cells[cell] = i
    # Folds: rule neighbours along the shared edge, same edge in 2D.
    adj: list[list[tuple[int, int]]] = [[] for _ in range(nf)]
    seen_pairs: set[tuple[int, int]] = set()
    kinds = {1: 0, -1: 0, 0: 0}
    lookup = {
        (tuple(v3[i].tolist()), tuple(n3[i].tolist())): i for i in range(nf) if good[i]
    }
    folds = np.asarray(net.folds, dtype=np.int64).reshape(-1, 2)
    for t, (i, j) in enumerate(folds.tolist()):
        if not (0 <= i < nf and 0 <= j < nf) or i == j:
            err(f"{tag}fold {t} [{i}, {j}] does not join two faces of the net")
            continue
        pair = (min(i, j), max(i, j))
        if pair in seen_pairs:
            err(f"{tag}fold {t} [{i}, {j}] is listed twice")
            continue
        seen_pairs.add(pair)
        if not (good[i] and good[j]):
            continue
        kind = _fold_kind(g, v3, n3, c3, c2, i, j)
        if isinstance(kind, str):
            err(f"{tag}fold {t} [{i}, {j}]: {kind}")
            continue
        kinds[kind] += 1
        adj[i].append((j, kind))
        adj[j].append((i, kind))
    if (net.mountain, net.valley, net.flat) != (kinds[1], kinds[-1], kinds[0]):
        err(
            f"{tag}fold counts (mountain, valley, flat) = {(net.mountain, net.valley, net.flat)} "
            f"but the folds are {(kinds[1], kinds[-1], kinds[0])}"
        )
    # One piece, and refolding along a spanning tree lands every face on its 3D face.
    if nf:
        _refold(c2, c3, n3, adj, good, err, tag)
    seams, no_room = _seams(g, v3, n3, c3, c2, lookup, seen_pairs, cells, good, err, tag)
    if net.seams_without_tab_room != no_room:
        err(f"{tag}seams_without_tab_room = {net.seams_without_tab_room} but {no_room} seams "
            "have no tab room")
    return seams, no_room


def _shared(c3, i, j):
    a = {tuple(c): k for k, c in enumerate(c3[i].tolist())}
    b = {tuple(c): k for k, c in enumerate(c3[j].tolist())}
    common = [pt for pt in a if pt in b]
    return common, a, b


def _fold_kind(g, v3, n3, c3, c2, i, j):
    common, a, b = _shared(c3, i, j)
    if len(common) != 2:
        return "the faces share no edge"
    mid = (np.array(common[0]) + np.array(common[1])) / 2.0
    centre = c3[i].sum(axis=0) / 4.0  # the mean, without its per-call cost
    u = np.rint((mid - centre) * 2).astype(np.int64)
    want, kind = _rule_neighbour(g, v3[i], n3[i], u)
    have = (tuple(v3[j].tolist()), tuple(n3[j].tolist()))
    if want != have:
        return "the faces are not neighbours across their shared edge (6-connectivity rule)"
    for pt in common:
        if not np.array_equal(c2[i, a[pt]], c2[j, b[pt]]):
            return "the shared edge is at different places in 2D"
    return kind


def _refold(c2, c3, n3, adj, good, err, tag):
    nf = c2.shape[0]
    start = int(np.flatnonzero(good)[0]) if good.any() else 0
    maps: dict[int, tuple[np.ndarray, np.ndarray]] = {}

    def affine(i):
        # 3D = o + A @ 2D, from corners 0, 1, 3.
        e = np.stack([c2[i, 1] - c2[i, 0], c2[i, 3] - c2[i, 0]], axis=1).astype(float)
        big = np.stack([c3[i, 1] - c3[i, 0], c3[i, 3] - c3[i, 0]], axis=1).astype(float)
        a = big @ np.linalg.inv(e)
        return c3[i, 0] - a @ c2[i, 0], a

    maps[start] = affine(start)
    queue = deque([start])
    while queue:
        i = queue.popleft()
        o, a = maps[i]
        normal = _cross(a[:, 0], a[:, 1])
        for j, kind in adj[i]:
            if j in maps:
                continue
            common = [pt for pt in map(tuple, c2[i].tolist()) if pt in set(map(tuple, c2[j].tolist()))]
            p0 = np.array(common[0], dtype=float)
            q0 = o + a @ p0
            # Unit vector in i's plane pointing across the edge, towards j.
            centre_j = o + a @ (c2[j].sum(axis=0) / 4.0)
            line = o + a @ np.array(common[1], dtype=float) - q0
            w = centre_j - q0
            w = w - line * (w @ line) / (line @ line)
            u = w / np.linalg.norm(w)
            if kind == 0:
                rot = np.eye(3)
            else:
                # Mountain: u turns to -n (the face bends away from the outside); valley: to +n.
                s = -kind
                rot = np.eye(3) - np.outer(u, u) - np.outer(normal, normal)
                rot += s * np.outer(normal, u) - s * np.outer(u, normal)
            maps[j] = (q0 + rot @ (o - q0), rot @ a)
            queue.append(j)
    unreached = [i for i in range(nf) if i not in maps]
    if unreached:
        err(f"{tag}the folds do not connect the net: {len(unreached)} face(s) are not joined "
            f"to face {start} (e.g. face {unreached[0]})")
    wrong = []
    done = [i for i in maps if good[i]]
    if done:
        # every placed face at once: o + A @ corner for its four corners, against its 3D corners
        o = np.array([maps[i][0] for i in done])
        a = np.array([maps[i][1] for i in done])
        placed = o[:, None, :] + np.einsum("fij,fkj->fki", a, c2[done].astype(float))
        close = (np.abs(placed - c3[done]) <= 1e-6 + 1e-5 * np.abs(c3[done])).all(axis=(1, 2))
        wrong = [i for i, ok in zip(done, close.tolist()) if not ok]
    if wrong:
        err(f"{tag}refolding puts {len(wrong)} face(s) off their 3D place (e.g. face {wrong[0]})")


def _seams(g, v3, n3, c3, c2, lookup, folded, cells, good, err, tag):
    seams = no_room = slits = 0
    for i in range(v3.shape[0]):
        if not good[i]:
            continue
        centre = c3[i].sum(axis=0) / 4.0  # the mean, without its per-call cost
        for k in range(4):
            p3, q3 = c3[i, k], c3[i, (k + 1) % 4]
            u = np.rint(((p3 + q3) / 2.0 - centre) * 2).astype(np.int64)
            other, _ = _rule_neighbour(g, v3[i], n3[i], u)
            j = lookup.get(other)
            if j is None or j <= i or (i, j) in folded:
                continue
            seams += 1
            ja = _corner_index(c3[j], q3)
            jb = _corner_index(c3[j], p3)
            if ja < 0 or jb < 0:
                continue
            if np.array_equal(c2[j, ja], c2[i, (k + 1) % 4]) and np.array_equal(c2[j, jb], c2[i, k]):
                slits += 1
                continue
            if _beyond(c2, i, k, (k + 1) % 4) in cells and _beyond(c2, j, ja, jb) in cells:
                no_room += 1
    if slits:
        err(f"{tag}{slits} cut edge(s) close up in the plane (slits): leave them as folds")
    return seams - slits, no_room


def _corner_index(corners, point):
    hit = np.flatnonzero((corners == point).all(axis=1))
    return int(hit[0]) if hit.size else -1


def _beyond(c2, i, a, b):
    """The cell across the 2D edge from corner a to corner b of face i (outside of a CCW square)."""
    p, q = c2[i, a], c2[i, b]
    step = np.array([q[1] - p[1], p[0] - q[0]])
    return tuple((c2[i].min(axis=0) + step).tolist())


_NORMAL = {"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0),
           "+z": (0, 0, 1), "-z": (0, 0, -1)}


def _check_constraints(g, faces, nets, constraints: EdgeConstraints, problems: list[str]) -> None:
    """Cut edges are not folds, kept edges are folds, and both name surface edges."""
    where: dict[tuple, tuple[int, int]] = {}
    folded: set[tuple[int, tuple[int, int]]] = set()
    for p, piece in enumerate(nets):
        for i, (v, n) in enumerate(zip(np.asarray(piece.voxel).tolist(), np.asarray(piece.normal).tolist())):
            where[(tuple(v), tuple(n))] = (p, i)
        for i, j in np.asarray(piece.folds, dtype=np.int64).reshape(-1, 2).tolist():
            folded.add((p, (min(i, j), max(i, j))))
    for name, edges in (("cut", constraints.cut), ("keep", constraints.keep)):
        for edge in sorted(edges):
            a, b = ((tuple(f[:3]), _NORMAL[f[3]]) for f in edge)
            label = f"{name} edge {list(edge[0])}-{list(edge[1])}"
            if a not in faces or b not in faces:
                problems.append(f"{label}: not an edge between exposed faces")
                continue
            va, na = np.array(a[0]), np.array(a[1])
            axes = [u for u in np.eye(3, dtype=np.int64) if not (u * na).any()]
            if b not in {_rule_neighbour(g, va, na, s * u)[0] for u in axes for s in (1, -1)}:
                problems.append(f"{label}: the faces do not meet along an edge (6-connectivity rule)")
                continue
            (pa, ia), (pb, ib) = where.get(a, (-1, -1)), where.get(b, (-2, -2))
            is_fold = pa == pb and (pa, (min(ia, ib), max(ia, ib))) in folded
            if name == "cut" and is_fold:
                problems.append(f"{label} is a fold of the net")
            if name == "keep" and not is_fold:
                problems.append(f"{label} is not a fold of the net")
