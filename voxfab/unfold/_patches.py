"""pieces="flat": pieces grown from whole flat patches of the surface, joined rigidly along shared edges."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import check_cancelled
from voxfab.shape import SurfaceGraph

from ._constraints import _SIDE_STEP as _STEP
from ._job import MIN_SHARE, Job, surface_parts
from ._searchboard import SearchBoard, board_of

#: pieces="auto" from flat patches: a piece stops growing at this share of the
#: box's cells, so the box keeps room to take the small pieces left over.
_PATCH_SHARE = 0.25


def _flat_patches(sg: SurfaceGraph, faces: npt.NDArray[np.int64]) -> list[npt.NDArray[np.int64]]:
    """``faces`` grouped into flat patches: connected faces of one outward direction (so one plane).

    Patches come in the order of their lowest face; a walk over the faces (not scipy's graph
    components, whose import alone costs more than the walk on a 4000-face surface).
    """
    inside = np.zeros(sg.face_count, dtype=bool)
    inside[faces] = True
    inside_list = inside.tolist()
    direction = sg.direction.tolist()
    neighbor = sg.neighbor.tolist()
    seen = [False] * sg.face_count
    out = []
    for f in sorted(faces.tolist()):
        if seen[f]:
            continue
        seen[f] = True
        patch = [f]
        for a in patch:
            for b in neighbor[a]:
                if inside_list[b] and not seen[b] and direction[b] == direction[a]:
                    seen[b] = True
                    patch.append(b)
        out.append(np.array(sorted(patch), dtype=np.int64))
    return out


def _lay_flat(sg: SurfaceGraph, root: int, in_patch: npt.NDArray[np.bool_], cell: npt.NDArray[np.int64],
              rot: npt.NDArray[np.int64], par: npt.NDArray[np.int64], *, laid: bool = False) -> None:
    """Unfold the flat patch of ``root`` (``in_patch`` marks its faces) breadth first from ``root``.

    Writes each face's cell, rotation and fold-tree parent into ``cell``,
    ``rot`` and ``par``, ``root`` at cell (0, 0) turned 0 with no parent.  A flat
    patch lies in a plane, so its unfolding is its own shape and never overlaps.

    ``laid``: the patch is laid out already (``cell`` and ``rot`` are read, not written): only its fold tree
    is made, across the edges whose faces meet in the plane (a band cut open is not crossed at its cut,
    where its ends do not meet).
    """
    if not laid:
        cell[root] = (0, 0)
        rot[root] = 0
    par[root] = -1
    seen = {root}
    walk = [root]
    for a in walk:
        for k in range(4):
            c = int(sg.neighbor[a, k])
            if not in_patch[c] or c in seen:
                continue
            s = (k + int(rot[a])) % 4
            turned = (s + 2 - int(sg.neighbor_edge[a, k])) % 4
            if not laid:
                cell[c] = cell[a] + _STEP[s]
                rot[c] = turned
            elif (int(cell[c, 0]) - int(cell[a, 0]), int(cell[c, 1]) - int(cell[a, 1])) != _STEP[s] or \
                    int(rot[c]) != turned:
                continue
            seen.add(c)
            par[c] = a
            walk.append(c)


def _tiles(sg: SurfaceGraph, patch: npt.NDArray[np.int64], cell: npt.NDArray[np.int64],
           box: tuple[int, int]) -> list[npt.NDArray[np.int64]]:
    """A flat patch laid out at ``cell`` cut into tiles of ``box`` cells, each tile's connected parts apart."""
    x, y = cell[patch, 0], cell[patch, 1]
    if np.ptp(x) < box[0] and np.ptp(y) < box[1]:
        return [patch]
    tile = ((x - x.min()) // box[0]) * 100003 + (y - y.min()) // box[1]
    out = []
    for t in np.unique(tile).tolist():
        out += surface_parts(sg, patch[tile == t])
    return out


def flat_layouts(sg: SurfaceGraph, faces: npt.NDArray[np.int64], side: int, pcell: npt.NDArray[np.int64],
                 prot: npt.NDArray[np.int64], ppar: npt.NDArray[np.int64]) -> list[npt.NDArray[np.int64]]:
    """``faces`` as flat patches (those past ``side`` cells cut into tiles), each laid out from its first face.

    Writes each patch's layout into ``pcell``, ``prot`` and ``ppar``.
    """
    in_patch = np.zeros(sg.face_count, dtype=bool)
    patches: list[npt.NDArray[np.int64]] = []
    for patch in _flat_patches(sg, faces):
        in_patch[patch] = True
        _lay_flat(sg, int(patch[0]), in_patch, pcell, prot, ppar)
        in_patch[patch] = False
        tiles = _tiles(sg, patch, pcell, (side, side))
        if len(tiles) > 1:
            for tile in tiles:  # each tile laid out from its own first face, as a patch of its own
                in_patch[tile] = True
                _lay_flat(sg, int(tile[0]), in_patch, pcell, prot, ppar)
                in_patch[tile] = False
        patches += tiles
    return patches


def patch_pieces(job: Job, faces: npt.NDArray[np.int64]) -> list[tuple[SearchBoard, npt.NDArray[np.int64]]]:
    """Pieces grown from whole flat patches of the surface, each joined rigidly to the piece along a shared edge.

    A flat patch unfolds to its own shape, so pieces made of patches are as
    compact as the surface and pack densely on a sheet (:func:`join_patches`).
    """
    f_all = job.sg.face_count
    pcell = np.zeros((f_all, 2), dtype=np.int64)
    prot = np.zeros(f_all, dtype=np.int64)
    ppar = np.full(f_all, -1, dtype=np.int64)
    patches = flat_layouts(job.sg, faces, min(job.fit), pcell, prot, ppar)
    return join_patches(job, patches, pcell, prot, _PATCH_SHARE)


def join_patches(job: Job, patches: list[npt.NDArray[np.int64]], pcell: npt.NDArray[np.int64],
                 prot: npt.NDArray[np.int64], share: float, loose: npt.NDArray[np.bool_] | None = None,
                 apart: bool = False, seed_first: list[bool] | None = None
                 ) -> list[tuple[SearchBoard, npt.NDArray[np.int64]]]:
    """Pieces of rigid patches (each laid out at ``pcell``, ``prot``, in one piece in the plane), joined along shared edges.

    A piece starts from the largest patch left and takes, one at a time, the
    neighbouring patch whose rigid placement shares the most edges with the
    piece in the plane (then keeps its bounding box smallest), so strips of a
    band round the shape line up; it stops growing at ``share`` of the box's
    cells.  A placement must fit the box either way round, overlap no face,
    and lay no face beside another across an edge they do not share on the
    surface: every seam then keeps the cell beyond it free on both sides for
    its glue tab.  A face is laid beside an edge only once the edge's partner
    is laid, so no patch left loses the edge it could hang from, unless the
    partner is ``loose`` (a face of a patch large enough to start a piece):
    the partner's own side then keeps the seam's tab room.  Patches marked
    ``seed_first`` start pieces before the others.
    """
    sg = job.sg
    f_all = sg.face_count
    loose = np.zeros(f_all, dtype=bool) if loose is None else loose
    seed_first = seed_first or []
    box = job.fit
    pcell, prot = pcell.copy(), prot.copy()
    in_patch = np.zeros(f_all, dtype=bool)
    patch_of = [-1] * f_all
    for t, p in enumerate(patches):
        for f in p.tolist():
            patch_of[f] = t
    free = [True] * len(patches)
    cell = np.zeros((f_all, 2), dtype=np.int64)
    rot = np.zeros(f_all, dtype=np.int64)
    par = np.full(f_all, -1, dtype=np.int64)
    nb, ne = sg.neighbor, sg.neighbor_edge
    nbl, nel = nb.tolist(), ne.tolist()
    turns: dict[tuple[int, int], tuple] = {}  # each patch's layout turned, by (patch, quarter turns)
    blocked: set[tuple[int, int]] = set()  # edges with a face beside them that is not their partner
    placed = np.zeros(f_all, dtype=bool)

    def grow(members: list[int], limit: float) -> None:
        """Add the best-placed free neighbouring patch to the piece ``members`` until none fits or it reaches ``limit``."""
        occ = {(int(cell[f, 0]), int(cell[f, 1])): f for f in members}
        lo = cell[members].min(axis=0).tolist()
        hi = cell[members].max(axis=0).tolist()

        def edges_out(faces: list[int]) -> list[tuple[int, int, int, int, int]]:
            # Per edge of a laid face: the face, the face across, the cell across, and its side turned.
            out = []
            for a, (x, y), r in zip(faces, cell[faces].tolist(), rot[faces].tolist()):
                for k in range(4):
                    s = (k + r) % 4
                    out.append((a, nbl[a][k], x + _STEP[s][0], y + _STEP[s][1], (s + 2 - nel[a][k]) % 4))
            return out

        frontier = edges_out(members)
        while len(members) < limit:
            check_cancelled()  # between patches: a cancelled studio job stops within one patch's placements
            best = None
            tried: set[tuple[int, int, int, int]] = set()
            # Edges into patches laid already never lead anywhere again.
            frontier = [e for e in frontier if patch_of[e[1]] >= 0 and free[patch_of[e[1]]]]
            for a, c, tx, ty, turn in frontier:
                t = patch_of[c]
                q = (turn - int(prot[c])) % 4
                vx, vy = int(pcell[c, 0]), int(pcell[c, 1])
                for _ in range(q):
                    vx, vy = -vy, vx
                key = (t, q, tx - vx, ty - vy)
                if key in tried:
                    continue
                tried.add(key)
                if (t, q) not in turns:
                    turns[t, q] = _turned(patches[t], pcell, prot, q)
                found = _place_patch(nbl, nel, turns[t, q], (tx - vx, ty - vy), occ, rot, (lo[0], lo[1]),
                                     (hi[0], hi[1]), box, blocked, placed, loose)
                if found is not None and _blocks_ok(found[2], sg):
                    score = (-found[0], found[1], len(found[2]), t)
                    if best is None or score < best[0]:
                        best = (score, t, q, key[2:], a, c, found[2])
            if best is None:
                return
            _, t, q, (ox, oy), a, c, new = best
            blocked.update(new)
            patch = patches[t]
            v = pcell[patch].copy()
            for _ in range(q):
                v = np.stack([-v[:, 1], v[:, 0]], axis=1)
            cell[patch] = v + (ox, oy)
            rot[patch] = (prot[patch] + q) % 4
            # The fold tree of the patch hangs from the shared edge the placement came from.
            in_patch[patch] = True
            _lay_flat(sg, c, in_patch, cell, rot, par, laid=True)
            in_patch[patch] = False
            par[c] = a
            free[t] = False
            placed[patch] = True
            members += patch.tolist()
            frontier += edges_out(patch.tolist())
            for f in patch.tolist():
                occ[(int(cell[f, 0]), int(cell[f, 1]))] = f
            lo = np.minimum(lo, cell[patch].min(axis=0)).tolist()
            hi = np.maximum(hi, cell[patch].max(axis=0)).tolist()

    def seed_pieces(groups: list[list[int]]) -> None:
        """New pieces from the free patches left, each from the largest one left."""
        for start in sorted(range(len(patches)), key=lambda t: (t >= len(seed_first) or not seed_first[t],
                                                                -patches[t].size, int(patches[t][0]))):
            if not free[start]:
                continue
            free[start] = False
            placed[patches[start]] = True
            cell[patches[start]] = pcell[patches[start]]
            rot[patches[start]] = prot[patches[start]]
            in_patch[patches[start]] = True
            _lay_flat(sg, int(patches[start][0]), in_patch, cell, rot, par, laid=True)
            in_patch[patches[start]] = False
            members = list(patches[start].tolist())
            grow(members, share * box[0] * box[1])
            groups.append(members)

    groups: list[list[int]] = []
    seed_pieces(groups)
    # Pieces under the size rule go back to single faces, which the other pieces (the smallest
    # first) take where they have room; what is left starts new pieces.
    least = MIN_SHARE * max(len(m) for m in groups)
    small = [m for m in groups if len(m) < least]
    if small:
        groups = [m for m in groups if len(m) >= least]
        for f in sorted(f for m in small for f in m):
            patch_of[f] = len(patches)
            patches.append(np.array([f], dtype=np.int64))
            free.append(True)
            pcell[f] = (0, 0)
            prot[f] = 0
            placed[f] = False
        blocked = {e for e in blocked if placed[e[0]]}
        for m in sorted(groups, key=lambda m: (len(m), m[0])):
            grow(m, math.inf)
        seed_pieces(groups)
    groups = _absorb(sg, groups, cell, rot, par, box, blocked)
    # With ``apart``, each board is a cell wider all round than the box: no wall then stands beside a
    # face, and the board counts the seams without tab room as the net does (none), so the tab-room
    # repair leaves the piece as it is.
    on = dataclasses.replace(job, fit=(box[0] + 2, box[1] + 2)) if apart else job
    return [board_of(on, np.array(sorted(m), dtype=np.int64), cell, rot, par, [job.seed, 6000 + t])
            for t, m in enumerate(groups)]


def _absorb(sg: SurfaceGraph, groups: list[list[int]], cell: npt.NDArray[np.int64], rot: npt.NDArray[np.int64],
            par: npt.NDArray[np.int64], box: tuple[int, int], blocked: set[tuple[int, int]]) -> list[list[int]]:
    """Join each piece, the smallest first, rigidly to a neighbouring piece while one takes it.

    The same rule as for patches: the union fits the box and lays no face
    beside another across an edge they do not share.  The joined piece keeps
    its layout turned and moved; its fold tree is re-rooted at the shared edge.
    """
    owner = np.full(sg.face_count, -1, dtype=np.int64)
    for t, m in enumerate(groups):
        owner[m] = t
    nb, ne = sg.neighbor, sg.neighbor_edge
    nbl, nel = nb.tolist(), ne.tolist()
    everywhere = np.ones(sg.face_count, dtype=bool)
    alive = [True] * len(groups)
    changed = True
    while changed:
        changed = False
        for q in sorted((t for t in range(len(groups)) if alive[t]), key=lambda t: (len(groups[t]), groups[t][0])):
            small = np.array(groups[q], dtype=np.int64)
            pcell, prot = cell.copy(), rot.copy()
            turns: dict[int, tuple] = {}  # the small piece's layout turned, by quarter turns
            near = owner[nb[small].ravel()]
            counts = np.bincount(near[(near >= 0) & (near != q)], minlength=len(groups))
            for r in sorted(np.flatnonzero(counts).tolist(), key=lambda r: (-counts[r], r)):
                big = groups[r]
                occ = {(int(cell[f, 0]), int(cell[f, 1])): f for f in big}
                lo, hi = tuple(cell[big].min(axis=0).tolist()), tuple(cell[big].max(axis=0).tolist())
                tried: set[tuple[int, int, int]] = set()
                done = None
                for a in big:
                    for k in range(4):
                        c = int(nb[a, k])
                        if owner[c] != q:
                            continue
                        s = (k + int(rot[a])) % 4
                        qq = ((s + 2 - int(ne[a, k])) - int(prot[c])) % 4
                        vx, vy = int(pcell[c, 0]), int(pcell[c, 1])
                        for _ in range(qq):
                            vx, vy = -vy, vx
                        off = (int(cell[a, 0]) + _STEP[s][0] - vx, int(cell[a, 1]) + _STEP[s][1] - vy)
                        if (qq,) + off in tried:
                            continue
                        tried.add((qq,) + off)
                        if qq not in turns:
                            turns[qq] = _turned(small, pcell, prot, qq)
                        found = _place_patch(nbl, nel, turns[qq], off, occ, rot, lo, hi, box, blocked, everywhere,
                                             everywhere)
                        if found is not None and _blocks_ok(found[2], sg):
                            done = (qq, off, a, c)
                            blocked.update(found[2])
                            break
                    if done is not None:
                        break
                if done is None:
                    continue
                qq, off, a, c = done
                v = pcell[small]
                for _ in range(qq):
                    v = np.stack([-v[:, 1], v[:, 0]], axis=1)
                cell[small] = v + off
                rot[small] = (prot[small] + qq) % 4
                node, above = c, a  # re-root the small piece's tree at c, then hang c from a
                while node >= 0:
                    nxt = int(par[node])
                    par[node] = above
                    above, node = node, nxt
                groups[r] = big + groups[q]
                owner[small] = r
                alive[q] = False
                changed = True
                break
            if changed:
                break
    return [m for t, m in enumerate(groups) if alive[t]]


def _turned(patch: npt.NDArray[np.int64], pcell: npt.NDArray[np.int64], prot: npt.NDArray[np.int64],
            q: int) -> tuple[list[int], list[tuple[int, int]], list[int], tuple[int, int], tuple[int, int]]:
    """A patch laid out at ``pcell``, ``prot`` turned ``q`` quarter turns: its faces, cells, rotations and bounding box."""
    v = pcell[patch]
    for _ in range(q):
        v = np.stack([-v[:, 1], v[:, 0]], axis=1)
    lo, hi = v.min(axis=0).tolist(), v.max(axis=0).tolist()
    return (patch.tolist(), [(x, y) for x, y in v.tolist()], ((prot[patch] + q) % 4).tolist(), (lo[0], lo[1]),
            (hi[0], hi[1]))


def _place_patch(nb: list[list[int]], ne: list[list[int]], turned: tuple, offset: tuple[int, int], occ: dict,
                 rot: npt.NDArray[np.int64], lo: tuple[int, int], hi: tuple[int, int], box: tuple[int, int],
                 blocked: set[tuple[int, int]], placed: npt.NDArray[np.bool_], loose: npt.NDArray[np.bool_]
                 ) -> tuple[int, int, list] | None:
    """A patch turned (:func:`_turned`) and moved by ``offset`` beside a piece: how well it sits.

    Returns the edges it shares with the piece in the plane, the piece's
    bounding box area after, and the edges it blocks (a face beside another
    across an edge they do not share: no tab there); None when it overlaps,
    leaves the box, or blocks an edge whose seam is blocked on its other side
    already, which would leave that seam no room for a tab.  ``nb`` and ``ne``
    are the surface graph's neighbours and their edges, as lists.
    """
    faces, cells, rots, vlo, vhi = turned
    ox, oy = offset
    w = max(hi[0], vhi[0] + ox) - min(lo[0], vlo[0] + ox) + 1
    h = max(hi[1], vhi[1] + oy) - min(lo[1], vlo[1] + oy) + 1
    if not ((w <= box[0] and h <= box[1]) or (w <= box[1] and h <= box[0])):
        return None
    joined = 0
    new: list[tuple[int, int]] = []
    for g, (x, y), rg in zip(faces, cells, rots):
        x += ox
        y += oy
        if (x, y) in occ:
            return None
        for s in range(4):
            h_ = occ.get((x + _STEP[s][0], y + _STEP[s][1]))
            if h_ is None:
                continue
            kg = (s - rg) % 4
            if nb[g][kg] == h_ and (ne[g][kg] + int(rot[h_])) % 4 == (s + 2) % 4:
                joined += 1
                continue
            kh = (s + 2 - int(rot[h_])) % 4
            for e in ((g, kg), (h_, kh)):
                partner = (nb[e[0]][e[1]], ne[e[0]][e[1]])
                # The seam's other side must be laid already (its cell beyond stays free), so no face
                # left to place loses the edge it could hang from (a loose face has other ways to go).
                if partner in blocked or partner in new or not (placed[partner[0]] or loose[partner[0]]):
                    return None
                new.append(e)
    return joined, w * h, new


def _blocks_ok(new: list[tuple[int, int]], sg: SurfaceGraph) -> bool:
    """No seam blocked on both sides within one placement."""
    mine = set(new)
    return not any((int(sg.neighbor[f, k]), int(sg.neighbor_edge[f, k])) in mine for f, k in new)
