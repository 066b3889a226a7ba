"""Colour in the shape model: the palette, moves that carry colours, files that keep them."""

from __future__ import annotations

import numpy as np
import pytest
from _voxart import CHARACTER_COLOURS, character, character_rgba, read_vox_independently

from voxfab import io
from voxfab.errors import InvalidShapeError
from voxfab.shape import VoxelColours, VoxelShape, default_palette, parse_colour, srgb_to_lab


def test_default_palette_is_magicavoxels():
    # Entries of the spec's table (0xAABBGGRR, indexed by colour index).
    spec = {1: 0xFFFFFFFF, 2: 0xFFCCFFFF, 7: 0xFFFFCCFF, 37: 0xFFFFFFCC, 215: 0xFF330000,
            216: 0xFF0000EE, 226: 0xFF00EE00, 236: 0xFFEE0000, 246: 0xFFEEEEEE, 255: 0xFF111111}
    palette = default_palette()
    for index, word in spec.items():
        expected = [(word >> shift) & 0xFF for shift in (0, 8, 16, 24)]
        assert list(palette[index]) == expected, index
    assert len({tuple(row) for row in palette[1:]}) == 255


def test_character_is_voxel_art():
    shape = character()
    assert shape.colours.count == len(CHARACTER_COLOURS) >= 10
    assert shape.components == 5  # body, two arms by edges, sword and feather by corners
    assert max(shape.extents) >= 19


@pytest.mark.parametrize("move", [
    lambda s: s.rotate("x", 1), lambda s: s.rotate("y", 3), lambda s: s.rotate("z", 2),
    lambda s: s.mirror("x"), lambda s: s.mirror("z"),
])
def test_moves_carry_each_voxels_colour(move):
    shape = character()
    moved = move(shape)
    # Moving the RGBA grid channel by channel gives what the shape's own move gave.
    rgba = character_rgba()
    expected = np.stack([_moved_channel(move, rgba[..., c]) for c in range(4)], axis=-1)
    assert np.array_equal(moved.colours.rgba, expected)


def _moved_channel(move, channel: np.ndarray) -> np.ndarray:
    """One channel moved as a colour index grid: 0..255 values go through the same moves."""
    index = channel.astype(np.uint8)
    fake = VoxelShape(np.ones(index.shape, bool), 1.0, VoxelColours(np.maximum(index, 1), np.arange(256)[:, None].repeat(4, 1)))
    moved = move(fake).colours.index
    return np.where(move(VoxelShape(index > 0)).grid, moved, 0)


def test_crop_pad_and_shift_keep_colours():
    shape = character()
    cropped = shape.crop()
    assert cropped.grid.shape == shape.extents
    assert sorted(map(tuple, cropped.colours.rgba[cropped.grid])) == sorted(map(tuple, shape.colours.rgba[shape.grid]))
    padded = cropped.pad_to((25, 25, 25))
    assert padded.colours.count == shape.colours.count and padded.volume == shape.volume
    shifted = padded.translate((1, 0, -1))
    assert np.array_equal(shifted.colours.rgba[1:, :, :-1], padded.colours.rgba[:-1, :, 1:])


def test_edits_take_the_nearest_colour():
    shape = character()
    grid = shape.grid.copy()
    grid[9:11, 9, 19] = True  # a hat on the hair
    grid[8, 7, 16] = False  # an eye removed
    edited = shape._new(grid)
    assert tuple(edited.colours.rgba[9, 9, 19]) == CHARACTER_COLOURS["hair"]
    assert edited.colours.index[8, 7, 16] == 0


def test_paint_by_mask_and_count():
    shape = VoxelShape(np.ones((4, 4, 4), bool))
    top = np.indices((4, 4, 4))[2] >= 2
    painted = shape.painted(parse_colour("#c03020"), top)
    assert painted.colours.count == 2
    assert tuple(painted.colours.rgba[0, 0, 3]) == (0xC0, 0x30, 0x20, 255)
    assert tuple(painted.colours.rgba[0, 0, 0]) == (255, 255, 255, 255)


def test_palette_limit_and_bad_colours():
    grid = np.ones((16, 16, 1), bool)
    rgba = np.zeros((16, 16, 1, 4), np.uint8)
    rgba[..., 0] = np.arange(256).reshape(16, 16, 1)
    rgba[..., 1] = 1  # 256 distinct colours
    with pytest.raises(InvalidShapeError, match="at most 255"):
        VoxelColours.from_rgba(grid, rgba)
    with pytest.raises(InvalidShapeError, match="colour: expected .#rrggbb."):
        parse_colour("#12345")
    with pytest.raises(InvalidShapeError, match="not the shape's filled voxels"):
        VoxelShape(np.ones((2, 2, 2), bool), 1.0, VoxelColours.uniform(np.eye(2, dtype=bool)[..., None].repeat(2, 2),
                                                                        (1, 2, 3, 255)))


def test_lab_of_known_colours():
    lab = srgb_to_lab([[255, 255, 255], [0, 0, 0], [255, 0, 0]])
    assert lab[0] == pytest.approx([100, 0, 0], abs=0.01)
    assert lab[1] == pytest.approx([0, 0, 0], abs=0.01)
    assert lab[2] == pytest.approx([53.24, 80.09, 67.20], abs=0.05)


def test_vox_round_trip_keeps_every_voxels_rgba(tmp_path):
    shape = character()
    path = tmp_path / "char.vox"
    io.write(shape, path)
    size, voxels = read_vox_independently(path)
    assert size == shape.grid.shape
    expected = {tuple(map(int, v)): tuple(map(int, shape.colours.rgba[tuple(v)])) for v in np.argwhere(shape.grid)}
    assert voxels == expected
    back = io.read(path).shape(shape.pitch)
    assert back == shape
    first = path.read_bytes()
    io.write(back, path)
    assert path.read_bytes() == first


def test_npz_keeps_pitch_and_colours(tmp_path):
    shape = character(pitch=3.4)
    path = tmp_path / "char.npz"
    io.write(shape, path)
    result = io.read(path)
    assert result.pitch == 3.4 and result.shape() == shape
    first = path.read_bytes()
    io.write(result.shape(), path)
    assert path.read_bytes() == first
    # An uncoloured shape pays nothing: no colour arrays are written.
    io.write(VoxelShape(shape.grid, 3.4), path)
    with np.load(path) as data:
        assert sorted(data.files) == ["pitch_mm", "shape"]
    assert io.read(path).colours is None
