"""pieces="auto": one surface part cut into pieces that each fit the sheet's box.

Two ways to cut compete: slabs across an axis (straight cuts along layers,
:func:`_sheet_pieces`) and branches of one free net (:func:`_tree_pieces`);
small pieces are then joined to neighbours (:func:`_merge_small`) and the size
rule (none under a tenth of the largest) is kept by moving branches
(:func:`_balance`).  Pieces from flat patches (pieces="flat") are
:mod:`._patches`'.
"""

from __future__ import annotations

import math
import time

import numpy as np
import numpy.typing as npt

from voxfab.errors import UnfoldError
from voxfab.shape import SurfaceGraph

from ._bands import band_cuts
from ._job import FIT_STEPS_PER_FACE, MIN_SHARE, Job, Strategy, growth_settings, orientations, surface_parts
from ._net import Net
from ._onepiece import one_piece
from ._patches import patch_pieces
from ._searchboard import SearchBoard, board_of

#: pieces="auto": branches of a neighbour a too-small piece may try to take.
_BRANCH_TRIES = 24
#: pieces="auto": pairs of neighbouring pieces tried for a join (once the
#: size rule holds).
_JOIN_TRIES = 24
#: pieces="auto" in a box: faces of a piece as a share of the box's cells.  The
#: cells left free take the glue tabs (up to four each, one from every side),
#: so a denser piece leaves seams without room.
_PIECE_SHARE = 0.5
#: pieces="auto" in a box: the largest share of the box a piece of a free net's branches fills
#: after the joins (measured on the bundled shapes at 8.6 mm on A3 to A5: at most 0.58); a split that would need denser
#: pieces to beat the slabs is not tried.
_BRANCH_FILL = 0.65
#: Tries (each a fixed budget of growth steps) to lay one piece in its box
#: before it is cut in two.
_PIECE_TRIES = 3


def split(job: Job, faces: npt.NDArray[np.int64]) -> list[Net]:
    """One surface part as few pieces as the budget allows."""
    if job.fit is None or job.fit[0] * job.fit[1] >= faces.size:  # else one piece cannot fit
        try:
            return [one_piece(job, faces)]
        except UnfoldError:
            pass
    boards = _partition(job, faces)
    nets = []
    for b, placed in boards:
        b.exclude_unplaced()
        if job.tab_aware and job.strategy is Strategy.DEFAULT:
            if job.bands:
                # A piece of bands laid rigidly keeps room for every tab, though the board counts a seam
                # to another piece as without room: only pieces that lack room in the net are repaired.
                net = b.net(job, placed)
                if net.seams_without_tab_room == 0:
                    nets.append(net)
                    continue
            b.anneal(job.growth(placed.size), job.deadline)
        nets.append(b.net(job, placed))
    return nets


def _partition(job: Job, faces: npt.NDArray[np.int64]) -> list[tuple[SearchBoard, npt.NDArray[np.int64]]]:
    """Cut the faces into pieces that each fit the box, then join pieces while they fit.

    Without constraints the pieces are branches of one free net, each cut off
    where its layout stops fitting the box: every piece is a connected net
    from the start, with no stray faces left over.  With constraints (a kept
    group must not be cut) each piece is instead the largest net that
    ruin-and-recreate packs into the box from the faces left over.
    """
    if job.constraints is None and job.fit is not None and job.bands:
        cuts = band_cuts(job, faces)
        for cut in cuts:
            try:
                return _balance(job, list(cut))
            except UnfoldError:
                pass  # this cut breaks the size rule: the next
        try:
            # No cut keeps the size rule as it is: the small pieces of the one with fewest seams joined to neighbours.
            return _balance(job, _merge_small(job, list(cuts[0]), mend_only=True))
        except UnfoldError:
            pass  # cut from flat patches instead
    if job.constraints is None and job.fit is not None and (job.flat or job.bands):
        patches = patch_pieces(job, faces)
        try:
            return _balance(job, list(patches))
        except UnfoldError:
            pass
        try:
            # Branches did not mend the size rule: join the small pieces to neighbours first.
            return _balance(job, _merge_small(job, patch_pieces(job, faces), mend_only=True))
        except UnfoldError:
            pass  # no split from patches keeps the size rule: cut as "auto" does
    if job.constraints is None and job.fit is not None:
        # Two ways to cut, the fewer pieces kept: slabs give straight cuts and
        # room for tabs; branches of a free net suit boxes too small for a slab.
        slabs = _sheet_pieces(job, faces)
        w, h = job.fit
        # Branches win only with fewer pieces than the slabs, so their largest piece would hold at
        # least faces / (slabs - 1) of the box's cells: past _BRANCH_FILL of the box (denser than any
        # branch piece measured) they cannot win, and their joins (most of the cut's time) are skipped.
        if faces.size > _BRANCH_FILL * (len(slabs) - 1) * w * h:
            return _balance(job, slabs)
        branches = _tree_pieces(job, faces)
        if branches is not None:
            branches = _merge_small(job, branches)
            if len(branches) < len(slabs):
                return _balance(job, branches)
        return _balance(job, slabs)
    return _balance(job, _merge_small(job, _greedy_pieces(job, faces)))


def _fold_tree(faces: npt.NDArray[np.int64], par: npt.NDArray[np.int64]) -> tuple[int, dict[int, list[int]], list[int]]:
    """The root, the children of each face and a breadth-first walk (every face after its parent) of a net's folds."""
    children: dict[int, list[int]] = {}
    root = -1
    for f in faces.tolist():
        p = int(par[f])
        if p >= 0:
            children.setdefault(p, []).append(f)
        else:
            root = f
    walk = [root]
    for f in walk:
        walk.extend(children.get(f, ()))
    return root, children, walk


def _tree_pieces(job: Job, faces: npt.NDArray[np.int64]) -> list | None:
    """Branches of a free net that fit the box, bottom up; None when no free net grows."""
    n = int(faces.size)
    free = SearchBoard(job.sg, faces, [job.seed, 1999], None, None, n)
    if not free.grow(job.growth(n), math.inf, FIT_STEPS_PER_FACE * n):
        return None
    w_box, h_box = job.fit
    x, y = free.pos % free.width, free.pos // free.width

    def fits(b: tuple[int, int, int, int]) -> bool:
        w, h = b[1] - b[0] + 1, b[3] - b[2] + 1
        return (w <= w_box and h <= h_box) or (w <= h_box and h <= w_box)

    root, children, walk = _fold_tree(faces, free.par)
    box: dict[int, tuple[int, int, int, int]] = {}
    members: dict[int, list[int]] = {}
    cut: list[list[int]] = []
    for f in reversed(walk):
        b = (int(x[f]), int(x[f]), int(y[f]), int(y[f]))
        mem = [f]
        # The smallest branches join first, so that fewer faces are cut off.
        for c in sorted(children.get(f, ()), key=lambda c: (len(members[c]), c)):
            cb = box.pop(c)
            joined = (min(b[0], cb[0]), max(b[1], cb[1]), min(b[2], cb[2]), max(b[3], cb[3]))
            if fits(joined):
                b = joined
                mem += members.pop(c)
            else:
                cut.append(members.pop(c))
        box[f], members[f] = b, mem
    cut.append(members[root])
    return [_laid_out(job, free, np.array(sorted(m), dtype=np.int64), t) for t, m in enumerate(cut)]


def _laid_out(job: Job, free: SearchBoard, piece: npt.NDArray[np.int64], t: int) -> tuple[SearchBoard, npt.NDArray[np.int64]]:
    """A board in the box holding ``piece`` as laid out on the free board ``free``."""
    cells = np.stack([free.pos % free.width, free.pos // free.width], axis=1)
    return board_of(job, piece, cells, free.rot, free.par, [job.seed, 2000 + t])


def _layout(b: SearchBoard) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    return np.stack([b.pos % b.width, b.pos // b.width], axis=1), b.rot.copy(), b.par.copy()


def _join_layouts(job: Job, q: tuple, r: tuple, seed: list[int]) -> tuple | None:
    """Pieces q and r as one, r turned and moved rigidly to fold onto q along a shared edge.

    No face is regrown: both keep their layouts, so the join works even when
    each fills most of the box.  None when no shared edge gives a layout
    without overlap inside the box.
    """
    sg = job.sg
    (bq, fq), (br, fr) = q, r
    cq, rq, pq = _layout(bq)
    cr, rr, pr = _layout(br)
    taken = {tuple(c) for c in cq[fq].tolist()}
    in_r = np.zeros(sg.face_count, dtype=bool)
    in_r[fr] = True
    step = np.array([[0, -1], [1, 0], [0, 1], [-1, 0]], dtype=np.int64)
    for a in fq.tolist():
        for k in range(4):
            c = int(sg.neighbor[a, k])
            if not in_r[c]:
                continue
            s_ = (k + int(rq[a])) % 4
            target = cq[a] + step[s_]
            if tuple(target.tolist()) in taken:
                continue
            turns = ((s_ + 2 - int(sg.neighbor_edge[a, k])) - int(rr[c])) % 4
            v = cr[fr] - cr[c]
            for _ in range(turns):  # a quarter turn counter-clockwise: (x, y) -> (-y, x)
                v = np.stack([-v[:, 1], v[:, 0]], axis=1)
            moved = v + target
            lo = np.minimum(moved.min(axis=0), cq[fq].min(axis=0))
            side = np.maximum(moved.max(axis=0), cq[fq].max(axis=0)) - lo + 1
            if job.fit is not None and not ((side[0] <= job.fit[0] and side[1] <= job.fit[1]) or (side[0] <= job.fit[1] and side[1] <= job.fit[0])):
                continue
            if any(tuple(m) in taken for m in moved.tolist()):
                continue
            cells, rot, par = cq.copy(), rq.copy(), pq.copy()
            cells[fr] = moved
            rot[fr] = (rr[fr] + turns) % 4
            par[fr] = pr[fr]
            # Re-root r's tree at c, then hang c from a.
            node, above = c, a
            while node >= 0:
                nxt = int(par[node])
                par[node] = above
                above, node = node, nxt
            both = np.sort(np.concatenate([fq, fr]))
            return board_of(job, both, cells, rot, par, seed)
    return None


def _greedy_pieces(job: Job, faces: npt.NDArray[np.int64]) -> list[tuple[SearchBoard, npt.NDArray[np.int64]]]:
    """Pieces grown one by one into the box from the faces left over, the largest first."""
    n = int(faces.size)
    p = job.growth(n)
    pieces: list[tuple[SearchBoard, npt.NDArray[np.int64]]] = []
    left = np.zeros(job.sg.face_count, dtype=bool)
    left[faces] = True
    t = 0
    while left.any():
        for part in surface_parts(job.sg, np.flatnonzero(left)):
            t += 1
            b = SearchBoard(job.sg, part, [job.seed, 2000 + t], job.fit, job.resolved(part), n)
            if b.started:
                b.grow(p, math.inf, _steps_left(job, part.size))
            placed = part[b.pos[part] >= 0]
            if placed.size == 0:
                raise UnfoldError(
                    f"no piece fits {job.fit[0]}x{job.fit[1]} cells: the box is too small for the "
                    "faces kept together, or for a single face")
            pieces.append((b, placed))
            left[placed] = False
    return pieces


def _steps_left(job: Job, faces: int) -> int:
    # Growth steps for one piece: a full budget while the clock allows, and a
    # short greedy one after it, so that pieces="auto" always returns pieces.
    return (FIT_STEPS_PER_FACE if time.monotonic() < job.deadline else 4) * int(faces)


def _merge_small(job: Job, pieces: list, mend_only: bool = False) -> list:
    """Join neighbouring pieces, the smallest first, while their union grows inside the box.

    A join is tried only when no piece would end under a tenth of the
    largest, or when it swallows a piece that breaks that rule; with
    ``mend_only``, only while some piece breaks it.
    """
    sg = job.sg
    area = math.inf if job.fit is None else job.fit[0] * job.fit[1]
    tried: set[tuple[int, int]] = set()
    while True:
        pieces.sort(key=lambda bp: (bp[1].size, int(bp[1][0])))
        owner = np.full(sg.face_count, -1, dtype=np.int64)
        for q, (_, placed) in enumerate(pieces):
            owner[placed] = q
        sizes = [int(bp[1].size) for bp in pieces]
        # Joins for fewer pieces stop with the clock or the tries; joins that
        # mend the size rule go on while a pair is left to try.
        if not _too_small(sizes) and (mend_only or time.monotonic() > job.deadline or len(tried) >= _JOIN_TRIES):
            break
        joined = False
        for q in range(len(pieces)):
            near = owner[sg.neighbor[pieces[q][1]].ravel()]
            for r in sorted(set(near[(near >= 0) & (near != q)].tolist())):
                key = (int(pieces[q][1][0]), int(pieces[r][1][0]))
                if key in tried or sizes[q] + sizes[r] > area:
                    continue
                rest = [z for t, z in enumerate(sizes) if t not in (q, r)] + [sizes[q] + sizes[r]]
                mends = _too_small(sizes) and sizes[q] < MIN_SHARE * max(sizes)  # q breaks the rule
                if _too_small(rest) and not mends:
                    continue
                tried.add(key)
                both = np.sort(np.concatenate([pieces[q][1], pieces[r][1]]))
                box = None if job.fit is None else orientations(job.fit)[len(tried) % len(orientations(job.fit))]
                seed = [job.seed, 3000 + len(tried)]
                joinable = job.constraints is None
                one = _join_layouts(job, pieces[q], pieces[r], seed) if joinable else None
                if one is None:
                    b = SearchBoard(sg, both, seed, box, job.resolved(both), sg.face_count)
                    # Past the clock a join still gets a full budget while the split breaks the rule.
                    steps = FIT_STEPS_PER_FACE * int(both.size) if _too_small(sizes) else _steps_left(job, both.size)
                    if b.started and b.grow(growth_settings(Strategy.DEFAULT, both.size), math.inf, steps):
                        one = (b, both)
                if one is not None:
                    pieces = [bp for t, bp in enumerate(pieces) if t not in (q, r)] + [one]
                    joined = True
                    break
            if joined:
                break
        if not joined:
            break
    return pieces


def _too_small(sizes: list[int]) -> bool:
    return min(sizes) < MIN_SHARE * max(sizes)


def _balance(job: Job, pieces: list) -> list:
    """Guarantee the size rule: no piece under a tenth of the largest.

    A piece still too small after merging (its neighbours fill their boxes)
    takes a branch of a neighbour's fold tree: the neighbour keeps its layout
    minus the branch (still a net, still inside the box), and the small piece
    is grown anew with the branch's faces.  UnfoldError when no branch works.
    """
    for _ in range(2 * len(pieces) + 8):
        pieces.sort(key=lambda bp: -bp[1].size)
        sizes = [int(bp[1].size) for bp in pieces]
        if not _too_small(sizes):
            return pieces
        if not _take_branch(job, pieces, len(pieces) - 1):
            break
    sizes = sorted((int(bp[1].size) for bp in pieces), reverse=True)
    where = "" if job.fit is None else f" that fit {job.fit[0]}x{job.fit[1]} cells"
    raise UnfoldError(
        f"could not split the {sum(sizes)}-face surface into pieces{where} "
        f"with none under a tenth of the largest (sizes "
        f"{sizes[:3]} ... {sizes[-3:]}); use a larger sheet or smaller faces")


def _take_branch(job: Job, pieces: list, q: int) -> bool:
    """Grow piece ``q`` with a branch of a neighbouring piece; False when none fits."""
    sg = job.sg
    small = pieces[q][1]
    large = max(int(bp[1].size) for bp in pieces)
    floor = math.ceil(MIN_SHARE * large)  # every piece must keep at least this many faces
    owner = np.full(sg.face_count, -1, dtype=np.int64)
    for r, (_, placed) in enumerate(pieces):
        owner[placed] = r
    near = owner[sg.neighbor[small].ravel()]
    tries = 0
    for r in sorted(set(near[(near >= 0) & (near != q)].tolist()), key=lambda r: (-pieces[r][1].size, r)):
        b, placed = pieces[r]
        for u, branch in _branches(b, placed, small, floor - small.size, placed.size - floor):
            both = np.sort(np.concatenate([small, branch]))
            tries += 1
            trial = SearchBoard(sg, both, [job.seed, 4000 + tries], job.fit, job.resolved(both), sg.face_count)
            if trial.started and trial.grow(growth_settings(Strategy.DEFAULT, both.size), math.inf,
                                            FIT_STEPS_PER_FACE * int(both.size)):
                b.k.remove_subtree(*b.sf, *b.b[:4], u)
                pieces[r] = (b, np.setdiff1d(placed, branch))
                pieces[q] = (trial, both)
                return True
            if tries >= _BRANCH_TRIES:
                return False
    return False


def _branches(b: SearchBoard, placed: npt.NDArray[np.int64], small: npt.NDArray[np.int64], least: int,
              most: int):
    """Branches of board ``b``'s fold tree of ``least`` to ``most`` faces that touch ``small``.

    Yields (the branch's top face, its faces), smallest first: the neighbour
    then loses as little as it can.  A branch never starts inside a kept group.
    """
    nf = b.sf.link.shape[0]
    par = b.par
    size = np.zeros(nf, dtype=np.int64)
    touch = np.zeros(nf, dtype=bool)  # the branch holds a neighbour of the small piece
    near_small = np.zeros(nf, dtype=bool)
    near_small[b.sf.link[small, b.k.NB].ravel()] = True
    root, children, walk = _fold_tree(placed, par)
    for f in reversed(walk):
        size[f] += 1
        touch[f] |= near_small[f]
        p = int(par[f])
        if p >= 0:
            size[p] += size[f]
            touch[p] |= touch[f]
    cands = [f for f in walk if f != root and least <= size[f] <= most and touch[f]
             and int(b.k.entry(b.sf.link, b.b.face, b.cnt, f)) == f]
    cands.sort(key=lambda f: (int(size[f]), f))
    for u in cands:
        branch = []
        stack = [u]
        while stack:
            f = stack.pop()
            branch.append(f)
            stack.extend(children.get(f, ()))
        yield u, np.array(sorted(branch), dtype=np.int64)


def _sweep_regions(sg: SurfaceGraph, faces: npt.NDArray[np.int64], k: int) -> list[npt.NDArray[np.int64]]:
    """``faces`` cut into about ``k`` slabs of equal size across one axis, each slab's connected parts apart.

    Slabs end between two layers of face centres, so each cut runs along a
    straight line of voxel edges round the shape; of the three axes the one
    whose cuts are shortest (fewest seams between slabs) wins.
    """
    centre = sg.corners[faces].mean(axis=1)
    best: tuple[int, list[npt.NDArray[np.int64]]] | None = None
    for axis in range(3):
        # Face centres lie on half-integer layers: doubled, they are integers.
        level = np.rint(2 * centre[:, axis]).astype(np.int64)
        levels, counts = np.unique(level, return_counts=True)
        cum = np.cumsum(counts)
        cuts = [int(levels[np.argmin(np.abs(cum - faces.size * t / k))]) for t in range(1, k)]
        slab = np.searchsorted(np.array(sorted(set(cuts)), dtype=np.int64), level, side="left")
        if k > 1 and slab.max() == slab.min():
            continue  # the faces lie in one layer across this axis
        owner = np.full(sg.face_count, -1, dtype=np.int64)
        owner[faces] = slab
        nb = owner[sg.neighbor[faces]]
        seams = int(np.count_nonzero((nb >= 0) & (nb != slab[:, None])))
        if best is None or seams < best[0]:
            parts = [p for s in np.unique(slab).tolist() for p in surface_parts(sg, faces[slab == s])]
            best = (seams, parts)
    if best is None:
        return surface_parts(sg, faces)
    return best[1]


def _merge_parts(sg: SurfaceGraph, parts: list[npt.NDArray[np.int64]], least: int) -> list[npt.NDArray[np.int64]]:
    """Parts under ``least`` faces joined to the neighbouring part they share most edges with."""
    parts = [p for p in parts if p.size]
    while len(parts) > 1:
        sizes = [int(p.size) for p in parts]
        q = int(np.argmin(sizes))
        if sizes[q] >= least:
            break
        owner = np.full(sg.face_count, -1, dtype=np.int64)
        for t, p in enumerate(parts):
            owner[p] = t
        near = owner[sg.neighbor[parts[q]].ravel()]
        near = near[(near >= 0) & (near != q)]
        if near.size == 0:
            break  # a separate surface: it stays a piece of its own
        r = int(np.bincount(near).argmax())
        joined = np.sort(np.concatenate([parts[q], parts[r]]))
        parts = [p for t, p in enumerate(parts) if t not in (q, r)] + [joined]
    return parts


def _lay_in_box(job: Job, faces: npt.NDArray[np.int64], tries: int) -> SearchBoard | None:
    """A net of ``faces`` grown inside the fit box (either way round), or None within ``tries`` tries."""
    n = int(faces.size)
    p = job.growth(n)
    boxes = orientations(job.fit)
    for t in range(tries):
        trial = SearchBoard(job.sg, faces, [job.seed, 5000 + n, t], boxes[t % len(boxes)], None, job.sg.face_count)
        if trial.grow(p, math.inf, FIT_STEPS_PER_FACE * n):
            return trial
    return None


def _sheet_pieces(job: Job, faces: npt.NDArray[np.int64]) -> list[tuple[SearchBoard, npt.NDArray[np.int64]]]:
    """Pieces of about :data:`_PIECE_SHARE` of the box each, cut along straight runs of seams.

    The surface is cut into slabs across its best axis (:func:`_sweep_regions`),
    each slab's parts apart and the tiny ones joined to a neighbour; a part
    that does not grow inside the box is cut in two the same way.  Every piece
    is laid in the box from the start, with room left round it for its tabs.
    """
    w, h = job.fit
    target = max(_PIECE_SHARE * w * h, 1.0)
    least = max(1, int(MIN_SHARE * target))
    k = max(1, math.ceil(faces.size / target))
    queue = _merge_parts(job.sg, _sweep_regions(job.sg, faces, k), least)
    pieces: list[tuple[SearchBoard, npt.NDArray[np.int64]]] = []
    while queue:
        part = queue.pop(0)
        board = _lay_in_box(job, part, _PIECE_TRIES) if part.size <= w * h else None
        if board is not None:
            pieces.append((board, part))
            continue
        if part.size == 1:
            raise UnfoldError(f"no piece fits {w}x{h} cells: the box is too small for a single face")
        halves = _merge_parts(job.sg, _sweep_regions(job.sg, part, 2), max(1, part.size // 10))
        if len(halves) < 2 or min(int(p.size) for p in halves) * 4 < part.size:
            # A ring, or a cut that would shave a sliver: halve the walk instead.
            halves = _split_in_two(job.sg, part)
        queue[:0] = halves
    return pieces


def _split_in_two(sg: SurfaceGraph, faces: npt.NDArray[np.int64]) -> list[npt.NDArray[np.int64]]:
    """``faces`` (connected, in one layer) as the first and second half of a breadth-first walk."""
    inside = np.zeros(sg.face_count, dtype=bool)
    inside[faces] = True
    seen = {int(faces[0])}
    walk = [int(faces[0])]
    for f in walk:
        for g in sg.neighbor[f].tolist():
            if inside[g] and g not in seen:
                seen.add(g)
                walk.append(g)
    half = len(walk) // 2
    first = np.sort(np.array(walk[:half], dtype=np.int64))
    return [first] + surface_parts(sg, np.setdiff1d(faces, first))
