"""Fitting continuous shapes into the 25³ grid."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.digitize import implicit, implicit_field
from voxfab.digitize._fit import fit
from voxfab.errors import InvalidShapeError
from voxfab.shape import extents, well_formed_reasons


@pytest.mark.parametrize("mode", ["solid", "surface"])
@pytest.mark.parametrize(
    "expression",
    ["x^2 + y^2 + z^2 - 1", "(x/3)^2 + (y/2)^2 + z^2 - 1", "max(abs(x) - 2, max(abs(y) - 0.5, abs(z - 7) - 1.3))"],
)
def test_default_fit_is_well_formed(expression, mode):
    g = implicit(expression, mode=mode)
    assert g.shape == (25, 25, 25)
    assert max(extents(g)) == 25
    assert well_formed_reasons(g) == []


def test_grid_size_option():
    g = implicit("(x/3)^2 + (y/2)^2 + z^2 - 1", size=41)
    assert g.shape == (41,) * 3 and extents(g)[0] == 41


def test_explicit_scale():
    g = implicit("x^2 + y^2 + z^2 - 4", scale=3.0, size=25)
    # radius 2 at 3 voxels per unit: 13 voxels across (centre ± 6)
    assert extents(g) == (13, 13, 13)
    with pytest.raises(InvalidShapeError, match="^scale: at 20"):
        implicit("x^2 + y^2 + z^2 - 4", scale=20.0)


def test_loose_bounds_are_recentred():
    fld = implicit_field("x^2 + y^2 + (z - 3)^2 - 1", bounds=[-1, 1, -1, 1, -5, 4.5])
    assert well_formed_reasons(fit(fld)) == []


def test_bad_fit_options():
    fld = implicit_field("x^2 + y^2 + z^2 - 1")
    with pytest.raises(InvalidShapeError, match="^size"):
        fit(fld, size=1)
    with pytest.raises(InvalidShapeError, match="^mode: unknown choice"):
        fit(fld, mode="hollow")
    with pytest.raises(InvalidShapeError, match="^bounds"):
        implicit_field("x^2 + y^2 + z^2 - 1", bounds=[1, 0, 0, 1, 0, 1])
    with pytest.raises(InvalidShapeError, match="^expression: unknown name 'v'"):
        implicit("x^2 + v^2 - 1")
    with pytest.raises(InvalidShapeError, match="^k: expected an integer in 0..2"):
        fit(fld, k=3)
    assert np.any(fit(fld, k=2))


def test_center_fixes_the_placement():
    from voxfab.digitize import revolution

    opts = dict(k=0, mode="surface", size=25, scale=4.0)
    gen = "(x-2)^2 + y^2 - 0.64"
    base = revolution("x^2 + y^2 - 1", gen, center=[0.0, 0.0, 0.0], **opts)
    # moving the center by one voxel moves the shape by one voxel the other way, nothing else
    moved = revolution("x^2 + y^2 - 1", gen, center=[0.25, 0.0, -0.5], **opts)
    assert np.array_equal(moved[:-1, :, 2:], base[1:, :, :-2]) and not moved[-1].any()
    # the fitted (scale-only) path recentres each shape on its own box: a half torus lands elsewhere
    half_fixed = revolution("x^2 + y^2 - 1", gen, arc=[0, 180], center=[0.0, 0.0, 0.0], **opts)
    half_fitted = revolution("x^2 + y^2 - 1", gen, arc=[0, 180], **opts)
    assert np.all(half_fixed <= base)
    assert not np.all(half_fitted <= base)


def test_center_errors():
    fld = implicit_field("x^2 + y^2 + z^2 - 1")
    with pytest.raises(InvalidShapeError, match="needs scale"):
        fit(fld, center=[0, 0, 0])
    with pytest.raises(InvalidShapeError, match="center: expected 3 finite numbers"):
        fit(fld, scale=5.0, center=[0, 0])
    with pytest.raises(InvalidShapeError, match="center: expected 3 finite numbers"):
        fit(fld, scale=5.0, center=[0, 0, float("inf")])
    with pytest.raises(InvalidShapeError, match="reaches outside the 25-voxel grid"):
        fit(fld, scale=11.0, center=[1.0, 0, 0])
    with pytest.raises(InvalidShapeError, match="empty"):
        fit(fld, scale=5.0, center=[20.0, 0, 0], size=5)
