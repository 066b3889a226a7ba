"""Deterministic text formatting of number rows."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def format_rows(rows: npt.NDArray, template: str) -> str:
    """``template % row`` for every row, joined; floats as ``%.9g`` keep float64 mm to 1 nm."""
    return "".join(template % tuple(r) for r in np.asarray(rows).tolist())
