"""Emptying the last sheet: the torus's last sheet on A5, cut along folds into the gaps of the others, saves a
sheet; the pieces refold, every seam has a tab, the written outlines lie apart, the same seed writes the same
files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _dxf_read import closed_rings
from _net_sheets import pieces_of

from voxfab.fabricate.netdraw import DrawingOptions, _nesting, draw_pieces, find_sheet_nets, write_net_drawing
from voxfab.fabricate.netdraw._drawing import sheets_needed
from voxfab.shape import examples, fill_cavities
from voxfab.unfold import validate
from voxfab.unfold._job import MIN_SHARE

OPTIONS = DrawingOptions(pitch=8.6, sheet="A5", label_height=2.0)


@pytest.fixture(scope="module")
def torus():
    """The torus cut by default without the step, and with it (the default)."""
    grid = fill_cavities(examples.torus(7.0, 3.0))
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(_nesting, "nest_last_sheet", lambda grid, pieces, options, constraints=None: pieces)
        without = list(find_sheet_nets(grid, OPTIONS, rng=0, pieces="auto").nets[0])
    nested = list(find_sheet_nets(grid, OPTIONS, rng=0, pieces="auto").nets[0])
    return grid, without, nested


def test_the_torus_takes_a_sheet_fewer_and_its_pieces_refold_with_a_tab_on_every_seam(torus) -> None:
    grid, without, nested = torus
    before, after = sheets_needed(grid, without, OPTIONS), sheets_needed(grid, nested, OPTIONS)
    assert after[0] == before[0] - 1
    assert len(nested) > len(without)
    assert validate(grid, nested).ok
    assert after[2] == 0 and all(p.seams_without_tab_room == 0 for p in nested)
    sizes = [p.face_count for p in nested]
    assert min(sizes) >= MIN_SHARE * max(sizes)  # the size rule holds for the gap fillers too
    drawing = draw_pieces(grid, nested, options=OPTIONS)
    assert len(drawing.sheets) == after[0]


def test_the_written_sheets_show_every_piece_once_none_over_another(torus, tmp_path: Path) -> None:
    import ezdxf

    grid, _, nested = torus
    write_net_drawing(grid, nested, tmp_path / "torus.dxf", OPTIONS, title="torus")
    dxfs = sorted(tmp_path.glob("torus.sheet-*.dxf"), key=lambda p: int(p.stem.rsplit("-", 1)[1]))
    assert len(dxfs) == sheets_needed(grid, nested, OPTIONS)[0]
    sheets = [pieces_of(closed_rings(ezdxf.readfile(p))) for p in dxfs]
    assert sum(len(s) for s in sheets) == len(nested)
    w, h = OPTIONS.sheet_size
    for polygons in sheets:
        for i, a in enumerate(polygons):
            x0, y0, x1, y1 = a.bounds
            assert x0 >= OPTIONS.margin - 1e-6 and x1 <= w - OPTIONS.margin + 1e-6
            assert y0 >= OPTIONS.margin - 1e-6 and y1 <= h - OPTIONS.margin + 1e-6
            for b in polygons[i + 1:]:
                assert a.intersection(b).area < 1e-6, "two pieces overlap"


def test_same_seed_same_pieces_and_files(torus, tmp_path: Path) -> None:
    grid, without, nested = torus
    again = _nesting.nest_last_sheet(grid, without, OPTIONS)
    assert [p.to_json() for p in again] == [p.to_json() for p in nested]
    for run in ("a", "b"):
        (tmp_path / run).mkdir()
        write_net_drawing(grid, again if run == "a" else nested, tmp_path / run / "t.svg", OPTIONS)
    a, b = sorted((tmp_path / "a").glob("*.svg")), sorted((tmp_path / "b").glob("*.svg"))
    assert len(a) == len(b) > 1 and all(x.read_bytes() == y.read_bytes() for x, y in zip(a, b))


def test_a_last_sheet_too_full_for_the_gaps_is_left_as_it_is() -> None:
    """The queen on A4: its last sheet's paper is over half the free room before it; the pieces come back
    the same objects, uncut."""
    from _net_sheets import queen

    grid = fill_cavities(queen())
    options = DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(_nesting, "nest_last_sheet", lambda grid, pieces, options, constraints=None: pieces)
        pieces = list(find_sheet_nets(grid, options, rng=0, pieces="auto").nets[0])
    out = _nesting.nest_last_sheet(grid, pieces, options)
    assert out is pieces and np.array_equal(sheets_needed(grid, out, options), sheets_needed(grid, pieces, options))


def test_edges_kept_folded_stay_folded(torus) -> None:
    """Marks that keep every fold of the cut: no branch may be cut off, the pieces come back as they are."""
    from voxfab.unfold import EdgeConstraints

    grid, without, nested = torus
    sign = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y", (0, 0, 1): "+z", (0, 0, -1): "-z"}

    def face(net, i: int) -> tuple:
        return (*net.voxel[i].tolist(), sign[tuple(net.normal[i].tolist())])

    keep = {(face(p, a), face(p, b)) for p in without for a, b in p.folds.tolist()}
    assert len(nested) > len(without)  # unmarked, the step cuts some of them
    assert _nesting.nest_last_sheet(grid, without, OPTIONS, EdgeConstraints(keep=keep)) is without
