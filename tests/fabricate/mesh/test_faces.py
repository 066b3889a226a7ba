"""Mesh from voxel faces: manifold by index, exact volume and box, no T-junctions."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from voxfab.fabricate.mesh import MeshData, check_mesh, voxel_mesh
from voxfab.shape import examples, exposed_faces

grids = arrays(np.bool_, st.tuples(st.integers(1, 5), st.integers(1, 5), st.integers(1, 5)), elements=st.booleans())


def _edge_counts(m: MeshData) -> np.ndarray:
    """How many triangles use each undirected edge, counted by vertex index."""
    t = m.triangles
    e = np.sort(np.stack([t, np.roll(t, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return counts


def _area(m: MeshData) -> float:
    v = m.vertices[m.triangles]
    return float(np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1).sum() / 2)


def _t_junctions(m: MeshData) -> int:
    """Vertices lying strictly inside some triangle edge (brute force, small meshes only)."""
    t = m.triangles
    a = m.vertices[t.ravel()]
    b = m.vertices[np.roll(t, -1, axis=1).ravel()]
    p = m.vertices
    ab = b - a
    ap = p[:, None, :] - a[None]
    s = np.einsum("vek,ek->ve", ap, ab) / np.einsum("ek,ek->e", ab, ab)
    dist = np.linalg.norm(ap - s[..., None] * ab[None], axis=2)
    return int(np.count_nonzero((dist < 1e-9) & (s > 1e-9) & (s < 1 - 1e-9)))


@pytest.mark.parametrize(
    "grid",
    [examples.box(3, 4, 5), examples.tunnel_cube(5), examples.ball(6), examples.torus(6, 2), examples.vase(12)],
    ids=["box", "tunnel", "ball", "torus", "vase"],
)
def test_examples_are_closed_with_exact_volume_and_box(grid):
    pitch = 1.5
    m = voxel_mesh(grid, pitch=pitch)
    assert (_edge_counts(m) == 2).all()
    r = check_mesh(m, expected_volume=grid.sum() * pitch**3)
    assert r.bodies == 1
    lo, hi = np.array(r.bounds)
    nz = np.argwhere(grid)
    assert np.allclose(lo, nz.min(axis=0) * pitch) and np.allclose(hi, (nz.max(axis=0) + 1) * pitch)


def test_merging_keeps_the_surface_and_shrinks_the_mesh():
    g = examples.ball(8)
    plain = voxel_mesh(g, merge=False)
    merged = voxel_mesh(g)
    assert plain.triangles.shape[0] == 2 * exposed_faces(g)
    assert merged.triangles.shape[0] < 0.7 * plain.triangles.shape[0]
    assert _area(merged) == pytest.approx(_area(plain)) == pytest.approx(exposed_faces(g))
    assert voxel_mesh(examples.box(25, 25, 25)).triangles.shape[0] == 12


def test_merged_mesh_has_no_t_junctions():
    for g in (examples.tunnel_cube(5), examples.ball(4), examples.random_shape(3, side=6, fill=0.4)):
        m = voxel_mesh(g)
        assert _t_junctions(m) == 0
        check_mesh(m, expected_volume=float(g.sum()))


def test_edge_contact_closed_at_both_ends_gets_midpoints():
    # Two voxels touch along an edge whose both ends are shared through full layers
    # below and above: without a midpoint the edge would be in four triangles.
    g = np.zeros((3, 3, 3), bool)
    g[:, :, 0] = g[:, :, 2] = True
    g[0, 0, 1] = g[1, 1, 1] = True
    for merge in (False, True):
        m = voxel_mesh(g, merge=merge)
        assert (_edge_counts(m) == 2).all()
        check_mesh(m, expected_volume=float(g.sum()))


@settings(max_examples=60, deadline=None)
@given(grids, st.booleans())
def test_any_grid_gives_a_manifold_mesh(g, merge):
    if not g.any():
        return
    m = voxel_mesh(g, pitch=2.0, merge=merge)
    check_mesh(m, expected_volume=g.sum() * 8.0)
    assert (_edge_counts(m) == 2).all()
    assert _area(m) == pytest.approx(exposed_faces(g) * 4.0)


def test_parts_follow_face_connected_components():
    g = np.zeros((5, 1, 1), bool)
    g[[0, 2, 4]] = True
    m = voxel_mesh(g)
    assert m.part_count == 3
    r = check_mesh(m, expected_volume=3.0)
    assert r.bodies == 3


def _same_partition(a: np.ndarray, b: np.ndarray) -> bool:
    pairs = set(zip(a.ravel().tolist(), b.ravel().tolist()))
    return len(pairs) == len(set(a.ravel().tolist())) == len(set(b.ravel().tolist()))


def _corner_vertices(m: MeshData, g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mesh vertex used at each corner of each surface-graph face, read off an unmerged mesh.

    Each triangle lies in one voxel face: its normal gives the direction, its
    centroid the face.  Returns the surface graph's ids ``(F, 4)`` and the mesh's.
    """
    from voxfab.shape import surface_graph
    from voxfab.shape._surface import DIRECTIONS

    sg = surface_graph(g)
    v = m.vertices[m.triangles]
    normal = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    d = np.argmax(np.rint(normal / np.linalg.norm(normal, axis=1)[:, None]) @ DIRECTIONS.T, axis=1)
    centroid = v.mean(axis=1)
    voxel = np.floor(centroid).astype(np.int64)
    a = d // 2
    rows = np.arange(len(d))
    # The face plane is the voxel's side: step back inside for faces facing +axis.
    voxel[rows, a] = np.rint(centroid[rows, a]).astype(np.int64) - (d % 2 == 0)
    face_key = {(tuple(vx), int(dd)): i for i, (vx, dd) in enumerate(zip(sg.voxel.tolist(), sg.direction.tolist()))}
    mesh_ids = np.full(sg.vertex.shape, -1)
    for t, vx, dd in zip(m.triangles, voxel.tolist(), d.tolist()):
        f = face_key[(tuple(vx), dd)]
        for vid in t:
            hit = np.flatnonzero((sg.corners[f] == m.vertices[vid]).all(axis=1))
            if hit.size:
                mesh_ids[f, hit[0]] = vid
    assert (mesh_ids >= 0).all()
    return sg.vertex, mesh_ids


@settings(max_examples=80, deadline=None)
@given(grids)
def test_vertex_ids_split_like_the_surface_graph(g):
    if not g.any():
        return
    graph_ids, mesh_ids = _corner_vertices(voxel_mesh(g, merge=False), g)
    assert _same_partition(graph_ids, mesh_ids)


def test_bridged_grid_meshed_without_a_contact_search_is_checked():
    from voxfab.fabricate.mesh import bridge_boxes, find_contacts
    from voxfab.fabricate.mesh._contacts import NO_CONTACTS, bridged_grid

    g = examples.random_shape(5, side=6, fill=0.3)
    cells, coords = bridged_grid(g, bridge_boxes(find_contacts(g), pitch=1.0, width=0.6), pitch=1.0)
    fast = voxel_mesh(cells, coords=coords, contacts=NO_CONTACTS)
    slow = voxel_mesh(cells, coords=coords)
    sizes = [np.diff(c) for c in coords]
    exact = float(np.einsum("ijk,i,j,k->", cells, *sizes))
    for m in (fast, slow):
        assert check_mesh(m, expected_volume=exact).bodies == check_mesh(slow).bodies
    assert _t_junctions(fast) == 0


def test_vertex_ids_on_worst_cases():
    checker = np.indices((7, 7, 7)).sum(axis=0) % 2 == 0
    for g in (checker, ~checker, examples.random_shape(0, side=10), examples.torus(6, 2)):
        graph_ids, mesh_ids = _corner_vertices(voxel_mesh(g, merge=False), g)
        assert _same_partition(graph_ids, mesh_ids)


@settings(max_examples=60, deadline=None)
@given(grids, st.booleans())
def test_rectangles_tile_the_exposed_faces_once(g, merge):
    from voxfab.fabricate.mesh._faces import face_rectangles
    from voxfab.shape import surface_graph

    if not g.any():
        return
    rects = face_rectangles(g, merge=merge)
    covered = []
    for d, plane, u0, v0, u1, v1 in rects.tolist():
        a = d // 2
        for u in range(u0, u1):
            for v in range(v0, v1):
                voxel = [0, 0, 0]
                voxel[a], voxel[(a + 1) % 3], voxel[(a + 2) % 3] = plane, u, v
                covered.append((*voxel, d))
    sg = surface_graph(g)
    faces = sorted(zip(*sg.voxel.T.tolist(), sg.direction.tolist()))
    assert sorted(covered) == faces  # every exposed face in exactly one rectangle
    if not merge:
        assert len(rects) == len(faces)


@settings(max_examples=40, deadline=None)
@given(grids)
def test_point_configs_read_the_eight_cells_around_each_point(g):
    from voxfab.fabricate.mesh._faces import point_configs

    p = np.pad(g, 1)
    config = point_configs(p).reshape(tuple(s + 1 for s in g.shape))
    for x, y, z in np.ndindex(config.shape):
        expect = sum(int(p[x + dx, y + dy, z + dz]) << (4 * dx + 2 * dy + dz)
                     for dx in (0, 1) for dy in (0, 1) for dz in (0, 1))
        assert config[x, y, z] == expect
