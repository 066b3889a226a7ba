"""The checker rejects every kind of broken mesh it claims to detect."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab.errors import FabricationError
from voxfab.fabricate.mesh import MeshData, check_mesh, voxel_mesh
from voxfab.shape import examples


def _cube() -> MeshData:
    return voxel_mesh(examples.box(1, 1, 1), pitch=10.0)


def _with(m: MeshData, vertices=None, triangles=None, part=None) -> MeshData:
    t = m.triangles if triangles is None else triangles
    return MeshData(
        vertices=m.vertices if vertices is None else vertices,
        triangles=t,
        part=np.zeros(len(t), dtype=np.int64) if part is None else part,
    )


def test_a_good_cube_passes_with_its_measures():
    r = check_mesh(_cube(), expected_volume=1000.0, expected_bounds=[[0, 0, 0], [10, 10, 10]], expected_bodies=1)
    assert (r.triangles, r.vertices, r.shells, r.bodies, r.parts) == (12, 8, 1, 1, 1)
    assert r.volume == pytest.approx(1000.0)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda t: t[1:], "only one triangle"),
        (lambda t: np.concatenate([t[:1, ::-1], t[1:]]), "directed edges used twice"),
        (lambda t: np.concatenate([t, t[:1]]), "more than two triangles"),
        (lambda t: t[:, ::-1], "no positive volume"),
        (lambda t: np.concatenate([t[:1, [0, 0, 1]], t[1:]]), "repeat a vertex"),
    ],
    ids=["hole", "flipped", "duplicate", "inside-out", "degenerate"],
)
def test_broken_meshes_are_rejected(change, message):
    m = _cube()
    with pytest.raises(FabricationError, match=message):
        check_mesh(_with(m, triangles=change(m.triangles.copy())))


def test_edge_shared_by_four_triangles_is_rejected():
    # Two cubes touching along an edge, vertices welded by position (what a naive
    # mesher or an STL reader does): the shared edge is in four triangles.
    g = np.zeros((2, 2, 1), bool)
    g[0, 0, 0] = g[1, 1, 0] = True
    m = voxel_mesh(g)
    pos, inv = np.unique(m.vertices, axis=0, return_inverse=True)
    welded = _with(m, vertices=pos, triangles=inv.reshape(-1)[m.triangles])
    with pytest.raises(FabricationError, match="more than two triangles"):
        check_mesh(welded)
    assert check_mesh(m).bodies == 2


def test_pinched_vertex_is_rejected():
    # Two cubes touching at one corner, welded: every edge is fine but the corner
    # vertex has two fans (a bow tie), which trimesh's watertight test misses.
    g = np.zeros((2, 2, 2), bool)
    g[0, 0, 0] = g[1, 1, 1] = True
    m = voxel_mesh(g)
    pos, inv = np.unique(m.vertices, axis=0, return_inverse=True)
    with pytest.raises(FabricationError, match="more than one fan"):
        check_mesh(_with(m, vertices=pos, triangles=inv.reshape(-1)[m.triangles], part=m.part))


def test_expectations_are_enforced():
    m = _cube()
    with pytest.raises(FabricationError, match="volume"):
        check_mesh(m, expected_volume=999.0)
    with pytest.raises(FabricationError, match="volume"):
        check_mesh(m, expected_volume=(1001.0, 1100.0))
    with pytest.raises(FabricationError, match="bounding box"):
        check_mesh(m, expected_bounds=[[0, 0, 0], [10, 10, 11]])
    with pytest.raises(FabricationError, match="bodies"):
        check_mesh(m, expected_bodies=2)


def test_unused_vertex_and_bad_index_are_rejected():
    m = _cube()
    with pytest.raises(FabricationError, match="used by no triangle"):
        check_mesh(_with(m, vertices=np.concatenate([m.vertices, [[5.0, 5.0, 5.0]]])))
    t = m.triangles.copy()
    t[0, 0] = 99
    with pytest.raises(FabricationError, match="outside"):
        check_mesh(_with(m, triangles=t))


def test_a_cavity_shell_stays_in_its_part():
    g = np.ones((3, 3, 3), bool)
    g[1, 1, 1] = False
    m = voxel_mesh(g)
    r = check_mesh(m, expected_volume=26.0)
    assert (r.shells, r.bodies, r.parts) == (2, 1, 1)
    # The 12 cavity triangles face inward: a part of their own would be inside out.
    v = m.vertices[m.triangles].mean(axis=1)
    inner = (np.abs(v - 1.5) < 0.51).all(axis=1)
    assert inner.sum() == 12
    with pytest.raises(FabricationError, match="no positive volume"):
        check_mesh(_with(m, part=inner.astype(np.int64)))
    half = np.zeros(len(m.triangles), dtype=np.int64)
    half[np.flatnonzero(~inner)[:4]] = 1
    with pytest.raises(FabricationError, match="no positive volume|split between parts"):
        check_mesh(_with(m, part=half))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(0, 3))
def test_compiled_pass_agrees_with_the_numpy_pass(seed, how):
    # Damage a good mesh at random: the compiled edge/fan/shell pass must refuse
    # exactly the meshes the numpy pass refuses, and count the same shells.
    from voxfab.fabricate.mesh._check import _edge_and_fan_problems
    from voxfab.fabricate.mesh._data import shell_labels
    from voxfab.fabricate.mesh._edges import edge_fan_shells

    rng = np.random.default_rng(seed)
    g = rng.random((3, 3, 3)) < 0.5
    g[1, 1, 1] = True
    m = voxel_mesh(g)
    v, t = m.vertices, m.triangles.copy()
    if how == 1:  # flip one triangle
        i = rng.integers(len(t))
        t[i] = t[i, ::-1]
    elif how == 2:  # drop one triangle, keep the vertices in use
        t = np.delete(t, rng.integers(len(t)), axis=0)
        v = v[: t.max() + 1]
    elif how == 3:  # glue two vertices into one (may pinch or duplicate edges)
        a, b = rng.choice(len(v), 2, replace=False)
        t[t == b] = a
        keep = (t[:, 0] != t[:, 1]) & (t[:, 1] != t[:, 2]) & (t[:, 0] != t[:, 2])
        t = t[keep]
        used = np.zeros(len(v), bool)
        used[t.ravel()] = True
        remap = np.cumsum(used) - 1
        v, t = v[used], remap[t]
    status, labels, n_shells = edge_fan_shells(np.ascontiguousarray(t, dtype=np.int64), len(v))
    try:
        _edge_and_fan_problems("m", v, t)
        numpy_ok = True
    except FabricationError:
        numpy_ok = False
    assert (status == 0) == numpy_ok
    if numpy_ok:
        ref, n_ref = shell_labels(t, len(v))
        assert n_shells == n_ref and np.array_equal(labels, ref)
