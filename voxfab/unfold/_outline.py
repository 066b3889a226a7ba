"""Net outlines as seen on the sheet, the same under the 8 rotations and mirrors."""

from __future__ import annotations

import numpy as np

from ._net import Net

#: The 8 symmetries of the square grid as 2x2 integer matrices.
_SYMMETRIES = [np.array(m, dtype=np.int64) for m in (
    [[1, 0], [0, 1]], [[0, -1], [1, 0]], [[-1, 0], [0, -1]], [[0, 1], [-1, 0]],
    [[-1, 0], [0, 1]], [[1, 0], [0, -1]], [[0, 1], [1, 0]], [[0, -1], [-1, 0]],
)]


def outline_key(net: Net) -> bytes:
    """A key equal for two nets exactly when their sheets look alike.

    What a sheet shows is the set of cells the faces cover and, between two
    covered cells side by side, whether the paper is folded or cut there.  The
    key is the smallest encoding of that picture over the 8 rotations and
    mirrors of the sheet, translated to the origin.
    """
    c2 = net.corners2d
    cells = c2.min(axis=1)
    # A fold lies on a cell side: the sum of its two end corners (its doubled
    # midpoint) names it, on the same doubled grid as the cell centres 2c + 1.
    i, j = net.folds[:, 0], net.folds[:, 1]
    shared = (c2[i][:, :, None, :] == c2[j][:, None, :, :]).all(axis=3).any(axis=2)
    folds = (c2[i] * shared[:, :, None]).sum(axis=1)
    best = None
    for m in _SYMMETRIES:
        # Cells map by their centres (2c + 1), fold midpoints as they are.
        centres = (2 * cells + 1) @ m.T
        fm = folds @ m.T
        shift = centres.min(axis=0) - 1
        # Cells and fold midpoints are each distinct: sorted scalar codes (x, y) -> x * span + y name them.
        a, b = centres - shift, fm - shift
        span = int(max(a.max(initial=0), b.max(initial=0))) + 1
        ka = np.sort(a[:, 0] * span + a[:, 1])
        kb = np.sort(b[:, 0] * span + b[:, 1])
        key = np.int64(a.shape[0]).tobytes() + np.int64(span).tobytes() + ka.tobytes() + kb.tobytes()
        if best is None or key < best:
            best = key
    return best
