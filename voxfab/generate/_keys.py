"""The symmetric canonical key of a cropped grid, compiled: the hot step of ``explore``.

It returns exactly :func:`voxfab.shape.canonical_key` ``(grid, symmetric=True)``:
the sha256 of the grid's shape and packed bits in the orientation, among the 48
cube symmetries giving the smallest shape, whose encoding is smallest.  The
shape's own function builds each of those orientations as an array; here they are
walked in one compiled loop that drops a candidate at its first larger bit.
"""

from __future__ import annotations

import functools
import hashlib

import numpy as np

from voxfab._shared.typing import BoolGrid

__all__ = ["symmetric_key"]


@functools.cache
def _moves() -> np.ndarray:
    """The 48 cube symmetries as rows ``(p0, p1, p2, f0, f1, f2)`` (see ``smallest_orientation``)."""
    from voxfab.shape._ops import _rotation_moves

    rows = []
    for perm, flips in _rotation_moves():
        for mirror in (False, True):
            # ``mirror(g, "x")`` first flips input axis 0 before the move: the output
            # axis that reads input axis 0 has its flip toggled.
            f = [1 if a in flips else 0 for a in range(3)]
            if mirror:
                f[perm.index(0)] ^= 1
            rows.append((*perm, *f))
    return np.array(rows, dtype=np.int64)


def symmetric_key(cropped: BoolGrid) -> str:
    """Return ``canonical_key(cropped, symmetric=True)`` for a grid cut to its bounding box."""
    from ._kernels import smallest_orientation

    g = np.ascontiguousarray(cropped, dtype=bool)
    shape = np.array(g.shape, dtype=np.int64)
    smallest = np.sort(shape)
    rows = _moves()
    # Only the orientations with the smallest shape can win: the encoding starts with the shape.
    keep = (shape[rows[:, :3]] == smallest).all(axis=1)
    bits = smallest_orientation(g.view(np.uint8).ravel(), shape, rows[keep])
    data = smallest.astype("<u2").tobytes() + np.packbits(bits).tobytes()
    return hashlib.sha256(data).hexdigest()
