"""Digital surfaces of revolution: sources, runs, 4D, errors."""

from __future__ import annotations

import json

import numpy as np
import pytest
from PIL import Image, ImageDraw
from scipy import ndimage

from voxfab.digitize import (
    Run,
    load_revolution_curve,
    revolution,
    revolution_field,
    slices,
    split_runs,
)
from voxfab.digitize._revolution import _runs_digitizer
from voxfab.errors import InvalidShapeError
from voxfab.shape import well_formed_reasons

from .test_flake import adjacency


def jaccard(a: np.ndarray, b: np.ndarray) -> float:
    return np.count_nonzero(a & b) / np.count_nonzero(a | b)


@pytest.fixture()
def sources(tmp_path):
    (tmp_path / "circle.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><circle cx="50" cy="50" r="20"/></svg>'
    )
    disk = Image.new("L", (81, 81), 255)
    ImageDraw.Draw(disk).ellipse((0, 0, 80, 80), fill=0)
    disk.save(tmp_path / "disk.png")
    (tmp_path / "cyl.json").write_text(json.dumps([[0, 0], [4, 0], [4, 10], [0, 10]]))
    Image.new("L", (40, 100), 0).save(tmp_path / "cyl.png")
    return tmp_path


CURVES = ["x^2 + y^2 - 1", "circle.svg", "disk.png"]
GENERATRICES = ["max(x - 4, abs(y - 5) - 5)", "cyl.json", "cyl.png"]


@pytest.mark.parametrize("curve", CURVES)
@pytest.mark.parametrize("generatrix", GENERATRICES)
def test_all_nine_source_combinations_make_the_same_cylinder(sources, curve, generatrix):
    ref = revolution(CURVES[0], GENERATRICES[0], base_dir=sources)
    got = revolution(curve, generatrix, base_dir=sources)
    assert well_formed_reasons(got) == []
    assert jaccard(got, ref) > 0.85, (curve, generatrix)


def test_torus_of_revolution_reproduces_the_reference_counts():
    fld = revolution_field("x^2 + y^2 - 1", "(x - 10)^2 + y^2 - 16")
    got = [int(fld.digitize((31, 31, 11), np.array([-15.0, -15, -5]), np.ones(3), k)[0].sum()) for k in range(3)]
    assert got == [2288, 1984, 1368]


def test_4d_sphere_of_revolution_reproduces_the_reference_counts():
    fld = revolution_field("x^2 + y^2 + z^2 - 1", "(x - 6)^2 + y^2 - 4")
    assert fld.ndim == 4
    org = np.array([-9.0, -9, -9, -3])
    got = [int(fld.digitize((19, 19, 19, 7), org, np.ones(4), k)[0].sum()) for k in range(4)]
    assert got == [9760, 8928, 7528, 4916]


def test_4d_array_and_its_3d_slices():
    g = revolution("x^2 + y^2 + z^2 - 1", "(x - 3)^2 + y^2 - 1", mode="surface")
    assert g.shape == (25,) * 4
    # a sphere as curve of revolution: symmetric in x, y, z
    assert np.array_equal(g, g.transpose(1, 0, 2, 3)) and np.array_equal(g, g.transpose(2, 1, 0, 3))
    parts = list(slices(g))
    assert len(parts) == 25 and all(p.shape == (25, 25, 25) for p in parts)
    assert np.array_equal(parts[7], g[..., 7])
    sliced = revolution("x^2 + y^2 + z^2 - 1", "(x - 3)^2 + y^2 - 1", at=0.3)
    assert sliced.shape == (25,) * 3 and well_formed_reasons(sliced) == []


def test_split_runs_of_a_non_monotone_generatrix():
    pts = [(0, 0), (2, 0), (3, 2), (2, 4), (4, 4), (5, 4), (3, 6), (1, 3)]
    runs = split_runs(pts)
    assert [r.horizontal for r in runs] == [True, False, True, False, False]
    assert runs[0].z_range == (0, 0) and list(runs[0].r) == [0, 2]
    assert list(runs[1].z) == [0, 2, 4] and list(runs[1].r) == [2, 3, 2]
    assert list(runs[2].r) == [2, 5]
    assert runs[3].z_range == (4, 6) and runs[4].z_range == (3, 6)
    # consecutive runs share their endpoint heights
    assert runs[1].z_range[1] == runs[2].z_range[0] == runs[3].z_range[0]


@pytest.mark.parametrize("k", [0, 1, 2])
def test_monotone_generatrix_split_into_runs_equals_whole(k):
    rc = load_revolution_curve("x^2 + y^2 - 1")
    z = np.array([0.0, 2.6, 5.1, 8.3, 10.0])
    r = np.array([3.0, 5.2, 4.1, 6.0, 5.5])
    whole = Run(z, r, False)
    pieces = [Run(z[i : i + 2], r[i : i + 2], False) for i in range(len(z) - 1)]
    shape, org, step = (33, 33, 25), np.array([-8.13, -8.07, -0.71]), np.full(3, 0.5)
    a = _runs_digitizer(rc, [whole])(shape, org, step, k)[0]
    b = _runs_digitizer(rc, pieces)(shape, org, step, k)[0]
    assert a.sum() > 500
    assert np.array_equal(a, b)


@pytest.mark.parametrize("k", [0, 1, 2])
def test_open_generatrix_from_axis_to_axis_closes_and_separates(k):
    pts = [[0, 0], [4, 0], [4, 1], [2, 3], [2.5, 6], [1, 8], [0, 8.5]]
    fld = revolution_field("x^2 + y^2 - 1", pts)
    surf, inside = fld.digitize((27, 27, 27), np.array([-6.5, -6.5, -2.0]), np.full(3, 0.5), k)
    assert inside.sum() > 500
    labels, _ = ndimage.label(~surf, structure=adjacency(3, k))
    outside = labels == labels[0, 0, 0]
    assert not (outside & inside).any()
    assert np.array_equal(~surf & ~outside, inside)
    # the same polygon closed along the axis, as a region, gives nearly the same solid
    region = revolution_field("x^2 + y^2 - 1", pts + [[0, 0]])
    s2, i2 = region.digitize((27, 27, 27), np.array([-6.5, -6.5, -2.0]), np.full(3, 0.5), k)
    assert jaccard(s2 | i2, surf | inside) > 0.9


def test_curve_of_revolution_with_two_components():
    curve = "min((x - 0.6)^2 + y^2 - 0.09, (x + 0.6)^2 + y^2 - 0.09)"
    rc = load_revolution_curve(curve)
    assert not rc.star
    g = revolution(curve, [[2, 0], [3, 4], [2, 8]], mode="surface")
    mid = g[:, :, 12]
    _, n = ndimage.label(mid, structure=np.ones((3, 3)))
    assert n == 2
    with pytest.raises(InvalidShapeError, match="not star-shaped"):
        revolution(curve, "(x - 2)^2 + y^2 - 1")


def test_bad_inputs_name_the_input(tmp_path):
    with pytest.raises(InvalidShapeError, match=r"^generatrix.*crosses the axis"):
        revolution("x^2 + y^2 - 1", [[0.5, 0], [2, 1], [1, 3]], axis=1.0)
    with pytest.raises(InvalidShapeError, match=r"^curve: unknown name 'q'"):
        revolution("x^2 + q^2 - 1", [[0, 0], [1, 1]])
    with pytest.raises(InvalidShapeError, match=r"^generatrix: syntax error at column"):
        revolution("x^2 + y^2 - 1", "(x - 2)^2 + (y")
    (tmp_path / "empty.json").write_text("[]")
    with pytest.raises(InvalidShapeError, match=r"^generatrix.*empty drawing"):
        revolution("x^2 + y^2 - 1", "empty.json", base_dir=tmp_path)
    with pytest.raises(InvalidShapeError, match=r"^generatrix.*degenerate"):
        revolution("x^2 + y^2 - 1", [[0, 0], [0, 5]])
    with pytest.raises(InvalidShapeError, match="empty"):
        revolution("x^2 + y^2 - 1", "(x - 2)^2 + y^2 - 1", scale=0.01)
    with pytest.raises(InvalidShapeError, match=r"^generatrix.*left of the axis|^generatrix.*empty or unbounded"):
        revolution("x^2 + y^2 - 1", "(x + 5)^2 + y^2 - 1")


def test_4d_object_from_an_open_generatrix_and_its_slice():
    pts = [[0, 0], [2, 0.5], [2.5, 2], [0, 3]]
    g4 = revolution("x^2 + y^2 + z^2 - 1", pts, size=15)
    assert g4.shape == (15,) * 4 and np.array_equal(g4, g4.transpose(1, 0, 2, 3))
    g3 = revolution("x^2 + y^2 + z^2 - 1", pts, at=1.5)
    assert well_formed_reasons(g3) == []


RECIPES = __import__("pathlib").Path(__file__).resolve().parents[2] / "recipes"


@pytest.mark.parametrize("k", [0, 1, 2])
@pytest.mark.parametrize(
    ("generatrix", "scale", "center", "cuts"),
    [
        # the bundled vase's bitmap generatrix, the circle split into two half circles and at 30°/250°
        ("vase_generatrix.png", 0.2, [0.0, 0.0, 59.5], (0, 180, 360)),
        ("vase_generatrix.png", 0.2, [0.0, 0.0, 59.5], (30, 250, 390)),
        # a torus, off the lattice
        ("(x-2)^2 + y^2 - 0.64", 4.0, [0.1, -0.2, 0.05], (10, 200, 370)),
    ],
)
def test_union_rule_open_curves_of_revolution(k, generatrix, scale, center, cuts):
    opts = dict(k=k, mode="surface", size=25, scale=scale, center=center, base_dir=RECIPES)
    whole = revolution("x^2 + y^2 - 1", generatrix, **opts)
    first = revolution("x^2 + y^2 - 1", generatrix, arc=cuts[:2], **opts)
    second = revolution("x^2 + y^2 - 1", generatrix, arc=cuts[1:], **opts)
    assert whole.sum() > 800
    assert np.array_equal(first | second, whole), (k, int((whole ^ (first | second)).sum()))
    # each half is a real open surface: it leaves out much of the whole, and the halves share only their ends
    for part in (first, second):
        assert 0.2 * whole.sum() < part.sum() < 0.8 * whole.sum()
    assert (first & second).sum() < 0.1 * whole.sum()


def test_open_curve_of_revolution_lies_in_its_half():
    grid = revolution("x^2 + y^2 - 1", "vase_generatrix.png", arc=[0, 180], k=0, mode="surface", size=25,
                      scale=0.2, center=[0.0, 0.0, 59.5], base_dir=RECIPES)
    ys = np.argwhere(grid)[:, 1]
    # grid index 12 is y = 0, the cut plane: the flakes of the row below reach it only at their tips
    assert ys.min() == 12 and np.count_nonzero(ys == 12) > 100
    assert ys.max() > 20


def test_open_curve_of_revolution_errors():
    with pytest.raises(InvalidShapeError, match="surface"):
        revolution("x^2 + y^2 - 1", "(x-2)^2 + y^2 - 0.64", arc=[0, 90], k=0, mode="solid", scale=4.0, center=[0, 0, 0])
    with pytest.raises(InvalidShapeError, match="region generatrix"):
        revolution("x^2 + y^2 - 1", [[1, 0], [1, 1]], arc=[0, 90], mode="surface", scale=4.0, center=[0, 0, 0])
    with pytest.raises(InvalidShapeError, match="arc"):
        revolution("x^2 + y^2 - 1", "(x-2)^2 + y^2 - 0.64", arc=[90, 0], mode="surface", scale=4.0, center=[0, 0, 0])


def _open_arc_drawing(folder, degrees=(0.0, 300.0), points=601, *, svg=False):
    """One open stroke along the unit circle from ``degrees[0]`` to ``degrees[1]``, as JSON or SVG."""
    t = np.radians(np.linspace(*degrees, points))
    pts = np.c_[np.cos(t), np.sin(t)]
    if svg:
        d = "M " + " L ".join(f"{x:.9f} {y:.9f}" for x, y in pts)
        path = folder / "arc.svg"
        path.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="-2 -2 4 4"><path d="{d}"/></svg>')
        return path.name
    path = folder / "arc.json"
    path.write_text(__import__("json").dumps({"polylines": [{"points": pts.tolist(), "closed": False}]}))
    return path.name


@pytest.mark.parametrize("k", [0, 1, 2])
def test_a_drawn_open_curve_of_revolution_is_the_arc_of_the_closed_one(tmp_path, k):
    # An open stroke drawn along 300° of the unit circle (its box is centred on the circle's
    # centre) sweeps the same surface as the circle with arc = [0, 300].
    opts = dict(k=k, mode="surface", size=25, scale=4.0, center=[0.1, -0.2, 0.05], base_dir=tmp_path)
    drawn = revolution(_open_arc_drawing(tmp_path), "(x-2)^2 + y^2 - 0.64", curve_open=True, **opts)
    exact = revolution("x^2 + y^2 - 1", "(x-2)^2 + y^2 - 0.64", arc=[0, 300], **opts)
    assert exact.sum() > 500
    assert np.array_equal(drawn, exact), int((drawn ^ exact).sum())


def test_an_open_svg_path_is_an_open_curve_of_revolution(tmp_path):
    opts = dict(k=0, mode="surface", size=25, scale=4.0, center=[0.0, 0.0, 0.0], base_dir=tmp_path)
    from_svg = revolution(_open_arc_drawing(tmp_path, svg=True), "(x-2)^2 + y^2 - 0.64", curve_open=True, **opts)
    from_json = revolution(_open_arc_drawing(tmp_path), "(x-2)^2 + y^2 - 0.64", curve_open=True, **opts)
    closed = revolution("x^2 + y^2 - 1", "(x-2)^2 + y^2 - 0.64", **opts)
    # the SVG's y axis points down: the same stroke seen mirrored, the same count of voxels
    assert from_svg.sum() == from_json.sum() and 0.6 * closed.sum() < from_svg.sum() < 0.95 * closed.sum()


def test_open_drawn_curves_of_revolution_refuse_what_they_cannot_be(tmp_path):
    name = _open_arc_drawing(tmp_path)
    opts = dict(scale=4.0, center=[0, 0, 0], base_dir=tmp_path)
    with pytest.raises(InvalidShapeError, match="curve_open.*surface"):
        revolution(name, "(x-2)^2 + y^2 - 0.64", curve_open=True, mode="solid", **opts)
    with pytest.raises(InvalidShapeError, match="not both"):
        revolution(name, "(x-2)^2 + y^2 - 0.64", curve_open=True, arc=[0, 90], mode="surface", **opts)
    with pytest.raises(InvalidShapeError, match="drawing"):
        revolution("x^2 + y^2 - 1", "(x-2)^2 + y^2 - 0.64", curve_open=True, mode="surface", **opts)
