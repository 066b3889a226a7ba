"""Sheet fit, pieces that fit the sheet, and visibly distinct nets, on real shapes."""

from __future__ import annotations

import time

import numpy as np
import pytest

from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.shape import examples, surface_graph
from voxfab.unfold import NoFitError, unfold, unfold_many, validate


def _extent(net) -> tuple[int, int]:
    """Sides in cells of a net, measured from its 2D corners."""
    c = net.corners2d.reshape(-1, 2)
    w, h = (c.max(axis=0) - c.min(axis=0)).tolist()
    return w, h


def _fits(net, box: tuple[int, int]) -> bool:
    w, h = _extent(net)
    return (w <= box[0] and h <= box[1]) or (h <= box[0] and w <= box[1])


@pytest.mark.parametrize("box", [(40, 12), (12, 40), (21, 21)])
def test_net_grows_inside_the_box_either_way_round(box):
    grid = examples.ball(4)
    net = unfold(grid, rng=1, fit=box)
    assert _fits(net, box)
    report = validate(grid, net)
    assert report.ok and report.seams_without_tab_room == net.seams_without_tab_room
    # Tab room is made inside the box too.
    plain = unfold(grid, rng=1, fit=box, tab_aware=False)
    assert _fits(plain, box)
    assert net.seams_without_tab_room < plain.seams_without_tab_room / 4


def test_no_fit_says_how_compact_a_net_was_found():
    grid = examples.ball(4)
    faces = surface_graph(grid).face_count
    with pytest.raises(NoFitError) as err:
        unfold(grid, rng=0, fit=(17, 17))  # 289 cells for 294 faces
    assert isinstance(err.value, UnfoldError)
    w, h = err.value.best_extent
    assert w <= h and w * h >= faces and h < 40
    assert "17x17" in str(err.value) and f"{w}x{h}" in str(err.value)
    # The extent reported is one the search can reach.
    assert _fits(unfold(grid, rng=0, fit=(w, h), tab_aware=False), (w, h))


def test_pieces_auto_splits_into_pieces_that_each_fit():
    grid = examples.ball(6)
    faces = surface_graph(grid).face_count
    nets = unfold(grid, rng=0, fit=(18, 18), pieces="auto", timeout=20)
    assert len(nets) >= 3  # 678 faces cannot fit 324 cells in fewer
    assert all(_fits(n, (18, 18)) for n in nets)
    assert sum(n.face_count for n in nets) == faces
    sizes = sorted((n.face_count for n in nets), reverse=True)
    assert len(nets) <= 9  # a few large pieces, no scraps
    assert sizes[-1] * 10 >= sizes[0]
    assert validate(grid, nets).ok


def test_pieces_from_flat_patches_fit_refold_and_leave_room_for_every_tab():
    from voxfab.shape import SurfaceGraph

    grid = examples.ball(6)
    sg: SurfaceGraph = surface_graph(grid)
    nets = unfold(grid, rng=0, fit=(18, 18), pieces="flat", timeout=20)
    assert len(nets) >= 3
    assert all(_fits(n, (18, 18)) for n in nets)
    keys = [(tuple(v), tuple(d)) for n in nets for v, d in zip(n.voxel.tolist(), n.normal.tolist())]
    assert len(keys) == len(set(keys)) == sg.face_count
    sizes = sorted((n.face_count for n in nets), reverse=True)
    assert sizes[-1] * 10 >= sizes[0]
    assert validate(grid, nets).ok
    # A piece of whole flat patches lays no face beside another across an edge they do not share; only
    # pieces regrown to mend the size rule may leave a seam or two without room.
    assert sum(n.seams_without_tab_room for n in nets) <= 0.01 * sg.face_count
    # Flat patches stay flat: most edges between faces of one direction in a piece are folds in the plane.
    flat = sum(n.flat for n in nets)
    assert flat >= 0.5 * sum(n.folds.shape[0] for n in nets)


def _picture(net) -> np.ndarray:
    """A raster of the sheet: cells covered, and folds between cells (3 pixels per cell)."""
    cells = net.corners2d.min(axis=1)
    cells = cells - cells.min(axis=0)
    size = 3 * (cells.max(axis=0) + 1)
    img = np.zeros((size[0], size[1]), dtype=np.uint8)
    for x, y in cells.tolist():
        img[3 * x:3 * x + 3, 3 * y:3 * y + 3] = 1
    for i, j in net.folds.tolist():
        (xi, yi), (xj, yj) = cells[i].tolist(), cells[j].tolist()
        # The middle pixel of each cell's side along the fold.
        img[3 * xi + 1 + (xj - xi), 3 * yi + 1 + (yj - yi)] = 2
        img[3 * xj + 1 + (xi - xj), 3 * yj + 1 + (yi - yj)] = 2
    return img


def _symmetric_forms(img: np.ndarray) -> list[bytes]:
    forms = []
    for flip in (img, img[::-1]):
        for k in range(4):
            r = np.rot90(flip, k)
            forms.append(np.int64(r.shape).tobytes() + r.tobytes())
    return forms


def test_unfold_many_outlines_differ_up_to_rotations_and_mirrors():
    grid = examples.ball(3)
    nets = unfold_many(grid, count=12, rng=5, budget=30, tab_aware=False)
    assert len(nets) == 12
    seen: set[bytes] = set()
    for net in nets:
        assert validate(grid, net).ok
        forms = _symmetric_forms(_picture(net))
        assert not seen & set(forms)
        seen.update(forms)


def test_the_unit_cube_has_eleven_nets():
    nets = unfold_many(np.ones((1, 1, 1), bool), count=20, rng=0, budget=30)
    assert len(nets) == 11  # the classic count, up to rotations and mirrors
    pictures = {min(_symmetric_forms(_picture(n))) for n in nets}
    assert len(pictures) == 11


def test_unfold_many_stops_at_its_budget():
    grid = examples.ball(3)
    t = time.monotonic()
    nets = unfold_many(grid, count=10**9, rng=1, budget=1.5, timeout=20, tab_aware=False)
    assert time.monotonic() - t < 6
    assert 1 <= len(nets) < 10**9
    with pytest.raises(InvalidShapeError, match="budget"):
        unfold_many(grid, count=2, rng=1, budget=0)
    with pytest.raises(InvalidShapeError, match="count"):
        unfold_many(grid, count=True, rng=1)


@pytest.mark.parametrize(("radius", "box", "seed"), [(4, (9, 9), 0), (6, (12, 12), 1)])
def test_pieces_auto_keeps_every_piece_over_a_tenth_of_the_largest(radius, box, seed):
    # The box holds far fewer cells than the ball has faces, so the surface must be
    # split; no piece may be a stray scrap of a few faces.
    grid = examples.ball(radius)
    faces = surface_graph(grid).face_count
    nets = unfold(grid, rng=seed, fit=box, pieces="auto", timeout=30)
    sizes = [n.face_count for n in nets]
    assert len(nets) >= -(-faces // (box[0] * box[1]))
    assert sum(sizes) == faces
    assert min(sizes) * 10 >= max(sizes)
    assert all(_fits(n, box) for n in nets)
    report = validate(grid, nets)
    assert report.ok and report.pieces == len(nets)
    assert [n.to_json() for n in unfold(grid, rng=seed, fit=box, pieces="auto", timeout=30)] == \
        [n.to_json() for n in nets]


def test_pieces_auto_does_not_cut_branches_that_cannot_beat_the_slabs(monkeypatch):
    """The queen on A4 at 8.6 mm (21 x 30 cells): 3 slabs, and 2 branch pieces would each fill over two
    thirds of the box; the free net's branches and their joins (most of the cut's time) are not cut,
    and the pieces are those of the cut that tries them."""
    from pathlib import Path

    import voxfab.unfold._pieces as pieces_module
    from voxfab.recipe import load_recipe, make_shape

    grid = make_shape(load_recipe(Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml")).grid
    tree = pieces_module._tree_pieces
    calls = []
    monkeypatch.setattr(pieces_module, "_tree_pieces", lambda *a: calls.append(1) or tree(*a))
    nets = unfold(grid, rng=7, fit=(21, 30), pieces="auto", timeout=120)
    assert calls == [] and len(nets) == 3
    validate(grid, nets)
    monkeypatch.setattr(pieces_module, "_BRANCH_FILL", float("inf"), raising=False)  # branches always cut
    assert [n.to_json() for n in unfold(grid, rng=7, fit=(21, 30), pieces="auto", timeout=120)] == \
        [n.to_json() for n in nets]
    assert calls == [1]
