"""Array helpers that numpy has, without what numpy loads for them on first use."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def unique(values: npt.ArrayLike, axis: int | None = None) -> np.ndarray:
    """``np.unique(values, axis=axis)``: the sorted distinct values (or rows, ``axis=0``).

    Asked for no more than the values, ``np.unique`` first checks for a masked array, which
    loads numpy.ma: about 8 ms of the start of a command that draws a small net.  Asking for
    the counts too takes its sorting path, which gives the same values.
    """
    return np.unique(values, axis=axis, return_counts=True)[0]
