"""Tab room: drive the seams with no free cell for a glue tab to zero (compiled).

A seam is a cut edge of the net whose two sides do not meet in the plane.  It
has tab room when the cell beyond its edge is free on at least one side.  The
board keeps the list of seams without tab room up to date as faces come and go
(:func:`voxfab.unfold._board.seam_update`) and logs what each move touches, so
a move and its undo cost only the faces they move, not the whole net.
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
    C_OFF,
    C_REGROW_FAILED,
    C_ROOT,
    C_TRACK,
    C_UNPLACED,
    NB,
    NE,
    PAR,
    POS,
    ROT,
    SL,
    entry,
    randint,
    random,
    remove_subtree,
    restore,
    subtree_size,
    track_seams,
    undo,
)
from ._growth import grow


class Annealing(NamedTuple):
    """Move schedule: temperatures ``t0`` to ``t1`` (in seams) over ``total``
    moves, growth steps a regrowth may spend, and the largest subtree a move
    may remove: ``ruin_cap`` mostly, ``big_cap`` with chance ``p_big`` (a seam
    whose faces and tab cells all lie on the trunk of the tree needs it)."""

    total: int
    t0: float
    t1: float
    regrow_steps: int
    ruin_cap: int
    big_cap: int = 0
    p_big: float = 0.0


@njit(cache=True)
def _ruin_near_seams(link, gmem, face, half, board, cnt, sched):
    # Remove one or two subtrees, mostly next to a seam without tab room: one of
    # its faces, or the face on one of its tab cells.
    f = face.shape[0]
    root = cnt[C_ROOT]
    for _ in range(1 + randint(cnt, 2)):
        n = cnt[C_NBAD]
        if n > 0 and random(cnt) < 0.9:
            e = half[randint(cnt, n), SL]
            a = e >> 2
            ka = e & 3
            if randint(cnt, 2) == 1:
                a, ka = link[a, NB, ka], link[a, NE, ka]
            if face[a, POS] < 0:
                continue
            m = a if randint(cnt, 2) == 0 else board[face[a, POS] + cnt[C_OFF + ((ka + face[a, ROT]) & 3)]]
        else:
            m = randint(cnt, f)
        if m < 0 or face[m, POS] < 0:
            continue
        m = entry(link, face, cnt, m)
        cap = sched.big_cap if random(cnt) < sched.p_big else sched.ruin_cap
        if m == root or subtree_size(link, face, half, m, -1, cap) > cap:
            continue
        remove_subtree(link, gmem, face, half, board, cnt, m)


@njit(cache=True)
def _save(face, cnt, best):
    best[:, 0] = face[:, POS]
    best[:, 1] = face[:, ROT]
    best[:, 2] = face[:, PAR]
    cnt[C_BESTBAD] = cnt[C_NBAD]


@njit(cache=True)
def begin(link, face, half, board, cnt, best):
    """Start tracking a complete net's seams and save it as the best; returns their count."""
    track_seams(link, face, half, board, cnt)
    _save(face, cnt, best)
    return cnt[C_NBAD]


@njit(cache=True)
def anneal(link, gmem, face, half, board, cnt, root_cells, gw, sched, moves, mv0, best):
    """Drive the count of seams without tab room down by ruin-and-recreate moves.

    Starts from a complete net after :func:`begin`; each move removes one or two
    subtrees next to a seam without tab room and regrows them (preferring cells
    with few placed neighbours); a move whose regrowth does not complete is
    undone.  Metropolis acceptance with a geometric temperature from ``t0`` to
    ``t1`` over ``sched.total`` moves, of which this call runs ``moves``
    starting at move ``mv0``.  The best net goes to ``best`` (columns POS, ROT,
    PAR).  Returns the moves used.
    """
    total = sched.total
    used = 0
    for mv in range(moves):
        cur = cnt[C_NBAD]
        if cur == 0:
            break
        used = mv + 1
        temp = sched.t0 * (sched.t1 / sched.t0) ** (min(mv0 + mv, total) / max(total, 1))
        cnt[C_MOVE] += 1
        cnt[C_NLOG] = 0
        cnt[C_LOGGING] = 1
        _ruin_near_seams(link, gmem, face, half, board, cnt, sched)
        ok = True
        if cnt[C_UNPLACED] > 0:
            ok = grow(link, gmem, face, half, board, cnt, root_cells, gw, sched.regrow_steps, True)
        cnt[C_LOGGING] = 0
        if ok:
            new = cnt[C_NBAD]
            if new <= cur or random(cnt) < np.exp(-(new - cur) / temp):
                cnt[C_ACCEPTED] += 1
                if new < cnt[C_BESTBAD]:
                    _save(face, cnt, best)
                continue
        else:
            cnt[C_REGROW_FAILED] += 1
        undo(link, gmem, face, half, board, cnt)
    return used


@njit(cache=True)
def finish(face, half, board, cnt, best):
    """End tracking and lay out the best net seen; returns its seams without tab room."""
    if cnt[C_BESTBAD] < cnt[C_NBAD]:
        restore(face, half, board, cnt, best)
    cnt[C_TRACK] = 0
    return cnt[C_BESTBAD]
