"""Renders in the voxels' colours: each visible voxel is drawn in its colour times its shade."""

from __future__ import annotations

import numpy as np
from _voxart import character

from voxfab.render import render
from voxfab.shape import VoxelShape


def _visible_from_front(shape: VoxelShape) -> set[tuple[int, int, int]]:
    """The colours of the voxels seen from -y: the first filled voxel of each (x, z) column, by hand."""
    seen = set()
    for x in range(shape.grid.shape[0]):
        for z in range(shape.grid.shape[2]):
            ys = np.flatnonzero(shape.grid[x, :, z])
            if len(ys):
                seen.add(tuple(int(c) for c in shape.colours.rgba[x, ys[0], z, :3]))
    return seen


def _chroma(rgb: np.ndarray) -> np.ndarray:
    rgb = np.asarray(rgb, dtype=np.float64)
    return rgb / np.maximum(rgb.max(axis=-1, keepdims=True), 1)


def test_front_view_shows_each_visible_voxels_colour():
    shape = character()
    picture = np.asarray(render(shape, view="-y", size=400, antialias=1))
    pixels = picture.reshape(-1, 3)
    pixels = pixels[(pixels != 255).any(axis=1) & (pixels.max(axis=1) > 40)]
    chroma = _chroma(pixels)
    for colour in _visible_from_front(shape):
        if max(colour) < 60:
            continue  # the belt and shoes: too dark for their hue to be measured after shading
        assert np.abs(chroma - _chroma(colour)).max(axis=1).min() < 0.04, colour
    # And the uncoloured shape is drawn in the one card colour as before.
    plain = np.asarray(render(VoxelShape(shape.grid), view="-y", size=400, antialias=1)).reshape(-1, 3)
    plain = plain[(plain != 255).any(axis=1) & (plain.max(axis=1) > 40)]
    assert np.abs(_chroma(plain) - _chroma((236, 204, 150))).max() < 0.03


def test_the_eyes_are_white_and_the_shirt_red_where_they_are():
    shape = character()
    picture = np.asarray(render(shape, view="-y", size=200, scale=10, antialias=1)).astype(int)
    # Find each part by its colour's hue: the white eyes lie above the red shirt in the picture.
    white = np.argwhere((picture.min(axis=2) > 150) & (np.ptp(picture, axis=2) < 10) & (picture.max(axis=2) < 255))
    red = np.argwhere((picture[..., 0] > 2 * picture[..., 1] + 40) & (picture[..., 0] > 2 * picture[..., 2] + 40))
    assert len(white) and len(red)
    assert white[:, 0].max() < red[:, 0].min() + 1e-9 or white[:, 0].mean() < red[:, 0].mean()
