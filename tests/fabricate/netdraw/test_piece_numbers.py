"""Piece numbers a maker can read: on the queen's net in pieces, at least as tall as the seam labels.

Measured from the written DXF sheets, read back with ezdxf: the LABEL layer's strokes
at each piece number's place against the tallest seam-label glyph of the sheet.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _dxf_read import polylines

ROOT = Path(__file__).resolve().parents[3]


def _label_strokes(path: str) -> list[np.ndarray]:
    import ezdxf

    return [pts for _, pts, _ in polylines(ezdxf.readfile(path), "LABEL")]


def _distance(lo: np.ndarray, hi: np.ndarray, c: np.ndarray) -> np.ndarray:
    """From point ``c`` to each box ``lo``-``hi`` (0 inside it)."""
    dx = np.maximum(0, np.maximum(lo[:, 0] - c[0], c[0] - hi[:, 0]))
    dy = np.maximum(0, np.maximum(lo[:, 1] - c[1], c[1] - hi[:, 1]))
    return np.hypot(dx, dy)


@pytest.mark.slow
def test_piece_numbers_are_at_least_as_tall_as_the_seam_labels(tmp_path: Path) -> None:
    from voxfab.fabricate.netdraw import DrawingOptions, draw_pieces, write_net_drawing
    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape
    from voxfab.unfold import unfold

    queen = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid
    options = DrawingOptions(sheet="A4", pitch=8.6)  # the smallest faces with legible marks
    pieces = unfold(queen, rng=0, pieces="flat", fit=(21, 29), timeout=60.0)
    assert len(pieces) > 2
    drawing = draw_pieces(queen, pieces, options=options)  # where each number stands, per sheet
    files = write_net_drawing(queen, pieces, tmp_path / "queen.dxf", options, title="queen").files
    heading = float(options.margin) + float(options.title_height) + 1.5  # the title band at the foot
    measured = 0
    for s, path in enumerate(files):
        strokes = _label_strokes(path)
        lo = np.array([p.min(axis=0) for p in strokes])
        hi = np.array([p.max(axis=0) for p in strokes])
        centres = [c for sheet, c in drawing.number_at if sheet == s]

        near_a_number = np.zeros(len(strokes), dtype=bool)
        for c in centres:
            near_a_number |= _distance(lo, hi, c) < options.pitch
        # Seam-label glyphs: strokes of several points (not the straight bars of tape seams), away from
        # the piece numbers and the title; the tallest is the labels' cap height, along or across the sheet.
        glyph = (~near_a_number) & (np.array([len(p) for p in strokes]) >= 3) & (lo[:, 1] > heading)
        seam_height = float((hi - lo)[glyph].max())
        for c in centres:
            middle = _distance(lo, hi, c) < 0.6 * seam_height  # the strokes of the number's middle characters
            assert middle.any(), f"no piece number at {c} on sheet {s + 1}"
            height = float(hi[middle, 1].max() - lo[middle, 1].min())
            assert height >= seam_height - 1e-3, (s + 1, c, height, seam_height)
            measured += 1
    assert measured == len(pieces)


def _number_boxes_and_strokes(path: str) -> tuple[np.ndarray, np.ndarray, list[np.ndarray]]:
    """The LABEL layer of a written DXF sheet: the piece numbers' boxes (its closed rectangles, as lo and hi
    corners) and every other stroke."""
    import ezdxf

    boxes, strokes = [], []
    for _, pts, closed in polylines(ezdxf.readfile(path), "LABEL"):
        if closed and len(pts) == 4:
            boxes.append((pts.min(axis=0), pts.max(axis=0)))
        else:
            strokes.append(pts)
    lo = np.array([b[0] for b in boxes]).reshape(-1, 2)
    hi = np.array([b[1] for b in boxes]).reshape(-1, 2)
    return lo, hi, strokes


@pytest.mark.parametrize(("shape", "sheet", "cut", "box"), [
    ("queen", "A5", "flat", None), ("queen", "A4", "auto", None), ("queen", "80x80", "flat", None),
    ("ball", "A4", "auto", (2, 1)),  # dozens of one-face pieces, packed side by side
])
def test_piece_numbers_are_boxed_apart_from_each_other_and_from_the_seam_labels(tmp_path: Path, shape, sheet, cut,
                                                                                box) -> None:
    """Measured from the written DXF sheets: each number's box is taller than a seam label, no two boxes
    meet, and every other stroke of the labels layer lies wholly inside a box (the number's own) or
    wholly outside every box, one-face pieces included."""
    from voxfab.fabricate.netdraw import DrawingOptions, write_net_drawing
    from voxfab.fabricate.netdraw._sheets import sheet_cells
    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape
    from voxfab.shape import examples
    from voxfab.unfold import unfold

    grid = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid if shape == "queen" else \
        examples.ball(2)
    options = DrawingOptions(sheet=sheet, pitch=8.6)
    pieces = unfold(grid, rng=0, pieces=cut, fit=box or sheet_cells(options, 8.6), timeout=60.0)
    written = write_net_drawing(grid, pieces, tmp_path / "net.dxf", options, title=shape)
    boxes = 0
    for path in written.files:
        lo, hi, strokes = _number_boxes_and_strokes(path)
        boxes += len(lo)
        seam = [s for s in strokes if len(s) >= 3]  # glyph strokes (a tape mark is a bar of 2 points)
        seam_height = max(float(np.ptp(s[:, 1])) for s in seam) if seam else 0.0
        for a in range(len(lo)):
            assert hi[a, 1] - lo[a, 1] > seam_height + 1e-6
            for b in range(a + 1, len(lo)):
                apart = (hi[a] < lo[b]).any() or (hi[b] < lo[a]).any()
                assert apart, (path, lo[a], hi[a], lo[b], hi[b])
        for s in strokes:
            s_lo, s_hi = s.min(axis=0), s.max(axis=0)
            inside = ((s_lo >= lo - 1e-6) & (s_hi <= hi + 1e-6)).all(axis=1)
            meets = ((s_lo <= hi) & (s_hi >= lo)).all(axis=1)
            assert inside.sum() == 1 or not meets.any(), (path, s_lo, s_hi)
    assert boxes == len(pieces) > 1
    if shape == "ball":
        assert sum(p.face_count == 1 for p in pieces) >= 10


def test_a_number_box_is_on_its_piece_only_where_its_nine_points_fall_on_cells_of_the_piece() -> None:
    """The cells of a piece looked up as a raster: a box whose points fall past the raster on any side (left
    and below too, where an index would wrap round to the far side) is off the piece, as is one over a
    notch; every answer is that of the nine points looked up one by one."""
    from voxfab.fabricate.netdraw._assembly import _on_cells

    pitch, origin = 8.6, np.array([30.0, 40.0])
    # An L of cells with a notch: (0, 0) (1, 0) (2, 0) (0, 1) (0, 2), and (2, 2) alone across the notch.
    cells = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [0, 2], [2, 2]])
    rng = np.random.default_rng(0)
    lo = origin + rng.uniform(-2.5, 3.5, (4000, 2)) * pitch
    hi = lo + rng.uniform(0.1, 2.0, (4000, 2)) * pitch
    on = {tuple(c) for c in cells.tolist()}
    eps = 1e-6 * pitch
    want = []
    for a, b in zip(lo, hi):
        points = [(a[0] + eps if fx == 0 else b[0] - eps if fx == 1 else (a[0] + b[0]) / 2,
                   a[1] + eps if fy == 0 else b[1] - eps if fy == 1 else (a[1] + b[1]) / 2)
                  for fx in (0, 0.5, 1) for fy in (0, 0.5, 1)]
        want.append(all((int(np.floor((x - origin[0]) / pitch)), int(np.floor((y - origin[1]) / pitch))) in on
                        for x, y in points))
    got = _on_cells(lo, hi, origin, pitch, cells)
    assert got.tolist() == want
    assert 50 < sum(want) < 3000  # boxes on the piece and off it, on every side
    wrapped = np.array([[-1.0, 2.0], [2.0, -1.0], [-1.0, -1.0], [3.0, 0.0], [1.0, 3.0]]) * pitch + origin + 0.3
    assert not _on_cells(wrapped, wrapped + 0.5, origin, pitch, cells).any()
    assert _on_cells(origin + [[0.3, 0.3], [2.3, 2.3]], origin + [[2.0, 1.0], [2.8, 2.8]], origin, pitch,
                     cells).tolist() == [True, True]


def test_a_number_takes_the_first_clear_spot_of_all_though_the_spots_are_tried_a_block_at_a_time() -> None:
    """The spot found a block at a time is the first of the whole table: in the first block, past it (a
    piece whose first faces are crowded with labels), or none; on the piece's cells or inside the area."""
    from voxfab.fabricate.netdraw._assembly import _BLOCK, NUMBER_CLEAR, _first_clear

    rng = np.random.default_rng(1)
    n = 3 * _BLOCK + 17
    lo = rng.uniform(0, 200, (n, 2))
    hi = lo + 4.0
    area = (10.0, 10.0, 190.0, 190.0)
    for taken in (0, _BLOCK + 40, 2 * _BLOCK - 1, n):  # labels cover the spots before this one
        lo_b, hi_b = lo[:taken] + 0.5, hi[:taken] - 0.5
        inside = (lo[:, 0] >= area[0]) & (lo[:, 1] >= area[1]) & (hi[:, 0] <= area[2]) & (hi[:, 1] <= area[3])
        clear = ~((lo[:, None] < hi_b[None] + NUMBER_CLEAR) & (hi[:, None] > lo_b[None] - NUMBER_CLEAR)).all(axis=2).any(axis=1)
        ok = inside & clear
        want = int(np.argmax(ok)) if ok.any() else None
        assert _first_clear(lo, hi, lo_b, hi_b, area=area) == want
        assert want is None or want >= taken
    # On the cells: a 30 x 30 block of cells of 8.6 mm from the origin; the first spot past it is not one.
    pitch, origin = 8.6, np.zeros(2)
    cells = np.array([(x, y) for x in range(30) for y in range(30)])
    spots = np.concatenate([np.full((_BLOCK + 5, 2), 300.0), [[20.0, 20.0]]])
    got = _first_clear(spots, spots + 4.0, np.zeros((0, 2)), np.zeros((0, 2)), on=(origin, pitch, cells))
    assert got == _BLOCK + 5
