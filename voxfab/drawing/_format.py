"""Deterministic number formatting shared by the text-based writers."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def numbers(values: npt.ArrayLike, *, decimals: int = 4) -> list[str]:
    """Shortest text of each value rounded to ``decimals`` places (no ``-0``)."""
    v = np.round(np.asarray(values, dtype=np.float64).ravel(), decimals) + 0.0
    out = []
    for x in v.tolist():
        s = repr(x)
        out.append(s[:-2] if s.endswith(".0") else s)
    return out


def polyline_text(
    points: npt.NDArray[np.float64],
    offsets: npt.NDArray[np.int64],
    first: npt.ArrayLike,
    rest: npt.ArrayLike,
    end: npt.ArrayLike,
    *,
    decimals: int = 3,
) -> str:
    """Text of many polylines from per-polyline templates, formatted in one pass.

    Parameters
    ----------
    points : (P, 2) float ndarray
        All vertices.
    offsets : (S + 1,) int ndarray
        Polyline ``i`` is ``points[offsets[i]:offsets[i + 1]]``.
    first, rest : str or (S,) str array_like
        Template of the first and of the following vertices of each polyline,
        each holding two ``%s`` slots for x and y.
    end : str or (S,) str array_like
        Text after the last vertex of each polyline.
    decimals : int
        Decimals of every coordinate.

    Returns
    -------
    str
    """
    s = offsets.size - 1
    if s == 0:
        return ""
    counts = np.diff(offsets)
    owner = np.repeat(np.arange(s), counts)
    tpl = np.asarray(np.broadcast_to(np.asarray(rest, dtype=object), (s,)))[owner].astype(object)
    tpl[offsets[:-1]] = np.broadcast_to(np.asarray(first, dtype=object), (s,))
    last = offsets[1:] - 1
    tpl[last] = tpl[last] + np.broadcast_to(np.asarray(end, dtype=object), (s,))
    fmt = f"%.{decimals}f"
    template = "".join(tpl.tolist()).replace("%s", fmt)
    values = np.round(points, decimals) + 0.0
    return template % tuple(values.ravel().tolist())
