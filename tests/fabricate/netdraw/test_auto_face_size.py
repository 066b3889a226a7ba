"""The automatic face size is the largest at which a one-piece net was found, refusals name that very face
size, and every way out offered was checked to give nets (issue #44, items 1 and 2)."""

from __future__ import annotations

import re

import pytest
from _net_sheets import queen

from voxfab.fabricate.netdraw import DrawingOptions, find_sheet_nets
from voxfab.fabricate.netdraw._fit import FaceSizeError
from voxfab.fabricate.netdraw._sheets import SheetFitError, extent_of, fits, sheet_cells
from voxfab.unfold import validate


@pytest.fixture(scope="module")
def grid():
    return queen()


@pytest.fixture(scope="module")
def auto_a2(grid):
    return find_sheet_nets(grid, DrawingOptions(sheet="A2"), rng=0)


def test_the_queen_on_a2_gets_the_largest_face_size_found(grid, auto_a2):
    # 10.8, 11.5 and 12.5 mm each give a one-piece net on A2 when asked for: the automatic one is not smaller
    face = float(auto_a2.options.pitch)
    assert face >= 12.5, auto_a2.notes
    for asked in (10.8, 11.5, 12.5):
        assert asked <= face
    (net,) = auto_a2.nets[0]
    assert validate(grid, net).ok
    # the net lies in the sheet's cells at that face size, measured from its own corners
    assert fits(extent_of(net.corners2d), DrawingOptions(sheet="A2"), face) is not None
    w, h = sheet_cells(DrawingOptions(sheet="A2"), face)
    ex, ey = extent_of(net.corners2d)
    assert (ex <= w and ey <= h) or (ey <= w and ex <= h)
    assert any(f"{face:g} mm" in note for note in auto_a2.notes)


def test_a_refusal_names_the_face_size_that_was_found(grid, auto_a2):
    face = float(auto_a2.options.pitch)
    with pytest.raises(SheetFitError) as info:
        find_sheet_nets(grid, DrawingOptions(sheet="A2", pitch=14.0), rng=0)
    said = re.search(r"fits A2 at faces up to ([\d.]+) mm", str(info.value))
    assert said is not None, str(info.value)
    assert float(said.group(1)) == face == info.value.largest_face_size
    assert {"face_size": face} in [w["options"] for w in info.value.ways_out]
    # and that face size, asked for, gives a one-piece net on A2
    again = find_sheet_nets(grid, DrawingOptions(sheet="A2", pitch=face), rng=0)
    assert len(again.nets[0]) == 1 and validate(grid, again.nets[0][0]).ok


def _applied(options: DrawingOptions, way: dict, pieces: str) -> tuple[DrawingOptions, str]:
    chosen = dict(way["options"])
    pieces = chosen.pop("pieces", pieces)
    if "face_size" in chosen:
        chosen["pitch"] = chosen.pop("face_size")
    return options.replace(**chosen), pieces


@pytest.mark.parametrize(("sheet", "pitch", "asked"), [("60x60", None, "one"), ("60x60", 5.0, "one"),
                                                      ("A4", 5.0, "one"), ("60x60", 5.0, "auto")])
def test_every_way_out_offered_gives_nets(grid, sheet, pitch, asked):
    options = DrawingOptions(sheet=sheet, pitch=pitch)
    with pytest.raises(FaceSizeError) as info:
        find_sheet_nets(grid, options, rng=0, pieces=asked)
    ways = info.value.ways_out
    assert ways
    for way in ways:
        chosen, pieces = _applied(options, way, asked)
        got = find_sheet_nets(grid, chosen, rng=0, pieces=pieces)  # no refusal: the way out works
        assert got.nets and got.nets[0], way
        for net in got.nets[0]:
            assert net.face_count > 0
        if pieces == "one":
            (net,) = got.nets[0]
            assert validate(grid, net).ok
            assert fits(extent_of(net.corners2d), chosen, float(got.options.pitch)) is not None


def test_the_queen_on_60_by_60_is_not_offered_pieces_that_need_55_sheets(grid):
    with pytest.raises(FaceSizeError) as info:
        find_sheet_nets(grid, DrawingOptions(sheet="60x60"), rng=0)
    for way in info.value.ways_out:
        if way["options"].get("pieces") == "auto":
            assert way["options"].get("sheet") not in (None, "60x60"), way
