"""Every polycube of n cubes once, up to rotation ("one-sided"), in a fixed order; the free ones counted too.

Canonical growth: the polycubes of n + 1 cubes are the canonical forms of the
polycubes of n cubes with one face neighbour added.  A polycube's canonical
form is the least, over the 24 rotations, of its sorted cell codes after
translation to the origin (code ``(x * B + y) * B + z`` with ``B = n``, so
every coordinate is a digit); two polycubes are the same up to rotation
exactly when their forms are equal.  Each level is kept as one sorted int array
of forms, so the same ``n`` always gives the same list in the same order, and
the whole growth is vectorised over chunks of candidates.

Counts, in the OEIS's words: one-sided polycubes (up to rotation, A000162)
1, 1, 2, 8, 29, 166, 1023, 6922, 48311, 346543, and free polycubes (up to
rotation and reflection, a mirror image counted as the same, A038119) 1, 1, 2,
7, 23, 112, 607, 3811, 25413, 178083.  The census lists the one-sided ones.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import numpy.typing as npt

from voxfab.shape import rotation_matrices

__all__ = ["MAX_CUBES", "canonical_cells", "count_free", "count_polycubes", "polycube_levels", "polycubes"]

#: The largest n enumerated: the level of 11 cubes holds 2.5 million forms (about 0.5 GB while it grows).
MAX_CUBES = 11

#: Candidates canonicalised at once: their 24 rotations take about 300 MB at n = 10 (int64 cells).
_CHUNK = 50_000


# The 24 proper rotations of the cube, as the shape package orders them.
_ROTATIONS = np.stack(rotation_matrices())
_MIRROR = np.diag([-1, 1, 1]).astype(np.int64)


def _lexmin_rows(codes: npt.NDArray[np.int32]) -> npt.NDArray[np.int32]:
    """For ``(m, r, n)`` codes sorted along the last axis, the lexicographically least of the ``r`` rows of each m."""
    m, r, n = codes.shape
    alive = np.ones((m, r), dtype=bool)
    big = np.iinfo(codes.dtype).max
    for j in range(n):
        col = np.where(alive, codes[:, :, j], big)
        alive &= col == col.min(axis=1, keepdims=True)
    return codes[np.arange(m), alive.argmax(axis=1)]


def _forms(cells: npt.NDArray[np.int64], base: int, *, mirror: bool = False) -> npt.NDArray[np.int32]:
    """Canonical forms ``(m, n)`` of ``(m, n, 3)`` cell arrays (coordinates may be negative)."""
    out = np.empty((cells.shape[0], cells.shape[1]), dtype=np.int32)
    for lo in range(0, cells.shape[0], _CHUNK):
        part = cells[lo:lo + _CHUNK]
        if mirror:
            part = part @ _MIRROR.T
        turned = np.einsum("rij,mnj->mrni", _ROTATIONS, part)  # (m, 24, n, 3)
        turned = turned - turned.min(axis=2, keepdims=True)
        codes = ((turned[..., 0] * base + turned[..., 1]) * base + turned[..., 2]).astype(np.int32)
        codes.sort(axis=2)
        out[lo:lo + _CHUNK] = _lexmin_rows(codes)
    return out


def _decode(forms: npt.NDArray[np.int32], base: int) -> npt.NDArray[np.int64]:
    """Cells ``(m, n, 3)`` of canonical forms."""
    f = forms.astype(np.int64)
    return np.stack([f // (base * base), (f // base) % base, f % base], axis=-1)


_STEPS = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.int64)


def _grow(forms: npt.NDArray[np.int32], n: int) -> npt.NDArray[np.int32]:
    """The sorted, distinct canonical forms of n + 1 cubes grown from the forms of n cubes."""
    cells = _decode(forms, n)  # (m, n, 3)
    m = cells.shape[0]
    found = []
    for lo in range(0, m, max(1, _CHUNK // (6 * n))):
        part = cells[lo:lo + max(1, _CHUNK // (6 * n))]
        k = part.shape[0]
        new = (part[:, :, None, :] + _STEPS[None, None, :, :]).reshape(k, 6 * n, 3)  # every face neighbour
        # A neighbour already in the polycube is no new cube.
        inside = (new[:, :, None, :] == part[:, None, :, :]).all(axis=3).any(axis=2)
        rows, slots = np.nonzero(~inside)
        grown = np.concatenate([part[rows], new[rows, slots][:, None, :]], axis=1)  # (c, n + 1, 3)
        found.append(np.unique(_forms(grown, n + 1), axis=0))
    return np.unique(np.concatenate(found), axis=0)


def polycube_levels(n_max: int) -> Iterator[tuple[int, npt.NDArray[np.int32]]]:
    """``(n, forms)`` for n = 1..n_max: every polycube of n cubes up to rotation, as sorted canonical forms."""
    if not isinstance(n_max, int) or isinstance(n_max, bool) or not 1 <= n_max <= MAX_CUBES:
        raise ValueError(f"n: expected a whole number of cubes from 1 to {MAX_CUBES}, got {n_max!r}")
    forms = np.zeros((1, 1), dtype=np.int32)
    yield 1, forms
    for n in range(1, n_max):
        forms = _grow(forms, n)
        yield n + 1, forms


def canonical_cells(cells: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The canonical cells ``(n, 3)`` of one polycube up to rotation (the census lists each polycube so)."""
    c = np.asarray(cells, dtype=np.int64).reshape(1, -1, 3)
    n = c.shape[1]
    return _decode(_forms(c, n), n)[0]


def count_polycubes(n: int, forms: npt.NDArray[np.int32]) -> tuple[int, int]:
    """``(one-sided, free)`` counts of the forms of n cubes: up to rotation (A000162), and up to rotation and
    reflection (A038119)."""
    cells = _decode(forms, n)
    mirrored = _forms(cells, n, mirror=True)
    # A chiral pair is one shape up to reflection: count each pair once by its lesser form.
    both = np.stack([forms, mirrored], axis=1)
    least = _lexmin_rows(both)
    return int(forms.shape[0]), int(np.unique(least, axis=0).shape[0])


#: The earlier name of :func:`count_polycubes`, whose first count is one-sided, not free.
count_free = count_polycubes


def polycubes(n_max: int) -> Iterator[tuple[int, int, npt.NDArray[np.int64]]]:
    """Stream ``(n, index, cells)`` for every polycube of 1..n_max cubes up to rotation, in the fixed order."""
    for n, forms in polycube_levels(n_max):
        for i, cells in enumerate(_decode(forms, n)):
            yield n, i, cells
