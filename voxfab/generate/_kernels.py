"""Compiled loops (numba) of the growth generator.

Randomness comes from a splitmix64 stream seeded by the caller, so a shape
depends only on its seed (never on numba's or numpy's global state) and the
same seed gives the same shape on every machine.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["grow"]

_MASK = 0xFFFFFFFFFFFFFFFF


@njit(cache=True, nogil=True)
def _next(state: np.ndarray) -> np.uint64:
    """splitmix64: advance ``state[0]`` and return 64 random bits."""
    state[0] = state[0] + np.uint64(0x9E3779B97F4A7C15)
    z = state[0]
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


@njit(cache=True, nogil=True)
def _below(state: np.ndarray, n: int) -> int:
    """A random integer in ``[0, n)`` (the modulo bias is below 2**-50 for n < 2**14)."""
    return np.int64(_next(state) % np.uint64(n))


@njit(cache=True, nogil=True)
def _push_neighbours(cell: int, side: int, filled: np.ndarray, front: np.ndarray, size: int) -> int:
    x = cell // (side * side)
    y = (cell // side) % side
    z = cell % side
    if x > 0 and not filled[cell - side * side]:
        front[size] = cell - side * side
        size += 1
    if x < side - 1 and not filled[cell + side * side]:
        front[size] = cell + side * side
        size += 1
    if y > 0 and not filled[cell - side]:
        front[size] = cell - side
        size += 1
    if y < side - 1 and not filled[cell + side]:
        front[size] = cell + side
        size += 1
    if z > 0 and not filled[cell - 1]:
        front[size] = cell - 1
        size += 1
    if z < side - 1 and not filled[cell + 1]:
        front[size] = cell + 1
        size += 1
    return size


@njit(cache=True, nogil=True)
def grow(seed: np.uint64, volume: int, side: int, wander: float) -> np.ndarray:
    """Grow one face-connected shape of ``volume`` voxels that spans ``side`` along z.

    First a spine: a lattice walk from the bottom layer to the top one that steps
    up, or sideways with probability ``wander`` (never more sideways steps than
    the volume allows).  Then Eden growth: a random empty face neighbour of the
    shape is filled until the volume is reached.  A candidate is drawn from a list
    that holds a cell once per filled neighbour, so cells in hollows fill sooner
    and the surface stays compact but irregular.

    Returns
    -------
    (side**3,) bool ndarray
        The shape raveled in C order ``[x, y, z]``.
    """
    state = np.empty(1, dtype=np.uint64)
    state[0] = seed
    n = side * side * side
    filled = np.zeros(n, dtype=np.bool_)
    front = np.empty(6 * volume + 6 * side, dtype=np.int64)
    x = _below(state, side)
    y = _below(state, side)
    z = 0
    count = 0
    size = 0
    threshold = np.uint64(int(wander * 4294967296.0))
    while True:
        cell = (x * side + y) * side + z
        if not filled[cell]:
            filled[cell] = True
            count += 1
        if z == side - 1:
            break
        spare = volume - count - (side - 1 - z)
        if spare > 0 and (_next(state) >> np.uint64(32)) < threshold:
            d = _below(state, 4)
            if d == 0 and x > 0:
                x -= 1
            elif d == 1 and x < side - 1:
                x += 1
            elif d == 2 and y > 0:
                y -= 1
            elif d == 3 and y < side - 1:
                y += 1
        else:
            z += 1
    for cell in range(n):
        if filled[cell]:
            size = _push_neighbours(cell, side, filled, front, size)
    while count < volume and size > 0:
        i = _below(state, size)
        cell = front[i]
        size -= 1
        front[i] = front[size]
        if filled[cell]:
            continue
        filled[cell] = True
        count += 1
        if size + 6 > front.shape[0]:
            # Compact the list: drop the cells filled meanwhile (rare, bounded growth).
            k = 0
            for j in range(size):
                if not filled[front[j]]:
                    front[k] = front[j]
                    k += 1
            size = k
        size = _push_neighbours(cell, side, filled, front, size)
    return filled


@njit(cache=True, nogil=True)
def smallest_orientation(flat: np.ndarray, shape: np.ndarray, moves: np.ndarray) -> np.ndarray:
    """The lexicographically smallest C-order bit sequence of a grid over ``moves``.

    ``flat`` is the grid raveled in C order, ``shape`` its shape.  ``moves[m]`` =
    ``(p0, p1, p2, f0, f1, f2)``: output axis ``a`` reads input axis ``p_a``, reversed
    when ``f_a`` is 1 (``np.transpose`` then ``np.flip``).  All moves must give the
    same output shape.  A candidate is compared with the best so far while it is
    walked (as a start offset and three signed strides), and dropped at its first
    larger bit.
    """
    stride = np.empty(3, dtype=np.int64)
    stride[2] = 1
    stride[1] = shape[2]
    stride[0] = shape[1] * shape[2]
    n0, n1, n2 = shape[moves[0, 0]], shape[moves[0, 1]], shape[moves[0, 2]]
    best = np.empty(n0 * n1 * n2, dtype=np.uint8)
    have = False
    for m in range(moves.shape[0]):
        start = 0
        steps = np.empty(3, dtype=np.int64)
        for a in range(3):
            s = stride[moves[m, a]]
            if moves[m, 3 + a]:
                start += (shape[moves[m, a]] - 1) * s
                steps[a] = -s
            else:
                steps[a] = s
        smaller = not have
        k = 0
        aborted = False
        for a in range(n0):
            oa = start + a * steps[0]
            for b in range(n1):
                ob = oa + b * steps[1]
                for c in range(n2):
                    bit = flat[ob + c * steps[2]]
                    if not smaller:
                        if bit > best[k]:
                            aborted = True
                            break
                        if bit < best[k]:
                            smaller = True
                    if smaller:
                        best[k] = bit
                    k += 1
                if aborted:
                    break
            if aborted:
                break
        have = True
    return best
