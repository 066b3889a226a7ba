"""pieces="bands": the surface cut into rows of faces round the shape, laid flat as straight strips."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from voxfab.fabricate.netdraw import DrawingOptions
from voxfab.fabricate.netdraw._drawing import sheets_needed
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import examples, fill_cavities, surface_graph
from voxfab.unfold import unfold, validate
from voxfab.unfold._bands import band_layouts
from voxfab.unfold._constraints import _SIDE_STEP
from voxfab.unfold._job import Job, Strategy

ROOT = Path(__file__).parents[2]
BOX = (21, 30)  # an A4 sheet's cells at 8.6 mm faces, less a face for the tabs


def _queen() -> np.ndarray:
    return fill_cavities(make_shape(load_recipe(ROOT / "recipes/chess/queen.toml")).grid)


def _fits(net, box: tuple[int, int]) -> bool:
    w, h = np.ptp(net.corners2d.reshape(-1, 2), axis=0)
    return (w <= box[0] and h <= box[1]) or (w <= box[1] and h <= box[0])


@pytest.mark.parametrize("make", [_queen, lambda: examples.torus(7.0, 3.0)], ids=["queen", "torus"])
def test_bands_refold_fit_and_keep_room_for_every_tab(make):
    grid = make()
    sg = surface_graph(grid)
    nets = unfold(grid, rng=0, fit=BOX, pieces="bands", timeout=60)
    keys = [(tuple(v), tuple(d)) for n in nets for v, d in zip(n.voxel.tolist(), n.normal.tolist())]
    assert len(keys) == len(set(keys)) == sg.face_count
    assert all(_fits(n, BOX) for n in nets)
    sizes = sorted((n.face_count for n in nets), reverse=True)
    assert sizes[-1] * 10 >= sizes[0]
    assert validate(grid, nets).ok
    # Every seam, inside a piece or between two, has a free cell beyond one of its sides for a tab.
    assert sum(n.seams_without_tab_room for n in nets) == 0
    _, _, untabbed = sheets_needed(grid, nets, DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0))
    assert untabbed == 0


def _job(grid: np.ndarray) -> Job:
    sg = surface_graph(grid)
    return Job(grid, sg, 0, Strategy.DEFAULT, BOX, True, False, time.monotonic() + 60, 60.0, None, bands=True)


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_a_band_lays_out_as_a_straight_strip_of_upright_faces(axis):
    grid = _queen()
    sg = surface_graph(grid)
    f = sg.face_count
    cell, rot, par = np.zeros((f, 2), dtype=np.int64), np.zeros(f, dtype=np.int64), np.full(f, -1, dtype=np.int64)
    patches = band_layouts(sg, np.arange(f), axis, BOX, cell, rot, par)
    assert sorted(np.concatenate(patches).tolist()) == list(range(f))
    strips = [p for p in patches if (sg.direction[p] // 2 != axis).all()]
    side = np.flatnonzero(sg.direction // 2 != axis)
    assert sum(p.size for p in strips) == side.size  # every side face is in a strip
    for p in strips:
        assert p.size <= max(BOX)
        assert (cell[p, 1] == 0).all() and sorted(cell[p, 0].tolist()) == list(range(p.size))
        for a in p.tolist():
            # Each face's edge towards the axis's + end lies on its cell's top side (2) ...
            up = sg.corners[a][:, axis]
            k_top = [k for k in range(4) if up[k] == up[(k + 1) % 4] == up.max()][0]
            assert (k_top + rot[a]) % 4 == 2
            if par[a] >= 0:
                # ... and it folds from its parent across their shared edge, side by side in the strip.
                b = int(par[a])
                k = int(np.flatnonzero(sg.neighbor[b] == a)[0])
                s = (k + rot[b]) % 4
                assert s in (1, 3) and tuple(cell[a] - cell[b]) == _SIDE_STEP[s]
                assert rot[a] == (s + 2 - sg.neighbor_edge[b, k]) % 4
        assert np.count_nonzero(par[p] < 0) == 1


def _cylinder() -> np.ndarray:
    """A round column 20 voxels high: its wall goes straight on from layer to layer."""
    x, y, z = np.ogrid[:25, :25, :25]
    return ((x - 12) ** 2 + (y - 12) ** 2 <= 36) & (z >= 2) & (z < 22)


def test_the_wall_of_a_column_comes_as_rectangles_of_strips():
    grid = _cylinder()
    sg = surface_graph(grid)
    nets = unfold(grid, rng=0, fit=BOX, pieces="bands", timeout=60)
    assert validate(grid, nets).ok
    wall = 0
    for n in nets:
        w, h = np.ptp(n.corners2d.reshape(-1, 2), axis=0)
        side = int(np.count_nonzero(n.normal[:, 2] == 0))
        if side == n.face_count:  # a piece of the wall alone: a rectangle, every cell of its box a face
            assert n.face_count == w * h
            wall += side
    assert wall == np.count_nonzero(sg.direction // 2 != 2)  # the whole wall, in rectangles
    # Two rectangles of the wall and the two end discs: the paper's own number of A4 sheets.
    opts = DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0)
    sheets, goal, untabbed = sheets_needed(grid, nets, opts)
    assert sheets == goal == 3 and untabbed == 0


def test_pieces_auto_keeps_the_cut_on_fewer_sheets():
    """``voxfab net --pieces auto``: the bands of a column take fewer sheets than its flat patches, so they are kept."""
    from voxfab.fabricate.netdraw import find_sheet_nets
    from voxfab.fabricate.netdraw._sheets import sheet_cells

    grid = _cylinder()
    opts = DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0)
    flat = unfold(grid, rng=0, fit=sheet_cells(opts, 8.6), pieces="flat", timeout=60)
    chosen = find_sheet_nets(grid, opts, rng=0, pieces="auto").nets[0]
    assert validate(grid, chosen).ok
    assert sheets_needed(grid, chosen, opts)[0] < sheets_needed(grid, flat, opts)[0]
