"""Edge-unzipping in the DDEO model beside the unit-square zipper, on the cube, boxes, a zipless polycube."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from voxfab.census import cut_path_problem, grid_of, topology, unzip
from voxfab.census._certificate import check_certificate
from voxfab.errors import NoNetExistsError, UnfoldError
from voxfab.unfold import Net, unfold, validate

from ._examples import ZIPLESS_14, ZIPLESS_17


def _assert_one_path_through_corners(grid: np.ndarray, net: Net) -> None:
    """The cut edges form one simple path that holds every corner vertex (counted from the cubes)."""
    problem = cut_path_problem(np.argwhere(grid).tolist(), net)
    assert problem is None, problem


def test_the_unit_cube_unzips_with_a_path_through_its_8_corners() -> None:
    g = np.ones((1, 1, 1), dtype=bool)
    found = unzip(g)
    assert found.outcome == "found"
    validate(g, found.net)
    _assert_one_path_through_corners(g, found.net)
    assert found.net.folds.shape[0] == 5 and len(found.path) == 8  # 12 edges: 5 folds, 7 cuts


def test_the_2x2x2_cube_unzips_in_the_paper_model_but_has_no_unit_square_zipper() -> None:
    g = np.ones((2, 2, 2), dtype=bool)
    found = unzip(g)
    assert found.outcome == "found"
    validate(g, found.net)
    _assert_one_path_through_corners(g, found.net)
    # Coplanar squares stay joined round the uncut flat vertices: the folds hold cycles.
    assert found.net.folds.shape[0] > found.net.face_count - 1
    with pytest.raises(NoNetExistsError, match="14 vertices of one colour and 12"):
        unfold(g, rng=0, strategy="exact", zipper=True, timeout=20)


@pytest.mark.parametrize("cells", [
    [[0, 0, 0], [1, 0, 0], [2, 0, 0]],  # the 1 x 1 x 3 box (Uno's overlapping development)
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]],  # a chiral tetracube
    [[x, y, 0] for x in range(3) for y in range(3)],  # a 3 x 3 plate: flat vertices on both sides
])
def test_small_polycubes_unzip_and_refold(cells: list[list[int]]) -> None:
    g = grid_of(cells)
    found = unzip(g, timeout=30)
    assert found.outcome == "found"
    validate(g, found.net)
    _assert_one_path_through_corners(g, found.net)


def test_the_zipless_polycube_has_no_unzipping_by_its_colour_count_yet_unfolds() -> None:
    g = grid_of(ZIPLESS_14)
    assert topology(g).kind == "manifold"
    found = unzip(g)
    assert found.outcome == "none" and found.certificate["kind"] == "colours"
    assert "alternating path" in check_certificate(ZIPLESS_14, found.certificate)
    # The certificate is checked, not trusted: other counts, or another polycube, are refused.
    with pytest.raises(ValueError, match="not those of the certificate"):
        check_certificate(ZIPLESS_14, {**found.certificate, "flats": [6, 1]})
    with pytest.raises(ValueError, match="not those of the certificate"):
        check_certificate(ZIPLESS_14[:-1], found.certificate)
    # Like the paper's polycubes, it has an edge unfolding all the same.
    net = unfold(g, rng=0, timeout=60, tab_aware=False)
    validate(g, net)


def test_a_polycube_without_an_unzipping_is_proved_by_the_solver_and_re_checked() -> None:
    g = grid_of(ZIPLESS_17)
    assert topology(g).kind == "manifold"
    found = unzip(g, timeout=120)
    assert found.outcome == "none", found.why
    cert = found.certificate
    assert cert["kind"] == "solver" and cert["overlaps"]
    assert "no cut path through the 54 corners" in check_certificate(ZIPLESS_17, cert)
    # Each no-good is re-derived, not trusted: a chain that does not fold onto itself is refused ...
    bad = {**cert, "overlaps": [*cert["overlaps"][:-1], [[0, 1]]]}
    with pytest.raises(ValueError):
        check_certificate(ZIPLESS_17, bad)
    # ... and too few no-goods leave a path: the re-solved model finds it.
    with pytest.raises(ValueError, match="proves nothing"):
        check_certificate(ZIPLESS_17, {**cert, "overlaps": cert["overlaps"][: len(cert["overlaps"]) // 2]})
    # It has an edge unfolding in the unit-square model all the same.
    validate(g, unfold(g, rng=0, timeout=60, tab_aware=False))


def test_cuts_that_are_not_one_path_are_caught() -> None:
    g = np.ones((1, 1, 2), dtype=bool)
    cells = np.argwhere(g).tolist()
    zipped = unzip(g).net
    assert cut_path_problem(cells, zipped) is None
    # One fold fewer is one more cut edge: the cuts branch (or close a cycle), never one path.
    for drop in range(zipped.folds.shape[0]):
        fewer = dataclasses.replace(zipped, folds=np.delete(zipped.folds, drop, axis=0))
        assert cut_path_problem(cells, fewer) is not None
    # A unit-square zipper (cuts through every vertex) is an unzipping too; a plain net's cut tree need not be.
    plain = unfold(g, rng=0, tab_aware=False)
    assert cut_path_problem(cells, plain) == "the cut edges do not form one simple path"


def test_a_surface_outside_the_model_is_refused() -> None:
    with pytest.raises(UnfoldError, match="2-manifold of genus 0"):
        unzip(grid_of([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [2, 1, 0], [0, 2, 0], [1, 2, 0], [2, 2, 0]]))


def test_a_cancelled_job_stops_the_unzipping_search() -> None:
    """The census's search runs through the cancel-aware solve: a cancelled studio or batch job stops it."""
    import threading

    from voxfab._shared.progress import cancel_scope
    from voxfab.errors import CancelledError

    event = threading.Event()
    event.set()
    with cancel_scope(event), pytest.raises(CancelledError):
        unzip(grid_of(ZIPLESS_17), timeout=60)
    assert unzip(grid_of(ZIPLESS_17), timeout=60).outcome == "none"  # outside the scope it runs to its proof


@pytest.mark.parametrize("seconds", [1e-9, 1e-4])
def test_a_search_out_of_time_before_it_began_is_undecided(seconds: float) -> None:
    """Time that runs out while the short overlaps are ruled out, before the solver, is undecided, not an error."""
    found = unzip(grid_of(ZIPLESS_17), timeout=seconds)
    assert found.outcome == "undecided" and found.net is None and found.certificate is None
    assert "ran out of time" in found.why and "raise the timeout" in found.why
