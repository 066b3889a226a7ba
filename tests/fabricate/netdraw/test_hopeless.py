"""Sheets hopeless for a net in pieces are refused before any search, with a larger sheet and smaller faces."""

from __future__ import annotations

from pathlib import Path

import pytest
from _net_sheets import queen

from voxfab.fabricate.netdraw import DrawingOptions, find_sheet_nets
from voxfab.fabricate.netdraw._sheets import (
    PIECES_LEAST_ACROSS,
    PIECES_MOST_SHEETS,
    HopelessSheetError,
    check_pieces_sheet,
    pieces_sheets_at_least,
    sheet_cells,
)
from voxfab.shape import surface_graph


@pytest.fixture(scope="module")
def grid():
    return queen()


@pytest.fixture(scope="module")
def vase():
    from voxfab.recipe import load_recipe, make_shape

    return make_shape(load_recipe(Path(__file__).parents[3] / "recipes" / "vase.toml")).grid


@pytest.fixture
def no_search(monkeypatch):
    """Any net search fails the test: the refusal must come before it."""
    import voxfab.unfold

    def searched(*args, **kwargs):
        raise AssertionError("a net search ran before the refusal")

    monkeypatch.setattr(voxfab.unfold, "unfold", searched)
    monkeypatch.setattr(voxfab.unfold, "unfold_many", searched)


def test_a_60_mm_sheet_is_refused_before_any_search_with_a_larger_sheet(grid, no_search) -> None:
    opts = DrawingOptions(pitch=8.6, sheet="60x60", label_height=2.0)
    faces = surface_graph(grid).face_count
    assert pieces_sheets_at_least(faces, opts, 8.6) > PIECES_MOST_SHEETS
    with pytest.raises(HopelessSheetError) as info:
        find_sheet_nets(grid, opts, rng=0, pieces="auto")
    err = info.value
    assert "60x60" in str(err) and f"more than {PIECES_MOST_SHEETS}" in str(err)
    # The ways out: a larger sheet that works (never "split into pieces": it is split already).
    assert all("pieces" not in w["options"] for w in err.ways_out)
    sheets = [w["options"]["sheet"] for w in err.ways_out if "sheet" in w["options"]]
    assert sheets == [err.smallest_sheet] == ["A5"]
    check_pieces_sheet(faces, DrawingOptions(pitch=8.6, sheet="A5", label_height=2.0), 8.6, 8.6)


def test_a_sheet_one_face_wide_is_refused(grid, no_search) -> None:
    opts = DrawingOptions(pitch=8.6, sheet="40x297", label_height=2.0)
    assert min(sheet_cells(opts, 8.6)) == 1 < PIECES_LEAST_ACROSS
    with pytest.raises(HopelessSheetError, match=f"fewer than {PIECES_LEAST_ACROSS} across"):
        find_sheet_nets(grid, opts, rng=0, pieces="auto")


def test_more_than_50_sheets_for_the_faces_alone_is_refused(vase, no_search) -> None:
    opts = DrawingOptions(pitch=8.6, sheet="80x80", label_height=2.0)
    assert min(sheet_cells(opts, 8.6)) >= PIECES_LEAST_ACROSS
    assert pieces_sheets_at_least(surface_graph(vase).face_count, opts, 8.6) > PIECES_MOST_SHEETS
    with pytest.raises(HopelessSheetError, match=f"more than {PIECES_MOST_SHEETS}"):
        find_sheet_nets(vase, opts, rng=0, pieces="auto")


def test_smaller_faces_are_offered_when_they_work(vase) -> None:
    faces = surface_graph(vase).face_count
    opts = DrawingOptions(pitch=8.6, sheet="100x100", label_height=2.0, min_label_height=1.5)
    with pytest.raises(HopelessSheetError) as info:
        check_pieces_sheet(faces, opts, 8.6, 5.0)
    best = info.value.largest_face_size
    assert {"face_size": best} in [w["options"] for w in info.value.ways_out]
    assert 5.0 <= best < 8.6
    # The face size offered works, and 0.1 mm more does not.
    check_pieces_sheet(faces, opts, best, 5.0)
    with pytest.raises(HopelessSheetError):
        check_pieces_sheet(faces, opts, round(best + 0.1, 1), 5.0)
    assert pieces_sheets_at_least(faces, opts, best) <= PIECES_MOST_SHEETS


def test_a_sheet_that_works_is_not_refused(grid) -> None:
    faces = surface_graph(grid).face_count
    for sheet in ("A4", "Letter", "mat12", "100x100"):
        check_pieces_sheet(faces, DrawingOptions(pitch=8.6, sheet=sheet, label_height=2.0), 8.6, 8.6)


def test_the_studio_gallery_refuses_in_the_same_words(grid, no_search) -> None:
    from voxfab.fabricate.netdraw import NetOptions, net_gallery

    opts = DrawingOptions(pitch=8.6, sheet="60x60", label_height=2.0)
    with pytest.raises(HopelessSheetError) as cli:
        find_sheet_nets(grid, opts, rng=0, pieces="auto")
    with pytest.raises(HopelessSheetError) as studio:
        net_gallery(grid, NetOptions(face_size=8.6, pieces="auto"), opts, count=8, seed=0)
    assert str(studio.value) == str(cli.value)
    assert studio.value.ways_out == cli.value.ways_out
