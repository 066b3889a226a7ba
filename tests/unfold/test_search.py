"""unfold / unfold_many on real shapes: valid, reproducible, varied, honest about failure."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.shape import cavity_count, examples, surface_graph
from voxfab.unfold import Net, seam_pairs, tab_room, unfold, unfold_many, validate


@pytest.mark.parametrize("radius", [2, 3, 4, 6])
def test_balls_unfold_in_one_valid_piece(radius):
    grid = examples.ball(radius)
    net = unfold(grid, rng=radius, timeout=30, tab_aware=radius < 4)
    assert isinstance(net, Net)
    sg = surface_graph(grid)
    assert net.face_count == sg.face_count
    np.testing.assert_array_equal(net.voxel, sg.voxel)  # face i is surface face i
    assert validate(grid, net).ok


@pytest.mark.parametrize("name", ["tunnel5", "torus", "random0", "random1", "vase"])
def test_corpus_shapes_unfold(name):
    grid = {
        "tunnel5": lambda: examples.tunnel_cube(5),
        "torus": lambda: examples.torus(6, 2.5),
        "random0": lambda: examples.random_shape(0, side=12),
        "random1": lambda: examples.random_shape(1, side=12),
        "vase": lambda: examples.vase(12),
    }[name]()
    net = unfold(grid, rng=7, timeout=30, tab_aware=False)
    report = validate(grid, net)
    assert report.ok
    assert net.seams_without_tab_room == report.seams_without_tab_room


def test_tab_aware_search_beats_plain_growth():
    grid = examples.tunnel_cube(5)
    plain = unfold(grid, rng=3, tab_aware=False)
    aware = unfold(grid, rng=3)
    assert plain.seams_without_tab_room > 20  # plain growth blocks many tabs
    assert aware.seams_without_tab_room == 0
    assert validate(grid, plain).ok and validate(grid, aware).ok
    torus = examples.torus(6, 2.5)
    net = unfold(torus, rng=1)
    assert net.seams_without_tab_room == 0 == validate(torus, net).seams_without_tab_room


def test_same_seed_same_bytes_and_other_seed_other_net():
    grid = examples.ball(4)
    a = unfold(grid, rng=11).to_json()
    b = unfold(grid, rng=11).to_json()
    c = unfold(grid, rng=12).to_json()
    assert a == b
    assert a != c
    assert Net.from_json(a).seed == 11


def test_generator_rng_is_accepted_and_recorded():
    grid = examples.ball(2)
    net = unfold(grid, rng=np.random.default_rng(4))
    again = unfold(grid, rng=net.seed)
    assert net.to_json() == again.to_json()


def test_unfold_many_gives_distinct_valid_nets():
    grid = examples.ball(3)
    nets = unfold_many(grid, count=4, rng=9)
    keys = {n.corners2d.tobytes() + n.folds.tobytes() for n in nets}
    assert len(keys) == 4
    for net in nets:
        assert validate(grid, net).ok
    again = unfold_many(grid, count=4, rng=9)
    assert [n.to_json() for n in again] == [n.to_json() for n in nets]


def test_paper_strategy_finds_valid_nets_of_small_shapes():
    for grid in (examples.ball(2), examples.tunnel_cube(5)):
        net = unfold(grid, rng=1, strategy="paper", timeout=30)
        assert net.strategy == "paper"
        assert validate(grid, net).ok


def test_seam_pairs_and_tab_room_agree_with_net():
    grid = examples.torus(5, 2)
    net = unfold(grid, rng=2, tab_aware=False)
    sg = surface_graph(grid)
    seams = seam_pairs(grid, net)
    total_edges = 2 * sg.face_count
    assert seams.shape == (total_edges - len(net.folds), 2, 2)
    for (f, k), (g, kk) in seams.tolist():
        assert sg.neighbor[f, k] == g and sg.neighbor_edge[f, k] == kk
    room = tab_room(grid, net)
    assert room.shape == (seams.shape[0], 2)
    assert int((~room.any(axis=1)).sum()) == net.seams_without_tab_room
    assert validate(grid, net).seams_without_tab_room == net.seams_without_tab_room


def test_no_slits_are_cut():
    # A flat 2x2 block's centre vertex must not end a cut: the 4x4x1 slab has many.
    grid = examples.box(4, 4, 1)
    for seed in range(4):
        net = unfold(grid, rng=seed, tab_aware=seed % 2 == 0)
        assert validate(grid, net).ok  # the validator reports slits


def test_fit_keeps_the_net_inside_the_box():
    grid = examples.ball(3)
    net = unfold(grid, rng=1, fit=(20, 16), timeout=30, tab_aware=False)
    x0, y0, x1, y1 = net.bounds()
    assert x1 - x0 <= 20 and y1 - y0 <= 16
    assert validate(grid, net).ok


def test_compact_shrinks_the_bounding_box():
    grid = examples.ball(4)
    loose = unfold(grid, rng=3, tab_aware=False)
    tight = unfold(grid, rng=3, tab_aware=False, compact=True)
    area = [(b[2] - b[0]) * (b[3] - b[1]) for b in (loose.bounds(), tight.bounds())]
    assert area[1] < area[0]
    assert validate(grid, tight).ok
    assert tight.to_json() == unfold(grid, rng=3, tab_aware=False, compact=True).to_json()


def test_fit_smaller_than_surface_is_refused():
    with pytest.raises(UnfoldError, match="more than the 10x10"):
        unfold(examples.ball(3), rng=0, fit=(10, 10))


def test_cavity_is_refused_with_offer():
    grid = examples.box(3, 3, 3)
    grid[1, 1, 1] = False
    with pytest.raises(UnfoldError, match=r"cavity.*fill=True.*pieces='auto'"):
        unfold(grid, rng=0)
    filled = unfold(grid, rng=0, fill=True)
    assert validate(examples.box(3, 3, 3), filled).ok


def test_void_open_along_an_edge_is_one_surface():
    # The centre void touches the notch at (0, 0, 1) only along an edge: it is a
    # cavity for water and printing, but by the 6-connectivity rule its walls join
    # the outer surface, so one net covers both.
    grid = examples.box(3, 3, 3)
    grid[1, 1, 1] = grid[0, 0, 1] = False
    assert cavity_count(grid) == 1
    net = unfold(grid, rng=0, tab_aware=False)
    assert validate(grid, net).ok and net.face_count == surface_graph(grid).face_count


def test_disconnected_shape_is_refused():
    grid = np.zeros((3, 3, 3), dtype=bool)
    grid[0, 0, 0] = grid[1, 1, 0] = True  # touching along an edge only
    with pytest.raises(UnfoldError, match="not 6-connected"):
        unfold(grid, rng=0)
    nets = unfold(grid, rng=0, pieces="auto")
    assert len(nets) == 2 and validate(grid, nets).ok


def test_timeout_failure_says_what_was_tried():
    grid = examples.ball(8)
    with pytest.raises(UnfoldError, match=r"strategy 'paper'.*dead ends.*best partial net"):
        unfold(grid, rng=0, strategy="paper", timeout=0.05)


def test_pieces_auto_falls_back_to_several_pieces_when_budget_ends():
    grid = examples.ball(8)
    nets = unfold(grid, rng=0, strategy="paper", timeout=0.05, pieces="auto")
    assert isinstance(nets, list) and len(nets) >= 1
    report = validate(grid, nets)
    assert report.ok and report.pieces == len(nets)


def test_bad_options_are_refused():
    grid = examples.ball(2)
    with pytest.raises(InvalidShapeError, match="strategy"):
        unfold(grid, rng=0, strategy="magic")
    with pytest.raises(InvalidShapeError, match="pieces"):
        unfold(grid, rng=0, pieces="two")
    with pytest.raises(InvalidShapeError, match="seed"):
        unfold(grid, rng=-1)
    with pytest.raises(InvalidShapeError, match="fit"):
        unfold(grid, rng=0, fit=(0, 3))
    with pytest.raises(InvalidShapeError, match="count"):
        unfold_many(grid, count=0, rng=0)


def test_a_net_of_the_filled_surface_says_so_and_keeps_it_in_json():
    import numpy as np

    from voxfab.shape import fill_cavities
    from voxfab.unfold import Net, unfold, validate

    g = np.ones((5, 5, 5), bool)
    g[2, 2, 2] = False  # one enclosed cavity
    net = unfold(g, rng=3, fill=True)
    assert net.filled
    validate(fill_cavities(g), net)
    again = Net.from_json(net.to_json())
    assert again.filled and again.to_json() == net.to_json()
    assert not unfold(fill_cavities(g), rng=3).filled


def test_search_counts_its_progress(monkeypatch):
    import contextlib

    from voxfab._shared.progress import Meter
    from voxfab.unfold import _many, _onepiece

    meters: list[Meter] = []

    @contextlib.contextmanager
    def recording(total=None, *, desc=""):
        m = Meter(total, desc)
        meters.append(m)
        yield m

    monkeypatch.setattr(_many, "meter", recording)  # the nets
    monkeypatch.setattr(_onepiece, "meter", recording)  # each net's growth and tab room
    g = examples.ball(4)
    nets = unfold_many(g, count=2, rng=3)
    by_desc = {}
    for m in meters:
        by_desc.setdefault(m.desc, []).append(m)
    faces = surface_graph(g).face_count
    assert [m.done for m in by_desc["nets"]] == [2]
    assert all(m.done == m.total == faces for m in by_desc["net: faces placed"])
    # One net search per seed tried, each growing and then annealing for tab room.
    assert len(by_desc["net: tab room, moves (at most)"]) == len(by_desc["net: faces placed"]) >= len(nets)


def test_small_surfaces_skip_the_compiler_and_give_the_same_nets(monkeypatch):
    import subprocess
    import sys

    from voxfab.unfold import _searchboard

    grid = examples.ball(3)  # 174 faces: plain Python by default
    plain = [unfold(grid, rng=s).to_json() for s in range(3)]
    monkeypatch.setattr(_searchboard, "_PURE_FACES", 0)
    compiled = [unfold(grid, rng=s).to_json() for s in range(3)]
    assert plain == compiled  # the same source, the same arithmetic
    code = ("import sys; from voxfab.shape import examples; from voxfab.unfold import unfold, validate; "
            "g = examples.ball(2); validate(g, unfold(g, rng=0)); print('numba' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False"
