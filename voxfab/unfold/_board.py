"""The board of a net search: faces on cells, the fold tree, the placeable half-edges.

The search state lives in six arrays with named columns, grouped in two
structures (:class:`Surface`, :class:`Board`).  The kernels take those arrays as
arguments (``link, gmem`` of the surface, then ``face, half, board, cnt`` of the
board) rather than the structures themselves: numba counts references to every
array of a tuple at each call, which made a placement forty times slower when
the state was a tuple of two dozen arrays.

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

from ._constraints import CUT, KEEP
from ._jit import inline, njit

# ``link[f, row, k]``: the surface graph and constraints per face and edge.
NB = 0  # neighbour face across edge k
NE = 1  # that edge's index as seen from the neighbour
EDGE = 2  # FREE, CUT or KEEP
GRP = 3  # faces kept together: [group id (-1 alone), x, y, rotation in the group's layout]
G_ID, G_X, G_Y, G_ROT = 0, 1, 2, 3
# ``gmem[0]``: start of each group's members in ``gmem[1]``.
# ``face[f, col]``: where each face lies, and its state before the current move.
POS = 0  # board cell, -1 unplaced, -3 excluded (a face of another piece)
ROT = 1  # rotation r: edge k lies on cell side (k + r) % 4
PAR = 2  # parent in the fold tree, -1 for the root, -2 unplaced
LPOS, LROT, LPAR = 3, 4, 5  # state before the move that first touched the face
STAMP = 6  # id of the move that last logged the face
MARK = 7  # scratch: id of the last subtree walk that reached the face
N_FACE = 8
# ``half[t, col]``: lists over half-edges and faces, with positions.
CL = 0  # placeable half-edges (slots 0..), then unplaced faces (slots 4F..)
CP = 1  # position of each half-edge (4F + face) in CL, -1 absent
SL = 2  # seams without tab room, each by its smaller half-edge
SP = 3  # position of each half-edge in SL, -1 absent
STACK = 4  # scratch for subtree walks
OPT = 5  # scratch for repair options
BLK = 6  # scratch for the faces in the way of a repair
LOG = 7  # faces the current move touched
N_HALF = 8

# Slots in ``cnt``.
C_NCAND = 0  # size of the placeable set
C_UNPLACED = 1  # faces not yet placed
C_ROOT = 2  # root face
C_DEADENDS = 3  # dead ends met (ruins or repairs)
C_RESTARTS = 4  # restarts from scratch
C_BEST = 5  # most faces placed at once
C_STEPS = 6  # total steps
C_NFREE = 7  # size of the unplaced list
C_REGROW_FAILED = 8  # tab-room moves undone because regrowth did not complete
C_ACCEPTED = 9  # tab-room moves accepted
C_WIDTH = 10  # board row length in cells
C_CONSTRAINED = 11  # 1 when some edge is cut or kept by constraints
C_TRACK = 12  # 1 while the seams without tab room are kept up to date
C_NBAD = 13  # seams without tab room (while tracked)
C_LOGGING = 14  # 1 while faces touched are logged for an undo
C_MOVE = 15  # id of the current logged move
C_NLOG = 16  # faces logged in this move
C_BESTBAD = 17  # fewest seams without tab room seen (annealing)
C_RNG = 18  # xorshift state (the bits of a uint64)
C_OFF = 19  # 4 slots: cell offset across sides 0..3
C_STALE = 23  # tab-room moves since the best count last fell
C_MARK = 24  # id of the last marking subtree walk
N_COUNTERS = 25


class Surface(NamedTuple):
    """The faces being unfolded and their constraints (read only).

    ``link`` : (F, 4, 4) int64, rows NB, NE, EDGE per edge and GRP per face.
    ``gmem`` : (2, M + 1) int64, group starts and members of the kept groups
    (see :class:`voxfab.unfold._constraints.Resolved`).
    """

    link: npt.NDArray[np.int64]
    gmem: npt.NDArray[np.int64]


class Board(NamedTuple):
    """The search state.

    ``face`` : (F, N_FACE) int64, see POS .. MARK.
    ``half`` : (5F + 4, N_HALF) int64, see CL .. LOG.  The placeable set holds
    the half-edges of placed faces whose neighbour is unplaced, whose forced
    cell is free and whose constraints are met, kept exact incrementally so a
    growth step is O(1); slots ``4F + t`` of CL list the unplaced faces, so a
    dead end scans only those.
    ``board`` : (N,) int64, face on each cell, -1 free, -2 wall (a border).
    ``cnt`` : counters and settings, see the ``C_*`` constants.
    ``root_cells`` : cells where a root may go.
    """

    face: npt.NDArray[np.int64]
    half: npt.NDArray[np.int64]
    board: npt.NDArray[np.int64]
    cnt: npt.NDArray[np.int64]
    root_cells: npt.NDArray[np.int64]


def make_surface(nb, ne, edge, group, gx, gy, grot, members, gstart) -> Surface:
    """Pack a surface graph and resolved constraints into a :class:`Surface`."""
    f = nb.shape[0]
    link = np.zeros((f, 4, 4), dtype=np.int64)
    link[:, NB] = nb
    link[:, NE] = ne
    link[:, EDGE] = edge
    link[:, GRP, G_ID] = group
    if members.size:
        link[members, GRP, G_X] = gx[members]
        link[members, GRP, G_Y] = gy[members]
        link[members, GRP, G_ROT] = grot[members]
    gmem = np.zeros((2, members.size + 1), dtype=np.int64)
    gmem[0, :gstart.size] = gstart
    gmem[1, :members.size] = members
    return Surface(link, gmem)


def make_board(faces: npt.NDArray[np.int64], f: int, board: npt.NDArray[np.int64], width: int,
               root_cells: npt.NDArray[np.int64], seed: int, constrained: bool) -> Board:
    """An empty board for ``faces`` (of ``f`` surface faces) on the given cells."""
    face = np.zeros((f, N_FACE), dtype=np.int64)
    face[:, POS] = -3
    face[faces, POS] = -1
    face[:, PAR] = -2
    face[:, STAMP] = -1
    face[:, MARK] = -1
    half = np.zeros((5 * f + 4, N_HALF), dtype=np.int64)
    half[:, CP] = -1
    half[:, SP] = -1
    cnt = np.zeros(N_COUNTERS, dtype=np.int64)
    cnt[C_ROOT] = -1  # not started
    cnt[C_WIDTH] = width
    cnt[C_CONSTRAINED] = int(constrained)
    cnt[C_RNG] = np.int64(np.uint64(seed) | np.uint64(1))
    cnt[C_OFF:C_OFF + 4] = (-width, 1, width, -1)
    return Board(face, half, board.astype(np.int64), cnt, root_cells)


# --- random numbers: a seeded xorshift kept in cnt, never a global generator ---

@inline
def randint(cnt, n):
    """Uniform integer in ``[0, n)``."""
    x = np.uint64(cnt[C_RNG])
    x ^= x >> np.uint64(12)
    x ^= x << np.uint64(25)
    x ^= x >> np.uint64(27)
    cnt[C_RNG] = np.int64(x)
    return np.int64(((x * np.uint64(2685821657736338717)) >> np.uint64(11)) % np.uint64(n))


@inline
def random(cnt):
    """Uniform float in ``[0, 1)``."""
    return randint(cnt, 9007199254740992) * (1.0 / 9007199254740992.0)


# --- geometry of a placement ---

@inline
def forced(link, face, cnt, h):
    """Face, cell and rotation that half-edge h lays."""
    i = h >> 2
    k = h & 3
    s = (k + face[i, ROT]) & 3
    return link[i, NB, k], face[i, POS] + cnt[C_OFF + s], (s + 2 - link[i, NE, k]) & 3


@njit(cache=True)
def meets_cut(link, face, cnt, j, c, r):
    """Whether face j on cell c with rotation r meets a placed face across a cut edge.

    Such a cut would close up in the plane, so the net would not show it.
    """
    for e in range(4):
        if link[j, EDGE, e] != CUT:
            continue
        q = link[j, NB, e]
        if face[q, POS] < 0:
            continue
        s = (e + r) & 3
        if face[q, POS] == c + cnt[C_OFF + s] and face[q, ROT] == ((s + 2 - link[j, NE, e]) & 3):
            return True
    return False


@njit(cache=True)
def member_cell(link, board, cnt, j, c, r, m):
    """Cell and rotation of face m of j's kept group when j lies on c with rotation r.

    The cell is -1 outside the board.
    """
    w = cnt[C_WIDTH]
    turn = (r - link[j, GRP, G_ROT]) & 3
    dx = link[m, GRP, G_X] - link[j, GRP, G_X]
    dy = link[m, GRP, G_Y] - link[j, GRP, G_Y]
    for _ in range(turn):
        dx, dy = -dy, dx
    x = c % w + dx
    y = c // w + dy
    if x < 0 or y < 0 or x >= w or y >= board.shape[0] // w:
        return -1, 0
    return y * w + x, (link[m, GRP, G_ROT] + turn) & 3


@inline
def fits(link, gmem, face, board, cnt, j, c, r):
    """Whether face j (with its kept group) can lie on cell c with rotation r."""
    if board[c] != -1:
        return False
    if cnt[C_CONSTRAINED] == 0:
        return True
    return _fits_constrained(link, gmem, face, board, cnt, j, c, r)


@njit(cache=True)
def _fits_constrained(link, gmem, face, board, cnt, j, c, r):
    # The rest of fits, for cut and kept edges: called, not inlined, since
    # growth without constraints never gets here.
    g = link[j, GRP, G_ID]
    if g < 0:
        return not meets_cut(link, face, cnt, j, c, r)
    for t in range(gmem[0, g], gmem[0, g + 1]):
        m = gmem[1, t]
        cm, rm = member_cell(link, board, cnt, j, c, r, m)
        if cm < 0 or board[cm] != -1 or meets_cut(link, face, cnt, m, cm, rm):
            return False
    return True


# --- the placeable set and the seams without tab room ---

@inline
def _set(half, cnt, col_list, col_pos, slot, key, present):
    # Add ``key`` to the list in column col_list (positions in col_pos, size in
    # cnt[slot]) or take it out.
    p = half[key, col_pos]
    if present:
        if p < 0:
            n = cnt[slot]
            half[n, col_list] = key
            half[key, col_pos] = n
            cnt[slot] = n + 1
    elif p >= 0:
        n = cnt[slot] - 1
        last = half[n, col_list]
        half[p, col_list] = last
        half[last, col_pos] = p
        half[key, col_pos] = -1
        cnt[slot] = n


@inline
def update(link, gmem, face, half, board, cnt, h):
    """Put half-edge h in the placeable set or take it out, as it now is."""
    i = h >> 2
    ok = False
    if face[i, POS] >= 0 and link[i, EDGE, h & 3] != CUT:
        j, c, r = forced(link, face, cnt, h)
        if face[j, POS] == -1:
            ok = fits(link, gmem, face, board, cnt, j, c, r)
    _set(half, cnt, CL, CP, C_NCAND, h, ok)


@inline
def seam_update(link, face, half, board, cnt, h):
    """Put the seam across half-edge h in the list of seams without tab room, or take it out.

    A seam is a cut edge between two placed faces whose sides do not meet in
    the plane (those are left uncut); it has no tab room when the cells beyond
    its edge on both sides hold faces.  A wall is room: the sheet keeps a tab's
    depth free all round the box.  A seam to a face of another piece (excluded)
    needs room on the copy of its lower face: the other piece, laid out on its
    own board, sees the seam from the higher face and leaves it to this one.
    """
    a = h >> 2
    k = h & 3
    c = link[a, NB, k]
    kc = link[a, NE, k]
    hc = 4 * c + kc
    bad = False
    if face[a, POS] >= 0 and face[c, POS] == -3:
        if a < c:
            bad = board[face[a, POS] + cnt[C_OFF + ((k + face[a, ROT]) & 3)]] >= 0
    elif face[a, POS] >= 0 and face[c, POS] >= 0 and face[c, PAR] != a and face[a, PAR] != c:
        s = (k + face[a, ROT]) & 3
        ca = face[a, POS] + cnt[C_OFF + s]
        if ca != face[c, POS] or face[c, ROT] != ((s + 2 - kc) & 3):
            cc = face[c, POS] + cnt[C_OFF + ((kc + face[c, ROT]) & 3)]
            bad = board[ca] >= 0 and board[cc] >= 0
    _set(half, cnt, SL, SP, C_NBAD, h if h < hc else hc, bad)


@njit(cache=True)
def _touch(link, gmem, face, half, board, cnt, j, c):
    # Every half-edge whose validity depends on face j or on cell c.  Kept groups
    # reach further; the growth re-checks those at a pick and rescans at a dead end.
    for k in range(4):
        update(link, gmem, face, half, board, cnt, 4 * j + k)
        update(link, gmem, face, half, board, cnt, 4 * link[j, NB, k] + link[j, NE, k])
    for s in range(4):
        q = board[c + cnt[C_OFF + s]]
        if q >= 0:
            update(link, gmem, face, half, board, cnt, 4 * q + (((s + 2) - face[q, ROT]) & 3))
    if cnt[C_CONSTRAINED]:
        for e in range(4):
            if link[j, EDGE, e] == CUT:
                p = link[j, NB, e]
                for e2 in range(4):
                    update(link, gmem, face, half, board, cnt, 4 * link[p, NB, e2] + link[p, NE, e2])
    if cnt[C_TRACK]:
        # A seam's status depends on its two faces and the two cells beyond it.
        for k in range(4):
            seam_update(link, face, half, board, cnt, 4 * j + k)
        for s in range(4):
            q = board[c + cnt[C_OFF + s]]
            if q >= 0:
                seam_update(link, face, half, board, cnt, 4 * q + (((s + 2) - face[q, ROT]) & 3))


@inline
def _log(face, half, cnt, j):
    # Remember face j's state before the current move first touched it.
    if cnt[C_LOGGING] and face[j, STAMP] != cnt[C_MOVE]:
        face[j, STAMP] = cnt[C_MOVE]
        half[cnt[C_NLOG], LOG] = j
        cnt[C_NLOG] += 1
        face[j, LPOS] = face[j, POS]
        face[j, LROT] = face[j, ROT]
        face[j, LPAR] = face[j, PAR]


@inline
def _free_list(face, half, cnt, j, present):
    # The unplaced faces: listed in slots 4F + t of CL, positions in slots 4F + j of CP.
    f4 = 4 * face.shape[0]
    p = half[f4 + j, CP]
    if present:
        n = cnt[C_NFREE]
        half[f4 + n, CL] = j
        half[f4 + j, CP] = n
        cnt[C_NFREE] = n + 1
    elif p >= 0:
        n = cnt[C_NFREE] - 1
        last = half[f4 + n, CL]
        half[f4 + p, CL] = last
        half[f4 + last, CP] = p
        half[f4 + j, CP] = -1
        cnt[C_NFREE] = n


# --- placing and removing faces ---

@njit(cache=True)
def place(link, gmem, face, half, board, cnt, j, c, r, p):
    """Put face j on cell c with rotation r, child of p (-1: root)."""
    _log(face, half, cnt, j)
    face[j, POS] = c
    face[j, ROT] = r
    face[j, PAR] = p
    board[c] = j
    cnt[C_UNPLACED] -= 1
    _free_list(face, half, cnt, j, False)
    _touch(link, gmem, face, half, board, cnt, j, c)


@njit(cache=True)
def unplace(link, gmem, face, half, board, cnt, j):
    """Take face j off the board (its children are left dangling: use remove_subtree)."""
    _log(face, half, cnt, j)
    c = face[j, POS]
    board[c] = -1
    face[j, POS] = -1
    face[j, PAR] = -2
    cnt[C_UNPLACED] += 1
    _free_list(face, half, cnt, j, True)
    _touch(link, gmem, face, half, board, cnt, j, c)


@njit(cache=True)
def place_group(link, gmem, face, half, board, cnt, j, c, r, p):
    """Put face j on cell c with rotation r, child of p, and the rest of its kept group."""
    place(link, gmem, face, half, board, cnt, j, c, r, p)
    if cnt[C_CONSTRAINED] == 0 or link[j, GRP, G_ID] < 0:
        return
    half[0, STACK] = j  # breadth first through the keep edges
    head = 0
    tail = 1
    while head < tail:
        a = half[head, STACK]
        head += 1
        for k in range(4):
            if link[a, EDGE, k] == KEEP and face[link[a, NB, k], POS] == -1:
                m, cm, rm = forced(link, face, cnt, 4 * a + k)
                place(link, gmem, face, half, board, cnt, m, cm, rm, a)
                half[tail, STACK] = m
                tail += 1


@njit(cache=True)
def place_via(link, gmem, face, half, board, cnt, h):
    """Lay the neighbour across half-edge h (and its kept group) onto its forced cell."""
    j, c, r = forced(link, face, cnt, h)
    place_group(link, gmem, face, half, board, cnt, j, c, r, h >> 2)


@inline
def entry(link, face, cnt, m):
    """The face through which m's kept group hangs in the tree (m itself when alone)."""
    if cnt[C_CONSTRAINED] == 0:
        return m
    while face[m, PAR] >= 0:
        p = face[m, PAR]
        kept = False
        for k in range(4):
            if link[m, NB, k] == p and link[m, EDGE, k] == KEEP:
                kept = True
        if not kept:
            break
        m = p
    return m


@njit(cache=True)
def remove_subtree(link, gmem, face, half, board, cnt, m):
    """Remove face m and everything hanging from it; return the count removed."""
    half[0, STACK] = m
    top = 1
    n = 0
    while top > 0:
        top -= 1
        f = half[top, STACK]
        for k in range(4):
            g = link[f, NB, k]
            if face[g, POS] >= 0 and face[g, PAR] == f and top < face.shape[0]:
                half[top, STACK] = g
                top += 1
        unplace(link, gmem, face, half, board, cnt, f)
        n += 1
    return n


@inline
def _meets(link, face, cnt, u, e):
    # Whether u's neighbour across edge e lies where a fold across e would lay it.
    z = link[u, NB, e]
    if face[z, POS] < 0:
        return False
    s = (e + face[u, ROT]) & 3
    return face[z, POS] == face[u, POS] + cnt[C_OFF + s] and face[z, ROT] == ((s + 2 - link[u, NE, e]) & 3)


@njit(cache=True)
def rehang(link, face, half, cnt, m, limit):
    """Shrink m's subtree without moving a face: re-hang its branches elsewhere.

    A fold between faces that meet in the plane is a fold whether or not it is
    a tree edge, so the layout, the seams and the placeable set stay as they
    are.  When a face u below m meets a face z outside m's subtree, the branch
    holding u is turned to hang from u, and u from z.  Subtrees over ``limit``
    faces are left alone (the walk costs their size).  Without constraints
    only: kept groups hang from their entry face.
    """
    if cnt[C_CONSTRAINED]:
        return
    for _ in range(4):  # at most one pass per child of m
        cnt[C_MARK] += 1
        mark = cnt[C_MARK]
        half[0, STACK] = m  # breadth first, so the walk lists the subtree in STACK
        face[m, MARK] = mark
        head = 0
        tail = 1
        while head < tail:
            a = half[head, STACK]
            head += 1
            for k in range(4):
                g = link[a, NB, k]
                if face[g, POS] >= 0 and face[g, PAR] == a:
                    if tail >= limit:
                        return
                    face[g, MARK] = mark
                    half[tail, STACK] = g
                    tail += 1
        found = False
        for t in range(1, tail):
            u = half[t, STACK]
            for e in range(4):
                z = link[u, NB, e]
                if face[z, MARK] == mark or not _meets(link, face, cnt, u, e):
                    continue
                # Reverse the path from u up to m's child, then hang u from z.
                a = u
                p = z
                while a != m:
                    up = face[a, PAR]
                    _log(face, half, cnt, a)
                    face[a, PAR] = p
                    p = a
                    a = up
                found = True
                break
            if found:
                break
        if not found:
            return


@njit(cache=True)
def subtree_size(link, face, half, m, i, cap):
    """Size of m's subtree, or cap + 1 when it is larger or holds face i (-1: none).

    Bounded by cap, unlike a walk up from i, which costs the depth of the tree.
    """
    half[0, STACK] = m
    top = 1
    n = 0
    while top > 0:
        top -= 1
        f = half[top, STACK]
        n += 1
        if f == i or n > cap:
            return cap + 1
        for k in range(4):
            g = link[f, NB, k]
            if face[g, POS] >= 0 and face[g, PAR] == f and top < face.shape[0]:
                half[top, STACK] = g
                top += 1
    return n


@inline
def in_subtree(face, i, m):
    """Whether face i hangs (directly or not) from face m."""
    a = i
    while a >= 0:
        if a == m:
            return True
        a = face[a, PAR]
    return False


@njit(cache=True)
def refresh(link, gmem, face, half, board, cnt):
    """Re-check every half-edge that lays an unplaced face."""
    f4 = 4 * face.shape[0]
    for t in range(cnt[C_NFREE]):
        j = half[f4 + t, CL]
        for k in range(4):
            update(link, gmem, face, half, board, cnt, 4 * link[j, NB, k] + link[j, NE, k])


@njit(cache=True)
def restore(face, half, board, cnt, saved):
    """Lay out a saved complete net (columns POS, ROT, PAR); the placeable set ends empty."""
    f = face.shape[0]
    for j in range(f):
        if face[j, POS] >= 0:
            board[face[j, POS]] = -1
    for j in range(f):
        face[j, POS] = saved[j, 0]
        face[j, ROT] = saved[j, 1]
        face[j, PAR] = saved[j, 2]
        if face[j, POS] >= 0:
            board[face[j, POS]] = j
    for t in range(cnt[C_NCAND]):
        half[half[t, CL], CP] = -1
    for t in range(cnt[C_NFREE]):
        half[4 * f + half[4 * f + t, CL], CP] = -1
    cnt[C_NCAND] = 0
    cnt[C_UNPLACED] = 0
    cnt[C_NFREE] = 0


@njit(cache=True)
def undo(link, gmem, face, half, board, cnt):
    """Put every face the current move touched back where it was before the move."""
    cnt[C_LOGGING] = 0
    n = cnt[C_NLOG]
    move = cnt[C_MOVE]
    for t in range(n):
        j = half[t, LOG]
        if face[j, POS] >= 0:
            unplace(link, gmem, face, half, board, cnt, j)
    # Every face outside the log kept its place, and so did its ancestors; put
    # the logged ones back parents first.
    for t in range(n):
        j = half[t, LOG]
        if face[j, LPOS] < 0 or face[j, POS] >= 0:
            continue
        top = 0
        a = j
        while a >= 0 and face[a, POS] < 0 and face[a, STAMP] == move and face[a, LPOS] >= 0 \
                and top < face.shape[0]:
            half[top, STACK] = a
            top += 1
            a = face[a, LPAR]
        for u in range(top - 1, -1, -1):
            g = half[u, STACK]
            place(link, gmem, face, half, board, cnt, g, face[g, LPOS], face[g, LROT], face[g, LPAR])
    cnt[C_NLOG] = 0


@njit(cache=True)
def exclude_unplaced(link, gmem, face, half, board, cnt):
    """Leave the unplaced faces out for good: the placed ones become a whole piece."""
    f4 = 4 * face.shape[0]
    for t in range(cnt[C_NFREE]):
        j = half[f4 + t, CL]
        face[j, POS] = -3
        half[f4 + j, CP] = -1
    cnt[C_NFREE] = 0
    cnt[C_UNPLACED] = 0
    t = 0
    while t < cnt[C_NCAND]:
        h = half[t, CL]
        update(link, gmem, face, half, board, cnt, h)
        if half[h, CP] == t:
            t += 1


@njit(cache=True)
def track_seams(link, face, half, board, cnt):
    """Start keeping the list of seams without tab room; returns their count."""
    for t in range(cnt[C_NBAD]):
        half[half[t, SL], SP] = -1
    cnt[C_NBAD] = 0
    cnt[C_TRACK] = 1
    for a in range(face.shape[0]):
        if face[a, POS] >= 0:
            for k in range(4):
                seam_update(link, face, half, board, cnt, 4 * a + k)
    return cnt[C_NBAD]
