"""Ruin-and-recreate growth of a net on the board (compiled).

A step places one face, or repairs a dead end.  ``MODE_RUIN`` removes the
subtree on the blocking cell of a random blocked attachment (the smallest of a
few samples) and lays the blocked face there, never restarting.  ``MODE_PAPER``
is the published method: swap out a blocking leaf when it can, else drop the
smallest blocking subtree, and restart after too many repairs without progress.
"""

from __future__ import annotations

from typing import NamedTuple

from numba import njit

from ._board import (
    C_BEST,
    C_CONSTRAINED,
    C_DEADENDS,
    C_NCAND,
    C_NFREE,
    C_RESTARTS,
    C_ROOT,
    C_STEPS,
    C_UNPLACED,
    C_WIDTH,
    entry,
    fits,
    forced,
    in_subtree,
    member_cell,
    place_group,
    place_via,
    refresh,
    remove_subtree,
    subtree_size,
    update,
)
from ._constraints import CUT
from ._random import randint, random

MODE_RUIN = 0  # ruin-and-recreate, never restart
MODE_PAPER = 1  # published method: leaf swap, smallest subtree, restart
#: Random roots tried before a start gives up (a kept group may not fit a small box).
_ROOT_TRIES = 64


class Growth(NamedTuple):
    """How to grow: ``mode``, candidates per ``tour``nament, blocked options
    ``samples``d per dead end, chance ``p_lift`` of ruining further up the tree,
    and repairs without progress before a paper-mode restart."""

    mode: int
    tour: int
    samples: int
    p_lift: float
    restart_after: int


@njit(cache=True)
def start(sf, b):
    """Empty the board and put a random root face on a random allowed cell.

    Returns the root, or -1 when no try fits (a kept group larger than the box).
    """
    f = b.pos.shape[0]
    free = 0
    for j in range(f):
        if b.pos[j] == -3:
            continue
        if b.pos[j] >= 0:
            b.board[b.pos[j]] = -1
        b.pos[j] = -1
        b.par[j] = -2
        b.cl[4 * f + free] = j
        b.cp[4 * f + j] = free
        free += 1
    for t in range(b.cnt[C_NCAND]):
        b.cp[b.cl[t]] = -1
    b.cnt[C_NCAND] = 0
    b.cnt[C_UNPLACED] = free
    b.cnt[C_NFREE] = free
    for _ in range(_ROOT_TRIES):
        root = b.cl[4 * f + randint(b.st, free)]
        c = b.root_cells[randint(b.st, b.root_cells.shape[0])]
        r = randint(b.st, 4)
        if fits(sf, b, root, c, r):
            b.cnt[C_ROOT] = root
            place_group(sf, b, root, c, r, -1)
            return root
    return -1


@njit(cache=True)
def _pick(b, tour, sparse):
    # Tournament among ``tour`` random candidates: the farthest from the root
    # stretches the net; with ``sparse``, the one touching the fewest placed faces
    # keeps cells free beside future seams for glue tabs.
    n = b.cnt[C_NCAND]
    best = b.cl[randint(b.st, n)]
    if tour <= 1:
        return best
    width = b.cnt[C_WIDTH]
    rootcell = b.pos[b.cnt[C_ROOT]]
    rx = rootcell % width
    ry = rootcell // width
    bd = -(1 << 40)
    for _ in range(tour):
        h = b.cl[randint(b.st, n)]
        i = h >> 2
        c = b.pos[i] + b.off[((h & 3) + b.rot[i]) & 3]
        if sparse:
            occ = 0
            for s in range(4):
                if b.board[c + b.off[s]] != -1:
                    occ += 1
            d = -occ
        else:
            d = abs(c % width - rx) + abs(c // width - ry)
        if d > bd:
            bd = d
            best = h
    return best


@njit(cache=True)
def _blocked_options(sf, b):
    # Half-edges h = 4i+k (i placed, its neighbour unplaced, edge not cut) that
    # cannot lay their face: without constraints, those whose cell holds a face
    # other than the root.
    n = 0
    f4 = 4 * b.pos.shape[0]
    constrained = b.cnt[C_CONSTRAINED]
    root = b.cnt[C_ROOT]
    for t in range(b.cnt[C_NFREE]):
        j = b.cl[f4 + t]
        for k in range(4):
            i = sf.nb[j, k]
            if b.pos[i] < 0:
                continue
            ki = sf.ne[j, k]
            if constrained:
                if sf.edge[i, ki] != CUT:
                    b.opt[n] = 4 * i + ki
                    n += 1
                continue
            m = b.board[b.pos[i] + b.off[(ki + b.rot[i]) & 3]]
            if m >= 0 and m != root:
                b.opt[n] = 4 * i + ki
                n += 1
    return n


@njit(cache=True)
def blocker(b, h):
    """The face on the cell that option ``h`` would take."""
    i = h >> 2
    return b.board[b.pos[i] + b.off[((h & 3) + b.rot[i]) & 3]]


@njit(cache=True)
def _smallest_blocking(sf, b, n, tries, sampled):
    # The option among ``tries`` (random ones when ``sampled``, else the first)
    # whose blocking subtree is smallest and not above the option's own face.
    chosen = -1
    best_size = b.pos.shape[0] + 1
    for t in range(tries):
        h = b.opt[randint(b.st, n)] if sampled else b.opt[t]
        m = blocker(b, h)
        if in_subtree(h >> 2, m, b.par):
            continue
        size = subtree_size(sf, b, m, best_size)
        if size < best_size:
            best_size = size
            chosen = h
    return chosen


@njit(cache=True)
def _ruin_choice(sf, b, n, samples):
    chosen = _smallest_blocking(sf, b, n, min(n, samples), True)
    if chosen < 0:
        # Every sample hung under its own blocker: take the first usable one.
        t0 = randint(b.st, n)
        for t in range(n):
            h = b.opt[(t0 + t) % n]
            if not in_subtree(h >> 2, blocker(b, h), b.par):
                return h
    return chosen


@njit(cache=True)
def _paper_choice(sf, b, n):
    # Leaf swap first (a random blocking leaf), else the smallest subtree.
    leaves = 0
    for t in range(n):
        h = b.opt[t]
        m = blocker(b, h)
        if m != h >> 2 and subtree_size(sf, b, m, 1) == 1:
            b.opt[leaves], b.opt[t] = b.opt[t], b.opt[leaves]
            leaves += 1
    if leaves > 0:
        return b.opt[randint(b.st, leaves)]
    return _smallest_blocking(sf, b, n, n, False)


@njit(cache=True)
def _blockers(sf, b, h, out):
    # The faces in the way of option h, with its kept group: those on the cells it
    # needs, and those that would meet it across a cut edge.  Returns their count,
    # or -1 when a cell lies outside the board.
    j, c, r = forced(sf, b, h)
    g = sf.group[j]
    lo, hi = (sf.gstart[g], sf.gstart[g + 1]) if g >= 0 else (0, 1)
    n = 0
    for t in range(lo, hi):
        m = sf.members[t] if g >= 0 else j
        cm, rm = member_cell(sf, b, j, c, r, m) if g >= 0 else (c, r)
        if cm < 0 or b.board[cm] == -2:
            return -1
        if b.board[cm] >= 0:
            out[n] = b.board[cm]
            n += 1
        for e in range(4):
            if sf.edge[m, e] != CUT:
                continue
            q = sf.nb[m, e]
            if b.pos[q] < 0:
                continue
            s = (e + rm) & 3
            if b.pos[q] == cm + b.off[s] and b.rot[q] == ((s + 2 - sf.ne[m, e]) & 3):
                out[n] = ~(4 * m + e)  # face q would close the cut edge e of m
                n += 1
    return n


@njit(cache=True)
def _blocker_face(sf, b, code):
    return code if code >= 0 else sf.nb[(~code) >> 2, (~code) & 3]


@njit(cache=True)
def _loop_face(sf, b, code, i):
    # A face to remove so that a cut edge stops closing up: q itself, or a face
    # beside the cut edge on q's side (the loop around a flat vertex that lays q
    # against m passes through one of them).  -1 when none can go.
    m = (~code) >> 2
    e = (~code) & 3
    q = sf.nb[m, e]
    eq = sf.ne[m, e]
    root = b.cnt[C_ROOT]
    t0 = randint(b.st, 3)
    for t in range(3):
        u = (t0 + t) % 3
        f = q if u == 0 else sf.nb[q, (eq + 2 * u - 1) & 3]
        if b.pos[f] < 0:
            continue
        f = entry(sf, b, f)
        if f != root and not in_subtree(i, f, b.par):
            return f
    return -1


@njit(cache=True)
def _clearing_cost(sf, b, h, blk, cap):
    # Faces removed to lay option h (an upper bound: subtrees may overlap), or -1
    # when a blocker is the root or holds h's own face.
    n = _blockers(sf, b, h, blk)
    if n < 0:
        return -1
    cost = 0
    for t in range(n):
        m = entry(sf, b, _blocker_face(sf, b, blk[t]))
        if m == b.cnt[C_ROOT] or in_subtree(h >> 2, m, b.par):
            return -1
        cost += subtree_size(sf, b, m, cap)
    return cost


@njit(cache=True)
def _repair_constrained(sf, b, n, samples, blk):
    # Clear the way for the cheapest of a few random blocked options (any usable
    # one when none of the samples is), then lay it; False when none is usable.
    chosen = -1
    best = b.pos.shape[0] + 1
    for _ in range(min(n, samples)):
        h = b.opt[randint(b.st, n)]
        cost = _clearing_cost(sf, b, h, blk, best)
        if 0 <= cost < best:
            best = cost
            chosen = h
    if chosen < 0:
        t0 = randint(b.st, n)
        for t in range(n):
            h = b.opt[(t0 + t) % n]
            if _clearing_cost(sf, b, h, blk, b.pos.shape[0]) >= 0:
                chosen = h
                break
    if chosen < 0:
        return False
    k = _blockers(sf, b, chosen, blk)
    i = chosen >> 2
    root = b.cnt[C_ROOT]
    for t in range(k):
        m = _blocker_face(sf, b, blk[t])
        if b.pos[m] < 0:  # an earlier removal took it already
            continue
        m = entry(sf, b, m)
        if blk[t] < 0:
            m = _loop_face(sf, b, blk[t], i)
            if m < 0:
                continue
        if random(b.st) < 0.5:
            # Ruin further up half the time: a face that would close a cut edge
            # comes back to the same cell by the same path otherwise.
            for _ in range(1 + randint(b.st, 3)):
                p = entry(sf, b, b.par[m]) if b.par[m] >= 0 else -1
                if p < 0 or p == root or in_subtree(i, p, b.par):
                    break
                m = p
        remove_subtree(sf, b, m)
    j, c, r = forced(sf, b, chosen)
    if fits(sf, b, j, c, r):
        place_via(sf, b, chosen)
    return True


@njit(cache=True)
def _repair(sf, b, gw, give_up):
    # One dead-end repair; False when the search must restart instead.
    n = _blocked_options(sf, b)
    if give_up or n == 0:
        return False
    if b.cnt[C_CONSTRAINED]:
        return _repair_constrained(sf, b, n, max(gw.samples, 3), b.blk)
    chosen = _ruin_choice(sf, b, n, gw.samples) if gw.mode == MODE_RUIN else _paper_choice(sf, b, n)
    if chosen < 0:
        return False
    i = chosen >> 2
    m = blocker(b, chosen)
    root = b.cnt[C_ROOT]
    if gw.mode == MODE_RUIN and random(b.st) < gw.p_lift:
        # Now and then ruin further up the tree, so small swaps cannot cycle.
        lift = 1 + randint(b.st, 3)
        while lift > 0 and b.par[m] >= 0 and b.par[m] != root and not in_subtree(i, b.par[m], b.par):
            m = b.par[m]
            lift -= 1
    remove_subtree(sf, b, m)
    place_via(sf, b, chosen)
    return True


@njit(cache=True)
def grow(sf, b, gw, max_steps, sparse):
    """Grow until every face is placed or ``max_steps`` steps are spent.

    Returns True when the net is complete, False when out of steps or when a
    restart found no room for a root.
    """
    steps = 0
    since_best = 0
    f = b.pos.shape[0]
    constrained = b.cnt[C_CONSTRAINED]
    while b.cnt[C_UNPLACED] > 0 and steps < max_steps:
        steps += 1
        b.cnt[C_STEPS] += 1
        if b.cnt[C_NCAND] > 0:
            h = _pick(b, gw.tour, sparse)
            if constrained:
                j, c, r = forced(sf, b, h)
                if not fits(sf, b, j, c, r):
                    update(sf, b, h)  # a kept group's far cell was taken meanwhile
                    continue
            place_via(sf, b, h)
            placed = f - b.cnt[C_UNPLACED]
            if placed > b.cnt[C_BEST]:
                b.cnt[C_BEST] = placed
                since_best = 0
            continue
        if constrained:
            refresh(sf, b)
            if b.cnt[C_NCAND] > 0:
                continue
        b.cnt[C_DEADENDS] += 1
        since_best += 1
        give_up = gw.mode == MODE_PAPER and since_best > gw.restart_after
        if not _repair(sf, b, gw, give_up):
            b.cnt[C_RESTARTS] += 1
            since_best = 0
            if start(sf, b) < 0:
                return False
    return b.cnt[C_UNPLACED] == 0
