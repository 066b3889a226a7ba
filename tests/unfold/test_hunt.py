"""The hunt of one shape: a one-piece net by the random engine or the exact strategy, and a zipper net."""

from __future__ import annotations

import numpy as np
import pytest
from _batch_fixtures import column
from _zipper_checks import cuts_form_one_path

pytest.importorskip("ortools")

from voxfab.errors import InvalidShapeError, NoNetExistsError  # noqa: E402
from voxfab.unfold import hunt_shape, unfold, validate  # noqa: E402

ARMS = np.zeros((3, 2, 2), dtype=bool)
ARMS[:, 0, 0] = ARMS[0, :, 0] = ARMS[0, 0, :] = True  # three arms from a corner
RING = np.ones((3, 3, 1), dtype=bool)
RING[1, 1, 0] = False


@pytest.mark.parametrize("bumps", [(), (5,), (2, 9, 17)])
def test_zipper_nets_of_explore_sized_columns(bumps):
    """Columns spanning the grid (the smallest well-formed shapes) have zipper nets, found in any box."""
    grid = column(*bumps)
    net = unfold(grid, rng=0, strategy="exact", zipper=True, timeout=60)
    assert validate(grid, net, strict=True).ok
    assert cuts_form_one_path(grid, net)


def test_zipper_search_is_deterministic():
    grid = column(5)
    a = unfold(grid, rng=0, strategy="exact", zipper=True, timeout=60)
    b = unfold(grid, rng=7, strategy="exact", zipper=True, timeout=60)
    assert a.to_json() == b.to_json()


def test_hunt_records_a_random_net_and_a_zipper_net():
    out = hunt_shape(ARMS, zipper_timeout=30)
    assert (out.net, out.zipper, out.faces) == ("random", "found", 22)
    assert validate(ARMS, out.one_piece).ok and validate(ARMS, out.zipper_net).ok
    assert cuts_form_one_path(ARMS, out.zipper_net)
    assert out.one_piece.strategy == "default" and out.zipper_net.strategy == "exact"
    x0, y0, x1, y1 = out.zipper_net.bounds()
    assert out.to_dict()["zipper_box"] == sorted((x1 - x0, y1 - y0))


def test_hunt_passes_a_random_failure_to_the_exact_strategy():
    # A budget the random engine cannot meet: the exact strategy finds the net.
    out = hunt_shape(ARMS, timeout=1e-9, zipper=False)
    assert (out.net, out.zipper) == ("exact", "skipped")
    assert out.one_piece.strategy == "exact" and validate(ARMS, out.one_piece, strict=True).ok


def test_hunt_proves_that_a_ring_has_no_zipper_net():
    out = hunt_shape(RING)
    assert (out.net, out.zipper) == ("random", "none")
    assert out.zipper_net is None and "handle" in out.why[0]
    assert "zipper" not in {k for k in out.to_dict() if k.endswith("_box")}


def test_hunt_says_undecided_when_time_runs_out():
    grid = column(2, 9, 17)
    out = hunt_shape(grid, zipper_timeout=1e-6)
    assert (out.net, out.zipper) == ("random", "undecided")
    assert out.zipper_net is None and out.why[0].startswith("undecided")
    # The exact one-piece search starts from a growth net in the box, confirmed even when out of time.
    out = hunt_shape(grid, timeout=1e-9, exact_timeout=1e-6, zipper=False)
    assert out.net == "exact" and validate(grid, out.one_piece, strict=True).ok


def test_hunt_refuses_bad_input():
    with pytest.raises(InvalidShapeError, match="zipper_timeout"):
        hunt_shape(ARMS, zipper_timeout=0)
    with pytest.raises(InvalidShapeError, match="timeout"):
        hunt_shape(ARMS, timeout=float("nan"))
    two = np.zeros((3, 1, 1), dtype=bool)
    two[0] = two[2] = True
    with pytest.raises(InvalidShapeError, match="2 separate components"):
        hunt_shape(two)


def test_zipper_with_constraints_needs_a_box():
    from voxfab.shape import surface_graph
    from voxfab.unfold import EdgeConstraints
    from voxfab.unfold._constraints import face_of

    sg = surface_graph(ARMS)
    keep = EdgeConstraints(keep=[(face_of(sg, 0), face_of(sg, int(sg.neighbor[0, 0])))])
    with pytest.raises(InvalidShapeError, match="needs a box"):
        unfold(ARMS, rng=0, strategy="exact", zipper=True, constraints=keep)
    with pytest.raises(NoNetExistsError):
        unfold(RING, rng=0, strategy="exact", zipper=True)


def test_unbalanced_colours_have_no_zipper_net():
    """The 2x2x2 cube's vertices: 14 with x + y + z even, 12 odd; a cut path alternates, so none exists."""
    from voxfab.shape import surface_graph

    cube = np.ones((2, 2, 2), dtype=bool)
    sg = surface_graph(cube)
    pos = sg.vertex_position[np.unique(sg.vertex)]
    assert sorted(np.bincount(pos.sum(axis=1) % 2).tolist()) == [12, 14]  # counted here, independently
    with pytest.raises(NoNetExistsError, match="14 vertices of one colour and 12 of the other"):
        unfold(cube, rng=0, strategy="exact", zipper=True)
    out = hunt_shape(cube)
    assert (out.net, out.zipper) == ("random", "none")
