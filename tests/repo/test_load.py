"""Loading a shape by file or repository name, at its scale."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from voxfab import io
from voxfab.errors import VoxfabError
from voxfab.repo import Repository, load_shape
from voxfab.shape import crop, examples


def test_a_repository_name_loads_the_stored_shape_at_the_given_pitch(tmp_path: Path) -> None:
    grid = examples.random_shape(4, fill=0.08)
    repo = tmp_path / "r.sqlite"
    with Repository(repo) as r:
        name = r.add(grid).name
        draft = r.add(examples.box(2, 2, 2), draft=True).name
    loaded = load_shape(name, repo)
    assert loaded.name == name and loaded.notes == [] and not loaded.scaled
    assert np.array_equal(loaded.shape.grid, crop(grid)) and loaded.shape.pitch == 1.0
    scaled = load_shape(name, repo, pitch=2.5)
    assert scaled.scaled and scaled.shape.pitch == 2.5
    assert load_shape(draft, repo).shape.grid.sum() == 8


def test_a_file_loads_with_its_own_pitch_unless_one_is_given(tmp_path: Path) -> None:
    path = tmp_path / "ball.npy"
    io.write(examples.ball(3), path)
    shape, name, notes, scaled = load_shape(str(path))
    assert name is None and not scaled and shape.pitch == 1.0
    assert shape.grid.sum() == examples.ball(3).sum()
    assert load_shape(str(path), pitch=4.0).shape.pitch == 4.0


def test_unknown_names_and_bad_pitches_are_one_line_errors(tmp_path: Path) -> None:
    repo = tmp_path / "r.sqlite"
    with Repository(repo) as r:
        r.add(examples.random_shape(4, fill=0.08))
    with pytest.raises(VoxfabError, match="99999.001"):
        load_shape("99999.001", repo)
    with pytest.raises(VoxfabError, match="pitch"):
        load_shape("00001.001", repo, pitch=-1.0)
    with pytest.raises(VoxfabError):
        load_shape("00001.001", tmp_path / "missing.sqlite")


def test_the_commands_default_repository_is_the_repositorys_own() -> None:
    from voxfab.cli._common import DEFAULT_REPOSITORY
    from voxfab.repo import DEFAULT_PATH

    assert DEFAULT_REPOSITORY == DEFAULT_PATH
