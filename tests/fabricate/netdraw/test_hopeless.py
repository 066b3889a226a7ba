"""Sheets hopeless for a net in pieces are refused before any search, with a larger sheet and smaller faces."""

from __future__ import annotations

import pytest
from _net_sheets import queen

from voxfab.fabricate.netdraw import DrawingOptions, find_sheet_nets
from voxfab.fabricate.netdraw._sheets import (
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


@pytest.fixture
def no_search(monkeypatch):
    """Any net search fails the test: the refusal must come before it."""
    import voxfab.unfold

    def searched(*args, **kwargs):
        raise AssertionError("a net search ran before the refusal")

    monkeypatch.setattr(voxfab.unfold, "unfold", searched)
    monkeypatch.setattr(voxfab.unfold, "unfold_many", searched)


def test_a_55_mm_sheet_is_refused_before_any_search_with_a_larger_sheet(grid, no_search) -> None:
    opts = DrawingOptions(pitch=8.6, sheet="55x55", label_height=2.0)
    with pytest.raises(HopelessSheetError) as info:
        find_sheet_nets(grid, opts, rng=0, pieces="auto")
    err = info.value
    faces = surface_graph(grid).face_count
    assert pieces_sheets_at_least(faces, opts, 8.6) > PIECES_MOST_SHEETS
    assert "55x55" in str(err) and f"more than {PIECES_MOST_SHEETS}" in str(err)
    # The ways out: a larger sheet that works (never "split into pieces": it is split already).
    assert all("pieces" not in w["options"] for w in err.ways_out)
    sheets = [w["options"]["sheet"] for w in err.ways_out if "sheet" in w["options"]]
    assert sheets == [err.smallest_sheet] == ["A5"]
    check_pieces_sheet(faces, DrawingOptions(pitch=8.6, sheet="A5", label_height=2.0), 8.6, 8.6)


def test_a_sheet_one_face_wide_is_refused(grid, no_search) -> None:
    opts = DrawingOptions(pitch=8.6, sheet="40x297", label_height=2.0)
    assert min(sheet_cells(opts, 8.6)) == 1
    with pytest.raises(HopelessSheetError, match="fewer than 2 across"):
        find_sheet_nets(grid, opts, rng=0, pieces="auto")


def test_smaller_faces_are_offered_when_they_work(grid) -> None:
    faces = surface_graph(grid).face_count
    opts = DrawingOptions(pitch=8.6, sheet="58x58", label_height=2.0, min_label_height=1.5)
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
