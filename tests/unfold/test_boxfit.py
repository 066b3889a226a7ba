"""smallest_box: the last of a row of shrinking boxes a one-piece net is found in, the search behind a sheet's
automatic face size."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from voxfab.errors import InvalidShapeError
from voxfab.shape import surface_graph
from voxfab.unfold import validate
from voxfab.unfold._boxfit import smallest_box

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def pawn():
    from voxfab.recipe import load_recipe, make_shape

    return make_shape(load_recipe(ROOT / "recipes" / "chess" / "pawn.toml")).grid


def _boxes() -> list[tuple[int, int]]:
    """Boxes of a 2:3 sheet at growing face sizes, down to 3 x 2 cells."""
    out = []
    for side in range(80, 1, -1):
        box = (side, (3 * side) // 2)
        if not out or out[-1] != box:
            out.append(box)
    return out


def _holds(box, net) -> bool:
    c = net.corners2d.reshape(-1, 2)
    w, h = (c.max(axis=0) - c.min(axis=0)).tolist()
    return (w <= box[0] and h <= box[1]) or (h <= box[0] and w <= box[1])


def test_the_net_found_lies_in_its_box_refolds_and_is_the_same_every_run(pawn):
    faces = surface_graph(pawn).face_count
    boxes = _boxes()
    i, net = smallest_box(pawn, boxes, rng=3, tab_aware=False)
    assert _holds(boxes[i], net) and validate(pawn, net).ok
    # no box with fewer cells than faces was taken, and the next box is smaller than the net found
    assert boxes[i][0] * boxes[i][1] >= faces
    assert i + 1 == len(boxes) or not _holds(boxes[i + 1], net)
    j, again = smallest_box(pawn, boxes, rng=3, tab_aware=False)
    assert j == i and np.array_equal(again.corners2d, net.corners2d)


def test_boxes_too_small_for_the_faces_hold_no_net(pawn):
    faces = surface_graph(pawn).face_count
    boxes = _boxes()
    tiny = [b for b in boxes if b[0] * b[1] < faces]
    assert tiny and smallest_box(pawn, tiny, rng=0, tab_aware=False) is None


def test_the_exact_strategy_is_refused(pawn):
    with pytest.raises(InvalidShapeError, match="exact"):
        smallest_box(pawn, [(40, 60)], rng=0, strategy="exact")
