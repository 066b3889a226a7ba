"""Edge-unzipping in the DDEO model beside the unit-square zipper, on the cube, boxes, a zipless polycube."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.census import grid_of, topology, unzip
from voxfab.census._certificate import check_certificate
from voxfab.errors import NoNetExistsError, UnfoldError
from voxfab.unfold import Net, unfold, validate

from ._examples import ZIPLESS_17, ZIPLESS_43


def _cut_edges(net: Net) -> list[tuple[tuple[int, ...], tuple[int, ...]]]:
    """Surface edges that are not folds, from the net's 3D corners alone."""
    owners: dict[frozenset, list[int]] = {}
    for i, c3 in enumerate(net.corners3d.tolist()):
        for k in range(4):
            owners.setdefault(frozenset((tuple(c3[k]), tuple(c3[(k + 1) % 4]))), []).append(i)
    folds = {tuple(sorted(p)) for p in net.folds.tolist()}
    return [tuple(sorted(e)) for e, o in owners.items() if tuple(sorted(o)) not in folds]


def _assert_one_path_through_corners(grid: np.ndarray, net: Net) -> list[tuple[int, ...]]:
    """The cut edges form one simple path that holds every corner vertex (counted from the cubes)."""
    cuts = _cut_edges(net)
    degree: dict[tuple[int, ...], int] = {}
    for p, q in cuts:
        degree[p] = degree.get(p, 0) + 1
        degree[q] = degree.get(q, 0) + 1
    assert sorted(degree.values()).count(1) == 2 and max(degree.values()) <= 2
    assert len(degree) == len(cuts) + 1  # a path: one more vertex than edges, connected below
    seen, todo = {cuts[0][0]}, [cuts[0][0]]
    while todo:
        v = todo.pop()
        for p, q in cuts:
            for a, b in ((p, q), (q, p)):
                if a == v and b not in seen:
                    seen.add(b)
                    todo.append(b)
    assert seen == set(degree)
    filled = {tuple(c) for c in np.argwhere(grid).tolist()}
    corners = set()
    for x, y, z in filled:
        for dx in (0, 1):
            for dy in (0, 1):
                for dz in (0, 1):
                    p = (x + dx, y + dy, z + dz)
                    octs = [(p[0] - a, p[1] - b, p[2] - c) for a in (0, 1) for b in (0, 1) for c in (0, 1)]
                    inside = [o in filled for o in octs]
                    squares = sum(inside[i] != inside[j] for i in range(8) for j in range(i + 1, 8)
                                  if sum(abs(u - v) for u, v in zip(octs[i], octs[j])) == 1)
                    if squares not in (0, 4):
                        corners.add(p)
    assert corners <= set(degree)
    return cuts


def test_the_unit_cube_unzips_with_a_path_through_its_8_corners() -> None:
    g = np.ones((1, 1, 1), dtype=bool)
    found = unzip(g)
    assert found.outcome == "found"
    validate(g, found.net)
    cuts = _assert_one_path_through_corners(g, found.net)
    assert len(cuts) == 7 and len(found.path) == 8


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
    g = grid_of(ZIPLESS_43)
    assert topology(g).kind == "manifold"
    found = unzip(g)
    assert found.outcome == "none" and found.certificate["kind"] == "colours"
    assert "alternating path" in check_certificate(ZIPLESS_43, found.certificate)
    # The certificate is checked, not trusted: other counts, or another polycube, are refused.
    with pytest.raises(ValueError, match="not those of the certificate"):
        check_certificate(ZIPLESS_43, {**found.certificate, "flats": [2, 7]})
    with pytest.raises(ValueError, match="not those of the certificate"):
        check_certificate(ZIPLESS_43[:-1], found.certificate)
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


def test_a_surface_outside_the_model_is_refused() -> None:
    with pytest.raises(UnfoldError, match="2-manifold of genus 0"):
        unzip(grid_of([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [2, 1, 0], [0, 2, 0], [1, 2, 0], [2, 2, 0]]))
