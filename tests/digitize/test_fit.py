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
