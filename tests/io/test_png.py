"""PNG slice stacks: folders of images drawn with Pillow, read as grids."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from voxfab import io
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.io.png import natural_key
from voxfab.shape import examples


def save_layer(path, layer: np.ndarray, mode: str = "L") -> None:
    """Draw layer[x, y] (y up) as black-on-white pixels, row 0 = highest y."""
    pixels = np.where(layer.T[::-1, :], 0, 255).astype(np.uint8)
    Image.fromarray(pixels, "L").convert(mode).save(path)


def test_natural_order():
    names = ["z10.png", "z2.png", "z0.png", "z1.png", "Z11.png"]
    assert sorted(names, key=natural_key) == ["z0.png", "z1.png", "z2.png", "z10.png", "Z11.png"]


def test_stack_reads_layers_bottom_up_with_row_zero_highest_y(tmp_path):
    grid = np.zeros((4, 3, 12), dtype=bool)
    for z in range(12):
        grid[z % 4, z % 3, z] = True  # a different voxel per layer tells layers apart
    grid[0, 2, 0] = True  # top-left pixel of the bottom image
    for z in range(12):
        save_layer(tmp_path / f"z{z}.png", grid[:, :, z])
    (tmp_path / "notes.txt").write_text("not a slice")
    result = io.read(tmp_path)
    assert result.grid.shape == (4, 3, 12)
    assert np.array_equal(result.grid, grid)
    # independent check of the orientation on the bottom image
    img = np.asarray(Image.open(tmp_path / "z0.png"))
    assert img[0, 0] == 0 and result.grid[0, 2, 0]


def test_round_trip_of_a_real_shape_in_colour_modes(tmp_path):
    grid = examples.vase()
    for mode in ("L", "RGB", "P", "1"):
        folder = tmp_path / mode
        folder.mkdir()
        for z in range(grid.shape[2]):
            save_layer(folder / f"slice_{z:03d}.png", grid[:, :, z], mode)
        assert np.array_equal(io.read(folder).grid, grid), mode


def test_threshold_and_transparency(tmp_path):
    grey = np.array([[0, 100, 150, 250]], dtype=np.uint8)  # one row: x = 0..3
    Image.fromarray(grey, "L").save(tmp_path / "a.png")
    assert io.read(tmp_path).grid[:, 0, 0].tolist() == [True, True, False, False]
    assert io.read(tmp_path, threshold=200).grid[:, 0, 0].tolist() == [True, True, True, False]
    # a transparent black pixel is background, an opaque one is filled
    rgba = np.zeros((1, 2, 4), dtype=np.uint8)
    rgba[0, 0, 3] = 255
    Image.fromarray(rgba, "RGBA").save(tmp_path / "a.png")
    assert io.read(tmp_path).grid[:, 0, 0].tolist() == [True, False]
    for bad in (0, 257, 12.5, "128", True):
        with pytest.raises(InvalidShapeError, match="threshold"):
            io.read(tmp_path, threshold=bad)
    with pytest.raises(InvalidShapeError, match="resolution does not apply"):
        io.read(tmp_path, resolution=5)


def test_single_png_is_one_layer(tmp_path):
    layer = examples.ball(3)[:, :, 3]
    save_layer(tmp_path / "one.png", layer)
    result = io.read(tmp_path / "one.png")
    assert result.grid.shape == (7, 7, 1)
    assert np.array_equal(result.grid[:, :, 0], layer)
    assert any("single z layer" in n for n in result.notes)


def test_mismatched_sizes(tmp_path):
    save_layer(tmp_path / "z0.png", np.ones((3, 3), dtype=bool))
    save_layer(tmp_path / "z1.png", np.ones((3, 4), dtype=bool))
    with pytest.raises(FormatError, match="z1.png: image is 3x4 pixels, the first slice z0.png is 3x3"):
        io.read(tmp_path)


def test_folder_errors(tmp_path):
    with pytest.raises(FormatError, match="no .png slice"):
        io.read(tmp_path)
    (tmp_path / "z0.png").write_text("just text")
    with pytest.raises(FormatError, match="z0.png: not a PNG image"):
        io.read(tmp_path)
    Image.new("L", (2, 2)).save(tmp_path / "z0.png", format="JPEG")
    with pytest.raises(FormatError, match="not a PNG image"):
        io.read(tmp_path)
    Image.new("L", (300, 2)).save(tmp_path / "z0.png")
    with pytest.raises(InvalidShapeError, match="over the limit of 256"):
        io.read(tmp_path)
    Image.new("L", (2, 2), 255).save(tmp_path / "z0.png")
    with pytest.raises(InvalidShapeError, match="empty"):
        io.read(tmp_path)


def test_too_many_slices(tmp_path):
    save_layer(tmp_path / "z0.png", np.ones((1, 1), dtype=bool))
    data = (tmp_path / "z0.png").read_bytes()
    for z in range(1, 257):
        (tmp_path / f"z{z}.png").write_bytes(data)
    with pytest.raises(InvalidShapeError, match="257 slices"):
        io.read(tmp_path)


def test_sixteen_bit_grey_is_scaled_not_clipped(tmp_path):
    levels = np.array([[0, 20000, 40000, 65535]], dtype=np.uint16)  # 8-bit: 0, 78, 156, 255
    Image.fromarray(levels).save(tmp_path / "z0.png")
    assert Image.open(tmp_path / "z0.png").mode == "I;16"
    assert io.read(tmp_path).grid[:, 0, 0].tolist() == [True, True, False, False]


def test_slices_in_colour_round_trip_and_read_by_pillow(tmp_path):
    from _voxart import character

    shape = character()
    io.write(shape, f"{tmp_path / 'slices'}/")
    files = sorted((tmp_path / "slices").glob("*.png"))
    assert [f.name for f in files][:2] == ["z00.png", "z01.png"] and len(files) == shape.grid.shape[2]
    # Pillow alone: the eye at (8, 7, 16) is white on a transparent ground, in row Y - 1 - y, column x.
    layer = np.asarray(Image.open(files[16]))
    assert tuple(layer[shape.grid.shape[1] - 1 - 7, 8]) == (255, 255, 255, 255)
    assert layer[..., 3].min() == 0
    back = io.read(tmp_path / "slices")
    assert back.shape(shape.pitch) == shape  # light voxels (white eyes, yellow buttons) are filled: opaque pixels


def test_convert_writes_a_folder_of_slices(tmp_path):
    from _voxart import character

    from voxfab.cli import main

    io.write(character(), tmp_path / "char.vox")
    assert main(["convert", str(tmp_path / "char.vox"), f"{tmp_path / 'out'}/"]) == 0
    assert io.read(tmp_path / "out").colours.count == 12
