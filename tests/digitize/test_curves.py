"""2D curve sources: implicit, drawn (JSON, CSV, SVG), bitmap."""

from __future__ import annotations

import json

import numpy as np
import pytest
from PIL import Image, ImageDraw

from voxfab.digitize import load_curve, open_star_curve, polyline_curve, surface
from voxfab.errors import FormatError, InvalidShapeError

SQUARE = [[-3.0, -2.0], [3.0, -2.0], [3.0, 2.0], [-3.0, 2.0]]


def digitized(curve, k=0):
    return surface(curve, (31, 31), k, origin=(-7.5, -7.5), step=0.5)


def test_implicit_bounds_and_values():
    c = load_curve("(x - 30)^2 + (y + 5)^2 = 4")
    assert np.allclose(c.lo, [28, -7], atol=0.1) and np.allclose(c.hi, [32, -3], atol=0.1)
    assert c(30.0, -5.0) < 0 < c(33.0, -5.0)


def test_callable_source():
    c = load_curve(lambda x, y: np.maximum(np.abs(x), np.abs(y)) - 1)
    assert np.allclose(c.lo, -1, atol=0.05) and c.kind == "implicit"


def test_unbounded_implicit_region_is_an_error():
    with pytest.raises(InvalidShapeError, match="curve: the region f <= 0 is empty or unbounded"):
        load_curve("x + y")


def test_closed_drawings_from_every_format_match_the_implicit_square(tmp_path):
    ref = digitized(load_curve("max(abs(x) - 3, abs(y) - 2)"))
    (tmp_path / "sq.json").write_text(json.dumps({"points": SQUARE, "closed": True}))
    (tmp_path / "sq.csv").write_text("x,y\n" + "\n".join(f"{a},{b}" for a, b in SQUARE + SQUARE[:1]) + "\n")
    (tmp_path / "sq.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="20" height="20">'
        '<path d="M -3 2 L 3 2 L 3 -2 L -3 -2 Z"/></svg>'
    )
    for name in ("sq.json", "sq.csv", "sq.svg"):
        c = load_curve(name, base_dir=tmp_path)
        assert c.kind == "drawn" and c.closed == (True,)
        assert np.array_equal(digitized(c), ref), name


def test_drawn_polygon_sign_is_even_odd():
    c = polyline_curve([SQUARE, [[-1, -1], [1, -1], [1, 1], [-1, 1], [-1, -1]]], closed=[True, None])
    assert c.closed == (True, True)
    assert c(2.0, 0.0) < 0 and c(0.0, 0.0) > 0 and c(5.0, 0.0) > 0
    assert c(3.0, 0.0) == 0  # on an edge: both signs


def test_open_drawing_is_a_stroke():
    c = polyline_curve([[[0, 0], [10, 0], [10, 5]]], stroke=1.0)
    assert c.closed == (False,)
    assert c(5.0, 0.3) < 0 < c(5.0, 0.7)
    s = surface(c, (40, 40), 0, origin=(-5, -5), step=0.5)
    assert s.any()


def test_svg_curves_are_sampled_and_y_flipped(tmp_path):
    (tmp_path / "c.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
        '<circle cx="50" cy="30" r="20"/></svg>'
    )
    c = load_curve("c.svg", base_dir=tmp_path)
    assert np.allclose(c.lo, [30, -50], atol=0.01) and np.allclose(c.hi, [70, -10], atol=0.01)
    assert c(50.0, -30.0) < 0 and c(50.0, 30.0) > 0


def test_bitmap_dark_is_inside_with_threshold(tmp_path):
    im = Image.new("L", (20, 10), 255)
    ImageDraw.Draw(im).rectangle((2, 3, 7, 6), fill=0)
    ImageDraw.Draw(im).rectangle((12, 3, 17, 6), fill=160)
    im.save(tmp_path / "b.png")
    c = load_curve("b.png", base_dir=tmp_path)
    assert c.kind == "bitmap"
    # pixel (col 4, row 4) is at x = 4.5, y = 10 - 4.5
    assert c(4.5, 5.5) < 0 and c(14.5, 5.5) > 0 and c(-5.0, 5.0) > 0
    assert np.allclose(c.lo, [2, 3]) and np.allclose(c.hi, [8, 7])
    light = load_curve("b.png", base_dir=tmp_path, threshold=0.7)
    assert light(14.5, 5.5) < 0


@pytest.mark.parametrize(
    ("content", "name", "err", "pattern"),
    [
        ("[]", "e.json", InvalidShapeError, "empty drawing|expected a list"),
        ("[[1, 1], [1, 1]]", "d.json", InvalidShapeError, "empty drawing"),
        ("[[0,0],[1,1],[2,2],[0,0]]", "z.json", InvalidShapeError, "degenerate closed polyline"),
        ("{not json", "j.json", FormatError, "not valid JSON"),
        ('<svg xmlns="http://www.w3.org/2000/svg"></svg>', "s.svg", InvalidShapeError, "empty drawing"),
        ("x,y\n1,2\nfoo,bar\n", "c.csv", FormatError, "bad CSV row"),
    ],
)
def test_bad_drawings_name_the_input(tmp_path, content, name, err, pattern):
    (tmp_path / name).write_text(content)
    with pytest.raises(err, match=pattern) as info:
        load_curve(name, base_dir=tmp_path, name="profile")
    assert str(info.value).startswith("profile")


def test_missing_and_empty_bitmaps(tmp_path):
    with pytest.raises(InvalidShapeError, match="file not found"):
        load_curve("nope.png", base_dir=tmp_path)
    Image.new("L", (5, 5), 255).save(tmp_path / "w.png")
    with pytest.raises(InvalidShapeError, match="empty bitmap"):
        load_curve("w.png", base_dir=tmp_path)
    (tmp_path / "bad.png").write_bytes(b"not a png")
    with pytest.raises(FormatError, match="cannot read image"):
        load_curve("bad.png", base_dir=tmp_path)


def test_an_open_stroke_is_part_of_a_closed_star_shaped_curve() -> None:
    # 270° of a circle of radius 2: its box is centred on the circle's centre, the axis
    t = np.radians(np.linspace(-90.0, 180.0, 200))
    stroke = np.c_[2 * np.cos(t), 2 * np.sin(t)] + [5.0, 7.0]
    drawn = open_star_curve(stroke[::-1])  # drawn either way round
    start, end = drawn.arc
    assert np.isclose(np.degrees(end - start), 270.0)
    centre = (stroke.min(axis=0) + stroke.max(axis=0)) / 2
    rel = stroke - centre
    # every drawn point is on the completed curve, and points just inside/outside it have its sign
    on = drawn.curve(rel[:, 0], rel[:, 1])
    assert np.abs(on).max() < 1e-9
    assert np.all(drawn.curve(0.9 * rel[:, 0], 0.9 * rel[:, 1]) < 0)
    assert np.all(drawn.curve(1.1 * rel[:, 0], 1.1 * rel[:, 1]) > 0)
    # across the gap the radius goes from one end's to the other's: the curve stays closed round the axis
    gap = np.radians(np.linspace(0, 1, 9)) + end + 0.01
    assert np.all(drawn.curve(0.01 * np.cos(gap), 0.01 * np.sin(gap)) < 0)


@pytest.mark.parametrize(
    ("points", "words"),
    [
        ([[1, 0], [0, 1], [1, 0.5]], "turn one way"),
        ([[1, 0], [0, 0], [-1, 0]], "centre"),
        ([[1, 0], [1, 0]], "2 distinct points"),
    ],
)
def test_open_strokes_that_cannot_be_swept_are_refused(points, words) -> None:
    with pytest.raises(InvalidShapeError, match=words):
        open_star_curve(np.asarray(points, dtype=float))


def test_an_open_curve_comes_from_one_stroke_of_a_drawing(tmp_path) -> None:
    (tmp_path / "two.json").write_text(json.dumps({"polylines": [
        {"points": [[1, 0], [0, 1]], "closed": False}, {"points": [[-1, 0], [0, -1]], "closed": False}]}))
    with pytest.raises(InvalidShapeError, match="one stroke, got 2"):
        open_star_curve("two.json", base_dir=tmp_path)
    with pytest.raises(InvalidShapeError, match="arc = \\[start, end\\]"):
        open_star_curve("x^2 + y^2 - 1")
    t = np.radians(np.linspace(0.0, 400.0, 400))
    with pytest.raises(InvalidShapeError, match="full turn"):
        open_star_curve(np.c_[np.cos(t), np.sin(t)])
