"""Weighted focal-set shapes."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.digitize import fermat_weber, focal, focal_field, surface
from voxfab.errors import InvalidShapeError
from voxfab.shape import well_formed_reasons

from .test_flake import adjacency, tunnels


def test_one_focus_is_the_reference_sphere():
    fld = focal_field([[0.0, 0.0, 0.0]], None, 10.0)
    got = [int(fld.digitize((25,) * 3, np.full(3, -12.0), np.ones(3), k)[0].sum()) for k in range(3)]
    assert got == [1898, 1610, 1026]


def test_egg_has_the_analytic_ends_and_no_mirror_symmetry():
    foci, w = [[0, 0, -1], [0, 0, 1]], [1.0, 2.0]
    g = focal(foci, w, 5.0)
    assert well_formed_reasons(g) == []
    assert not np.array_equal(g, g[:, :, ::-1])
    # ends on the axis: (z + 1) + 2 (z - 1) = 5 -> z = 2; -(z + 1) - 2 (z - 1) = 5 -> z = -4/3
    s = focal(foci, w, 5.0, scale=6.0, size=25, mode="solid")
    z = np.flatnonzero(s.any(axis=(0, 1)))
    assert z[-1] - z[0] + 1 == round((2 + 4 / 3) * 6) + 1
    # equal weights: an ellipsoid, symmetric in z
    e = focal(foci, [1.0, 1.0], 3.0)
    assert np.array_equal(e, e[:, :, ::-1])


@pytest.mark.parametrize("k", [0, 1, 2])
def test_focal_surface_is_k_separating(k):
    fld = focal_field([[0, 0, -2.5], [0, 0, 2.5], [3, 0, 0]], [1.0, 2.0, 1.5], 22.0)
    surf, inside = fld.digitize((23, 23, 23), np.full(3, -11.0), np.ones(3), k)
    assert inside.sum() > 100
    assert not tunnels(surf, inside, k)
    g = focal([[0, 0, -2.5], [0, 0, 2.5], [3, 0, 0]], [1.0, 2.0, 1.5], 22.0, mode="surface", k=k)
    assert g.any() and not g[12, 12, 12]


def test_fermat_weber_minimum():
    # equal weights on a segment: the minimum is the segment length
    assert np.isclose(fermat_weber([[0, 0, 0], [4, 0, 0]], [1, 1]), 4.0)
    # a dominant weight: the minimum is at that focus
    assert np.isclose(fermat_weber([[0, 0, 0], [4, 0, 0], [0, 3, 0]], [10, 1, 1]), 7.0)


def test_4d_focal_slice():
    g = focal([[0, 0, 0, -1], [0, 0, 0, 1]], [1, 1], 4.0, at=0.5)
    assert g.shape == (25, 25, 25) and well_formed_reasons(g) == []


def test_bad_inputs_name_the_input():
    with pytest.raises(InvalidShapeError, match="^weights: every weight must be > 0"):
        focal([[0, 0, 0], [1, 0, 0]], [1.0, 0.0], 5.0)
    with pytest.raises(InvalidShapeError, match="^weights: expected 2 weights"):
        focal([[0, 0, 0], [1, 0, 0]], [1.0], 5.0)
    with pytest.raises(InvalidShapeError, match="^radius: 3 is not above the weighted Fermat-Weber minimum 4"):
        focal([[0, 0, 0], [4, 0, 0]], [1, 1], 3.0)
    with pytest.raises(InvalidShapeError, match="^foci"):
        focal([[0, 0]], None, 1.0)


def test_thin_surface_uses_the_flake_test():
    f = focal_field([[0, 0, 0]], None, 6.0).f
    assert np.array_equal(
        surface(f, (15,) * 3, 2, origin=(-7,) * 3),
        surface(lambda x, y, z: np.sqrt(x * x + y * y + z * z) - 6.0, (15,) * 3, 2, origin=(-7,) * 3),
    )
    assert adjacency(3, 2).sum() == 7
