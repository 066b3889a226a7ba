"""Polycube enumeration: OEIS counts, one polycube per class, a fixed order."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from voxfab.census import canonical_cells, count_free, polycube_levels, polycubes

# OEIS A000162 (up to rotation) and A038119 (up to rotation and reflection), n = 1..8.
FREE = [1, 1, 2, 8, 29, 166, 1023, 6922]
FREE_MIRROR = [1, 1, 2, 7, 23, 112, 607, 3811]


def test_counts_match_oeis_up_to_8() -> None:
    got = [count_free(n, forms) for n, forms in polycube_levels(8)]
    assert [a for a, _ in got] == FREE
    assert [b for _, b in got] == FREE_MIRROR


def _key(cells: np.ndarray) -> tuple:
    """Canonical key by brute force, independent of the enumeration: least sorted cell tuple over 24 rotations."""
    best = None
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1, -1), repeat=3):
            m = np.zeros((3, 3), dtype=int)
            for r, (c, s) in enumerate(zip(perm, signs)):
                m[r, c] = s
            if round(np.linalg.det(m)) != 1:
                continue
            t = cells @ m.T
            t = t - t.min(axis=0)
            k = tuple(sorted(map(tuple, t.tolist())))
            best = k if best is None or k < best else best
    return best


def test_every_polycube_of_6_is_distinct_connected_and_listed_in_canonical_form() -> None:
    shapes = [c for n, _, c in polycubes(6) if n == 6]
    assert len(shapes) == 166
    keys = {_key(c) for c in shapes}
    assert len(keys) == 166  # no two the same up to rotation
    for c in shapes:
        assert np.array_equal(canonical_cells(c), c)
        cells = set(map(tuple, c.tolist()))
        seen, todo = {next(iter(cells))}, [next(iter(cells))]
        while todo:  # face-connected
            x, y, z = todo.pop()
            for d in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
                q = (x + d[0], y + d[1], z + d[2])
                if q in cells and q not in seen:
                    seen.add(q)
                    todo.append(q)
        assert seen == cells


def test_the_order_is_fixed_and_a_rotated_copy_has_the_same_form() -> None:
    first = [(n, i, c.tolist()) for n, i, c in polycubes(5)]
    again = [(n, i, c.tolist()) for n, i, c in polycubes(5)]
    assert first == again
    rng = np.random.default_rng(3)
    for _, _, c in first[-10:]:
        c = np.array(c)
        turned = c[:, [2, 0, 1]] * np.array([1, -1, -1]) + rng.integers(-5, 5, 3)  # a proper rotation, shifted
        assert canonical_cells(turned).tolist() == c.tolist()


def test_a_bad_size_is_refused_in_one_line() -> None:
    with pytest.raises(ValueError, match="from 1 to"):
        list(polycube_levels(0))
