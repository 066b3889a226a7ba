"""The one seeding convention: explicit seeds, never numpy's global state."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError


def check_seed(seed: Any) -> int:
    """An int seed (Python's or numpy's) of at least 0, as an int; else :class:`InvalidShapeError`."""
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool):
        if seed < 0:
            raise InvalidShapeError(f"seed: expected an integer >= 0, got {seed}")
        return int(seed)
    raise InvalidShapeError(f"seed: expected an int or numpy Generator, got {type(seed).__name__}")


def as_rng(rng: np.random.Generator | int) -> np.random.Generator:
    """Return a Generator for ``rng`` (an int seed or a Generator)."""
    if isinstance(rng, np.random.Generator):
        return rng
    return np.random.default_rng(check_seed(rng))


_MASK = 0xFFFFFFFF
# The constants of numpy's SeedSequence (after M. E. O'Neill's seed_seq_fe): two hash multipliers and
# the mixer's.
_INIT_A, _MULT_A, _INIT_B, _MULT_B = 0x43B0D7E5, 0x931E8875, 0x8B51F9DD, 0x58F38DED
_MIX_L, _MIX_R = 0xCA01F9DD, 0x4973F715


def _words(entropy: int | Sequence[int]) -> list[int]:
    """The 32-bit words of ``entropy``, least significant first (a sequence: its items' words in turn)."""
    if isinstance(entropy, (list, tuple)):
        return [w for item in entropy for w in _words(item)]
    n = check_seed(entropy)
    out = [n & _MASK]
    while n > _MASK:
        n >>= 32
        out.append(n & _MASK)
    return out


def seed_state(entropy: int | Sequence[int]) -> int:
    """``numpy.random.SeedSequence(entropy).generate_state(1, numpy.uint64)[0]``, computed without numpy.random.

    The net search seeds each board this way; loading numpy.random (and the hashing it brings) costs
    about 9 ms, a twentieth of ``voxfab net`` on a small shape, which otherwise draws no random number
    from numpy.  ``entropy`` is a seed or a sequence of seeds, as SeedSequence takes them.
    """
    words = _words(entropy)
    h = _INIT_A

    def hashmix(value: int) -> int:
        nonlocal h
        value ^= h
        h = (h * _MULT_A) & _MASK
        value = (value * h) & _MASK
        return value ^ (value >> 16)

    def mix(x: int, y: int) -> int:
        r = (_MIX_L * x - _MIX_R * y) & _MASK
        return r ^ (r >> 16)

    pool = [hashmix(words[i] if i < len(words) else 0) for i in range(4)]
    for src in range(4):
        for dst in range(4):
            if src != dst:
                pool[dst] = mix(pool[dst], hashmix(pool[src]))
    for src in range(4, len(words)):
        for dst in range(4):
            pool[dst] = mix(pool[dst], hashmix(words[src]))
    h = _INIT_B
    state = 0
    for i in range(2):  # two 32-bit words make the 64-bit one, the low word first
        value = pool[i] ^ h
        h = (h * _MULT_B) & _MASK
        value = (value * h) & _MASK
        state |= (value ^ (value >> 16)) << (32 * i)
    return state
