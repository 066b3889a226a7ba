import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from voxfab.shape import FOLD_FLAT, FOLD_MOUNTAIN, FOLD_VALLEY, examples, exposed_faces, surface_graph
from voxfab.shape._surface import CORNER_OFFSETS, DIRECTIONS

grids = arrays(np.bool_, st.tuples(st.integers(1, 5), st.integers(1, 5), st.integers(1, 5)), elements=st.booleans())


@given(grids)
def test_graph_is_symmetric_and_edges_coincide(g):
    if not g.any():
        return
    sg = surface_graph(g)
    assert sg.face_count == exposed_faces(g)
    f = np.arange(sg.face_count)
    c = sg.corners
    for k in range(4):
        nb, kk = sg.neighbor[:, k], sg.neighbor_edge[:, k]
        assert (sg.neighbor[nb, kk] == f).all()
        assert (sg.neighbor_edge[nb, kk] == k).all()
        assert (sg.fold[nb, kk] == sg.fold[:, k]).all()
        # The neighbour runs the shared edge backwards: consistent orientation.
        assert (c[f, k] == c[nb, (kk + 1) % 4]).all()
        assert (c[f, (k + 1) % 4] == c[nb, kk]).all()


def _is_edge_contact(g, p, q):
    """Whether the unit edge p-q has filled voxels on one diagonal only (a pinch)."""
    axis = int(np.flatnonzero(p != q)[0])
    lo = np.minimum(p, q)
    others = [a for a in range(3) if a != axis]
    pad = np.pad(g, 1)
    ring = []
    for da, db in ((-1, -1), (0, -1), (0, 0), (-1, 0)):
        v = lo.copy()
        v[others[0]] += da
        v[others[1]] += db
        ring.append(bool(pad[tuple(v + 1)]))
    return ring in ([True, False, True, False], [False, True, False, True])


@given(grids)
def test_vertices_are_manifold_by_index_except_at_pinched_edges(g):
    if not g.any():
        return
    sg = surface_graph(g)
    assert (sg.vertex_position[sg.vertex] == sg.corners).all()
    edges = {}
    for k in range(4):
        for a, b in zip(sg.vertex[:, k], sg.vertex[:, (k + 1) % 4]):
            edges[(a, b)] = edges.get((a, b), 0) + 1
    assert all((b, a) in edges for a, b in edges)
    pos = sg.vertex_position
    for (a, b), n in edges.items():
        assert n == 1 or _is_edge_contact(g, pos[a], pos[b])


def test_corners_are_counter_clockwise_seen_from_outside():
    for d in range(6):
        c = CORNER_OFFSETS[d].astype(float)
        normal = np.cross(c[1] - c[0], c[2] - c[1])
        assert (normal == DIRECTIONS[d]).all()


def test_fold_types_of_an_l_shape():
    g = np.zeros((2, 1, 2), bool)
    g[0, 0, 0] = g[1, 0, 0] = g[0, 0, 1] = True
    counts = surface_graph(g).fold_counts()
    # 3 voxels, 14 faces, 28 edges; one concave edge along y.
    assert counts["valley"] == 1
    assert sum(counts.values()) == 28
    cube = surface_graph(np.ones((1, 1, 1), bool))
    assert cube.fold_counts() == {"mountain": 12, "valley": 0, "flat": 0}
    assert (cube.fold == FOLD_MOUNTAIN).all()
    assert FOLD_FLAT == 0 and FOLD_VALLEY == -1


def test_edge_contact_keeps_voxels_apart():
    g = np.zeros((2, 2, 1), bool)
    g[0, 0, 0] = g[1, 1, 0] = True
    sg = surface_graph(g)
    # Two separate cubes: 12 + 12 mountain edges and 8 + 8 vertices (none shared).
    assert sg.fold_counts()["mountain"] == 24
    assert sg.vertex.max() + 1 == 16


@pytest.mark.parametrize("radius", [2, 5])
def test_ball_surface_has_genus_zero(radius):
    sg = surface_graph(examples.ball(radius))
    v = sg.vertex.max() + 1
    f = sg.face_count
    assert v - 2 * f + f == 2
