import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from voxfab.errors import InvalidShapeError
from voxfab.shape import (
    bounding_box,
    cavity_count,
    component_count,
    crop,
    difference,
    examples,
    exposed_faces,
    extents,
    fill_cavities,
    intersection,
    label_components,
    largest_component,
    mirror,
    rotate,
    rotations,
    symmetries,
    translate,
    union,
    volume,
    well_formed_reasons,
)
from voxfab.shape._ops import _FACE_STRUCTURE

grids = arrays(
    np.bool_,
    st.tuples(st.integers(1, 7), st.integers(1, 7), st.integers(1, 7)),
    elements=st.booleans(),
)


def _faces_by_loops(g):
    # An independent oracle: count each face of each filled voxel whose neighbour is empty.
    p = np.pad(g, 1)
    count = 0
    for x, y, z in zip(*np.nonzero(p)):
        for d in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
            count += not p[x + d[0], y + d[1], z + d[2]]
    return count


@given(grids)
def test_exposed_faces_matches_voxel_by_voxel_count(g):
    assert exposed_faces(g) == _faces_by_loops(g)


@given(grids)
def test_rotations_keep_volume_and_faces_and_are_distinct_maps(g):
    rots = rotations(g)
    assert len(rots) == 24
    for r in rots:
        assert volume(r) == volume(g)
        assert exposed_faces(r) == exposed_faces(g)
        assert component_count(r) == component_count(g)


def test_24_rotations_of_an_asymmetric_shape_are_all_different():
    g = np.zeros((3, 3, 3), bool)
    g[0, 0, 0] = g[1, 0, 0] = g[2, 0, 0] = g[0, 1, 0] = g[0, 0, 1] = g[0, 0, 2] = g[0, 2, 0] = True
    g[2, 1, 0] = True  # breaks the x/y swap symmetry
    keys = {r.tobytes() + bytes(r.shape) for r in rotations(g)}
    assert len(keys) == 24
    assert len({s.tobytes() for s in symmetries(g, reflections=True)}) == 48


@given(grids)
def test_fill_never_removes_voxels_and_leaves_no_cavity(g):
    f = fill_cavities(g)
    assert (f | g == f).all()
    assert cavity_count(f) == 0


def test_fill_cavities_fills_a_hollow_box_and_not_an_open_one():
    g = np.ones((5, 5, 5), bool)
    g[1:4, 1:4, 1:4] = False
    assert cavity_count(g) == 1
    assert volume(fill_cavities(g)) == 125
    g[2, 2, 4] = False  # a hole to the outside
    assert cavity_count(g) == 0
    assert volume(fill_cavities(g)) == volume(g)


def test_cavity_reached_only_through_an_edge_is_enclosed():
    # Empty voxel (1,1,1) touches the outside only along an edge: water cannot pass.
    g = np.ones((3, 3, 3), bool)
    g[1, 1, 1] = False
    assert cavity_count(g) == 1


@given(grids)
def test_labelling_agrees_with_scipy(g):
    from scipy import ndimage

    labels, n = label_components(g)
    ref, m = ndimage.label(g, structure=_FACE_STRUCTURE)
    assert n == m
    assert (labels == ref).all()


def test_large_grid_labelling_uses_the_same_numbering():
    g = np.random.default_rng(1).random((70, 70, 70)) < 0.3
    labels, n = label_components(g)
    small, m = label_components(g[:40, :40, :40])
    assert n > m > 1
    assert labels.max() == n


def test_edge_contact_is_two_components():
    g = np.zeros((2, 2, 1), bool)
    g[0, 0, 0] = g[1, 1, 0] = True
    assert component_count(g) == 2
    assert volume(largest_component(g)) == 1


@given(grids)
def test_largest_component_is_one_piece_and_a_subset(g):
    if not g.any():
        return
    lc = largest_component(g)
    assert component_count(lc) == 1
    assert (lc <= g).all()


@given(grids, grids)
def test_boolean_laws(a, b):
    u, i = union(a, b), intersection(a, b)
    assert volume(u) + volume(i) == volume(a) + volume(b)
    assert volume(difference(a, b)) == volume(a) - volume(intersection(a, b))


def test_bounding_box_crop_extents():
    g = np.zeros((6, 7, 8), bool)
    g[1:3, 2:6, 4] = True
    assert bounding_box(g) == ((1, 2, 4), (3, 6, 5))
    assert extents(g) == (2, 4, 1)
    assert crop(g).shape == (2, 4, 1)


def test_translate_moves_and_refuses_to_cut():
    g = np.zeros((4, 4, 4), bool)
    g[0, 0, 0] = True
    t = translate(g, (1, 2, 3))
    assert t[1, 2, 3] and volume(t) == 1
    with pytest.raises(InvalidShapeError):
        translate(g, (-1, 0, 0))


def test_rotate_quarter_turn_about_z_is_counter_clockwise():
    g = np.zeros((3, 3, 1), bool)
    g[2, 1, 0] = True  # on +x
    r = rotate(g, "z", 1)
    assert r[1, 2, 0]  # now on +y
    assert (rotate(g, "z", 4) == g).all()


def test_mirror_is_an_involution():
    g = examples.random_shape(4, side=9)
    for axis in "xyz":
        assert (mirror(mirror(g, axis), axis) == g).all()


def test_well_formed_reasons():
    assert well_formed_reasons(examples.random_shape(0)) == []
    g = np.zeros((25, 25, 25), bool)
    g[:, 0, 0] = True
    g[5, 5, 5] = True
    reasons = well_formed_reasons(g)
    assert len(reasons) == 1 and "2 6-connected pieces" in reasons[0]
    assert "none is 25" in well_formed_reasons(np.ones((3, 3, 3), bool))[0]
    assert "do not fit" in well_formed_reasons(np.ones((26, 2, 2), bool))[0]
    assert well_formed_reasons(np.zeros((2, 2, 2), bool)) == ["the grid is empty"]


@pytest.mark.parametrize("bad", [np.zeros((2, 2)), np.full((2, 2, 2), 2), np.ones((300, 1, 1)), np.array([[["a"]]])])
def test_bad_grids_are_refused_with_a_named_message(bad):
    with pytest.raises(InvalidShapeError, match="shape"):
        volume(bad) if bad.dtype.kind != "i" or bad.max() < 2 else exposed_faces(bad)


def test_fill_cavities_works_at_the_size_limit():
    g = np.ones((256, 3, 3), bool)
    g[100, 1, 1] = False
    assert cavity_count(g) == 1
    assert fill_cavities(g).all()
