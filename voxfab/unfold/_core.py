"""Compiled search kernels: ruin-and-recreate growth of a net on a cell board.

State arrays shared by every kernel (F faces, board of N cells in row-major order
with a one-cell wall border):

* ``nb, ne`` : (F, 4) neighbour face and neighbour edge from the surface graph.
* ``pos`` : (F,) board cell of each face, -1 when unplaced, -3 when excluded (a
  face of another piece: never placed, never a candidate).
* ``rot`` : (F,) rotation r of each placed face: its edge k lies on cell side (k+r)%4.
* ``par`` : (F,) parent face in the fold tree, -1 for the root, -2 when unplaced.
* ``board`` : (N,) face on each cell, -1 free, -2 wall.
* ``off`` : (4,) cell offset across sides 0..3 (bottom, right, top, left).
* ``cl, cp`` : the set of placeable half-edges ``h = 4*i + k`` (placed face i whose
  neighbour across edge k is unplaced and whose forced cell is free) as a list and
  the position of each half-edge in it (-1: absent).  Kept exact incrementally, so a
  growth step is O(1).
  Both arrays have 5F entries: slots ``4F + t`` hold the list of unplaced faces
  and each face's position in it, so a dead end scans only the unplaced faces.
* ``cnt`` : counters, see the ``C_*`` constants.
* ``st`` : (1,) uint64 xorshift state: the kernels never touch a global generator,
  so the same seed replays the same search.

Laying face j across edge k of a face i at cell c with rotation r is a fixed
function: side ``s = (k + r) % 4``, cell ``c + off[s]``, rotation
``(s + 2 - ne[i, k]) % 4`` (j's copy of the edge lies on the opposite side).
"""

from __future__ import annotations

import numpy as np
from numba import njit

# Counter slots in ``cnt``.
C_NCAND = 0  # size of the placeable set
C_UNPLACED = 1  # faces not yet placed
C_ROOT = 2  # root face
C_DEADENDS = 3  # dead ends met (ruins or repairs)
C_RESTARTS = 4  # restarts from scratch
C_BEST = 5  # most faces placed at once
C_STEPS = 6  # total steps
C_NFREE = 7  # size of the unplaced list
C_REGROW_FAILED = 8  # annealing moves undone because regrowth ran out of steps
C_ACCEPTED = 9  # annealing moves accepted
N_COUNTERS = 12

MODE_RUIN = 0  # ruin-and-recreate, never restart
MODE_PAPER = 1  # published method: leaf swap, smallest subtree, restart


@njit(cache=True)
def _next(st):
    x = st[0]
    x ^= x >> np.uint64(12)
    x ^= x << np.uint64(25)
    x ^= x >> np.uint64(27)
    st[0] = x
    return x * np.uint64(2685821657736338717)


@njit(cache=True)
def randint(st, n):
    """Uniform integer in ``[0, n)``."""
    return np.int64((_next(st) >> np.uint64(11)) % np.uint64(n))


@njit(cache=True)
def random(st):
    """Uniform float in ``[0, 1)``."""
    return np.float64(_next(st) >> np.uint64(11)) * (1.0 / 9007199254740992.0)


@njit(cache=True)
def _update(h, nb, ne, pos, rot, board, off, cl, cp, cnt):
    i = h >> 2
    k = h & 3
    ok = False
    if pos[i] >= 0 and pos[nb[i, k]] == -1:
        if board[pos[i] + off[(k + rot[i]) & 3]] == -1:
            ok = True
    p = cp[h]
    if ok:
        if p < 0:
            n = cnt[C_NCAND]
            cl[n] = h
            cp[h] = n
            cnt[C_NCAND] = n + 1
    elif p >= 0:
        n = cnt[C_NCAND] - 1
        last = cl[n]
        cl[p] = last
        cp[last] = p
        cp[h] = -1
        cnt[C_NCAND] = n


@njit(cache=True)
def _touch(j, c, nb, ne, pos, rot, board, off, cl, cp, cnt):
    # Every half-edge whose validity depends on face j or on cell c.
    for k in range(4):
        _update(4 * j + k, nb, ne, pos, rot, board, off, cl, cp, cnt)
        _update(4 * nb[j, k] + ne[j, k], nb, ne, pos, rot, board, off, cl, cp, cnt)
    for s in range(4):
        q = board[c + off[s]]
        if q >= 0:
            _update(4 * q + (((s + 2) - rot[q]) & 3), nb, ne, pos, rot, board, off, cl, cp, cnt)


@njit(cache=True)
def place(j, c, r, p, nb, ne, pos, rot, par, board, off, cl, cp, cnt):
    """Put face j on cell c with rotation r, child of p (-1: root)."""
    pos[j] = c
    rot[j] = r
    par[j] = p
    board[c] = j
    cnt[C_UNPLACED] -= 1
    f4 = 4 * pos.shape[0]
    p_ = cp[f4 + j]
    n = cnt[C_NFREE] - 1
    last = cl[f4 + n]
    cl[f4 + p_] = last
    cp[f4 + last] = p_
    cp[f4 + j] = -1
    cnt[C_NFREE] = n
    _touch(j, c, nb, ne, pos, rot, board, off, cl, cp, cnt)


@njit(cache=True)
def unplace(j, nb, ne, pos, rot, par, board, off, cl, cp, cnt):
    """Take face j off the board (its children are left dangling: use remove_subtree)."""
    c = pos[j]
    board[c] = -1
    pos[j] = -1
    par[j] = -2
    cnt[C_UNPLACED] += 1
    f4 = 4 * pos.shape[0]
    n = cnt[C_NFREE]
    cl[f4 + n] = j
    cp[f4 + j] = n
    cnt[C_NFREE] = n + 1
    _touch(j, c, nb, ne, pos, rot, board, off, cl, cp, cnt)


@njit(cache=True)
def place_via(h, nb, ne, pos, rot, par, board, off, cl, cp, cnt):
    """Lay the neighbour across half-edge h onto its forced cell."""
    i = h >> 2
    k = h & 3
    s = (k + rot[i]) & 3
    place(nb[i, k], pos[i] + off[s], (s + 2 - ne[i, k]) & 3, i,
          nb, ne, pos, rot, par, board, off, cl, cp, cnt)


@njit(cache=True)
def remove_subtree(m, nb, ne, pos, rot, par, board, off, cl, cp, cnt, stack):
    """Remove face m and everything hanging from it; return the count removed."""
    stack[0] = m
    top = 1
    n = 0
    while top > 0:
        top -= 1
        f = stack[top]
        for k in range(4):
            g = nb[f, k]
            if pos[g] >= 0 and par[g] == f:
                stack[top] = g
                top += 1
        unplace(f, nb, ne, pos, rot, par, board, off, cl, cp, cnt)
        n += 1
    return n


@njit(cache=True)
def subtree_size(m, nb, pos, par, stack, cap):
    """Size of the subtree of m, stopping early once it exceeds ``cap``."""
    stack[0] = m
    top = 1
    n = 0
    while top > 0 and n <= cap:
        top -= 1
        f = stack[top]
        n += 1
        for k in range(4):
            g = nb[f, k]
            if pos[g] >= 0 and par[g] == f:
                stack[top] = g
                top += 1
    return n


@njit(cache=True)
def in_subtree(i, m, par):
    """Whether face i hangs (directly or not) from face m."""
    a = i
    while a >= 0:
        if a == m:
            return True
        a = par[a]
    return False


@njit(cache=True)
def start(nb, ne, pos, rot, par, board, off, cl, cp, cnt, st, root_cells, width):
    """Empty the board and put a random root face on a random allowed cell."""
    f = pos.shape[0]
    free = 0
    for j in range(f):
        if pos[j] == -3:
            continue
        if pos[j] >= 0:
            board[pos[j]] = -1
        pos[j] = -1
        par[j] = -2
        cl[4 * f + free] = j
        cp[4 * f + j] = free
        free += 1
    for t in range(cnt[C_NCAND]):
        cp[cl[t]] = -1
    cnt[C_NCAND] = 0
    cnt[C_UNPLACED] = free
    cnt[C_NFREE] = free
    root = cl[4 * f + randint(st, free)]
    cnt[C_ROOT] = root
    c = root_cells[randint(st, root_cells.shape[0])]
    place(root, c, randint(st, 4), -1, nb, ne, pos, rot, par, board, off, cl, cp, cnt)
    return root


@njit(cache=True)
def _pick(nb, pos, rot, board, off, cl, cnt, st, tour, width, rootcell, sparse):
    # Tournament among ``tour`` random candidates: the farthest from the root
    # stretches the net; with ``sparse``, the one touching the fewest placed faces
    # keeps cells free beside future seams for glue tabs.
    n = cnt[C_NCAND]
    best = cl[randint(st, n)]
    if tour <= 1:
        return best
    rx = rootcell % width
    ry = rootcell // width
    bd = -(1 << 40)
    for _ in range(tour):
        h = cl[randint(st, n)]
        i = h >> 2
        c = pos[i] + off[((h & 3) + rot[i]) & 3]
        d = abs(c % width - rx) + abs(c // width - ry)
        if sparse:
            occ = 0
            for s in range(4):
                if board[c + off[s]] != -1:
                    occ += 1
            d = -occ
        if d > bd:
            bd = d
            best = h
    return best


@njit(cache=True)
def _blocked_options(nb, ne, pos, rot, par, board, off, cl, cnt, opt, root):
    # Half-edges h = 4i+k (i placed, neighbour unplaced) whose cell holds a face.
    n = 0
    f4 = 4 * pos.shape[0]
    for t in range(cnt[C_NFREE]):
        j = cl[f4 + t]
        for k in range(4):
            i = nb[j, k]
            if pos[i] < 0:
                continue
            ki = ne[j, k]
            m = board[pos[i] + off[(ki + rot[i]) & 3]]
            if m >= 0 and m != root:
                opt[n] = 4 * i + ki
                n += 1
    return n


@njit(cache=True)
def blocker(h, pos, rot, board, off):
    """The face on the cell that option ``h`` (face ``h >> 2``, edge ``h & 3``) would take."""
    i = h >> 2
    return board[pos[i] + off[((h & 3) + rot[i]) & 3]]


@njit(cache=True)
def _smallest_blocking(opt, n, tries, sampled, st, nb, pos, rot, par, board, off, stack, f):
    """The option among ``tries`` (random ones when ``sampled``, else the first)
    whose blocking subtree is smallest and not above the option's own face; -1 if none."""
    chosen = -1
    best_size = f + 1
    for t in range(tries):
        h = opt[randint(st, n)] if sampled else opt[t]
        i = h >> 2
        m = blocker(h, pos, rot, board, off)
        if in_subtree(i, m, par):
            continue
        size = subtree_size(m, nb, pos, par, stack, best_size)
        if size < best_size:
            best_size = size
            chosen = h
    return chosen


@njit(cache=True)
def grow(nb, ne, pos, rot, par, board, off, cl, cp, cnt, st, stack, opt,
         root_cells, width, mode, tour, max_steps, restart_after, samples, p_lift, sparse):
    """Grow until every face is placed or ``max_steps`` steps are spent.

    A step places one face, or repairs a dead end.  ``MODE_RUIN`` removes the
    subtree on the blocking cell of a random blocked attachment (the smaller of
    a few samples) and lays the blocked face there, never restarting.
    ``MODE_PAPER`` swaps out a blocking leaf when it can, else drops the smallest
    blocking subtree, and restarts after ``restart_after`` repairs without a new
    best.  Returns True when the net is complete.
    """
    steps = 0
    since_best = 0
    f = pos.shape[0]
    while cnt[C_UNPLACED] > 0 and steps < max_steps:
        steps += 1
        cnt[C_STEPS] += 1
        root = cnt[C_ROOT]
        if cnt[C_NCAND] > 0:
            h = _pick(nb, pos, rot, board, off, cl, cnt, st, tour, width, pos[root], sparse)
            place_via(h, nb, ne, pos, rot, par, board, off, cl, cp, cnt)
            placed = f - cnt[C_UNPLACED]
            if placed > cnt[C_BEST]:
                cnt[C_BEST] = placed
                since_best = 0
            continue
        cnt[C_DEADENDS] += 1
        since_best += 1
        n = _blocked_options(nb, ne, pos, rot, par, board, off, cl, cnt, opt, root)
        if mode == MODE_PAPER and since_best > restart_after:
            n = 0
        chosen = -1
        if mode == MODE_RUIN:
            chosen = _smallest_blocking(opt, n, min(n, samples), True, st, nb, pos, rot, par, board, off,
                                        stack, f)
            if chosen < 0 and n > 0:
                # Every sample hung under its own blocker: take the first usable one.
                t0 = randint(st, n)
                for t in range(n):
                    h = opt[(t0 + t) % n]
                    i = h >> 2
                    m = blocker(h, pos, rot, board, off)
                    if not in_subtree(i, m, par):
                        chosen = h
                        break
        elif n > 0:
            # Leaf swap first (a random blocking leaf), else the smallest subtree.
            leaves = 0
            for t in range(n):
                h = opt[t]
                i = h >> 2
                m = blocker(h, pos, rot, board, off)
                if m != i and subtree_size(m, nb, pos, par, stack, 1) == 1:
                    opt[leaves], opt[t] = opt[t], opt[leaves]
                    leaves += 1
            if leaves > 0:
                chosen = opt[randint(st, leaves)]
            else:
                chosen = _smallest_blocking(opt, n, n, False, st, nb, pos, rot, par, board, off, stack, f)
        if chosen < 0:
            cnt[C_RESTARTS] += 1
            since_best = 0
            start(nb, ne, pos, rot, par, board, off, cl, cp, cnt, st, root_cells, width)
            continue
        i = chosen >> 2
        m = blocker(chosen, pos, rot, board, off)
        if mode == MODE_RUIN and random(st) < p_lift:
            # Now and then ruin further up the tree, so small swaps cannot cycle.
            lift = 1 + randint(st, 3)
            while lift > 0 and par[m] >= 0 and par[m] != root and not in_subtree(i, par[m], par):
                m = par[m]
                lift -= 1
        remove_subtree(m, nb, ne, pos, rot, par, board, off, cl, cp, cnt, stack)
        place_via(chosen, nb, ne, pos, rot, par, board, off, cl, cp, cnt)
    return cnt[C_UNPLACED] == 0


@njit(cache=True)
def seam_score(nb, ne, pos, rot, par, board, off, bad):
    """Count seams without tab room; their (face, edge) go to ``bad`` (2 per seam).

    Edges of the fold tree and cut edges whose two sides meet in the plane (slits,
    which are left uncut) are not seams.
    """
    f = pos.shape[0]
    n = 0
    for a in range(f):
        if pos[a] < 0:
            continue
        for k in range(4):
            b = nb[a, k]
            if b < a or pos[b] < 0 or par[b] == a or par[a] == b:
                continue
            s = (k + rot[a]) & 3
            ca = pos[a] + off[s]
            if ca == pos[b] and rot[b] == ((s + 2 - ne[a, k]) & 3):
                continue
            kb = ne[a, k]
            cb = pos[b] + off[(kb + rot[b]) & 3]
            if board[ca] != -1 and board[cb] != -1:
                bad[2 * n] = 4 * a + k
                bad[2 * n + 1] = 4 * b + kb
                n += 1
    return n


@njit(cache=True)
def restore(src_pos, src_rot, src_par, pos, rot, par, board, cl, cp, cnt):
    f = pos.shape[0]
    for j in range(f):
        if pos[j] >= 0:
            board[pos[j]] = -1
    for j in range(f):
        pos[j] = src_pos[j]
        rot[j] = src_rot[j]
        par[j] = src_par[j]
        if pos[j] >= 0:
            board[pos[j]] = j
    for t in range(cnt[C_NCAND]):
        cp[cl[t]] = -1
    for t in range(cnt[C_NFREE]):
        cp[4 * f + cl[4 * f + t]] = -1
    cnt[C_NCAND] = 0
    cnt[C_UNPLACED] = 0
    cnt[C_NFREE] = 0


@njit(cache=True)
def anneal(nb, ne, pos, rot, par, board, off, cl, cp, cnt, st, stack, opt, bad,
           root_cells, width, tour, moves, mv0, total, t0, t1, regrow_steps, samples, p_lift,
           ruin_cap):
    """Drive the count of seams without tab room down by ruin-and-recreate moves.

    Starts from a complete net; each move removes one or two subtrees next to a
    seam without tab room (a face on one of its tab cells, or one of its own
    faces) and regrows.  Metropolis acceptance with a geometric temperature from
    ``t0`` to ``t1`` over ``total`` moves, of which this call runs ``moves``
    starting at move ``mv0``.  The state ends at the best net found.
    Returns ``(best score, moves used)``.
    """
    f = pos.shape[0]
    cur = seam_score(nb, ne, pos, rot, par, board, off, bad)
    best = cur
    save_pos = pos.copy()
    save_rot = rot.copy()
    save_par = par.copy()
    best_pos = pos.copy()
    best_rot = rot.copy()
    best_par = par.copy()
    root = cnt[C_ROOT]
    used = 0
    for mv in range(moves):
        if cur == 0:
            break
        used = mv + 1
        temp = t0 * (t1 / t0) ** (min(mv0 + mv, total) / max(total, 1))
        nruin = 1 + randint(st, 2)
        for _ in range(nruin):
            if cur > 0 and random(st) < 0.9:
                # Next to a seam without tab room: one of its faces, or the face on
                # one of its tab cells.
                hh = bad[randint(st, 2 * cur)]
                a = hh >> 2
                ka = hh & 3
                if pos[a] < 0:
                    continue
                choice = randint(st, 3)
                if choice == 0:
                    m = a
                elif choice == 1:
                    m = board[pos[a] + off[(ka + rot[a]) & 3]]
                else:
                    m = nb[a, ka]
            else:
                m = randint(st, f)
            if m < 0 or m == root or pos[m] < 0:
                continue
            if subtree_size(m, nb, pos, par, stack, ruin_cap) > ruin_cap:
                continue
            remove_subtree(m, nb, ne, pos, rot, par, board, off, cl, cp, cnt, stack)
        ok = True
        if cnt[C_UNPLACED] > 0:
            ok = grow(nb, ne, pos, rot, par, board, off, cl, cp, cnt, st, stack, opt,
                      root_cells, width, MODE_RUIN, tour, regrow_steps, 0, samples, p_lift, True)
        if not ok:
            cnt[C_REGROW_FAILED] += 1
        if ok and cnt[C_ROOT] == root:
            new = seam_score(nb, ne, pos, rot, par, board, off, bad)
            if new <= cur or random(st) < np.exp(-(new - cur) / temp):
                cnt[C_ACCEPTED] += 1
                cur = new
                save_pos[:] = pos
                save_rot[:] = rot
                save_par[:] = par
                if new < best:
                    best = new
                    best_pos[:] = pos
                    best_rot[:] = rot
                    best_par[:] = par
                continue
        cnt[C_ROOT] = root
        restore(save_pos, save_rot, save_par, pos, rot, par, board, cl, cp, cnt)
        cur = seam_score(nb, ne, pos, rot, par, board, off, bad)
    if best < cur:
        restore(best_pos, best_rot, best_par, pos, rot, par, board, cl, cp, cnt)
        cur = seam_score(nb, ne, pos, rot, par, board, off, bad)
    return cur, used
