"""Canonical keys: equal shapes (up to translation, optionally symmetry) share one key."""

from __future__ import annotations

import hashlib

import numpy as np
import numpy.typing as npt

from ._ops import _apply_move, _rotation_moves, crop, mirror


def _key_bytes(g: np.ndarray) -> bytes:
    return np.array(g.shape, dtype="<u2").tobytes() + np.packbits(g.ravel()).tobytes()


def canonical_key(grid: npt.ArrayLike, *, symmetric: bool = False) -> str:
    """Return a sha256 hex key of the shape up to translation.

    With ``symmetric`` the key is also invariant under the 48 symmetries of the
    cube (rotations and reflections): the smallest of the 48 encodings is hashed.
    """
    g = crop(grid)
    if symmetric:
        # The encoding starts with the grid's shape, so only the orientations with
        # the smallest shape can win: encode just those.
        candidates = [g, mirror(g, "x")]
        smallest = tuple(sorted(g.shape))
        data = min(
            _key_bytes(_apply_move(c, move))
            for c in candidates
            for move in _rotation_moves()
            if tuple(c.shape[a] for a in move[0]) == smallest
        )
    else:
        data = _key_bytes(g)
    return hashlib.sha256(data).hexdigest()
