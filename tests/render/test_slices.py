import numpy as np
import pytest

from voxfab.errors import InvalidShapeError
from voxfab.render import layers, png_bytes, slice_layout, slice_sheet
from voxfab.shape import crop, examples

FG = (236, 204, 150)


@pytest.mark.parametrize("axis", ["z", "x", "y"])
def test_every_layer_is_drawn_voxel_for_voxel(axis):
    g = examples.random_shape(4)
    stack = layers(g, axis=axis)
    c = crop(g)
    a = {"x": 0, "y": 1, "z": 2}[axis]
    assert len(stack) == c.shape[a]
    assert [int(layer.sum()) for layer in stack] == [int(np.take(c, i, axis=a).sum()) for i in range(c.shape[a])]
    img = np.asarray(slice_sheet(g, size=900, axis=axis, ghost=False))
    lay = slice_layout(len(stack), stack.shape[1:], width=900)
    assert img.shape == (lay.height, 900, 3)
    for i, layer in enumerate(stack):
        x0, y0 = lay.origins[i]
        rr, cc = np.meshgrid(np.arange(layer.shape[0]), np.arange(layer.shape[1]), indexing="ij")
        centre = img[y0 + rr * lay.cell + lay.cell // 2, x0 + cc * lay.cell + lay.cell // 2]
        filled = (centre == FG).all(axis=-1)
        assert np.array_equal(filled, layer), f"layer {i + 1}"


def test_z_layers_have_the_orientation_of_the_top_view():
    g = np.zeros((3, 2, 2), dtype=bool)
    g[2, 1, 0] = True  # +x, +y corner at the bottom
    g[0, 0, 1] = True
    st = layers(g)
    assert st.shape == (2, 2, 3)
    assert st[0, 0, 2] and st[0].sum() == 1  # top-right of layer 1
    assert st[1, 1, 0] and st[1].sum() == 1  # bottom-left of layer 2


def test_layers_are_numbered_and_sheet_is_deterministic():
    g = examples.vase()
    img = slice_sheet(g, size=700)
    a = np.asarray(img)
    stack = layers(g)
    lay = slice_layout(len(stack), stack.shape[1:], width=700)
    for i, (x0, y0) in enumerate(lay.origins):
        band = a[max(0, y0 - lay.label_height) : y0 - 1, x0 : x0 + lay.cell * 4]
        assert (band.sum(axis=-1) < 300).any(), f"no number above layer {i + 1}"
    assert png_bytes(img) == png_bytes(slice_sheet(g, size=700))


def test_fixed_height_sheet_fits():
    img = slice_sheet(examples.ball(5), size=400, height=300)
    assert img.size == (400, 300)


def test_bad_axis():
    with pytest.raises(InvalidShapeError, match="axis"):
        slice_sheet(examples.ball(2), axis="w")
