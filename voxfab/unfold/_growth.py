"""Ruin-and-recreate growth of a net on the board (compiled).

A step places one face, or repairs a dead end.  ``MODE_RUIN`` removes the
subtree on the blocking cell of a random blocked attachment (the smallest of a
few samples) and lays the blocked face there, never restarting.  ``MODE_PAPER``
is the published method: swap out a blocking leaf when it can, else drop the
smallest blocking subtree, and restart after too many repairs without progress.

Kernels take the surface arrays ``link, gmem`` and the board arrays ``face,
half, board, cnt`` (see :mod:`voxfab.unfold._board`).
"""

from __future__ import annotations

from voxfab.unfold._params import MODE_PAPER, MODE_RUIN

from ._board import (
    BLK,
    C_BEST,
    C_CONSTRAINED,
    C_DEADENDS,
    C_NCAND,
    C_NFREE,
    C_OFF,
    C_RESTARTS,
    C_ROOT,
    C_STEPS,
    C_UNPLACED,
    C_WIDTH,
    CL,
    CP,
    EDGE,
    G_ID,
    GRP,
    NB,
    NE,
    OPT,
    PAR,
    POS,
    ROT,
    entry,
    fits,
    forced,
    in_subtree,
    member_cell,
    place_group,
    place_via,
    randint,
    random,
    refresh,
    remove_subtree,
    subtree_size,
    update,
)
from ._constraints import CUT
from ._jit import inline, njit

#: Random roots tried before a start gives up (a kept group may not fit a small box).
_ROOT_TRIES = 64
#: Largest blocking subtree a repair weighs; past it any usable option will do.
_CAP = 128


@njit(cache=True)
def start(link, gmem, face, half, board, cnt, root_cells):
    """Empty the board and put a random root face on a random allowed cell.

    Returns the root, or -1 when no try fits (a kept group larger than the box).
    """
    f = face.shape[0]
    free = 0
    for j in range(f):
        if face[j, POS] == -3:
            continue
        if face[j, POS] >= 0:
            board[face[j, POS]] = -1
        face[j, POS] = -1
        face[j, PAR] = -2
        half[4 * f + free, CL] = j
        half[4 * f + j, CP] = free
        free += 1
    for t in range(cnt[C_NCAND]):
        half[half[t, CL], CP] = -1
    cnt[C_NCAND] = 0
    cnt[C_UNPLACED] = free
    cnt[C_NFREE] = free
    for _ in range(_ROOT_TRIES):
        root = half[4 * f + randint(cnt, free), CL]
        c = root_cells[randint(cnt, root_cells.shape[0])]
        r = randint(cnt, 4)
        if fits(link, gmem, face, board, cnt, root, c, r):
            cnt[C_ROOT] = root
            place_group(link, gmem, face, half, board, cnt, root, c, r, -1)
            return root
    return -1


@njit(cache=True)
def _pick(face, half, board, cnt, tour, sparse):
    # Tournament among ``tour`` random candidates: the farthest from the root
    # stretches the net; with ``sparse``, the one touching the fewest placed faces
    # keeps cells free beside future seams for glue tabs.
    n = cnt[C_NCAND]
    best = half[randint(cnt, n), CL]
    if tour <= 1:
        return best
    width = cnt[C_WIDTH]
    rootcell = face[cnt[C_ROOT], POS]
    rx = rootcell % width
    ry = rootcell // width
    bd = -(1 << 40)
    for _ in range(tour):
        h = half[randint(cnt, n), CL]
        i = h >> 2
        c = face[i, POS] + cnt[C_OFF + (((h & 3) + face[i, ROT]) & 3)]
        if sparse:
            d = 0
            for s in range(4):
                if board[c + cnt[C_OFF + s]] != -1:
                    d -= 1
        else:
            d = abs(c % width - rx) + abs(c // width - ry)
        if d > bd:
            bd = d
            best = h
    return best


@njit(cache=True)
def _blocked_options(link, face, half, board, cnt):
    # Half-edges h = 4i+k (i placed, its neighbour unplaced, edge not cut) that
    # cannot lay their face: without constraints, those whose cell holds a face
    # other than the root.
    n = 0
    f4 = 4 * face.shape[0]
    constrained = cnt[C_CONSTRAINED]
    root = cnt[C_ROOT]
    for t in range(cnt[C_NFREE]):
        j = half[f4 + t, CL]
        for k in range(4):
            i = link[j, NB, k]
            if face[i, POS] < 0:
                continue
            ki = link[j, NE, k]
            if constrained:
                if link[i, EDGE, ki] != CUT:
                    half[n, OPT] = 4 * i + ki
                    n += 1
                continue
            m = board[face[i, POS] + cnt[C_OFF + ((ki + face[i, ROT]) & 3)]]
            if m >= 0 and m != root:
                half[n, OPT] = 4 * i + ki
                n += 1
    return n


@inline
def blocker(face, board, cnt, h):
    """The face on the cell that option ``h`` would take."""
    i = h >> 2
    return board[face[i, POS] + cnt[C_OFF + (((h & 3) + face[i, ROT]) & 3)]]


@njit(cache=True)
def _smallest_blocking(link, face, half, board, cnt, n, tries, sampled):
    # The option among ``tries`` (random ones when ``sampled``, else the first)
    # whose blocking subtree is smallest, at most _CAP faces and not above the
    # option's own face; -1 if none.
    chosen = -1
    best_size = _CAP + 1
    for t in range(tries):
        h = half[randint(cnt, n), OPT] if sampled else half[t, OPT]
        size = subtree_size(link, face, half, blocker(face, board, cnt, h), h >> 2, best_size - 1)
        if size < best_size:
            best_size = size
            chosen = h
    return chosen


@njit(cache=True)
def _ruin_choice(link, face, half, board, cnt, n, samples, fallback):
    chosen = _smallest_blocking(link, face, half, board, cnt, n, min(n, samples), True)
    if chosen < 0 and fallback:
        # Every sample was too large or hung under its own blocker: take the
        # first usable option.
        t0 = randint(cnt, n)
        for t in range(n):
            h = half[(t0 + t) % n, OPT]
            if not in_subtree(face, h >> 2, blocker(face, board, cnt, h)):
                return h
    return chosen


@njit(cache=True)
def _paper_choice(link, face, half, board, cnt, n):
    # Leaf swap first (a random blocking leaf), else the smallest subtree.
    leaves = 0
    for t in range(n):
        h = half[t, OPT]
        m = blocker(face, board, cnt, h)
        if m != h >> 2 and subtree_size(link, face, half, m, -1, 1) == 1:
            half[leaves, OPT], half[t, OPT] = half[t, OPT], half[leaves, OPT]
            leaves += 1
    if leaves > 0:
        return half[randint(cnt, leaves), OPT]
    chosen = _smallest_blocking(link, face, half, board, cnt, n, n, False)
    if chosen < 0:
        return _ruin_choice(link, face, half, board, cnt, n, 0, True)
    return chosen


@njit(cache=True)
def _blockers(link, gmem, face, half, board, cnt, h):
    # The faces in the way of option h, with its kept group, into column BLK:
    # those on the cells it needs (as face ids), and those that would meet it
    # across a cut edge (as ~(4 m + e) for the cut edge e of group member m).
    # Returns their count, or -1 when a cell lies outside the board.
    j, c, r = forced(link, face, cnt, h)
    g = link[j, GRP, G_ID]
    lo, hi = (gmem[0, g], gmem[0, g + 1]) if g >= 0 else (0, 1)
    n = 0
    for t in range(lo, hi):
        m = gmem[1, t] if g >= 0 else j
        cm, rm = member_cell(link, board, cnt, j, c, r, m) if g >= 0 else (c, r)
        if cm < 0 or board[cm] == -2:
            return -1
        if board[cm] >= 0:
            half[n, BLK] = board[cm]
            n += 1
        for e in range(4):
            if link[m, EDGE, e] != CUT:
                continue
            q = link[m, NB, e]
            if face[q, POS] < 0:
                continue
            s = (e + rm) & 3
            if face[q, POS] == cm + cnt[C_OFF + s] and face[q, ROT] == ((s + 2 - link[m, NE, e]) & 3):
                half[n, BLK] = ~(4 * m + e)
                n += 1
    return n


@inline
def _blocker_face(link, code):
    return code if code >= 0 else link[(~code) >> 2, NB, (~code) & 3]


@njit(cache=True)
def _loop_face(link, face, cnt, code, i):
    # A face to remove so that a cut edge stops closing up: q itself, or a face
    # beside the cut edge on q's side (the loop around a flat vertex that lays q
    # against m passes through one of them).  -1 when none can go.
    m = (~code) >> 2
    e = (~code) & 3
    q = link[m, NB, e]
    eq = link[m, NE, e]
    root = cnt[C_ROOT]
    t0 = randint(cnt, 3)
    for t in range(3):
        u = (t0 + t) % 3
        f = q if u == 0 else link[q, NB, (eq + 2 * u - 1) & 3]
        if face[f, POS] < 0:
            continue
        f = entry(link, face, cnt, f)
        if f != root and not in_subtree(face, i, f):
            return f
    return -1


@njit(cache=True)
def _clearing_cost(link, gmem, face, half, board, cnt, h, cap):
    # Faces removed to lay option h (an upper bound: subtrees may overlap), or -1
    # when a blocker is the root or holds h's own face.
    n = _blockers(link, gmem, face, half, board, cnt, h)
    if n < 0:
        return -1
    cost = 0
    for t in range(n):
        m = entry(link, face, cnt, _blocker_face(link, half[t, BLK]))
        if m == cnt[C_ROOT] or in_subtree(face, h >> 2, m):
            return -1
        cost += subtree_size(link, face, half, m, -1, cap)
    return cost


@njit(cache=True)
def _constrained_choice(link, gmem, face, half, board, cnt, n, samples):
    # The cheapest of a few random blocked options (any usable one when none of
    # the samples is); -1 when none is usable.
    chosen = -1
    best = face.shape[0] + 1
    for _ in range(min(n, samples)):
        h = half[randint(cnt, n), OPT]
        cost = _clearing_cost(link, gmem, face, half, board, cnt, h, best)
        if 0 <= cost < best:
            best = cost
            chosen = h
    if chosen < 0:
        t0 = randint(cnt, n)
        for t in range(n):
            h = half[(t0 + t) % n, OPT]
            if _clearing_cost(link, gmem, face, half, board, cnt, h, face.shape[0]) >= 0:
                return h
    return chosen


@njit(cache=True)
def _repair_constrained(link, gmem, face, half, board, cnt, n, samples):
    # Clear the way for a blocked option's kept group (the faces on its cells,
    # and those that would close a cut edge in the plane), then lay it.
    chosen = _constrained_choice(link, gmem, face, half, board, cnt, n, samples)
    if chosen < 0:
        return False
    k = _blockers(link, gmem, face, half, board, cnt, chosen)
    i = chosen >> 2
    root = cnt[C_ROOT]
    for t in range(k):
        code = half[t, BLK]
        m = _blocker_face(link, code)
        if face[m, POS] < 0:  # an earlier removal took it already
            continue
        m = entry(link, face, cnt, m)
        if code < 0:
            m = _loop_face(link, face, cnt, code, i)
            if m < 0:
                continue
        if random(cnt) < 0.5:
            # Ruin further up half the time: a face that would close a cut edge
            # comes back to the same cell by the same path otherwise.
            for _ in range(1 + randint(cnt, 3)):
                p = entry(link, face, cnt, face[m, PAR]) if face[m, PAR] >= 0 else -1
                if p < 0 or p == root or in_subtree(face, i, p):
                    break
                m = p
        remove_subtree(link, gmem, face, half, board, cnt, m)
    j, c, r = forced(link, face, cnt, chosen)
    if fits(link, gmem, face, board, cnt, j, c, r):
        place_via(link, gmem, face, half, board, cnt, chosen)
    return True


@njit(cache=True)
def _repair(link, gmem, face, half, board, cnt, gw, give_up):
    # One dead-end repair; False when the search must restart (or stop) instead.
    n = _blocked_options(link, face, half, board, cnt)
    if give_up or n == 0:
        return False
    if cnt[C_CONSTRAINED]:
        return _repair_constrained(link, gmem, face, half, board, cnt, n, max(gw.samples, 3))
    if gw.mode == MODE_RUIN:
        # Without restarts (a tab-room move), a repair that would ruin a large
        # subtree gives up instead: the move is undone more cheaply.
        chosen = _ruin_choice(link, face, half, board, cnt, n, gw.samples, gw.restart)
    else:
        chosen = _paper_choice(link, face, half, board, cnt, n)
    if chosen < 0:
        return False
    i = chosen >> 2
    m = blocker(face, board, cnt, chosen)
    root = cnt[C_ROOT]
    if gw.mode == MODE_RUIN and gw.restart and random(cnt) < gw.p_lift:
        # Now and then ruin further up the tree, so small swaps cannot cycle.
        lift = 1 + randint(cnt, 3)
        while lift > 0 and face[m, PAR] >= 0 and face[m, PAR] != root and not in_subtree(face, i, face[m, PAR]):
            m = face[m, PAR]
            lift -= 1
    remove_subtree(link, gmem, face, half, board, cnt, m)
    place_via(link, gmem, face, half, board, cnt, chosen)
    return True


@njit(cache=True)
def grow(link, gmem, face, half, board, cnt, root_cells, gw, max_steps, sparse):
    """Grow until every face is placed or ``max_steps`` steps are spent.

    A board whose root is -1 is started first (:func:`start`), so one call
    both starts and grows.  Returns True when the net is complete, False when out of steps, or when a
    dead end found no repair and ``gw.restart`` is off, or a restart found no
    room for a root.
    """
    if cnt[C_ROOT] < 0 and start(link, gmem, face, half, board, cnt, root_cells) < 0:
        return False
    steps = 0
    since_best = 0
    f = face.shape[0]
    constrained = cnt[C_CONSTRAINED]
    while cnt[C_UNPLACED] > 0 and steps < max_steps:
        steps += 1
        cnt[C_STEPS] += 1
        if cnt[C_NCAND] > 0:
            h = _pick(face, half, board, cnt, gw.tour, sparse)
            if constrained:
                j, c, r = forced(link, face, cnt, h)
                if not fits(link, gmem, face, board, cnt, j, c, r):
                    update(link, gmem, face, half, board, cnt, h)  # a kept group's far cell was taken
                    continue
            place_via(link, gmem, face, half, board, cnt, h)
            placed = f - cnt[C_UNPLACED]
            if placed > cnt[C_BEST]:
                cnt[C_BEST] = placed
                since_best = 0
            continue
        if constrained:
            refresh(link, gmem, face, half, board, cnt)
            if cnt[C_NCAND] > 0:
                continue
        cnt[C_DEADENDS] += 1
        since_best += 1
        give_up = gw.mode == MODE_PAPER and since_best > gw.restart_after
        if not _repair(link, gmem, face, half, board, cnt, gw, give_up):
            if not gw.restart:
                return False
            cnt[C_RESTARTS] += 1
            since_best = 0
            if start(link, gmem, face, half, board, cnt, root_cells) < 0:
                return False
    return cnt[C_UNPLACED] == 0
