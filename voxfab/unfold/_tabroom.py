"""Tab room: drive the seams with no free cell for a glue tab to zero (compiled).

A seam is a cut edge of the net whose two sides do not meet in the plane.  It
has tab room when the cell beyond its edge is free on at least one side.  The
board keeps the list of seams without tab room up to date as faces come and go
(:func:`voxfab.unfold._board.seam_update`) and logs what each move touches, so
a move and its undo cost only the faces they move, not the whole net.
"""

from __future__ import annotations

import numpy as np

from ._board import (
    C_ACCEPTED,
    C_BESTBAD,
    C_LOGGING,
    C_MOVE,
    C_NBAD,
    C_NLOG,
    C_REGROW_FAILED,
    C_ROOT,
    C_STALE,
    C_TRACK,
    C_UNPLACED,
    C_WIDTH,
    NB,
    PAR,
    POS,
    ROT,
    SL,
    entry,
    randint,
    random,
    rehang,
    remove_subtree,
    restore,
    subtree_size,
    track_seams,
    undo,
)
from ._growth import grow
from ._jit import njit


@njit(cache=True)
def _ruin_near_seams(link, gmem, face, half, board, cnt, sched):
    # Mostly (while seams lack room) clear a square window of cells around a
    # seam without tab room: every face there whose subtree is small goes, so
    # regrowth can rearrange the crowded corner as a whole.  Removing only the
    # seam's own faces (often leaves) tends to lay them straight back.
    f = face.shape[0]
    root = cnt[C_ROOT]
    n = cnt[C_NBAD]
    cap = sched.big_cap if random(cnt) < sched.p_big else sched.ruin_cap
    if n == 0 or random(cnt) >= 0.9:
        m = entry(link, face, cnt, randint(cnt, f))
        if face[m, POS] >= 0 and m != root and subtree_size(link, face, half, m, -1, cap) <= cap:
            remove_subtree(link, gmem, face, half, board, cnt, m)
        return
    e = half[randint(cnt, n), SL]
    a = e >> 2
    if randint(cnt, 2) == 1:
        a = link[a, NB, e & 3]
    width = cnt[C_WIDTH]
    c0 = face[a, POS]
    r = 1 + randint(cnt, 2)
    if sched.patience > 0 and 2 * cnt[C_STALE] > sched.patience:
        r += 1  # no progress for a while: clear a wider corner
    left = cap
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            c = c0 + dy * width + dx
            if c < 0 or c >= board.shape[0]:
                continue
            m = board[c]
            if m < 0:
                continue
            m = entry(link, face, cnt, m)
            if m == root:
                continue
            size = subtree_size(link, face, half, m, -1, left)
            if size > left:
                # A crowded corner on the trunk of the tree: hang the trunk
                # around m where faces meet in the plane, then try again.
                rehang(link, face, half, cnt, m, sched.big_cap)
                size = subtree_size(link, face, half, m, -1, left)
            if size <= left:
                left -= remove_subtree(link, gmem, face, half, board, cnt, m)
            if left <= 0:
                return


@njit(cache=True)
def _save(face, cnt, best):
    # A loop, not slices: copying a slice may allocate, and the kernels run without numba's allocator.
    for j in range(face.shape[0]):
        best[j, 0] = face[j, POS]
        best[j, 1] = face[j, ROT]
        best[j, 2] = face[j, PAR]
    cnt[C_BESTBAD] = cnt[C_NBAD]


@njit(cache=True)
def begin(link, face, half, board, cnt, best):
    """Start tracking a complete net's seams and save it as the best; returns their count."""
    track_seams(link, face, half, board, cnt)
    _save(face, cnt, best)
    cnt[C_STALE] = 0
    return cnt[C_NBAD]


@njit(cache=True)
def anneal(link, gmem, face, half, board, cnt, root_cells, gw, sched, moves, mv0, best):
    """Drive the count of seams without tab room down by ruin-and-recreate moves.

    Starts from a complete net (tracking its seams first, :func:`begin`, unless
    an earlier call of the same run did); each move removes one or two
    subtrees next to a seam without tab room and regrows them (preferring cells
    with few placed neighbours); a move whose regrowth does not complete is
    undone.  Metropolis acceptance with a geometric temperature from ``t0`` to
    ``t1`` over ``sched.total`` moves, of which this call runs ``moves``
    starting at move ``mv0``.  The best net goes to ``best`` (columns POS, ROT,
    PAR); the run ends (:func:`finish`, the board then holds the best net and
    ``cnt[C_BESTBAD]`` its count) when no seam is left or the last move is
    done.  One compiled entry point for the whole run keeps start-up short:
    each kernel called from Python loads its own code from numba's cache.
    Returns the moves used.
    """
    if cnt[C_TRACK] == 0:
        begin(link, face, half, board, cnt, best)
    total = sched.total
    used = 0
    # Regrowth prefers sparse cells.  A value read from the board, not the
    # literal True, so numba reuses the one compiled grow the search calls.
    sparse = cnt[C_TRACK] != 0
    for mv in range(moves):
        cur = cnt[C_NBAD]
        if cur == 0 or (sched.patience > 0 and cnt[C_STALE] >= sched.patience):
            break
        used = mv + 1
        temp = sched.t0 * (sched.t1 / sched.t0) ** (min(mv0 + mv, total) / max(total, 1))
        cnt[C_MOVE] += 1
        cnt[C_NLOG] = 0
        cnt[C_LOGGING] = 1
        _ruin_near_seams(link, gmem, face, half, board, cnt, sched)
        ok = True
        if cnt[C_UNPLACED] > 0:
            ok = grow(link, gmem, face, half, board, cnt, root_cells, gw, sched.regrow_steps, sparse)
        cnt[C_LOGGING] = 0
        cnt[C_STALE] += 1
        if ok:
            new = cnt[C_NBAD]
            if new <= cur or random(cnt) < np.exp(-(new - cur) / temp):
                cnt[C_ACCEPTED] += 1
                if new < cnt[C_BESTBAD]:
                    _save(face, cnt, best)
                    cnt[C_STALE] = 0
                continue
        else:
            cnt[C_REGROW_FAILED] += 1
        undo(link, gmem, face, half, board, cnt)
    stale = sched.patience > 0 and cnt[C_STALE] >= sched.patience
    if cnt[C_NBAD] == 0 or mv0 + moves >= total or stale:
        finish(face, half, board, cnt, best)
    return used


@njit(cache=True)
def finish(face, half, board, cnt, best):
    """End tracking and lay out the best net seen; returns its seams without tab room."""
    if cnt[C_BESTBAD] < cnt[C_NBAD]:
        restore(face, half, board, cnt, best)
    cnt[C_TRACK] = 0
    return cnt[C_BESTBAD]
