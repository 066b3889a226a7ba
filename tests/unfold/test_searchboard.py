"""The search board's tab-room annealing: nets grown for tab room, and the rounds that start from them."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import examples, surface_graph
from voxfab.unfold import _searchboard as searchboard
from voxfab.unfold import unfold, validate
from voxfab.unfold._job import Strategy, growth_settings, tab_growth

QUEEN = Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml"


@pytest.fixture(scope="module")
def queen() -> np.ndarray:
    return make_shape(load_recipe(QUEEN)).grid


def test_a_net_grown_for_tab_room_starts_with_fewer_seams_without_it(queen):
    sg = surface_graph(queen)
    faces = np.arange(sg.face_count)
    gw = growth_settings(Strategy.DEFAULT, sg.face_count)
    dense, sparse = [], []
    for seed in range(6):
        b = searchboard.SearchBoard(sg, faces, seed, None)
        assert b.grow(gw, math.inf)
        dense.append(searchboard.count_seams(b))
        b = searchboard.SearchBoard(sg, faces, seed, None)
        assert b.grow(tab_growth(gw), math.inf, sparse=True)
        assert (b.pos[faces] >= 0).all()
        sparse.append(searchboard.count_seams(b))
    assert sum(sparse) <= 0.8 * sum(dense), (dense, sparse)


def _rounds(monkeypatch) -> list[int]:
    """The seams left by each annealing round of the searches that follow."""
    left: list[int] = []
    run = searchboard.SearchBoard._anneal_round

    def counted(self, *args):  # noqa: ANN001, ANN002, ANN202
        got = run(self, *args)
        left.append(got[0])
        return got

    monkeypatch.setattr(searchboard.SearchBoard, "_anneal_round", counted)
    return left


def test_nets_that_need_a_fresh_net_still_get_tab_room_on_every_seam(monkeypatch):
    # Seeds whose first round gets stuck (a fresh net, grown for tab room, fixes the rest).
    grid = examples.tunnel_cube(9)
    left = _rounds(monkeypatch)
    for seed in (0, 2, 18):
        left.clear()
        net = unfold(grid, rng=seed)
        assert len(left) > 1 and left[0] > 0 and left[-1] == 0, left
        report = validate(grid, net)  # refolds the net onto the shape
        assert report.ok, report.problems
        assert report.seams_without_tab_room == net.seams_without_tab_room == 0
        assert unfold(grid, rng=seed).to_json() == net.to_json()


def test_the_queens_nets_keep_tab_room_on_every_seam(queen, monkeypatch):
    left = _rounds(monkeypatch)
    for seed in range(4):
        net = unfold(queen, rng=seed)
        report = validate(queen, net)
        assert report.ok, report.problems
        assert report.seams_without_tab_room == 0
    assert left.count(0) == 4  # each search ended with every seam given room
