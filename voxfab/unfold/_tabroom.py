"""Tab room: drive the seams with no free cell for a glue tab to zero (compiled).

A seam is a cut edge of the net whose two sides do not meet in the plane.  It
has tab room when the cell beyond its edge is free on at least one side.  The
board keeps the list of seams without tab room up to date as faces come and go
(:func:`voxfab.unfold._board.seam_update`), and logs what each move touches,
so a move and its undo cost only the faces they move, not the whole net.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from ._board import (
    C_ACCEPTED,
    C_BESTBAD,
    C_LOGGING,
    C_MOVE,
    C_NBAD,
    C_NLOG,
    C_REGROW_FAILED,
    C_ROOT,
    C_TRACK,
    C_UNPLACED,
    entry,
    remove_subtree,
    restore,
    subtree_size,
    track_seams,
    undo,
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
def _ruin_near_seams(sf, b, ruin_cap):
    # Remove one or two subtrees, mostly next to a seam without tab room: one of
    # its faces, or the face on one of its tab cells.
    f = b.pos.shape[0]
    root = b.cnt[C_ROOT]
    for _ in range(1 + randint(b.st, 2)):
        n = b.cnt[C_NBAD]
        if n > 0 and random(b.st) < 0.9:
            e = b.sl[randint(b.st, n)]
            a = e >> 2
            ka = e & 3
            if randint(b.st, 2) == 1:
                a, ka = sf.nb[a, ka], sf.ne[a, ka]
            if b.pos[a] < 0:
                continue
            m = a if randint(b.st, 2) == 0 else b.board[b.pos[a] + b.off[(ka + b.rot[a]) & 3]]
        else:
            m = randint(b.st, f)
        if m < 0 or b.pos[m] < 0:
            continue
        m = entry(sf, b, m)
        if m == root or subtree_size(sf, b, m, ruin_cap) > ruin_cap:
            continue
        remove_subtree(sf, b, m)


@njit(cache=True)
def _save(b, best_pos, best_rot, best_par):
    best_pos[:] = b.pos
    best_rot[:] = b.rot
    best_par[:] = b.par
    b.cnt[C_BESTBAD] = b.cnt[C_NBAD]


@njit(cache=True)
def begin(sf, b, best_pos, best_rot, best_par):
    """Start tracking a complete net's seams and save it as the best; returns their count."""
    track_seams(sf, b)
    _save(b, best_pos, best_rot, best_par)
    return b.cnt[C_NBAD]


@njit(cache=True)
def anneal(sf, b, gw, sched, moves, mv0, best_pos, best_rot, best_par):
    """Drive the count of seams without tab room down by ruin-and-recreate moves.

    Starts from a complete net after :func:`begin`; each move removes one or two
    subtrees next to a seam without tab room and regrows them (preferring cells
    with few placed neighbours); a move whose regrowth does not complete is
    undone.  Metropolis acceptance with a geometric temperature from ``t0`` to
    ``t1`` over ``sched.total`` moves, of which this call runs ``moves``
    starting at move ``mv0``.  The best net goes to ``best_*``.  Returns the
    moves used.
    """
    total = sched.total
    used = 0
    for mv in range(moves):
        cur = b.cnt[C_NBAD]
        if cur == 0:
            break
        used = mv + 1
        temp = sched.t0 * (sched.t1 / sched.t0) ** (min(mv0 + mv, total) / max(total, 1))
        b.cnt[C_MOVE] += 1
        b.cnt[C_NLOG] = 0
        b.cnt[C_LOGGING] = 1
        _ruin_near_seams(sf, b, sched.ruin_cap)
        ok = True
        if b.cnt[C_UNPLACED] > 0:
            ok = grow(sf, b, gw, sched.regrow_steps, True)
        b.cnt[C_LOGGING] = 0
        if ok:
            new = b.cnt[C_NBAD]
            if new <= cur or random(b.st) < np.exp(-(new - cur) / temp):
                b.cnt[C_ACCEPTED] += 1
                if new < b.cnt[C_BESTBAD]:
                    _save(b, best_pos, best_rot, best_par)
                continue
        else:
            b.cnt[C_REGROW_FAILED] += 1
        undo(sf, b)
    return used


@njit(cache=True)
def finish(sf, b, best_pos, best_rot, best_par):
    """End tracking and lay out the best net seen; returns its seams without tab room."""
    if b.cnt[C_BESTBAD] < b.cnt[C_NBAD]:
        restore(sf, b, best_pos, best_rot, best_par)
    b.cnt[C_TRACK] = 0
    return b.cnt[C_BESTBAD]
