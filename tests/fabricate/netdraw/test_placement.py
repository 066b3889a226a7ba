"""Pieces placed on sheets by hand: a placement read from the packing, moved, turned, drawn and refused."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from _dxf_read import closed_rings

from voxfab.fabricate.netdraw import DrawingOptions, NetOptions, draw_pieces, fabricate_net, find_sheet_nets
from voxfab.fabricate.netdraw._drawing import placement_for
from voxfab.fabricate.netdraw._placement import Placement, PlacementError, turned
from voxfab.shape import VoxelShape, examples

OPTIONS = DrawingOptions(pitch=10.0, sheet="A4", label_height=2.0)


@pytest.fixture(scope="module")
def ball_pieces():
    grid = examples.ball(6)
    found = find_sheet_nets(grid, OPTIONS, rng=1, pieces="auto", timeout=60.0)
    pieces = found.nets[0]
    assert len(pieces) > 1
    return grid, pieces


def _moved(placement: Placement, piece: int, **change) -> Placement:
    places = list(placement.pieces)
    places[piece] = dataclasses.replace(places[piece], **change)
    return dataclasses.replace(placement, pieces=tuple(places))


def test_the_packing_read_as_a_placement_draws_the_same_sheets(ball_pieces, tmp_path: Path) -> None:
    grid, pieces = ball_pieces
    placement = placement_for(grid, pieces, OPTIONS)
    assert len(placement.pieces) == len(pieces) and placement.face_size == 10.0
    assert Placement.from_dict(placement.to_dict()) == placement
    packed = draw_pieces(grid, pieces, options=OPTIONS)
    placed = draw_pieces(grid, pieces, options=OPTIONS, placement=placement)
    assert len(placed.sheets) == len(packed.sheets) == placement.sheets
    for a, b in zip(packed.sheets, placed.sheets):
        assert np.allclose(a.faces, b.faces)
        for layer in a.layers:
            # the same lines, perhaps traced in another order
            pa, pb = a.layers[layer].points, b.layers[layer].points
            assert pa.shape == pb.shape
            assert np.allclose(pa[np.lexsort(pa.T[::-1])], pb[np.lexsort(pb.T[::-1])])


def test_a_moved_and_turned_piece_lands_where_the_placement_says(ball_pieces, tmp_path: Path) -> None:
    import ezdxf

    grid, pieces = ball_pieces
    placement = placement_for(grid, pieces, OPTIONS)
    # The smallest piece alone on a new sheet, turned half a turn, about the middle of the sheet.
    small = min(range(len(pieces)), key=lambda i: pieces[i].face_count)
    start = placement.pieces[small]
    turns = (start.turns + 2) % 4
    cells = turned(pieces[small].corners2d, turns).reshape(-1, 2)
    mid = (cells.min(axis=0) + cells.max(axis=0)) / 2 * 10.0
    x = start.x + 10.0 * round((105.0 - mid[0] - start.x) / 10.0)
    y = start.y + 10.0 * round((160.0 - mid[1] - start.y) / 10.0)
    moved = dataclasses.replace(_moved(placement, small, sheet=placement.sheets, x=x, y=y, turns=turns),
                                sheets=placement.sheets + 1)
    drawing = draw_pieces(grid, pieces, options=OPTIONS, placement=moved)
    last = drawing.sheets[-1]
    expect = np.array([x, y]) + turned(pieces[small].corners2d, turns) * 10.0
    assert last.faces.shape[0] == pieces[small].face_count
    assert np.allclose(np.sort(last.faces.reshape(-1, 2), axis=0), np.sort(expect.reshape(-1, 2), axis=0))
    # Through the net pipeline: the DXF of that sheet has its cut outline around those faces.
    made = fabricate_net(VoxelShape(grid), NetOptions(face_size=10.0, pieces="auto", formats=("dxf",)), OPTIONS,
                         tmp_path, name="ball", seed=1, chosen=pieces, placement=moved.to_dict())
    dxfs = sorted(tmp_path.glob("net.sheet-*.dxf"))
    assert len(dxfs) == made.report["sheets"] == moved.sheets
    doc = ezdxf.readfile(dxfs[-1])
    pts = np.concatenate(closed_rings(doc))
    lo, hi = expect.reshape(-1, 2).min(axis=0), expect.reshape(-1, 2).max(axis=0)
    assert (pts.min(axis=0) >= lo - OPTIONS.tab_width - 1e-6).all()
    assert (pts.max(axis=0) <= hi + OPTIONS.tab_width + 1e-6).all()
    assert (pts.min(axis=0) >= OPTIONS.margin).all() and (pts.max(axis=0) <= np.array(OPTIONS.sheet_size)
                                                            - OPTIONS.margin).all()


def test_pieces_over_each_other_or_across_the_margin_are_refused(ball_pieces) -> None:
    grid, pieces = ball_pieces
    placement = placement_for(grid, pieces, OPTIONS)
    a, b = placement.pieces[0], placement.pieces[1]
    # Piece 2 put exactly where piece 1 is, on its sheet.
    with pytest.raises(PlacementError, match=r"^pieces 1 and 2 overlap or touch on sheet \d+"):
        draw_pieces(grid, pieces, options=OPTIONS, placement=_moved(placement, 1, sheet=a.sheet, x=a.x, y=a.y,
                                                                    turns=a.turns))
    with pytest.raises(PlacementError, match=r"^piece 2 crosses the margin of sheet \d+"):
        draw_pieces(grid, pieces, options=OPTIONS, placement=_moved(placement, 1, x=b.x - 300.0))
    # A piece half a millimetre off the packer's 1 mm raster.
    with pytest.raises(PlacementError, match="^piece 2: not on the packing grid"):
        draw_pieces(grid, pieces, options=OPTIONS, placement=_moved(placement, 1, x=b.x + 0.5))
    with pytest.raises(PlacementError, match="mirrored"):
        draw_pieces(grid, pieces, options=OPTIONS, placement=_moved(placement, 1, mirror=True))
    with pytest.raises(PlacementError, match="made for a 5 mm margin"):
        draw_pieces(grid, pieces, options=OPTIONS, placement=dataclasses.replace(placement, margin=5.0))
    with pytest.raises(PlacementError, match="made for 12 mm faces"):
        draw_pieces(grid, pieces, options=OPTIONS, placement=dataclasses.replace(placement, face_size=12.0))


@pytest.mark.parametrize(("data", "words"), [
    (None, "expected an object"),
    ({"sheet": [210, 297], "margin": 10, "face_size": 10, "sheets": 1, "pieces": []}, "one entry per piece"),
    ({"sheet": [210], "margin": 10, "face_size": 10, "sheets": 1, "pieces": [{}]}, "sheet"),
    ({"sheet": [210, 297], "margin": 10, "face_size": 10, "sheets": 1,
      "pieces": [{"piece": 0, "sheet": 0, "x": 1, "y": 1, "turns": 4}]}, "turns: expected a whole number"),
    ({"sheet": [210, 297], "margin": 10, "face_size": 10, "sheets": 1,
      "pieces": [{"piece": 0, "sheet": 0, "x": 1, "y": 1}, {"piece": 0, "sheet": 0, "x": 1, "y": 1}]},
     "exactly once"),
    ({"sheet": [210, 297], "margin": 10, "face_size": "big", "sheets": 1, "pieces": [{}]}, "face_size"),
])
def test_bad_placements_get_one_line(data, words) -> None:
    with pytest.raises(PlacementError, match=words) as err:
        Placement.from_dict(data)
    assert "\n" not in str(err.value)


def test_a_placement_lays_the_pieces_two_cells_apart_and_each_face_where_it_says(ball_pieces) -> None:
    from voxfab.fabricate.netdraw._placement import plan_placement

    grid, pieces = ball_pieces
    placement = placement_for(grid, pieces, OPTIONS)
    plan, placed = plan_placement(placement, [p.corners2d for p in pieces], OPTIONS)
    # Each piece two cells past the one before (no offset growing with every piece, which costs the mm
    # their precision on a net of many pieces).
    for a, b in zip(placed, placed[1:]):
        assert b[..., 0].min() == a[..., 0].max() + 2
    faces = plan.face_positions()
    start = 0
    for place, piece in zip(placement.pieces, pieces):
        expect = np.array([place.x, place.y]) + turned(piece.corners2d, place.turns) * placement.face_size
        assert np.abs(faces[start:start + piece.face_count] - expect).max() < 1e-9
        start += piece.face_count
