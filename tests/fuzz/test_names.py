"""Hostile shape and range names: checked as names, whole, before anything is tried or made."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _fuzz import refused, run_cli

from voxfab.batch import parse_name_range
from voxfab.errors import RepositoryError, VoxfabError
from voxfab.recipe import load_recipe
from voxfab.repo import Repository, is_shape_name, load_shape

RECIPES = Path(__file__).resolve().parents[2] / "recipes"

LONG_MEMBER = "pc3:" + "a" * 300


@pytest.mark.parametrize("command", [
    ["info"], ["net", "-o", "{d}/n.svg"], ["mesh", "-o", "{d}/m.stl"], ["render", "-o", "{d}/r.png"],
    ["studio", "--no-browser", "--port", "1"],
])
def test_a_300_letter_member_name_is_refused_as_a_name(tmp_path, command):
    argv = [command[0], LONG_MEMBER, *(a.format(d=tmp_path) for a in command[1:])]
    line = refused([*argv, "--repo", tmp_path / "repo.sqlite"])
    assert "not a shape name" in line and len(line) < 400
    assert list(tmp_path.iterdir()) == []


def test_a_300_letter_file_name_is_one_line(tmp_path):
    line = refused(["info", str(tmp_path / ("a" * 300 + ".npy"))])
    assert "cannot read" in line and "too long" in line.lower()


def test_an_existing_file_named_like_a_member_is_read_as_a_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("pc3:abc").write_bytes(b"")
    with pytest.raises(VoxfabError, match="unknown extension"):  # the file, not a repository lookup
        load_shape("pc3:abc")


@pytest.mark.parametrize("name", ["queen\\n", "que\\nen"])  # TOML escapes
def test_a_recipe_name_with_a_newline_is_refused(tmp_path, name):
    recipe = tmp_path / "r.toml"
    recipe.write_text((RECIPES / "chess" / "queen.toml").read_text().replace('name = "queen"', f'name = "{name}"'))
    with pytest.raises(VoxfabError, match="folder-safe name"):
        load_recipe(recipe)


@pytest.mark.parametrize("text", ["００012.001:", "00012.001:00013.٠٠١"])
def test_a_batch_name_range_takes_ascii_digits_only(text):
    with pytest.raises(RepositoryError, match="not a shape name"):
        parse_name_range(text)


@pytest.mark.parametrize("name", ["00012.001\n", "draft-3\n", "pc2:02-000001\n", "０００１２.００１", "draft-٣"])
def test_names_match_whole_and_in_ascii(name):
    assert not is_shape_name(name)


@pytest.mark.parametrize("name", ["pc2\n", "pc2\n\n", "ｐｃ2"])
def test_census_refuses_a_range_name_with_a_newline_before_making_anything(tmp_path, name):
    out, repo = tmp_path / "census", tmp_path / "repo.sqlite"
    line = refused(["census", "2", "-o", out, "--workers", "0", "--store", name, "--repo", repo])
    assert "not a range name" in line
    assert not out.exists() and not repo.exists()


def test_the_library_refuses_a_range_name_with_a_newline(tmp_path):
    with Repository(tmp_path / "r.sqlite") as repo:
        with pytest.raises(RepositoryError, match="not a range name"):
            repo.add_range("pc2\n", [("02-000001", np.ones((1, 1, 2), bool))])
        assert repo.ranges() == [] and len(repo) == 0
    o = run_cli(["repo", "list", "--range", "pc2\n", "--repo", tmp_path / "r.sqlite"])
    assert o.code != 0 and "not a range name" in o.err
