"""Edge and corner contacts: found, bridged into one body, kept apart, or refused."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from voxfab.errors import FabricationError
from voxfab.fabricate.mesh import bridge_boxes, build_mesh, find_contacts
from voxfab.shape import component_count, examples, largest_component


def _pair(offset):
    g = np.zeros((2, 2, 2), bool)
    g[0, 0, 0] = True
    g[tuple(offset)] = True
    return g


def test_edge_and_corner_contacts_are_found_with_their_place():
    c = find_contacts(_pair((1, 1, 0)))
    assert c.edges.tolist() == [[[1, 1, 0], [1, 1, 1]]]
    assert c.edge_voxels.tolist() == [[[0, 0, 0], [1, 1, 0]]]
    assert c.points.shape == (0, 3)
    c = find_contacts(_pair((1, 1, 1)))
    assert c.edges.shape[0] == 0 and c.points.tolist() == [[1, 1, 1]]
    g = np.zeros((2, 2, 1), bool)
    g[1, 0, 0] = g[0, 1, 0] = True  # the other diagonal of the same square
    assert find_contacts(g).edges.tolist() == [[[1, 1, 0], [1, 1, 1]]]


def test_contacts_closed_by_a_third_voxel_are_not_contacts():
    g = _pair((1, 1, 0))
    g[1, 0, 0] = True
    assert find_contacts(g).count == 0
    g = _pair((1, 1, 1))
    g[1, 1, 0] = True  # now an edge contact (0,0,0)-(1,1,0), no corner-only one
    c = find_contacts(g)
    assert c.points.shape[0] == 0 and c.edges.shape[0] == 1


def test_one_voxel_shell_has_the_expected_contacts():
    c = np.arange(25) - 12
    d = np.sqrt(c[:, None, None] ** 2 + c[None, :, None] ** 2 + c[None, None, :] ** 2)
    shell = np.abs(d - 11) <= 0.5
    # Measured in the reference notes: 768 diagonal edge contacts, no corner-only ones.
    found = find_contacts(shell)
    assert found.edges.shape[0] == 768 and found.points.shape[0] == 0


@pytest.mark.parametrize("offset", [(1, 1, 0), (1, 1, 1), (0, 1, 1)])
def test_bridge_makes_one_body_split_keeps_two_error_refuses(offset):
    g = _pair(offset)
    bridged = build_mesh(g, pitch=4.0)
    assert bridged.report.bodies == 1 and bridged.report.shells == 1 and bridged.bridges == 1
    assert 128.0 < bridged.report.volume < 128.0 + 4.0  # a 1 mm bridge, 4 mm voxels
    split = build_mesh(g, pitch=4.0, contacts="split")
    assert split.report.bodies == 2 and split.report.parts == 2
    assert split.report.volume == pytest.approx(128.0)
    with pytest.raises(FabricationError, match=r"1 (edge|corner)-only .*\(0,0,0\)-"):
        build_mesh(g, pitch=4.0, contacts="error")


def test_bridge_width_default_and_clamp():
    g = _pair((1, 1, 0))
    small = build_mesh(g, pitch=1.0)  # default 1 mm is more than 0.6 x pitch
    # Two empty quadrants of a 0.6 mm square prism along the 1 mm edge get filled.
    assert small.report.volume - 2.0 == pytest.approx(2 * 0.3**2 * 1.0, rel=1e-9)
    wide = build_mesh(g, pitch=2.0, bridge_width=5.0)
    assert any("clamped" in w for w in wide.warnings)


grids = arrays(np.bool_, st.tuples(st.integers(2, 6), st.integers(2, 6), st.integers(2, 6)), elements=st.booleans())


@settings(max_examples=25, deadline=None)
@given(grids)
def test_every_face_connected_shape_prints_as_one_body(g):
    g = largest_component(g) if g.any() else g
    if not g.any():
        return
    exact = float(g.sum()) * 8.0
    r = build_mesh(g, pitch=2.0, fill=False)
    assert r.report.bodies == 1
    assert r.report.volume >= exact - 1e-9
    boxes = bridge_boxes(find_contacts(g), pitch=2.0, width=1.0)
    assert len(boxes) == r.bridges
    assert r.report.volume <= exact + np.prod(boxes[:, 1] - boxes[:, 0], axis=1).sum() + 1e-9
    split = build_mesh(g, pitch=2.0, fill=False, contacts="split")
    assert split.report.volume == pytest.approx(exact)
    assert split.report.parts == component_count(g) == 1


@settings(max_examples=8, deadline=None)
@given(st.integers(0, 2**16))
def test_random_shapes_bridge_to_one_solid(seed):
    g = examples.random_shape(seed, side=10, fill=0.3)
    r = build_mesh(g, pitch=2.0)
    assert r.report.bodies == 1 and r.report.shells == 1
    assert r.contacts == find_contacts(g).count


def test_grid_bridges_equal_the_cad_union_of_boxes():
    # The bridged mesh is built on a rectilinear grid; the CAD kernel's union of
    # the exact mesh with the same boxes must enclose the same volume.
    import manifold3d as m3d

    from voxfab.fabricate.mesh import _cad, voxel_mesh

    g = examples.random_shape(11, side=10, fill=0.3)
    r = build_mesh(g, pitch=2.0)
    boxes = bridge_boxes(find_contacts(g), pitch=2.0, width=1.0)
    assert r.bridges == len(boxes) > 0
    union = m3d.Manifold.batch_boolean(
        [_cad.to_manifold(voxel_mesh(g, pitch=2.0)), *_cad.box_solids(boxes)], m3d.OpType.Add
    )
    assert r.report.volume == pytest.approx(union.volume(), rel=1e-9)
    assert union.decompose().__len__() == 1


def test_cad_fallback_for_grids_too_fine_to_refine(monkeypatch):
    import voxfab.fabricate.mesh._build as build

    g = examples.random_shape(4, side=8, fill=0.3)
    via_grid = build_mesh(g, pitch=2.0)
    monkeypatch.setattr(build, "bridged_grid", lambda *a, **k: None)
    via_cad = build.build_mesh(g, pitch=2.0)
    assert via_cad.report.bodies == 1 and via_cad.bridges == via_grid.bridges > 0
    assert via_cad.report.volume == pytest.approx(via_grid.report.volume, rel=1e-9)


def _naive_contacts(g):
    """Contacts by definition, voxel pair by voxel pair (slow, small grids only)."""
    filled = {tuple(v) for v in np.argwhere(g)}
    edges, corners = set(), set()
    for a in filled:
        for b in filled:
            d = np.subtract(b, a)
            if tuple(d) <= (0, 0, 0) or np.abs(d).max() != 1:
                continue
            if np.abs(d).sum() == 2:
                beside = [tuple(np.add(a, e)) for e in np.diag(d) if e.any()]
                if not any(c in filled for c in beside):
                    edges.add((a, b))
            elif np.abs(d).sum() == 3:
                lo = np.minimum(a, b)
                block = {tuple(lo + o) for o in np.ndindex(2, 2, 2)}
                if len(block & filled) == 2:
                    corners.add((a, b))
    return edges, corners


@settings(max_examples=40, deadline=None)
@given(arrays(np.bool_, st.tuples(st.integers(1, 5), st.integers(1, 5), st.integers(1, 5)), elements=st.booleans()))
def test_contacts_match_the_definition(g):
    found = find_contacts(g)
    pairs = lambda vox: {tuple(sorted((tuple(a), tuple(b)))) for a, b in vox.tolist()}  # noqa: E731
    edges, corners = _naive_contacts(g)
    assert pairs(found.edge_voxels) == {tuple(sorted(p)) for p in edges}
    assert pairs(found.point_voxels) == {tuple(sorted(p)) for p in corners}
