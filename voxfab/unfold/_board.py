"""The board of a net search: faces on cells, the fold tree, the placeable half-edges.

Every kernel takes its state as two structured arguments:

* :class:`Surface` (read only): the surface graph and the edge constraints.
* :class:`Board` (mutated): where each face lies, the fold tree, the board
  cells, the candidate set, counters and the random state.

Laying face j across edge k of a placed face i (a half-edge ``h = 4*i + k``) is
a fixed function: side ``s = (k + rot[i]) % 4`` of i's cell, cell
``pos[i] + off[s]``, rotation ``(s + 2 - ne[i, k]) % 4`` (j's copy of the edge
lies on the opposite side).  Sides run 0 bottom, 1 right, 2 top, 3 left, so one
more quarter turn of rotation turns a face counter-clockwise.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt
from numba import njit

from ._constraints import CUT, KEEP

# Counter slots in ``Board.cnt``.
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
C_WIDTH = 10  # board row length in cells
C_CONSTRAINED = 11  # 1 when some edge is cut or kept by constraints
N_COUNTERS = 12


class Surface(NamedTuple):
    """The faces being unfolded and their constraints (read only).

    ``nb, ne`` : (F, 4) neighbour face and neighbour edge from the surface graph.
    ``edge`` : (F, 4) int8, FREE, CUT or KEEP per half-edge.
    ``group, gx, gy, grot, members, gstart`` : faces joined by keep edges, laid
    out flat once (see :class:`voxfab.unfold._constraints.Resolved`).
    """

    nb: npt.NDArray[np.int64]
    ne: npt.NDArray[np.int64]
    edge: npt.NDArray[np.int8]
    group: npt.NDArray[np.int64]
    gx: npt.NDArray[np.int64]
    gy: npt.NDArray[np.int64]
    grot: npt.NDArray[np.int64]
    members: npt.NDArray[np.int64]
    gstart: npt.NDArray[np.int64]


class Board(NamedTuple):
    """The search state.

    ``pos`` : (F,) board cell of each face, -1 unplaced, -3 excluded (a face of
    another piece: never placed, never a candidate).
    ``rot`` : (F,) rotation r of each placed face: its edge k lies on cell side (k+r)%4.
    ``par`` : (F,) parent face in the fold tree, -1 for the root, -2 when unplaced.
    ``board`` : (N,) face on each cell, -1 free, -2 wall (a one-cell border).
    ``off`` : (4,) cell offset across sides 0..3.
    ``cl, cp`` : the set of placeable half-edges (placed face, unplaced neighbour,
    free forced cell, constraints met) as a list and the position of each
    half-edge in it (-1: absent), kept exact incrementally so a growth step is
    O(1).  Slots ``4F + t`` hold the list of unplaced faces, so a dead end scans
    only those.
    ``cnt`` : counters, see the ``C_*`` constants.
    ``st`` : (1,) uint64 xorshift state.
    ``stack, opt, bad, blk`` : scratch for subtree walks, repair options, seams
    and the faces in the way of a repair.
    ``root_cells`` : cells where a root may go.
    """

    pos: npt.NDArray[np.int64]
    rot: npt.NDArray[np.int64]
    par: npt.NDArray[np.int64]
    board: npt.NDArray[np.int32]
    off: npt.NDArray[np.int64]
    cl: npt.NDArray[np.int64]
    cp: npt.NDArray[np.int64]
    cnt: npt.NDArray[np.int64]
    st: npt.NDArray[np.uint64]
    stack: npt.NDArray[np.int64]
    opt: npt.NDArray[np.int64]
    bad: npt.NDArray[np.int64]
    blk: npt.NDArray[np.int64]
    root_cells: npt.NDArray[np.int64]


@njit(cache=True)
def forced(sf, b, h):
    """Face, cell and rotation that half-edge h lays."""
    i = h >> 2
    k = h & 3
    s = (k + b.rot[i]) & 3
    return sf.nb[i, k], b.pos[i] + b.off[s], (s + 2 - sf.ne[i, k]) & 3


@njit(cache=True)
def meets_cut(sf, b, j, c, r):
    """Whether face j on cell c with rotation r meets a placed face across a cut edge.

    Such a cut would close up in the plane, so the net would not show it.
    """
    for e in range(4):
        if sf.edge[j, e] != CUT:
            continue
        q = sf.nb[j, e]
        if b.pos[q] < 0:
            continue
        s = (e + r) & 3
        if b.pos[q] == c + b.off[s] and b.rot[q] == ((s + 2 - sf.ne[j, e]) & 3):
            return True
    return False


@njit(cache=True)
def member_cell(sf, b, j, c, r, m):
    """Cell and rotation of face m of j's kept group when j lies on c with rotation r.

    The cell is -1 outside the board.
    """
    w = b.cnt[C_WIDTH]
    turn = (r - sf.grot[j]) & 3
    dx = sf.gx[m] - sf.gx[j]
    dy = sf.gy[m] - sf.gy[j]
    for _ in range(turn):
        dx, dy = -dy, dx
    x = c % w + dx
    y = c // w + dy
    if x < 0 or y < 0 or x >= w or y >= b.board.shape[0] // w:
        return -1, 0
    return y * w + x, (sf.grot[m] + turn) & 3


@njit(cache=True)
def fits(sf, b, j, c, r):
    """Whether face j (with its kept group) can lie on cell c with rotation r."""
    if b.board[c] != -1:
        return False
    if b.cnt[C_CONSTRAINED] == 0:
        return True
    g = sf.group[j]
    if g < 0:
        return not meets_cut(sf, b, j, c, r)
    for t in range(sf.gstart[g], sf.gstart[g + 1]):
        m = sf.members[t]
        cm, rm = member_cell(sf, b, j, c, r, m)
        if cm < 0 or b.board[cm] != -1 or meets_cut(sf, b, m, cm, rm):
            return False
    return True


@njit(cache=True)
def update(sf, b, h):
    """Put half-edge h in the placeable set or take it out, as it now is."""
    i = h >> 2
    ok = False
    if b.pos[i] >= 0 and sf.edge[i, h & 3] != CUT:
        j, c, r = forced(sf, b, h)
        if b.pos[j] == -1:
            ok = fits(sf, b, j, c, r)
    p = b.cp[h]
    if ok:
        if p < 0:
            n = b.cnt[C_NCAND]
            b.cl[n] = h
            b.cp[h] = n
            b.cnt[C_NCAND] = n + 1
    elif p >= 0:
        n = b.cnt[C_NCAND] - 1
        last = b.cl[n]
        b.cl[p] = last
        b.cp[last] = p
        b.cp[h] = -1
        b.cnt[C_NCAND] = n


@njit(cache=True)
def _touch(sf, b, j, c):
    # Every half-edge whose validity depends on face j or on cell c.  Kept groups
    # reach further; the growth re-checks those at a pick and rescans at a dead end.
    for k in range(4):
        update(sf, b, 4 * j + k)
        update(sf, b, 4 * sf.nb[j, k] + sf.ne[j, k])
    for s in range(4):
        q = b.board[c + b.off[s]]
        if q >= 0:
            update(sf, b, 4 * q + (((s + 2) - b.rot[q]) & 3))
    if b.cnt[C_CONSTRAINED]:
        for e in range(4):
            if sf.edge[j, e] == CUT:
                p = sf.nb[j, e]
                for e2 in range(4):
                    update(sf, b, 4 * sf.nb[p, e2] + sf.ne[p, e2])


@njit(cache=True)
def place(sf, b, j, c, r, p):
    """Put face j on cell c with rotation r, child of p (-1: root)."""
    b.pos[j] = c
    b.rot[j] = r
    b.par[j] = p
    b.board[c] = j
    b.cnt[C_UNPLACED] -= 1
    f4 = 4 * b.pos.shape[0]
    p_ = b.cp[f4 + j]
    n = b.cnt[C_NFREE] - 1
    last = b.cl[f4 + n]
    b.cl[f4 + p_] = last
    b.cp[f4 + last] = p_
    b.cp[f4 + j] = -1
    b.cnt[C_NFREE] = n
    _touch(sf, b, j, c)


@njit(cache=True)
def place_group(sf, b, j, c, r, p):
    """Put face j on cell c with rotation r, child of p, and the rest of its kept group."""
    place(sf, b, j, c, r, p)
    if b.cnt[C_CONSTRAINED] == 0 or sf.group[j] < 0:
        return
    queue = b.stack  # breadth first through the keep edges
    queue[0] = j
    head = 0
    tail = 1
    while head < tail:
        a = queue[head]
        head += 1
        for k in range(4):
            if sf.edge[a, k] == KEEP and b.pos[sf.nb[a, k]] == -1:
                m, cm, rm = forced(sf, b, 4 * a + k)
                place(sf, b, m, cm, rm, a)
                queue[tail] = m
                tail += 1


@njit(cache=True)
def place_via(sf, b, h):
    """Lay the neighbour across half-edge h (and its kept group) onto its forced cell."""
    j, c, r = forced(sf, b, h)
    place_group(sf, b, j, c, r, h >> 2)


@njit(cache=True)
def unplace(sf, b, j):
    """Take face j off the board (its children are left dangling: use remove_subtree)."""
    c = b.pos[j]
    b.board[c] = -1
    b.pos[j] = -1
    b.par[j] = -2
    b.cnt[C_UNPLACED] += 1
    f4 = 4 * b.pos.shape[0]
    n = b.cnt[C_NFREE]
    b.cl[f4 + n] = j
    b.cp[f4 + j] = n
    b.cnt[C_NFREE] = n + 1
    _touch(sf, b, j, c)


@njit(cache=True)
def entry(sf, b, m):
    """The face through which m's kept group hangs in the tree (m itself when alone)."""
    if b.cnt[C_CONSTRAINED] == 0:
        return m
    while b.par[m] >= 0:
        p = b.par[m]
        kept = False
        for k in range(4):
            if sf.nb[m, k] == p and sf.edge[m, k] == KEEP:
                kept = True
        if not kept:
            break
        m = p
    return m


@njit(cache=True)
def remove_subtree(sf, b, m):
    """Remove face m and everything hanging from it; return the count removed."""
    stack = b.stack
    stack[0] = m
    top = 1
    n = 0
    while top > 0:
        top -= 1
        f = stack[top]
        for k in range(4):
            g = sf.nb[f, k]
            if b.pos[g] >= 0 and b.par[g] == f:
                stack[top] = g
                top += 1
        unplace(sf, b, f)
        n += 1
    return n


@njit(cache=True)
def subtree_size(sf, b, m, cap):
    """Size of the subtree of m, stopping early once it exceeds ``cap``."""
    stack = b.stack
    stack[0] = m
    top = 1
    n = 0
    while top > 0 and n <= cap:
        top -= 1
        f = stack[top]
        n += 1
        for k in range(4):
            g = sf.nb[f, k]
            if b.pos[g] >= 0 and b.par[g] == f:
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
def refresh(sf, b):
    """Re-check every half-edge that lays an unplaced face."""
    f4 = 4 * b.pos.shape[0]
    for t in range(b.cnt[C_NFREE]):
        j = b.cl[f4 + t]
        for k in range(4):
            update(sf, b, 4 * sf.nb[j, k] + sf.ne[j, k])


@njit(cache=True)
def restore(sf, b, src_pos, src_rot, src_par):
    """Lay out a saved complete net (the placeable set ends empty)."""
    f = b.pos.shape[0]
    for j in range(f):
        if b.pos[j] >= 0:
            b.board[b.pos[j]] = -1
    for j in range(f):
        b.pos[j] = src_pos[j]
        b.rot[j] = src_rot[j]
        b.par[j] = src_par[j]
        if b.pos[j] >= 0:
            b.board[b.pos[j]] = j
    for t in range(b.cnt[C_NCAND]):
        b.cp[b.cl[t]] = -1
    for t in range(b.cnt[C_NFREE]):
        b.cp[4 * f + b.cl[4 * f + t]] = -1
    b.cnt[C_NCAND] = 0
    b.cnt[C_UNPLACED] = 0
    b.cnt[C_NFREE] = 0
