"""Plates: thickness, dowel holes, labels, scores and the reported problems."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab.errors import InvalidShapeError
from voxfab.fabricate.plates import make_plates, text_strokes
from voxfab.fabricate.plates._labels import text_size
from voxfab.fabricate.plates._outline import layer_stack
from voxfab.shape import examples


@pytest.fixture(scope="module")
def vase_stack():
    return make_plates(examples.vase(12), pitch=3.0, thickness=3.0)


def _regular_polygon_area(r: float, n: int) -> float:
    return 0.5 * n * r * r * math.sin(2 * math.pi / n)


@pytest.mark.parametrize("thickness", [3.0, 1.0])
def test_layer_area_is_voxels_times_pitch_squared_minus_holes(thickness: float) -> None:
    g = examples.vase(12)
    pitch = 3.0
    stack = make_plates(g, pitch=pitch, thickness=thickness)
    counts = layer_stack(g).sum(axis=(1, 2))
    assert len(stack.dowels) > 0
    for k, count in enumerate(counts):
        plates = [p for p in stack.plates if p.layer == k + 1 and p.copy == 1]
        holes = sum(len(p.holes) for p in plates)
        r = stack.dowel_diameter / 2
        exact = count * pitch**2 - holes * math.pi * r**2
        assert sum(p.area for p in plates) == pytest.approx(exact, abs=1e-9)
        # the same with the holes cut as 64-gons, checked by shapely
        poly_area = sum(p.polygon(quad_segs=16).area for p in plates)
        assert poly_area == pytest.approx(count * pitch**2 - holes * _regular_polygon_area(r, 64), abs=1e-6)


def test_dowel_holes_line_up_through_both_layers(vase_stack) -> None:
    stack = vase_stack
    r = stack.dowel_diameter / 2
    by_piece: dict[str, list] = {}
    for p in stack.plates:
        by_piece.setdefault(p.id, []).append(p)
    for d in stack.dowels:
        lower, upper = by_piece[d.lower], by_piece[d.upper]
        assert int(d.upper.split("-")[0]) == int(d.lower.split("-")[0]) + 1
        for plate in lower + upper:
            # the very same centre is a hole in every plate of both layers
            assert np.any(np.all(np.isclose(plate.holes, (d.x, d.y), atol=0), axis=1))
            # never closer than the margin to an edge of the plate
            dist = plate.outline.boundary.distance(shapely.Point(d.x, d.y))
            assert dist >= r + 1.0 - 1e-9
            others = plate.holes[~np.all(plate.holes == (d.x, d.y), axis=1)]
            if len(others):
                assert np.hypot(*(others - (d.x, d.y)).T).min() >= 2 * r + 1.0 - 1e-9
    # holes of a plate all come from dowels of its own joints
    for p in stack.plates:
        ids = {(d.x, d.y) for d in stack.dowels if p.id in (d.lower, d.upper)}
        assert {tuple(h) for h in p.holes.tolist()} == ids


def test_every_piece_that_has_room_gets_a_dowel(vase_stack) -> None:
    pieces = {p.id for p in vase_stack.plates}
    dowelled = {d.lower for d in vase_stack.dowels} | {d.upper for d in vase_stack.dowels}
    assert pieces == dowelled | set(vase_stack.undowelled)
    assert vase_stack.undowelled == ()


def test_thin_plates_multiply_layers_and_keep_the_stack_as_tall_as_the_object() -> None:
    g = examples.box(3, 3, 4)  # 18 mm plates: room for a whole 2 mm label beside the dowel hole
    exact = make_plates(g, pitch=6.0, thickness=2.0)
    assert exact.plates_per_layer == 3 and exact.drift == pytest.approx(0.0) and not exact.resampled
    assert [p.label.text for p in exact.plates[:3]] == ["1-1.1", "1-1.2", "1-1.3"]
    stack = make_plates(g, pitch=6.0, thickness=2.2)
    # 24 mm of object in 2.2 mm plates: round(10.9) = 11 plates, 24.2 mm; each plate takes the voxel
    # layer at its mid-height (1.1, 3.3, 5.5 | 7.7, 9.9 | 12.1, ... mm).
    assert stack.counts == (3, 2, 3, 3) and stack.plates_per_layer == 0 and stack.resampled
    assert len(stack.plates) == 11
    assert stack.drift == pytest.approx(11 * 2.2 - 24.0) and abs(stack.drift) < 2.2 / 2
    assert [p.z for p in stack.plates] == pytest.approx([i * 2.2 for i in range(11)])
    assert [p.label.text for p in stack.plates[3:5]] == ["2-1.1", "2-1.2"]
    for p in stack.plates:
        assert p.label.complete and p.polygon().contains(shapely.MultiLineString(list(p.label.strokes)))
        # plates under the layer's top one are hidden by an identical plate
        assert p.label.hidden or p.layer == 4
    thick = make_plates(g, pitch=6.0, thickness=6.4)
    assert thick.plates_per_layer == 1 and thick.drift == pytest.approx(4 * 0.4)


@pytest.mark.parametrize(("layers", "pitch", "thickness"), [(25, 2.0, 3.0), (25, 3.0, 3.1), (7, 1.0, 0.3),
                                                            (25, 2.5, 2.0), (1, 2.0, 3.0)])
def test_resampled_stack_takes_the_layer_at_each_plate_mid_height(layers, pitch, thickness) -> None:
    from voxfab.fabricate.plates._stack import layer_runs

    runs = layer_runs(layers, pitch, thickness)
    n = sum(c for _, c in runs)
    assert abs(n * thickness - layers * pitch) <= thickness / 2 + 1e-9
    taken = [k for k, c in runs for _ in range(c)]
    mids = [(i + 0.5) * thickness for i in range(n)]
    assert taken == [min(int(m // pitch), layers - 1) for m in mids]


def test_queen_scale_stack_is_17_plates_of_3_mm() -> None:
    """A 25-voxel shape at 2 mm in 3 mm plates: 17 plates, 51 mm (issue: not 25 plates, 75 mm)."""
    g = np.zeros((3, 3, 25), bool)
    g[1, 1, :] = True
    g[:, :, ::2] = True
    stack = make_plates(g, pitch=2.0, thickness=3.0)
    assert len(stack.plates) == 17 and stack.height == pytest.approx(51.0) and stack.drift == pytest.approx(1.0)
    assert stack.sources == (1, 3, 4, 6, 7, 9, 10, 12, 13, 15, 16, 18, 19, 21, 22, 24, 25)
    # a plate takes its voxel layer's outline: the odd voxel layers (index 0, 2, ...) are the full 3x3 square
    areas = [p.outline.area for p in stack.plates]
    assert areas == [36.0 if (s - 1) % 2 == 0 else 4.0 for s in stack.sources]
    assert [p.z for p in stack.plates] == pytest.approx([3.0 * i for i in range(17)])


def test_labels_are_on_the_plate_and_hidden_by_the_next_one() -> None:
    stack = make_plates(examples.vase(12), pitch=5.0, thickness=5.0)  # walls wide enough for 2 mm labels
    above = {}
    for p in stack.plates:
        above.setdefault(p.layer, []).append(p.outline)
    hidden = 0
    for p in stack.plates:
        lines = shapely.MultiLineString([s for s in p.label.strokes])
        assert p.polygon().contains(lines)
        if p.label.hidden:
            hidden += 1
            assert shapely.union_all(above[p.layer + 1]).contains(lines)
    assert hidden >= len(stack.plates) - 1  # only the top plate has nothing above it
    assert not stack.plates[-1].label.hidden


def test_stroke_font_draws_every_label_character() -> None:
    strokes = text_strokes("0123456789-.", 6.0)
    pts = np.concatenate(strokes)
    assert pts[:, 1].min() == 0.0 and pts[:, 1].max() == 6.0
    # Each glyph stays inside its cell of the shared font.
    width, height = text_size("0123456789-.", 6.0)
    assert pts[:, 0].min() >= 0.0 and pts[:, 0].max() <= width + 1e-9
    assert height == 6.0


def test_score_is_the_next_layer_outline_inside_the_plate() -> None:
    g = np.zeros((4, 4, 2), dtype=bool)
    g[:, :, 0] = True
    g[1:3, 1:3, 1] = True
    stack = make_plates(g, pitch=3.0, thickness=3.0, dowel=0)
    bottom = stack.plates[0]
    score = shapely.MultiLineString(list(bottom.score))
    assert score.length == pytest.approx(4 * 6.0)
    assert score.equals(shapely.box(3, 3, 9, 9).boundary)
    assert stack.plates[1].score == ()
    assert make_plates(g, pitch=3.0, thickness=3.0, score=False).plates[0].score == ()


def test_unsupported_and_thin_pieces_are_reported() -> None:
    g = np.zeros((5, 5, 3), dtype=bool)
    g[0:3, 0:3, 0] = True
    g[0:3, 0:3, 1] = True
    g[4, 4, 1] = True  # touches nothing above or below
    g[0, 0:3, 2] = True
    stack = make_plates(g, pitch=3.0, thickness=3.0)
    assert stack.unsupported == ("2-2",)
    assert stack.thin == ()
    fine = make_plates(g, pitch=0.8, thickness=0.8, dowel=0)
    assert set(fine.thin) == {"2-2", "3-1"}


def test_bad_options_are_refused() -> None:
    g = examples.box(2, 2, 2)
    with pytest.raises(InvalidShapeError, match="thickness"):
        make_plates(g, pitch=3.0, thickness=0)
    with pytest.raises(InvalidShapeError, match="dowel"):
        make_plates(g, pitch=3.0, dowel=-1)
    with pytest.raises(InvalidShapeError, match="axis"):
        make_plates(g, pitch=3.0, axis="q")


@settings(max_examples=12, deadline=None)
@given(
    seed=st.integers(0, 2**16),
    axis=st.sampled_from(["x", "y", "z"]),
    thickness=st.sampled_from([1.0, 1.4, 2.0]),
)
def test_random_grids_keep_area_holes_and_labels_on_their_plates(seed: int, axis: str, thickness: float) -> None:
    from voxfab.fabricate.plates import nest_plates

    rng = np.random.default_rng(seed)
    g = rng.random((6, 5, 4)) < 0.55
    if not g.any():
        g[0, 0, 0] = True
    pitch = 4.0
    stack = make_plates(g, pitch=pitch, axis=axis, thickness=thickness, dowel=1.5, dowel_margin=0.5)
    counts = layer_stack(g, axis=axis).sum(axis=(1, 2))
    r = 0.75
    for k, count in enumerate(counts):
        for copy in range(1, stack.plates_per_layer + 1):
            plates = [p for p in stack.plates if p.layer == k + 1 and p.copy == copy]
            holes = sum(len(p.holes) for p in plates)
            assert sum(p.area for p in plates) == pytest.approx(count * pitch**2 - holes * math.pi * r * r)
    for p in stack.plates:
        body = p.polygon()
        assert body.is_valid
        for x, y in p.holes:
            assert p.outline.boundary.distance(shapely.Point(x, y)) >= r + 0.5 - 1e-9
        if p.label.strokes:
            assert body.buffer(1e-9).contains(shapely.MultiLineString(list(p.label.strokes)))
    sheets = nest_plates(stack.plates, sheet="60x60", margin=2, spacing=1.0, kerf=0.1)
    polys = [(s.index, part.polygon()) for s in sheets for part in s.parts]
    assert len(polys) == len(stack.plates)
    for i, (si, a) in enumerate(polys):
        assert shapely.box(2, 2, 58, 58).buffer(1e-9).contains(a)
        for sj, b in polys[i + 1:]:
            if si == sj:
                assert a.distance(b) >= 1.0 - 1e-6
