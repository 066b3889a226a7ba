"""A seeded xorshift generator for the compiled search.

The kernels never touch a global generator: their state is one uint64 in an
array, so the same seed replays the same search on every machine.
"""

from __future__ import annotations

import numpy as np
from numba import njit


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
