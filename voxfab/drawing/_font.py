"""A single-stroke font for seam labels and titles on cutting and engraving layers.

Glyphs are polylines on a 4 × 6 grid (cap height 6, baseline 0), drawn with one
pass of the pen or laser, so shops never need our fonts installed.  Letters are
upper case only; lower case maps to upper case and any other character to ``?``.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import numpy.typing as npt

from ._polylines import Polylines

#: Glyph box: width and cap height in font units; the advance adds a gap of 2.
GLYPH_WIDTH = 4.0
CAP_HEIGHT = 6.0
ADVANCE = 6.0

# Strokes separated by ";", points "x,y" separated by spaces.
_GLYPHS: dict[str, str] = {
    "0": "0.5,1 0.5,5 1.5,6 2.5,6 3.5,5 3.5,1 2.5,0 1.5,0 0.5,1; 1,1.5 3,4.5",
    "1": "1,5 2,6 2,0; 1,0 3,0",
    "2": "0,5 1,6 3,6 4,5 4,4 0,0 4,0",
    "3": "0,5 1,6 3,6 4,5 4,4 3,3 1.5,3; 3,3 4,2 4,1 3,0 1,0 0,1",
    "4": "3,0 3,6 0,2 4,2",
    "5": "4,6 0,6 0,3.5 3,3.5 4,2.5 4,1 3,0 0,0",
    "6": "3.5,6 1,6 0,5 0,1 1,0 3,0 4,1 4,2.5 3,3.5 0,3.5",
    "7": "0,6 4,6 1.5,0",
    "8": "1,3 0,4 0,5 1,6 3,6 4,5 4,4 3,3 1,3 0,2 0,1 1,0 3,0 4,1 4,2 3,3",
    "9": "4,2.5 1,2.5 0,3.5 0,5 1,6 3,6 4,5 4,1 3,0 0.5,0",
    "A": "0,0 0,4 2,6 4,4 4,0; 0,2.5 4,2.5",
    "B": "0,0 0,6 3,6 4,5 4,4 3,3 0,3; 3,3 4,2 4,1 3,0 0,0",
    "C": "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1",
    "D": "0,0 0,6 3,6 4,5 4,1 3,0 0,0",
    "E": "4,6 0,6 0,0 4,0; 0,3 3,3",
    "F": "4,6 0,6 0,0; 0,3 3,3",
    "G": "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1 4,3 2,3",
    "H": "0,0 0,6; 4,0 4,6; 0,3 4,3",
    "I": "1,6 3,6; 2,6 2,0; 1,0 3,0",
    "J": "4,6 4,1 3,0 1,0 0,1",
    "K": "0,0 0,6; 4,6 0,2; 1.3,3.3 4,0",
    "L": "0,6 0,0 4,0",
    "M": "0,0 0,6 2,3 4,6 4,0",
    "N": "0,0 0,6 4,0 4,6",
    "O": "1,0 3,0 4,1 4,5 3,6 1,6 0,5 0,1 1,0",
    "P": "0,0 0,6 3,6 4,5 4,4 3,3 0,3",
    "Q": "1,0 3,0 4,1 4,5 3,6 1,6 0,5 0,1 1,0; 2.5,1.5 4,0",
    "R": "0,0 0,6 3,6 4,5 4,4 3,3 0,3; 2,3 4,0",
    "S": "4,5 3,6 1,6 0,5 0,4 1,3 3,3 4,2 4,1 3,0 1,0 0,1",
    "T": "0,6 4,6; 2,6 2,0",
    "U": "0,6 0,1 1,0 3,0 4,1 4,6",
    "V": "0,6 2,0 4,6",
    "W": "0,6 1,0 2,4 3,0 4,6",
    "X": "0,0 4,6; 0,6 4,0",
    "Y": "0,6 2,3 4,6; 2,3 2,0",
    "Z": "0,6 4,6 0,0 4,0",
    ".": "1.5,0 2.5,0 2.5,1 1.5,1 1.5,0",
    "-": "0.5,3 3.5,3",
    "_": "0,0 4,0",
    ":": "1.5,0 2.5,0 2.5,1 1.5,1 1.5,0; 1.5,3 2.5,3 2.5,4 1.5,4 1.5,3",
    "/": "0,0 4,6",
    "=": "0.5,2 3.5,2; 0.5,4 3.5,4",
    "+": "2,1 2,5; 0,3 4,3",
    "(": "3,6 1.5,4.5 1.5,1.5 3,0",
    ")": "1,6 2.5,4.5 2.5,1.5 1,0",
    "?": "0,5 1,6 3,6 4,5 4,4 2,2.5 2,1.5; 1.5,0 2.5,0 2.5,0.6 1.5,0.6 1.5,0",
    " ": "",
}


def _parse(spec: str) -> tuple[npt.NDArray[np.float64], ...]:
    strokes = []
    for stroke in spec.split(";"):
        pts = [tuple(float(v) for v in p.split(",")) for p in stroke.split()]
        if pts:
            strokes.append(np.array(pts, dtype=np.float64))
    return tuple(strokes)


GLYPHS: dict[str, tuple[npt.NDArray[np.float64], ...]] = {c: _parse(s) for c, s in _GLYPHS.items()}


def glyph_for(char: str) -> str:
    """The glyph drawn for ``char``: itself, its upper case, or ``?``."""
    if char in GLYPHS:
        return char
    up = char.upper()
    return up if up in GLYPHS else "?"


def text_width(text: str, height: float, advance: float = ADVANCE) -> float:
    """Width in mm of ``text`` drawn at cap ``height`` mm (without trailing gap), ``advance`` font units a character."""
    n = len(text)
    if n == 0:
        return 0.0
    return ((n - 1) * advance + GLYPH_WIDTH) * height / CAP_HEIGHT


@cache
def _local(text: str, advance: float = ADVANCE) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """Points (font units) and stroke lengths of ``text`` laid out from x = 0."""
    pts: list[npt.NDArray[np.float64]] = []
    lengths: list[int] = []
    for i, ch in enumerate(text):
        for stroke in GLYPHS[glyph_for(ch)]:
            pts.append(stroke + (i * advance, 0.0))
            lengths.append(len(stroke))
    if not pts:
        return np.zeros((0, 2)), np.zeros(0, dtype=np.int64)
    return np.concatenate(pts), np.array(lengths, dtype=np.int64)


def text_polylines(
    texts: list[str],
    origins: npt.ArrayLike,
    directions: npt.ArrayLike,
    height: float | npt.ArrayLike,
    *,
    center: bool = False,
    advance: float = ADVANCE,
) -> Polylines:
    """Lay out many strings as single-stroke polylines at once.

    Parameters
    ----------
    texts : list of str
        One string per instance.
    origins : (N, 2) array_like
        Baseline start (or baseline centre with ``center``) of each string, mm.
    directions : (N, 2) array_like
        Unit reading direction of each string; "up" is its left normal.
    height : float or (N,) array_like
        Cap height in mm.
    center : bool
        Centre each string horizontally on its origin.
    advance : float
        Font units from one character to the next (the glyphs are 4 wide):
        seam labels set their characters closer than the gap between labels.

    Returns
    -------
    Polylines
        Open strokes in mm.
    """
    n = len(texts)
    origins = np.asarray(origins, dtype=np.float64).reshape(n, 2)
    directions = np.asarray(directions, dtype=np.float64).reshape(n, 2)
    scale = np.broadcast_to(np.asarray(height, dtype=np.float64), (n,)) / CAP_HEIGHT
    local = [_local(t, advance) for t in texts]
    counts = np.array([p.shape[0] for p, _ in local], dtype=np.int64)
    if counts.sum() == 0:
        return Polylines.empty()
    pts = np.concatenate([p for p, _ in local])
    lengths = np.concatenate([s for _, s in local])
    inst = np.repeat(np.arange(n), counts)
    shift = np.array([((len(t) - 1) * advance + GLYPH_WIDTH) / 2 if center and t else 0.0 for t in texts])
    x = (pts[:, 0] - shift[inst]) * scale[inst]
    y = pts[:, 1] * scale[inst]
    d = directions[inst]
    up = np.stack([-d[:, 1], d[:, 0]], axis=1)
    world = origins[inst] + x[:, None] * d + y[:, None] * up
    offsets = np.concatenate([[0], np.cumsum(lengths)])
    return Polylines(world, offsets, np.zeros(lengths.size, dtype=bool))
