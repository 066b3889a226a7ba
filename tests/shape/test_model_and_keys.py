import numpy as np
import pytest

from voxfab.errors import InvalidShapeError
from voxfab.shape import VoxelShape, canonical_key, examples, mirror, rotations, translate


def test_voxelshape_is_immutable_and_compares_by_value():
    s = VoxelShape(examples.ball(3), pitch=2.0)
    with pytest.raises(ValueError):
        s.grid[0, 0, 0] = True
    assert s == VoxelShape(examples.ball(3), pitch=2.0)
    assert s != VoxelShape(examples.ball(3), pitch=1.0)
    assert hash(s) == hash(VoxelShape(examples.ball(3), pitch=2.0))
    assert s.volume == int(examples.ball(3).sum())
    with pytest.raises(InvalidShapeError):
        VoxelShape(np.ones((2, 2, 2)), pitch=0)


def test_operators_follow_set_meanings():
    a = VoxelShape(np.array([[[1, 1]]], bool))
    b = VoxelShape(np.array([[[0, 1]]], bool))
    assert (a | b).volume == 2 and (a & b).volume == 1
    assert (a - b).volume == 1 and (a ^ b).volume == 1


def test_key_is_translation_invariant_and_symmetry_optional():
    g = np.zeros((25, 25, 25), bool)
    g[3:6, 4, 0:25] = True
    g[3, 5, 7] = True
    moved = translate(g, (10, 10, 0))
    assert canonical_key(g) == canonical_key(moved)
    r = rotations(g)[5]
    assert canonical_key(g) != canonical_key(r)
    assert canonical_key(g, symmetric=True) == canonical_key(r, symmetric=True)
    assert canonical_key(g, symmetric=True) == canonical_key(mirror(g, "y"), symmetric=True)


def test_examples_match_the_literature():
    assert examples.tunnel_cube(5).sum() == 81
    assert examples.tunnel_cube(9).sum() == 425
    from voxfab.shape import exposed_faces

    assert exposed_faces(examples.tunnel_cube(5)) == 270
    assert exposed_faces(examples.tunnel_cube(9)) == 1350
    assert exposed_faces(examples.ball(12)) == 2646


def test_random_shapes_are_well_formed_and_seeded():
    a, b = examples.random_shape(7), examples.random_shape(7)
    assert (a == b).all()
    assert not (a == examples.random_shape(8)).all()
    assert VoxelShape(a).well_formed
