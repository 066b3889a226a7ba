"""Explicit generatrices ``x = g(y)``: no bounding term, from the library, recipes and the CLI."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.cli._main import main
from voxfab.digitize import polyline_curve, revolution, revolution_field
from voxfab.digitize._revolution import explicit_radius
from voxfab.errors import InvalidShapeError
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import well_formed_reasons

WAVY = "x = 0.6 + 0.3*sin(3*y)"


def test_explicit_radius_is_recognised():
    assert explicit_radius(WAVY) is not None
    assert explicit_radius("x = 2") is not None
    assert explicit_radius(" x=1+y^2 ") is not None
    # x on the right side, other left sides and files are not explicit
    assert explicit_radius("x = 1 - x*y") is None
    assert explicit_radius("x^2 + y^2 = 1") is None
    assert explicit_radius("2*x = y") is None
    assert explicit_radius("gen.json") is None


@pytest.mark.parametrize("k", [0, 1, 2])
def test_explicit_equals_the_bounded_region_voxel_for_voxel(k):
    # The explicit form is exactly the region under g(y) between the two heights.
    a = revolution_field("x^2 + y^2 - 1", WAVY, z_range=[-0.5, 2.0])
    b = revolution_field("x^2 + y^2 - 1", "max(x - (0.6 + 0.3*sin(3*y)), -0.5 - y, y - 2)")
    origin, step = np.array([-1.13, -1.07, -0.71]), np.full(3, 0.1)
    sa, ia = a.digitize((25, 25, 31), origin, step, k)
    sb, ib = b.digitize((25, 25, 31), origin, step, k)
    assert sa.sum() > 500
    assert np.array_equal(sa, sb) and np.array_equal(ia, ib)


def test_explicit_generatrix_makes_a_well_formed_wavy_solid():
    g = revolution("x^2 + y^2 - 1", WAVY)
    assert well_formed_reasons(g) == []
    # default heights -1..1: taller (2) than wide (<= 1.8), so z spans the grid
    zs = np.flatnonzero(g.any(axis=(0, 1)))
    assert len(zs) == 25
    # the radius follows g: widest where sin(3y) = 1, i.e. y = pi/6 -> above the middle
    widths = g.sum(axis=(0, 1))
    assert int(np.argmax(widths)) > 12


def test_sphere_from_its_explicit_half_circle():
    assert revolution("x^2 + y^2 - 1", "x = sqrt(1 - y^2)").sum() == revolution("x^2 + y^2 - 1", "x^2 + y^2 - 1").sum()


def test_explicit_generatrix_with_a_curve_of_several_components():
    two_squares = polyline_curve([
        np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]),
        np.array([[0, 2], [1, 2], [1, 3], [0, 3], [0, 2]]),
    ])
    g = revolution(two_squares, WAVY, mode="surface")
    assert g.any() and g.shape == (25, 25, 25)


def test_explicit_generatrix_errors():
    with pytest.raises(InvalidShapeError, match="never positive"):
        revolution("x^2 + y^2 - 1", "x = -1 - y^2")
    with pytest.raises(InvalidShapeError, match="z_range: only an explicit generatrix"):
        revolution("x^2 + y^2 - 1", "x^2 + y^2 - 1", z_range=[0, 1])
    with pytest.raises(InvalidShapeError, match="low < high"):
        revolution("x^2 + y^2 - 1", WAVY, z_range=[1, 0])


def test_explicit_generatrix_from_a_recipe_and_the_cli(tmp_path, capsys):
    recipe = tmp_path / "wavy.toml"
    recipe.write_text(
        'name = "wavy"\n[source]\nmaker = "revolution"\n'
        f'curve = "x^2 + y^2 = 1"\ngeneratrix = "{WAVY}"\nz_range = [-1.0, 1.0]\n'
    )
    shape = make_shape(load_recipe(recipe))
    assert np.array_equal(shape.grid, revolution("x^2 + y^2 - 1", WAVY))
    assert main(["build", str(recipe), "-o", str(tmp_path / "out")]) == 0
    built = np.load(tmp_path / "out" / "wavy" / "shape.npy")
    assert np.array_equal(built, shape.grid)


def test_explicit_generatrix_written_as_on_paper():
    # The issue's own spelling, with products side by side, gives the same solid.
    assert np.array_equal(revolution("x^2 + y^2 = 1", "x = 0.6 + 0.3 sin(3y)"), revolution("x^2 + y^2 - 1", WAVY))
