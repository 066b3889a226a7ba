"""Damaged range tables and shared drafts: every command refuses cleanly, and a range removes only its own drafts.

The range tables are damaged with :mod:`sqlite3` directly, as a hand edit or another tool would.
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, refused, run_cli

from voxfab.census import grid_of, polycubes, shape_id
from voxfab.repo import Repository


def _members(n_max: int) -> list[tuple[str, np.ndarray]]:
    return [(shape_id(n, i), grid_of(cells)) for n, i, cells in polycubes(n_max)]


def test_remove_range_keeps_the_artists_own_draft(tmp_path: Path) -> None:
    repo = tmp_path / "repo.sqlite"
    domino = tmp_path / "domino.npy"
    np.save(domino, np.ones((1, 1, 2), bool))
    o = check_outcome(run_cli(["repo", "add", "--draft", domino, "--repo", repo]))
    assert o.code == 0 and o.out.split() == ["draft-1", "created"]
    o = check_outcome(run_cli(["census", "2", "-o", tmp_path / "c", "--workers", "0", "--store", "pc2",
                               "--repo", repo]))
    assert o.code == 0, o.err
    with Repository(repo, create=False) as r:
        # the range shares the artist's draft (one row for one shape) and the artist still sees it
        assert r.show("pc2:02-000001")["key"] == r.show("draft-1")["key"]
        assert [e.name for e in r.list()] == ["draft-1"]
    o = check_outcome(run_cli(["repo", "remove-range", "pc2", "--repo", repo]))
    assert o.code == 0 and "2 members removed" in o.out
    with Repository(repo, create=False) as r:
        assert [e.name for e in r.list()] == ["draft-1"] and len(r) == 1 and r.check() == []
        assert int(r.get("draft-1").sum()) == 2


def test_a_draft_added_after_the_range_stored_it_becomes_the_artists(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        repo.add_range("pc3", _members(3))
        assert repo.list() == [] and len(repo) == 4
        tromino = repo.get("pc3:03-000001")
        added = repo.add(tromino, draft=True)
        assert not added.created and [e.name for e in repo.list()] == [added.name]
        assert repo.remove_range("pc3") == 4
        assert [e.name for e in repo.list()] == [added.name] and len(repo) == 1 and repo.check() == []


def test_a_schema_3_file_counts_its_range_drafts_as_the_ranges(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    with Repository(path) as repo:
        repo.add_range("pc3", _members(3))
    raw = sqlite3.connect(path)
    raw.executescript("DROP TABLE range_made; ALTER TABLE shapes DROP COLUMN colours; PRAGMA user_version = 3;")
    raw.close()
    with Repository(path, create=False) as repo:  # migrated to 4, then 5
        assert repo.check() == [] and repo.list() == []
        assert repo.remove_range("pc3") == 4 and len(repo) == 0


# (damage, SQL, what `repo check` says)
DAMAGES = {
    "range as a blob": ("UPDATE range_members SET range = CAST(range AS BLOB) WHERE member = '03-000001'",
                        "not a range member name"),
    "position as text": ("UPDATE range_members SET position = 'abc' WHERE member = '03-000001'",
                         "position 'abc'"),
    "dangling member": ("INSERT INTO range_members (range, member, position, shape) VALUES ('pc3', 'x', 99, 999)",
                        "points at row 999"),
    "shape as text": ("UPDATE range_members SET shape = 'one' WHERE member = '03-000001'", "points at row 'one'"),
    "no range table": ("DROP TABLE range_members", "range_members is missing"),
    "no made table": ("DROP TABLE range_made", "range_made is missing"),
}


@pytest.mark.parametrize("kind", sorted(DAMAGES))
def test_a_damaged_range_table_is_found_and_refused(tmp_path: Path, kind: str) -> None:
    path = tmp_path / "repo.sqlite"
    with Repository(path) as repo:
        repo.add_range("pc3", _members(3))
    sql, found = DAMAGES[kind]
    raw = sqlite3.connect(path)
    raw.execute(sql)
    raw.commit()
    raw.close()
    o = check_outcome(run_cli(["repo", "check", "--repo", path]))
    assert o.code != 0 and found in o.out and "problem" in o.error_lines[0], (o.out, o.err)
    out = tmp_path / "census"
    line = refused(["census", "3", "-o", out, "--workers", "0", "--store", "pc3", "--repo", path])
    assert found in line and "voxfab repo check" in line
    assert not out.exists()
    # Every other command: done, or refused in one line (check_outcome fails on a traceback).
    for argv in (["repo", "ranges"], ["repo", "list", "--range", "pc3"], ["repo", "list", "--range", "pc3", "--after",
                 "03-000001"], ["repo", "stats"], ["repo", "list"], ["repo", "show", "pc3:03-000002"],
                 ["repo", "remove", "pc3:03-000002"], ["repo", "remove-range", "pc3"]):
        check_outcome(run_cli([*argv, "--repo", path]))
    assert {p.name for p in tmp_path.iterdir()} <= {"repo.sqlite", "repo.sqlite-wal", "repo.sqlite-shm"}


@pytest.mark.parametrize("kind", ["range as a blob", "position as text"])
def test_reading_a_damaged_range_names_the_damage(tmp_path: Path, kind: str) -> None:
    path = tmp_path / "repo.sqlite"
    with Repository(path) as repo:
        repo.add_range("pc3", _members(3))
    raw = sqlite3.connect(path)
    raw.execute(DAMAGES[kind][0])
    raw.commit()
    raw.close()
    command = ["repo", "ranges"] if kind == "range as a blob" else ["repo", "list", "--range", "pc3", "--after",
                                                                     "03-000001"]
    assert "corrupt range table" in refused([*command, "--repo", path])
    assert "corrupt range table" in refused(["repo", "remove-range", "pc3", "--repo", path])
