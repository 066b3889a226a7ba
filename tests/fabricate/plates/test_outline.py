"""Slicing layers into exact voxel outlines (voxfab.fabricate.plates._outline)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from voxfab.errors import InvalidShapeError
from voxfab.fabricate.plates import slice_layers
from voxfab.fabricate.plates._outline import layer_stack
from voxfab.shape import examples


def _flat(cells: list[tuple[int, int]], side: int = 5) -> np.ndarray:
    g = np.zeros((side, side, 1), dtype=bool)
    for u, v in cells:
        g[u, v, 0] = True
    return g


def test_corner_touching_cells_are_separate_pieces() -> None:
    layers = slice_layers(_flat([(0, 0), (1, 1), (2, 2), (2, 3)]))
    assert len(layers) == 1
    pieces = layers[0]
    assert [p.id for p in pieces] == ["1-1", "1-2", "1-3"]
    assert [len(p.cells) for p in pieces] == [1, 1, 2]
    # each outline is built from its own cells only: they meet at single points
    for a in pieces:
        assert a.outline.geom_type == "Polygon" and a.outline.is_valid
        for b in pieces:
            if a is not b:
                assert a.outline.intersection(b.outline).area == 0.0


def test_outline_is_exact_with_holes_and_oriented() -> None:
    ring = [(u, v) for u in range(4) for v in range(4) if u in (0, 3) or v in (0, 3)]
    (piece,) = slice_layers(_flat(ring))[0]
    poly = piece.outline
    assert poly.area == 12.0
    assert len(poly.interiors) == 1 and shapely.Polygon(poly.interiors[0]).area == 4.0
    assert poly.exterior.is_ccw and not poly.interiors[0].is_ccw
    # collinear lattice points are dropped: a square ring has 4 corners
    assert len(poly.exterior.coords) == 5


def test_hole_touching_itself_at_a_corner_stays_valid() -> None:
    g = np.ones((4, 4, 1), dtype=bool)
    g[1, 1, 0] = g[2, 2, 0] = False
    (piece,) = slice_layers(g)[0]
    assert piece.outline.is_valid and piece.outline.area == 14.0
    assert len(piece.outline.interiors) == 2


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_areas_match_voxel_counts_along_each_axis(axis: str) -> None:
    g = examples.random_shape(3, side=12)
    stack = layer_stack(g, axis=axis)
    layers = slice_layers(g, axis=axis)
    assert len(layers) == stack.shape[0]
    for k, pieces in enumerate(layers):
        assert sum(p.outline.area for p in pieces) == stack[k].sum()
        # the outline covers exactly the layer's cells
        for p in pieces:
            centres = p.cells + 0.5
            assert shapely.contains_xy(p.outline, centres[:, 0], centres[:, 1]).all()
            assert all(p.layer == k + 1 for p in pieces)
    assert sum(len(p.cells) for pcs in layers for p in pcs) == g.sum()


def test_axes_are_right_handed_and_layers_count_from_the_bottom() -> None:
    g = np.zeros((3, 4, 5), dtype=bool)
    g[0, 0, 1] = True  # lowest filled z layer after cropping is layer 1
    g[2, 3, 4] = True
    assert layer_stack(g, axis="z").shape == (4, 3, 4)
    assert layer_stack(g, axis="x").shape == (3, 4, 4)
    assert layer_stack(g, axis="y").shape == (4, 4, 3)
    layers = slice_layers(g)
    assert [len(p) for p in layers] == [1, 0, 0, 1]
    # z layers: u = x, v = y, so the top voxel sits at (2, 3)
    assert layers[3][0].cells.tolist() == [[2, 3]]


def test_piece_order_is_deterministic() -> None:
    g = examples.random_shape(5, side=10)
    a = [[p.cells.tolist() for p in pcs] for pcs in slice_layers(g)]
    b = [[p.cells.tolist() for p in pcs] for pcs in slice_layers(g.copy())]
    assert a == b


def test_bad_axis_and_empty_grid_are_refused() -> None:
    with pytest.raises(InvalidShapeError, match="axis"):
        slice_layers(np.ones((2, 2, 2), bool), axis="w")
    with pytest.raises(InvalidShapeError, match="empty"):
        slice_layers(np.zeros((2, 2, 2), bool))
