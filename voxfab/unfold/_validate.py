"""Independent net validator: refold a net and compare it with the voxel surface.

Deliberately shares no code with the search: the exposed faces, their corners,
the neighbour rule across each edge and the fold kinds are recomputed here from
the grid alone, and each face's 3D placement is rebuilt by folding the 2D layout
along the net's folds.
"""

from __future__ import annotations

import dataclasses
import threading
from collections import deque
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from voxfab._shared.arrays import unique

# check_cancelled() in the face-by-face walks: a cancelled studio job stops within a face, not a whole check.
from voxfab._shared.progress import check_cancelled
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
        s, r = _check_piece(g, faces, piece, p, owner, problems, tag, remember=not isinstance(net, Net))
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


#: Pieces found sound, by shape and piece (all its fields): an edit changes one or two pieces of many, and
#: the others are not refolded again (a twentieth of a second on the queen's 35 pieces).
_SOUND: dict[bytes, tuple] = {}
_SOUND_KEPT = 256
_SOUND_LOCK = threading.Lock()  # studio edits run on worker threads


def _sound_key(g: npt.NDArray[np.bool_], net: Net) -> bytes:
    import hashlib  # here: it loads OpenSSL, which a command validating a one-piece net never needs

    h = hashlib.sha256(repr(g.shape).encode() + np.packbits(g).tobytes())
    for field in dataclasses.fields(net):
        v = getattr(net, field.name)
        if isinstance(v, np.ndarray):
            h.update(f"{field.name}{v.shape}{v.dtype}".encode() + np.ascontiguousarray(v).tobytes())
        else:
            h.update(f"{field.name}{v!r}".encode())
    return h.digest()


def _check_piece(g, faces, net: Net, p: int, owner: dict, problems: list[str], tag: str, *, remember: bool):
    """Check one net; a sound net is confirmed by whole-array checks, any other face by face with reasons.

    ``remember``: look the piece up among, and add it to, the pieces found sound (a net given as its list of
    pieces, which edits change a few at a time; a net given alone is checked once).
    """
    key = _sound_key(g, net) if remember else None
    with _SOUND_LOCK:
        sound = _SOUND.get(key) if remember else None
    if sound is not None and any(i in owner for i in sound[2][0]):
        sound = None  # a face an earlier piece has too: found and worded face by face
    elif sound is None:
        sound = _sound_piece(g, faces, net, owner)
        if sound is not None and remember:
            with _SOUND_LOCK:
                _SOUND[key] = sound
                while len(_SOUND) > _SOUND_KEPT:
                    del _SOUND[next(iter(_SOUND))]
    if sound is not None:
        for idx, i in zip(*sound[2]):
            owner[idx] = (p, i)
        return sound[0], sound[1]
    return _check_piece_by_face(g, faces, net, p, owner, problems, tag)


def _rule_neighbours(gp, v, n, u):
    """Vectorised :func:`_rule_neighbour` on the grid padded by one: neighbour voxels, normals and fold kinds."""
    side = v + u
    a = gp[tuple((side + 1).T)]
    b = gp[tuple((side + n + 1).T)]
    valley, flat = a & b, a & ~b
    voxel = np.where(valley[:, None], side + n, np.where(flat[:, None], side, v))
    normal = np.where(valley[:, None], -u, np.where(flat[:, None], n, u))
    kind = np.where(valley, -1, np.where(flat, 0, 1))
    return voxel, normal, kind


def _sound_piece(g, faces, net: Net, owner: dict):
    """Every condition of one net checked over whole arrays: ``(seams, no_room, (ids, faces))``, or None.

    None means some condition may fail: :func:`_check_piece_by_face` then finds
    and words the problems.  The conditions are those of the face-by-face check.
    """
    nf = net.face_count
    if nf == 0:
        return None
    v3 = np.asarray(net.voxel, dtype=np.int64)
    n3 = np.asarray(net.normal, dtype=np.int64)
    c3 = np.asarray(net.corners3d, dtype=np.int64)
    c2 = np.asarray(net.corners2d, dtype=np.int64)
    ids = [faces.get(k) for k in zip(map(tuple, v3.tolist()), map(tuple, n3.tolist()))]
    if any(i is None or i in owner for i in ids) or len(set(ids)) != nf:
        return None
    if not (np.abs(n3).sum(axis=1) == 1).all():
        return None
    # 3D: a unit square counter-clockwise seen from outside on the face of (voxel, normal).
    e1, e3 = c3[:, 1] - c3[:, 0], c3[:, 3] - c3[:, 0]
    if not ((np.cross(e1, e3) == n3).all() and (c3[:, 2] == c3[:, 1] + e3).all()
            and (np.abs(e1).sum(axis=1) == 1).all() and (np.abs(e3).sum(axis=1) == 1).all()):
        return None
    base = v3 + np.maximum(n3, 0)
    if not (c3.min(axis=1) == base).all():
        return None
    # 2D: a unit square on the grid, counter-clockwise; no two on one cell.
    d1, d3 = c2[:, 1] - c2[:, 0], c2[:, 3] - c2[:, 0]
    if not ((np.abs(d1).sum(axis=1) == 1).all() and (np.abs(d3).sum(axis=1) == 1).all()
            and (c2[:, 2] == c2[:, 1] + d3).all() and (d1[:, 0] * d3[:, 1] - d1[:, 1] * d3[:, 0] == 1).all()):
        return None
    cell = c2.min(axis=1)
    lo = cell.min(axis=0) - 2
    span = int((cell.max(axis=0) - lo).max()) + 3
    cell_key = (cell[:, 0] - lo[0]) * span + (cell[:, 1] - lo[1])
    if unique(cell_key).size != nf:
        return None
    # Folds: two faces that are rule neighbours across their shared edge, at the same place in 2D.
    folds = np.asarray(net.folds, dtype=np.int64).reshape(-1, 2)
    i, j = folds[:, 0], folds[:, 1]
    if folds.size and ((folds < 0).any() or (folds >= nf).any() or (i == j).any()):
        return None
    pair = np.minimum(i, j) * nf + np.maximum(i, j)
    if unique(pair).size != pair.size:
        return None
    gp = np.pad(np.asarray(g, dtype=bool), 1)
    if folds.size:
        same = (c3[i][:, :, None, :] == c3[j][:, None, :, :]).all(axis=3)  # (m, 4 of i, 4 of j)
        if not (same.sum(axis=(1, 2)) == 2).all():
            return None
        ai = np.argwhere(same)  # two rows per fold, in the order of i's corners
        a, b = ai[:, 1].reshape(-1, 2), ai[:, 2].reshape(-1, 2)
        rows = np.arange(folds.shape[0])[:, None]
        mid2 = c3[i][rows, a].sum(axis=1)  # twice the midpoint of the shared edge
        u = np.rint(mid2 - 2 * c3[i].mean(axis=1)).astype(np.int64)
        voxel, normal, kind = _rule_neighbours(gp, v3[i], n3[i], u)
        if not ((voxel == v3[j]).all() and (normal == n3[j]).all()
                and (c2[i][rows, a] == c2[j][rows, b]).all()):
            return None
        counts = (int((kind == 1).sum()), int((kind == -1).sum()), int((kind == 0).sum()))
    else:
        kind, counts = np.zeros(0, dtype=np.int64), (0, 0, 0)
    if (net.mountain, net.valley, net.flat) != counts:
        return None
    if not _refolds(c2, c3, folds, kind):
        return None
    seams, no_room = _sound_seams(gp, v3, n3, c3, c2, pair, cell_key, lo, span)
    if seams is None or net.seams_without_tab_room != no_room:
        return None
    return seams, no_room, (ids, range(nf))


def _refolds(c2, c3, folds, kind) -> bool:
    """Whether the folds join the net into one tree-connected piece whose refolding lands every face on its 3D face.

    Each face's own map 2D -> 3D is fixed by its corners; folding a face's map about
    the shared edge (a quarter turn, or none when flat) must give its neighbour's
    own map along a breadth-first tree from face 0: then refolding from face 0
    puts every face on its 3D face, as the face-by-face check rebuilds it.
    """
    nf = c2.shape[0]
    adj: list[list[tuple[int, int]]] = [[] for _ in range(nf)]
    for t, (i, j) in enumerate(folds.tolist()):
        adj[i].append((j, t))
        adj[j].append((i, t))
    seen = np.zeros(nf, dtype=bool)
    seen[0] = True
    queue = deque([0])
    tree_i, tree_j, tree_t = [], [], []
    while queue:
        i = queue.popleft()
        for j, t in adj[i]:
            if not seen[j]:
                seen[j] = True
                tree_i.append(i)
                tree_j.append(j)
                tree_t.append(t)
                queue.append(j)
    if not seen.all():
        return False
    if not tree_i:
        return True
    i, j, t = np.array(tree_i), np.array(tree_j), np.array(tree_t)
    c2f, c3f = c2.astype(float), c3.astype(float)
    # Own map of face i: 3D = o + A @ 2D, from corners 0, 1, 3 (a unit square: the inverse is the transpose).
    e = np.stack([c2f[i, 1] - c2f[i, 0], c2f[i, 3] - c2f[i, 0]], axis=2)  # (m, 2, 2), columns
    big = np.stack([c3f[i, 1] - c3f[i, 0], c3f[i, 3] - c3f[i, 0]], axis=2)  # (m, 3, 2)
    amap = big @ np.linalg.inv(e)
    o = c3f[i, 0] - np.einsum("mab,mb->ma", amap, c2f[i, 0])
    normal = np.cross(amap[:, :, 0], amap[:, :, 1])
    # A point of the shared edge, and the unit vector in i's plane across it towards j.
    shared = (c2[i][:, :, None, :] == c2[j][:, None, :, :]).all(axis=3).any(axis=2)  # (m, 4) corners of i
    k0 = np.argmax(shared, axis=1)
    rows = np.arange(i.size)
    p0 = c2f[i][rows, k0]
    edge_mid = (c2f[i] * shared[:, :, None]).sum(axis=1) / 2.0
    q0 = o + np.einsum("mab,mb->ma", amap, p0)
    u = 2.0 * np.einsum("mab,mb->ma", amap, c2f[j].mean(axis=1) - edge_mid)
    s = (-kind[t]).astype(float)[:, None, None]
    eye = np.broadcast_to(np.eye(3), (i.size, 3, 3))
    uu = u[:, :, None] * u[:, None, :]
    nn = normal[:, :, None] * normal[:, None, :]
    nu = normal[:, :, None] * u[:, None, :]
    turn = eye - uu - nn + s * (nu - nu.transpose(0, 2, 1))
    rot = np.where((kind[t] == 0)[:, None, None], eye, turn)
    o_j = q0 + np.einsum("mab,mb->ma", rot, o - q0)
    a_j = rot @ amap
    placed = o_j[:, None, :] + np.einsum("mab,mkb->mka", a_j, c2f[j])
    return bool(np.allclose(placed, c3f[j], atol=1e-6))


def _sound_seams(gp, v3, n3, c3, c2, fold_pairs, cell_key, lo, span):
    """Seams and seams without tab room over whole arrays, as :func:`_seams` counts them; None on a slit."""
    nf = v3.shape[0]
    f = np.repeat(np.arange(nf), 4)
    k = np.tile(np.arange(4), nf)
    k1 = (k + 1) % 4
    p3, q3 = c3[f, k], c3[f, k1]
    u = np.rint(p3 + q3 - 2 * c3[f].mean(axis=1)).astype(np.int64)
    voxel, normal, _ = _rule_neighbours(gp, v3[f], n3[f], u)
    # Neighbour face ids by (voxel, normal), sorted keys of this net's faces.
    vlo = np.minimum(v3.min(axis=0), voxel.min(axis=0)) - 1
    vspan = int((np.maximum(v3.max(axis=0), voxel.max(axis=0)) - vlo).max()) + 2

    def key(v, n):
        w = v - vlo
        d = np.argmax(np.abs(n), axis=1) * 2 + (n.sum(axis=1) < 0)
        return ((w[:, 0] * vspan + w[:, 1]) * vspan + w[:, 2]) * 6 + d

    own = key(v3, n3)
    order = np.argsort(own)
    want = key(voxel, normal)
    pos = np.clip(np.searchsorted(own[order], want), 0, nf - 1)
    found = own[order][pos] == want
    j = np.where(found, order[pos], -1)
    seam = found & (j > f) & ~np.isin(np.minimum(f, j) * nf + np.maximum(f, j), fold_pairs)
    f, k, k1, j, p3, q3 = f[seam], k[seam], k1[seam], j[seam], p3[seam], q3[seam]
    hit_a = (c3[j] == q3[:, None, :]).all(axis=2)
    hit_b = (c3[j] == p3[:, None, :]).all(axis=2)
    both = hit_a.any(axis=1) & hit_b.any(axis=1)
    ja, jb = np.argmax(hit_a, axis=1), np.argmax(hit_b, axis=1)
    rows = np.arange(f.size)
    slit = both & (c2[j, ja] == c2[f, k1]).all(axis=1) & (c2[j, jb] == c2[f, k]).all(axis=1)
    if slit.any():
        return None, None

    def beyond(face, a, b):
        pa, pb = c2[face, a], c2[face, b]
        step = np.stack([pb[:, 1] - pa[:, 1], pa[:, 0] - pb[:, 0]], axis=1)
        cell = c2[face].min(axis=1) + step - lo
        inside = (cell >= 0).all(axis=1) & (cell < span).all(axis=1)
        return inside & np.isin(cell[:, 0] * span + cell[:, 1], cell_key)

    del rows
    no_room = both & beyond(f, k, k1) & beyond(j, ja, jb)
    return int(f.size), int(np.count_nonzero(no_room))


def _check_piece_by_face(g, faces, net: Net, p: int, owner: dict, problems: list[str], tag: str):
    nf = net.face_count
    err = problems.append
    v3 = np.asarray(net.voxel, dtype=np.int64)
    n3 = np.asarray(net.normal, dtype=np.int64)
    c3 = np.asarray(net.corners3d, dtype=np.int64)
    c2 = np.asarray(net.corners2d, dtype=np.int64)
    good = np.ones(nf, dtype=bool)  # faces whose own geometry is sound
    for i in range(nf):
        check_cancelled()
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
        check_cancelled()
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
        check_cancelled()
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
        check_cancelled()
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
    check_cancelled()
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
        check_cancelled()
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
