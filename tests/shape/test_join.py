"""Joining voxel art's parts: the fewest voxels, in a neighbour's colour, and nets and prints of the result."""

from __future__ import annotations

import numpy as np
from _voxart import CHARACTER_COLOURS, character

from voxfab import io
from voxfab.cli import main
from voxfab.shape import VoxelShape, describe_parts, join_parts, label_components
from voxfab.unfold import Net, unfold, validate

_FACE_STEPS = [np.array(s) for s in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1))]


def test_the_character_is_joined_with_the_fewest_voxels():
    shape = character()
    joined, joins = shape.joined()
    assert joined.components == 1 and len(joins) == 4
    # Arms touch along edges (one voxel each is the least), sword and feather at corners (two each).
    assert sorted(len(j.added) for j in joins) == [1, 1, 2, 2]
    added = joined.grid & ~shape.grid
    assert added.sum() == 6 == sum(len(j.added) for j in joins)
    # The voxels kept their colours; each added one has a face neighbour of its own colour.
    assert np.array_equal(joined.colours.rgba[shape.grid], shape.colours.rgba[shape.grid])
    for v in np.argwhere(added):
        colour = tuple(joined.colours.rgba[tuple(v)])
        assert colour in CHARACTER_COLOURS.values()
        neighbours = [tuple(v + s) for s in _FACE_STEPS]
        assert any(shape.grid[n] and tuple(shape.colours.rgba[n]) == colour for n in neighbours
                   if all(0 <= n[a] < shape.grid.shape[a] for a in range(3))) or any(
            added[n] and tuple(joined.colours.rgba[n]) == colour for n in neighbours)


def test_join_is_exact_on_small_cases_and_leaves_one_piece_alone():
    corner = np.zeros((3, 3, 3), bool)
    corner[0, 0, 0] = corner[1, 1, 1] = True
    joined, joins = join_parts(corner)
    assert joined.sum() == 4 and label_components(joined)[1] == 1 and len(joins) == 1
    apart = np.zeros((7, 1, 1), bool)
    apart[0] = apart[6] = True
    joined, joins = join_parts(apart)
    assert joined.all() and len(joins[0].added) == 5
    one = np.ones((2, 2, 2), bool)
    assert join_parts(one)[1] == [] and np.array_equal(join_parts(one)[0], one)
    # Deterministic: the same voxels every time.
    assert [j.added for j in character().joined()[1]] == [j.added for j in character().joined()[1]]


def test_parts_are_described_with_the_small_ones_by_place():
    line = describe_parts(character().grid)
    assert line.startswith("5 parts (largest 714 voxels)")
    assert "1 at (13, 12, 19)" in line and "5 at (0, 7, 15)" in line


def test_joined_character_has_a_one_piece_net_that_refolds():
    joined, _ = character().joined()
    net = unfold(joined.grid, rng=3, timeout=60)
    assert isinstance(net, Net)
    assert validate(joined.grid, net).problems == ()


def test_cli_nets_each_part_or_the_joined_piece(tmp_path, capsys):
    from _net_sheets import read_pieces

    path = tmp_path / "char.vox"
    io.write(character(), path)
    parts = tmp_path / "parts"
    parts.mkdir()
    assert main(["net", str(path), "--pieces", "auto", "--sheet", "A3", "-o", str(parts / "net.svg")]) in (0, 1)
    assert "one net per part, as the shape is in 5 parts" in capsys.readouterr().err
    assert main(["net", str(path), "--pieces", "auto", "-o", str(parts / "net.json")]) in (0, 1)
    for piece in parts.glob("net-piece*.json"):
        piece.rename(parts / piece.name.replace("net-piece", "net.piece-"))
    # Every face of every part once, and each piece refolds onto its part's surface.
    assert len(read_pieces(parts, character().grid)) >= 5
    joined = tmp_path / "joined.json"
    assert main(["net", str(path), "--join", "-o", str(joined)]) == 0
    assert capsys.readouterr().err.count("joined the part of") == 4
    net = Net.from_json(joined.read_text())
    assert validate(character().joined()[0].grid, net).ok


def test_recipe_join_operation(tmp_path):
    from voxfab.recipe import load_recipe, make_shape

    io.write(character(), tmp_path / "char.vox")
    recipe = tmp_path / "char.toml"
    recipe.write_text('[source]\nfile = "char.vox"\n[[operations]]\nop = "join"\n')
    shape = make_shape(load_recipe(recipe))
    assert isinstance(shape, VoxelShape) and shape.components == 1 and shape.volume == character().volume + 6
