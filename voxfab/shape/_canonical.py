"""Canonical keys: equal shapes (up to translation, optionally symmetry) share one key."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ._ops import _apply_move, _rotation_moves, bounding_box, mirror

if TYPE_CHECKING:
    from ._colour import VoxelColours


def _key_bytes(g: np.ndarray, palette: np.ndarray | None) -> bytes:
    """The encoding hashed: the size, the voxels' bits, then (coloured) each voxel's RGBA in C order."""
    filled = g != 0
    data = np.array(g.shape, dtype="<u2").tobytes() + np.packbits(filled.ravel()).tobytes()
    if palette is not None:
        data += palette[g[filled]].tobytes()
    return data


def canonical_key(grid: npt.ArrayLike, *, symmetric: bool = False, colours: VoxelColours | None = None) -> str:
    """Return a sha256 hex key of the shape up to translation.

    With ``symmetric`` the key is also invariant under the 48 symmetries of the
    cube (rotations and reflections): the smallest of the 48 encodings is hashed.
    With ``colours`` the RGBA of every voxel is part of the key (two shapes of the
    same voxels in other colours differ); an uncoloured shape's key is unchanged.
    """
    g = np.asarray(grid, dtype=bool)
    lo, hi = bounding_box(g)
    box = tuple(slice(a, b) for a, b in zip(lo, hi))
    # A coloured shape is encoded through its index grid, which moves like the bool one.
    cells = g[box] if colours is None else colours.index[box]
    palette = None if colours is None else colours.palette
    if symmetric:
        # The encoding starts with the grid's shape, so only the orientations with
        # the smallest shape can win: encode just those.
        candidates = [cells, mirror(cells, "x")]
        smallest = tuple(sorted(cells.shape))
        data = min(
            _key_bytes(_apply_move(c, move), palette)
            for c in candidates
            for move in _rotation_moves()
            if tuple(c.shape[a] for a in move[0]) == smallest
        )
    else:
        data = _key_bytes(cells, palette)
    import hashlib  # here, not at the top: it loads OpenSSL (3 ms), which a command keying no shape never needs

    return hashlib.sha256(data).hexdigest()
