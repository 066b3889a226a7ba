"""The plain-text layer format: layout, round trips and line-numbered errors."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab import io
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.io.text import format_text
from voxfab.shape import examples


def test_layout_of_an_l_shape(tmp_path):
    grid = np.zeros((2, 2, 2), dtype=bool)
    grid[0, 0, 0] = grid[1, 0, 0] = grid[0, 1, 0] = True  # an L in the bottom layer
    grid[1, 1, 1] = True
    io.write(grid, tmp_path / "l.txt")
    text = (tmp_path / "l.txt").read_text()
    # highest y first, x along the row, bottom layer first; empty-looking layers kept
    assert text == "; voxfab layers 2 2 2\nz = 0\n#.\n##\n\nz = 1\n.#\n..\n"
    assert text == format_text(grid)
    assert np.array_equal(io.read(tmp_path / "l.txt").grid, grid)


def test_hand_edited_file_with_comments_and_blank_lines(tmp_path):
    path = tmp_path / "hand.txt"
    path.write_text("; voxfab layers 3 1 2\n; a comment\n\nz = 1\n  ..#  \n\nz = 0\n#..\n", encoding="utf-8")
    grid = io.read(path).grid
    assert sorted(map(tuple, np.argwhere(grid).tolist())) == [(0, 0, 0), (2, 0, 1)]


@pytest.mark.parametrize("make", [examples.vase, lambda: examples.tunnel_cube(9), lambda: examples.torus(5, 2)])
def test_round_trip(tmp_path, make):
    grid = make()
    io.write(grid, tmp_path / "s.txt")
    assert np.array_equal(io.read(tmp_path / "s.txt").grid, grid)


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ("", FormatError, ":1: expected the header"),
        ("voxfab layers 1 1 1\n", FormatError, ":1: expected the header"),
        ("; voxfab layers 2 1 1\nz = 0\n#\n", FormatError, ":3: expected 2 characters"),
        ("; voxfab layers 2 1 1\nz = 0\n#x\n", FormatError, ":3: expected 2 characters"),
        ("; voxfab layers 1 2 1\nz = 0\n#\n", FormatError, "has 1 rows, expected 2"),
        ("; voxfab layers 1 1 1\n#\n", FormatError, ":2: a row before any"),
        ("; voxfab layers 1 1 2\nz = 0\n#\nz = 0\n#\n", FormatError, ":4: layer z = 0 is repeated"),
        ("; voxfab layers 1 1 2\nz = 0\n#\nz = 2\n#\n", FormatError, "out of range"),
        ("; voxfab layers 1 1 3\nz = 0\n#\n", FormatError, "2 of 3 layers missing"),
        ("; voxfab layers 0 1 1\n", FormatError, "side below 1"),
        ("; voxfab layers 100000 100000 100000\n", InvalidShapeError, "over the limit of 256"),
        ("; voxfab layers 1 1 1\nz = 0\n.\n", InvalidShapeError, "empty"),
    ],
)
def test_errors_name_the_file_and_line(tmp_path, text, error, message):
    path = tmp_path / "bad.txt"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(error, match=message) as info:
        io.read(path)
    assert str(path) in str(info.value)


def test_binary_file_is_not_text(tmp_path):
    path = tmp_path / "bin.txt"
    path.write_bytes(b"\xff\xfe\x00\x81" * 10)
    with pytest.raises(FormatError, match="not a UTF-8 text file"):
        io.read(path)


def test_voxel_art_in_colour_is_drawn_and_read_in_text(tmp_path):
    from _voxart import character

    shape = character()
    path = tmp_path / "char.txt"
    io.write(shape, path)
    text = path.read_text()
    # One declared character per colour, read back by hand: the eye at (8, 7, 16) is white.
    declared = dict(line.split()[2:4] for line in text.splitlines() if line.startswith("; colour "))
    assert len(declared) == 12
    layer = text.split("z = 16\n")[1].split("\n\n")[0].splitlines()
    eye = layer[shape.grid.shape[1] - 1 - 7][8]
    assert declared[eye] == "#ffffff"
    assert io.read(path).shape(shape.pitch) == shape
    # A hand-written file: named colours, '#' a white voxel, an unknown character refused by line.
    (tmp_path / "hand.txt").write_text("; voxfab layers 2 1 1\n; colour r #c03020 shirt\nz = 0\nr#\n")
    hand = io.read(tmp_path / "hand.txt")
    assert [tuple(hand.colours.rgba[x, 0, 0]) for x in range(2)] == [(0xC0, 0x30, 0x20, 255), (255, 255, 255, 255)]
    (tmp_path / "bad.txt").write_text("; voxfab layers 2 1 1\n; colour r #c03020\nz = 0\nrq\n")
    with pytest.raises(FormatError, match=r"bad.txt:4: expected 2 characters of '#', '.' or a colour \(r\)"):
        io.read(tmp_path / "bad.txt")


def test_the_bundled_swordsman_is_voxel_art_in_twelve_colours():
    from pathlib import Path

    shape = io.read(Path(__file__).parents[2] / "recipes/character/swordsman.txt").shape()
    assert shape.colours.count == 12 and shape.components == 5 and shape.joined()[0].well_formed
