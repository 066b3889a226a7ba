"""Crafted repository rows: a corrupt row never becomes a shape, and every read names it.

The rows are damaged with :mod:`sqlite3` directly, as a disk error, another tool
or a hand edit would, under a real shape (the bundled queen).
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, refused, run_cli
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab.errors import RepositoryError
from voxfab.recipe import load_recipe
from voxfab.recipe._build import make_shape
from voxfab.repo import Repository

RECIPES = Path(__file__).resolve().parents[2] / "recipes"


@pytest.fixture(scope="module")
def queen() -> np.ndarray:
    return make_shape(load_recipe(RECIPES / "chess" / "queen.toml")).grid


@pytest.fixture()
def repo_path(tmp_path: Path, queen: np.ndarray) -> tuple[Path, str]:
    path = tmp_path / "repo.sqlite"
    with Repository(path) as repo:
        name = repo.add(queen).name
        other = queen.copy()
        other[12, 12, 24] = not other[12, 12, 24]
        repo.add(other)
    return path, name


def damage(path: Path, name: str, sql: str, *params: object) -> None:
    with sqlite3.connect(path) as db:
        db.execute(sql.format(where="WHERE name = ?"), (*params, name))


# (what is damaged, the SQL)
DAMAGES = {
    "empty bits": ("UPDATE shapes SET bits = X'' {where}",),
    "short bits": ("UPDATE shapes SET bits = substr(bits, 1, 40) {where}",),
    "long bits": ("UPDATE shapes SET bits = bits || X'00' {where}",),
    "bits as text": ("UPDATE shapes SET bits = 'abc' {where}",),
    "flipped voxel": ("UPDATE shapes SET bits = CAST(substr(bits, 1, 300) || X'55' || substr(bits, 302) AS BLOB) {where}",),
    "bits as bad text": ("UPDATE shapes SET bits = CAST(X'ff00' AS TEXT) {where}",),
    "bits a number": ("UPDATE shapes SET bits = 7 {where}",),
    "meta bad text": ("UPDATE shapes SET meta = CAST(X'ff7b' AS TEXT) {where}",),
    "volume as text": ("UPDATE shapes SET volume = 'many' {where}",),
    "wrong volume": ("UPDATE shapes SET volume = volume + 1 {where}",),
    "extents as text": ("UPDATE shapes SET nx = 'x' {where}",),
    "huge extents": ("UPDATE shapes SET nx = 1000000000 {where}",),
    "wrong key": ("UPDATE shapes SET key = zeroblob(32) {where}",),
    "wrong symmetric key": ("UPDATE shapes SET symmetric_key = zeroblob(32) {where}",),
    "meta not JSON": ("UPDATE shapes SET meta = '{{' {where}",),
    "meta a list": ("UPDATE shapes SET meta = '[1]' {where}",),
    "meta a blob": ("UPDATE shapes SET meta = X'7b7d' {where}",),
    "reasons not JSON": ("UPDATE shapes SET reasons = 'nope' {where}",),
    "reasons not strings": ("UPDATE shapes SET reasons = '[1, 2]' {where}",),
}
READS = {"empty bits", "short bits", "long bits", "bits as text", "bits as bad text", "bits a number",
         "flipped voxel", "volume as text",
         "wrong volume", "extents as text", "huge extents", "wrong key", "wrong symmetric key"}


@pytest.mark.parametrize("kind", sorted(DAMAGES))
def test_a_corrupt_row_is_named_by_every_read(repo_path, tmp_path, kind):
    path, name = repo_path
    damage(path, name, *DAMAGES[kind])
    with Repository(path, create=False) as repo:
        if kind in READS:
            with pytest.raises(RepositoryError, match=rf"^{name}: corrupt repository row"):
                repo.get(name)
            with pytest.raises(RepositoryError, match=rf"^{name}: corrupt repository row"):
                repo.packed(name)
        with pytest.raises(RepositoryError, match=rf"^{name}: corrupt repository row"):
            repo.show(name)
        problems = repo.check()
    assert len(problems) == 1 and problems[0].startswith("row 1 (") and name in problems[0], problems
    # The CLI: one line, no traceback, nothing written.
    line = refused(["repo", "show", name, "--repo", path])
    assert name in line and "corrupt" in line
    if kind in READS:
        out = tmp_path / "out.npy"
        assert name in refused(["repo", "export", name, str(out), "--repo", path])
        assert not out.exists()
        svg = tmp_path / "net.svg"
        assert name in refused(["net", name, "--repo", path, "-o", svg])
        assert not svg.exists()
    o = check_outcome(run_cli(["repo", "check", "--repo", path]))
    assert o.code != 0 and o.out.count("\n") == 1 and "1 problem" in o.error_lines[0]


def test_repo_check_lists_every_bad_row(repo_path):
    path, name = repo_path
    with Repository(path) as repo:
        names = [e.name for e in repo.list()]
    assert len(names) == 2
    damage(path, names[0], *DAMAGES["empty bits"])
    damage(path, names[1], *DAMAGES["meta not JSON"])
    o = check_outcome(run_cli(["repo", "check", "--repo", path]))
    assert o.code != 0 and "2 problem" in o.error_lines[0]
    listed = o.out.splitlines()
    assert len(listed) == 2 and {n for n in names for line in listed if f"({n})" in line} == set(names)
    assert any("bits" in line for line in listed) and any("meta" in line for line in listed)


def test_a_sound_repository_checks_clean(repo_path):
    path, name = repo_path
    o = check_outcome(run_cli(["repo", "check", "--repo", path]))
    assert o.code == 0 and "2 rows, all sound" in o.out
    o = check_outcome(run_cli(["repo", "show", name, "--repo", path, "--json"]))
    assert o.code == 0 and name in o.out


@settings(max_examples=40, database=None, derandomize=True)
@given(data=st.data())
def test_random_blobs_never_become_shapes(tmp_path_factory, queen, data):
    """Any bytes in place of a row's blob: either exactly the stored shape, or a clean error."""
    path = tmp_path_factory.mktemp("blob") / "repo.sqlite"
    with Repository(path) as repo:
        name = repo.add(queen).name
        bits, extents = repo.packed(name)
    new = data.draw(st.one_of(
        st.binary(max_size=len(bits) + 3),
        st.integers(0, len(bits) - 1).map(lambda i: bits[:i] + bytes([bits[i] ^ 1]) + bits[i + 1:]),
    ))
    damage(path, name, "UPDATE shapes SET bits = ? {where}", new)
    with Repository(path, create=False) as repo:
        try:
            grid = repo.get(name)
        except RepositoryError as exc:
            assert str(exc).startswith(f"{name}: corrupt repository row")
        else:
            assert new == bits and grid.sum() == queen.sum()


def test_list_filters_and_limits(repo_path, tmp_path):
    path, _ = repo_path
    assert "volume" in refused(["repo", "list", "--volume", "", "--repo", path])
    assert "volume" in refused(["repo", "list", "--volume", " : ", "--repo", path])
    o = check_outcome(run_cli(["repo", "list", "--limit", str(10**21), "--repo", path]))
    assert o.code == 0 and len(o.out.splitlines()) == 2


def test_export_refuses_a_missing_folder(repo_path, tmp_path):
    path, name = repo_path
    line = refused(["repo", "export", name, str(tmp_path / "missing" / "x.npy"), "--repo", path])
    assert "does not exist" in line and not (tmp_path / "missing").exists()


@pytest.mark.parametrize("argv", [
    ["--count", "0"],
    ["--count", str(10**12)],
    ["--count", "2", "--max-attempts", "-3"],
    ["--count", "2", "--max-attempts", str(10**12)],
    ["--count", "2", "--volume", "1:3"],
    ["--count", "2", "--volume", ""],
    # Valid arguments that find nothing: the run fails before storing a shape.
    ["--count", "3", "--max-attempts", "1", "--volume", "25:26", "--generator", "revolution"],
])
def test_a_refused_explore_leaves_no_repository(tmp_path, argv):
    repo = tmp_path / "r.sqlite"
    line = refused(["explore", *argv, "--repo", repo])
    assert line and not list(tmp_path.iterdir()), line
    assert "does not exist" in refused(["explore", "--count", "1", "--repo", tmp_path / "missing" / "r.sqlite"])
    assert not list(tmp_path.iterdir())
