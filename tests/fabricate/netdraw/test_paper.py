"""One sheet plan per net job: the sheet at its face size is worked out once, and the files repeat byte for byte."""

from __future__ import annotations

from pathlib import Path

import pytest
from _net_sheets import queen

from voxfab.fabricate.netdraw import DrawingOptions, NetOptions
from voxfab.fabricate.netdraw._pipeline import net_files
from voxfab.fabricate.netdraw._sheets import _paper, paper


@pytest.fixture(scope="module")
def grid():
    return queen()


def test_a_net_in_pieces_works_out_its_sheet_once_and_repeats_byte_for_byte(grid, tmp_path: Path) -> None:
    drawing = DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0)
    net = NetOptions(face_size=8.6, pieces="auto")
    _paper.cache_clear()
    (tmp_path / "a").mkdir()
    first = net_files(grid, net, drawing, [tmp_path / "a" / "q.svg", tmp_path / "a" / "q.dxf"], title="queen",
                      seed=3)
    # The search's box, the packing, the placement and two drawings read one Paper.
    assert _paper.cache_info().misses == 1
    (tmp_path / "b").mkdir()
    again = net_files(grid, net, drawing, [tmp_path / "b" / "q.svg", tmp_path / "b" / "q.dxf"], title="queen",
                      seed=3)
    assert first.nets == again.nets and len(first.nets[0]["fill"]) > 1
    names = sorted(p.name for p in (tmp_path / "a").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "b").iterdir()) and len(names) >= 4
    for name in names:
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name


def test_the_paper_of_a4_at_8_6_mm() -> None:
    opts = DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0)
    p = paper(opts, 8.6)
    assert p is paper(opts, 8.6, None)
    x0, y0, x1, y1 = p.area
    assert (x0, x1) == (10.0, 200.0) and y1 == 287.0
    assert p.per_cell == 4 and p.step == pytest.approx(2.15)
    # Faces with a tab all round fit the cells; the raster covers the drawable area to within a step.
    assert p.cells[0] * 8.6 + 2 * p.tab_depth <= x1 - x0 < (p.cells[0] + 1) * 8.6 + 2 * p.tab_depth
    assert 0 <= (x1 - x0) - p.raster[0] * p.step < p.step and 0 <= (y1 - y0) - p.raster[1] * p.step < p.step
    assert p.tab_steps * p.step >= p.tab_depth > (p.tab_steps - 1) * p.step
    assert p.clear * p.step >= 1.0
