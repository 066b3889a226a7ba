"""Nesting plates onto sheets, with kerf compensation."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import shapely

from voxfab.drawing import parse_sheet
from voxfab.errors import FabricationError, InvalidShapeError
from voxfab.fabricate.plates import make_plates, nest_plates
from voxfab.shape import examples


@pytest.fixture(scope="module")
def stack():
    return make_plates(examples.random_shape(2, side=14), pitch=3.0, thickness=1.5)


def _check_sheets(sheets, *, margin: float, spacing: float) -> None:
    for sheet in sheets:
        inside = shapely.box(margin, margin, sheet.width - margin, sheet.height - margin)
        polys = [p.polygon() for p in sheet.parts]
        for poly in polys:
            assert poly.is_valid
            assert inside.buffer(1e-9).contains(poly)
        for a, b in itertools.combinations(polys, 2):
            assert a.distance(b) >= spacing - 1e-6


@pytest.mark.parametrize("kerf", [0.0, 0.2])
def test_nested_parts_do_not_overlap_and_stay_inside(stack, kerf: float) -> None:
    sheets = nest_plates(stack.plates, sheet="160x120", margin=4, spacing=1.5, kerf=kerf)
    assert len(sheets) > 1
    placed = sorted(p.plate.number for s in sheets for p in s.parts)
    assert placed == list(range(1, len(stack.plates) + 1))
    assert any(p.rotated for s in sheets for p in s.parts)
    _check_sheets(sheets, margin=4, spacing=1.5)


def test_placement_is_a_rigid_motion_of_the_plate(stack) -> None:
    (sheet, *_) = nest_plates(stack.plates, sheet=(600, 400))
    for part in sheet.parts:
        plate = part.plate
        moved = shapely.Polygon(part.place(np.asarray(plate.outline.exterior.coords)))
        assert moved.area == pytest.approx(shapely.Polygon(plate.outline.exterior).area)
        assert shapely.Polygon(part.cut[0]).equals(moved)
        assert np.allclose(part.circles[:, :2], part.place(plate.holes))
        if plate.label.strokes:  # a plate too small for a whole label carries none
            label = np.concatenate(plate.label.strokes)
            assert np.allclose(np.concatenate(part.engrave), part.place(label))
        else:
            assert part.engrave == ()
    assert any(part.engrave for part in sheet.parts)


def test_small_plates_go_into_voxel_holes_of_big_ones() -> None:
    g = np.zeros((8, 8, 3), dtype=bool)
    g[:, :, 0] = True
    g[1:7, 1:7, 0] = False  # a frame 24 mm wide with an 18 mm hole
    g[0:2, 0:2, 1] = True
    g[0:2, 0:3, 2] = True
    stack = make_plates(g, pitch=3.0, thickness=3.0, dowel=1.0, dowel_margin=0.5)
    assert len(stack.plates) == 3
    sheets = nest_plates(stack.plates, sheet="30x30", margin=2, spacing=1.0)
    assert len(sheets) == 1
    parts = {p.plate.number: p for p in sheets[0].parts}
    assert parts[1].host == 0 and parts[2].host == 1 and parts[3].host == 1
    _check_sheets(sheets, margin=2, spacing=1.0)
    hole = shapely.Polygon(parts[1].cut[1])
    assert hole.contains(parts[2].polygon()) and hole.contains(parts[3].polygon())
    # without part-in-part the same plates need more sheets
    assert len(nest_plates(stack.plates, sheet="30x30", margin=2, spacing=1.0, in_holes=False)) == 2


def test_guests_keep_their_geometry_when_the_host_turns() -> None:
    g = np.zeros((12, 8, 2), dtype=bool)
    g[:, :, 0] = True
    g[1:11, 1:7, 0] = False  # a 36 x 24 mm frame: must turn on a tall sheet
    g[0:4, 0:1, 1] = True  # a 12 x 3 mm bar that fits the hole only lying along it
    stack = make_plates(g, pitch=3.0, thickness=3.0, dowel=0)
    (sheet,) = nest_plates(stack.plates, sheet="30x44", margin=1, spacing=1.0)
    host, guest = sheet.parts
    assert host.turns == 1 and guest.host == 1 and guest.turns in (1, 3)
    _check_sheets([sheet], margin=1, spacing=1.0)
    assert shapely.Polygon(host.cut[1]).contains(guest.polygon())
    assert guest.polygon().area == pytest.approx(36.0)
    label = np.concatenate(guest.plate.label.strokes)
    assert np.allclose(np.concatenate(guest.engrave), guest.place(label))


def test_kerf_grows_outlines_and_shrinks_holes() -> None:
    g = np.ones((4, 4, 2), dtype=bool)
    g[1:3, 1:3, :] = False  # a 4x4 ring: one outline and one voxel hole
    g[:, :, 1] = g[:, :, 0]
    stack = make_plates(g, pitch=5.0, thickness=5.0, dowel=2.0, dowel_margin=0.5)
    kerf = 0.2
    (plain,) = nest_plates(stack.plates[:1], sheet="100x100")
    (comp,) = nest_plates(stack.plates[:1], sheet="100x100", kerf=kerf)
    p0, p1 = plain.parts[0], comp.parts[0]
    outer0, outer1 = shapely.Polygon(p0.cut[0]), shapely.Polygon(p1.cut[0])
    hole0, hole1 = shapely.Polygon(p0.cut[1]), shapely.Polygon(p1.cut[1])
    assert outer1.area == pytest.approx((20 + kerf) ** 2)
    assert hole1.area == pytest.approx((10 - kerf) ** 2)
    assert outer0.area == pytest.approx(400) and hole0.area == pytest.approx(100)
    assert len(p1.circles) and np.allclose(p1.circles[:, 2], 1.0 - kerf / 2)


def test_plate_too_large_for_the_sheet_is_an_error(stack) -> None:
    with pytest.raises(FabricationError, match="does not fit"):
        nest_plates(stack.plates, sheet="20x20", margin=2)


def test_sheet_sizes_are_parsed_and_checked() -> None:
    assert parse_sheet("600x400") == (600.0, 400.0)
    assert parse_sheet(" 12.5 X 30 ") == (12.5, 30.0)
    for bad in ("600", "axb", "0x10", "-5x5"):
        with pytest.raises(InvalidShapeError, match="sheet"):
            parse_sheet(bad)
