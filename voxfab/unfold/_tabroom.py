"""Tab room: count the seams with no free cell for a glue tab, and drive them to zero (compiled).

A seam is a cut edge of the net whose two sides do not meet in the plane.  It
has tab room when the cell beyond its edge is free on at least one side.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from ._board import (
    C_ACCEPTED,
    C_REGROW_FAILED,
    C_ROOT,
    C_UNPLACED,
    entry,
    remove_subtree,
    restore,
    subtree_size,
)
from ._growth import grow
from ._random import randint, random


class Annealing(NamedTuple):
    """Move schedule: temperatures ``t0`` to ``t1`` (in seams) over ``total``
    moves, growth steps a regrowth may spend, and the largest subtree a move
    may remove."""

    total: int
    t0: float
    t1: float
    regrow_steps: int
    ruin_cap: int


@njit(cache=True)
def seam_score(sf, b):
    """Count seams without tab room; their (face, edge) go to ``b.bad`` (2 per seam).

    Edges of the fold tree and cut edges whose two sides meet in the plane (slits,
    which are left uncut) are not seams.
    """
    nb, ne, pos, rot, par, board, off, bad = sf.nb, sf.ne, b.pos, b.rot, b.par, b.board, b.off, b.bad
    n = 0
    for a in range(pos.shape[0]):
        if pos[a] < 0:
            continue
        for k in range(4):
            c = nb[a, k]
            if c < a or pos[c] < 0 or par[c] == a or par[a] == c:
                continue
            s = (k + rot[a]) & 3
            ca = pos[a] + off[s]
            if ca == pos[c] and rot[c] == ((s + 2 - ne[a, k]) & 3):
                continue
            kc = ne[a, k]
            cc = pos[c] + off[(kc + rot[c]) & 3]
            if board[ca] != -1 and board[cc] != -1:
                bad[2 * n] = 4 * a + k
                bad[2 * n + 1] = 4 * c + kc
                n += 1
    return n


@njit(cache=True)
def _ruin_near_seams(sf, b, cur, ruin_cap):
    # Remove one or two subtrees, mostly next to a seam without tab room: one of
    # its faces, or the face on one of its tab cells.
    f = b.pos.shape[0]
    root = b.cnt[C_ROOT]
    for _ in range(1 + randint(b.st, 2)):
        if cur > 0 and random(b.st) < 0.9:
            hh = b.bad[randint(b.st, 2 * cur)]
            a = hh >> 2
            ka = hh & 3
            if b.pos[a] < 0:
                continue
            choice = randint(b.st, 3)
            if choice == 0:
                m = a
            elif choice == 1:
                m = b.board[b.pos[a] + b.off[(ka + b.rot[a]) & 3]]
            else:
                m = sf.nb[a, ka]
        else:
            m = randint(b.st, f)
        if m < 0 or b.pos[m] < 0:
            continue
        m = entry(sf, b, m)
        if m == root or subtree_size(sf, b, m, ruin_cap) > ruin_cap:
            continue
        remove_subtree(sf, b, m)


@njit(cache=True)
def anneal(sf, b, gw, sched, moves, mv0):
    """Drive the count of seams without tab room down by ruin-and-recreate moves.

    Starts from a complete net; each move removes one or two subtrees next to a
    seam without tab room and regrows.  Metropolis acceptance with a geometric
    temperature from ``t0`` to ``t1`` over ``sched.total`` moves, of which this
    call runs ``moves`` starting at move ``mv0``.  The state ends at the best net
    found.  Returns ``(best score, moves used)``.
    """
    cur = seam_score(sf, b)
    best = cur
    save_pos = b.pos.copy()
    save_rot = b.rot.copy()
    save_par = b.par.copy()
    best_pos = b.pos.copy()
    best_rot = b.rot.copy()
    best_par = b.par.copy()
    root = b.cnt[C_ROOT]
    used = 0
    total = sched.total
    for mv in range(moves):
        if cur == 0:
            break
        used = mv + 1
        temp = sched.t0 * (sched.t1 / sched.t0) ** (min(mv0 + mv, total) / max(total, 1))
        _ruin_near_seams(sf, b, cur, sched.ruin_cap)
        ok = True
        if b.cnt[C_UNPLACED] > 0:
            ok = grow(sf, b, gw, sched.regrow_steps, True)
        if not ok:
            b.cnt[C_REGROW_FAILED] += 1
        if ok and b.cnt[C_ROOT] == root:
            new = seam_score(sf, b)
            if new <= cur or random(b.st) < np.exp(-(new - cur) / temp):
                b.cnt[C_ACCEPTED] += 1
                cur = new
                save_pos[:] = b.pos
                save_rot[:] = b.rot
                save_par[:] = b.par
                if new < best:
                    best = new
                    best_pos[:] = b.pos
                    best_rot[:] = b.rot
                    best_par[:] = b.par
                continue
        b.cnt[C_ROOT] = root
        restore(sf, b, save_pos, save_rot, save_par)
        cur = seam_score(sf, b)
    if best < cur:
        restore(sf, b, best_pos, best_rot, best_par)
        cur = seam_score(sf, b)
    return cur, used
