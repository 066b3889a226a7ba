"""Colours in the repository: stored with the voxels, part of a shape's identity, kept by old files."""

from __future__ import annotations

import sqlite3

import numpy as np
import pytest
from _voxart import character, read_vox_independently

from voxfab import io
from voxfab.cli import main
from voxfab.repo import Repository
from voxfab.shape import VoxelShape


def test_a_coloured_shape_is_stored_and_read_in_its_colours(tmp_path):
    shape = character()
    with Repository(tmp_path / "r.sqlite") as repo:
        name = repo.add(shape, draft=True).name
        back = repo.shape(name, pitch=shape.pitch)
        assert back == shape.crop()
        assert repo.show(name)["colours"] == 12
        assert repo.find(shape) == name
        # The same voxels in other colours are another shape; the same voxels uncoloured too.
        repainted = shape.painted((0, 0, 0, 255), np.indices(shape.grid.shape)[2] > 17)
        other = repo.add(repainted, draft=True)
        plain = repo.add(VoxelShape(shape.grid), draft=True)
        assert other.created and plain.created and len({name, other.name, plain.name}) == 3
        again = repo.add(shape, draft=True)
        assert again.name == name and not again.created
        repo.export(name, tmp_path / "back.vox")
    size, voxels = read_vox_independently(tmp_path / "back.vox")
    cropped = shape.crop()
    assert size == cropped.grid.shape
    assert voxels == {tuple(map(int, v)): tuple(map(int, cropped.colours.rgba[tuple(v)]))
                      for v in np.argwhere(cropped.grid)}


def test_a_repository_of_the_schema_before_colours_opens_unchanged(tmp_path):
    path = tmp_path / "old.sqlite"
    grid = character().joined()[0].grid
    with Repository(path) as repo:
        name = repo.add(grid, draft=True).name
        key = repo.show(name)["key"]
    raw = sqlite3.connect(path)
    raw.executescript("ALTER TABLE shapes DROP COLUMN colours; PRAGMA user_version = 4;")
    raw.close()
    with Repository(path, create=False) as repo:
        assert repo.check() == []
        assert np.array_equal(repo.get(name), grid[tuple(slice(a, b) for a, b in zip(*_box(grid)))])
        assert repo.show(name)["key"] == key and repo.show(name)["colours"] == 0
        assert repo.shape(name).colours is None


def _box(grid):
    idx = np.argwhere(grid)
    return idx.min(axis=0), idx.max(axis=0) + 1


def test_repo_check_finds_colours_that_do_not_match_the_key(tmp_path):
    path = tmp_path / "r.sqlite"
    with Repository(path) as repo:
        name = repo.add(character(), draft=True).name
    raw = sqlite3.connect(path)
    blob = bytearray(raw.execute("SELECT colours FROM shapes").fetchone()[0])
    blob[0] ^= 0xFF
    raw.execute("UPDATE shapes SET colours = ?", (bytes(blob),))
    raw.commit()
    raw.close()
    with Repository(path, create=False) as repo:
        problems = repo.check()
        assert len(problems) == 1 and "key does not match" in problems[0]
        with pytest.raises(Exception, match="corrupt repository row"):
            repo.shape(name)


def test_cli_adds_a_coloured_vox_and_info_counts_its_colours(tmp_path, capsys):
    io.write(character(), tmp_path / "char.vox")
    repo = tmp_path / "r.sqlite"
    assert main(["repo", "add", "--draft", str(tmp_path / "char.vox"), "--repo", str(repo)]) == 0
    name = capsys.readouterr().out.split()[0].rstrip(":")
    assert main(["info", name, "--repo", str(repo)]) == 0
    assert "colours        12" in capsys.readouterr().out
