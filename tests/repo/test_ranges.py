"""Named ranges: a census's polycubes stored as ``RANGE:MEMBER``, listed, grown, removed, checked."""

from __future__ import annotations

import json
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from voxfab.census import grid_of, polycubes, shape_id
from voxfab.errors import RepositoryError
from voxfab.repo import Repository, load_shape
from voxfab.shape import canonical_key, examples


def _members(n_max: int) -> list[tuple[str, np.ndarray]]:
    return [(shape_id(n, i), grid_of(cells)) for n, i, cells in polycubes(n_max)]


def test_a_census_range_is_stored_in_order_and_read_back_by_member_name(tmp_path: Path) -> None:
    members = _members(6)
    assert len(members) == 1 + 1 + 2 + 8 + 29 + 166
    with Repository(tmp_path / "r.sqlite") as repo:
        artist = repo.add(examples.random_shape(1, fill=0.08)).name  # a named shape beside the range
        assert repo.add_range("polycubes-6", members) == len(members)
        assert [(r.name, r.count) for r in repo.ranges()] == [("polycubes-6", len(members))]
        listed = repo.list_range("polycubes-6")
        assert [e.name for e in listed] == [f"polycubes-6:{m}" for m, _ in members]
        assert all(e.draft for e in listed)  # none spans the grid: drafts, as the census allows
        for (member, grid), entry in zip(members, listed):
            stored = repo.get(f"polycubes-6:{member}")
            assert canonical_key(stored) == canonical_key(grid)
            assert entry.volume == int(grid.sum())
        # The plain listing and counts are the artist's: the range's drafts stay out of them.
        assert [e.name for e in repo.list()] == [artist]
        stats = repo.stats()
        assert (stats["shapes"], stats["drafts"]) == (1, 0)
        assert stats["named_ranges"] == [{"name": "polycubes-6", "count": len(members)}]
        # Paging by member, with or without the range's name.
        page = repo.list_range("polycubes-6", after="04-000008", limit=2)
        assert [e.name for e in page] == ["polycubes-6:05-000001", "polycubes-6:05-000002"]
        assert repo.list_range("polycubes-6", after="polycubes-6:04-000008", limit=2) == page
        assert "polycubes-6:06-000166" in repo and "polycubes-6:06-000167" not in repo
        assert repo.check() == []


def test_a_range_grows_and_is_stored_again_without_copies(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        assert repo.add_range("polycubes", _members(5)) == 41
        rows = len(repo)
        assert repo.add_range("polycubes", _members(5)) == 0 and len(repo) == rows
        assert repo.add_range("polycubes", _members(6)) == 166  # a census of 6 after one of 5
        assert len(repo) == rows + 166
        # A second range holding the same shapes shares their rows.
        assert repo.add_range("small", _members(3)) == 4 and len(repo) == rows + 166
        assert repo.show("small:03-000002")["key"] == repo.show("polycubes:03-000002")["key"]


def test_a_member_name_for_another_shape_is_refused_and_nothing_is_written(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        repo.add_range("polycubes", _members(4))
        rows = len(repo)
        swapped = [("04-000001", grid_of([[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0]]))]
        with pytest.raises(RepositoryError, match="holds another shape under this name"):
            repo.add_range("polycubes", swapped)
        assert len(repo) == rows and repo.ranges()[0].count == 12
        for bad_range in ("Polycubes", "1x", "", "a" * 41, "a:b"):
            with pytest.raises(RepositoryError, match="not a range name"):
                repo.add_range(bad_range, _members(1))
        with pytest.raises(RepositoryError, match="not a shape name"):
            repo.add_range("polycubes", [("Bad Name", grid_of([[0, 0, 0]]))])
        with pytest.raises(RepositoryError, match="given twice"):
            repo.add_range("twice", [("a", grid_of([[0, 0, 0]])), ("a", grid_of([[0, 0, 0], [0, 0, 1]]))])
        with pytest.raises(RepositoryError, match="no such range"):
            repo.list_range("nothing")


def test_removing_members_and_ranges_removes_their_drafts_only(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        repo.add_range("polycubes", _members(4))
        repo.add_range("small", _members(2))
        rows = len(repo)
        held = repo.show("polycubes:04-000003")
        draft = repo.find(repo.get("polycubes:04-000003"))
        assert draft is not None and draft.startswith("draft-")
        with pytest.raises(RepositoryError, match="the range member polycubes:04-000003 is this shape"):
            repo.remove(draft)
        repo.remove("polycubes:04-000003")
        assert "polycubes:04-000003" not in repo and len(repo) == rows - 1
        assert repo.find(np.asarray(grid_of([[0, 0, 0]]))) is not None
        with pytest.raises(RepositoryError, match="no such shape"):
            repo.remove("polycubes:04-000003")
        assert held["volume"] == 4
        # "small" shares the 1- and 2-cubes: removing "polycubes" keeps them.
        assert repo.remove_range("polycubes") == 11
        assert [(r.name, r.count) for r in repo.ranges()] == [("small", 2)]
        assert len(repo) == 2 and repo.check() == []


def test_check_finds_a_member_that_points_at_no_shape(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    with Repository(path) as repo:
        repo.add_range("polycubes", _members(3))
    raw = sqlite3.connect(path)
    raw.execute("INSERT INTO range_members (range, member, position, shape) VALUES ('polycubes', 'x', 99, 999)")
    raw.commit()
    raw.close()
    with Repository(path, create=False) as repo:
        assert repo.check() == ["range member 'polycubes':'x': points at row 999, which is not there"]


def test_every_command_takes_a_member_name_and_the_census_stores_its_range(tmp_path: Path) -> None:
    repo_path = tmp_path / "r.sqlite"
    run = subprocess.run([sys.executable, "-m", "voxfab", "census", "5", "-o", str(tmp_path / "c"), "--workers", "0",
                          "--store", "polycubes-5", "--repo", str(repo_path)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    census = json.loads((tmp_path / "c" / "census.json").read_text())
    with Repository(repo_path, create=False) as repo:
        listed = repo.list_range("polycubes-5")
        assert [e.name.split(":")[1] for e in listed] == [s["id"] for s in census["shapes"]]
        for shape in census["shapes"]:
            stored = repo.get(f"polycubes-5:{shape['id']}")
            assert canonical_key(stored) == canonical_key(grid_of(shape["cells"]))
    loaded = load_shape("polycubes-5:05-000007", repo_path)
    assert loaded.name == "polycubes-5:05-000007" and int(loaded.shape.grid.sum()) == 5
    net = subprocess.run([sys.executable, "-m", "voxfab", "net", "polycubes-5:05-000007", "--repo", str(repo_path),
                          "-o", str(tmp_path / "n.json")], capture_output=True, text=True, timeout=300)
    assert net.returncode == 0, net.stderr
    from voxfab.unfold import Net, validate

    validate(loaded.shape.grid, Net.from_json((tmp_path / "n.json").read_text()))  # raises on a wrong net
    listing = subprocess.run([sys.executable, "-m", "voxfab", "repo", "list", "--range", "polycubes-5", "--limit",
                              "2", "--repo", str(repo_path)], capture_output=True, text=True, timeout=120)
    assert listing.stdout.split() == ["polycubes-5:01-000001", "1", "1x1x1", "draft",
                                      "polycubes-5:02-000001", "2", "1x1x2", "draft"]
    bad = subprocess.run([sys.executable, "-m", "voxfab", "census", "3", "-o", str(tmp_path / "d"), "--workers", "0",
                          "--store", "Bad Range", "--repo", str(repo_path)], capture_output=True, text=True, timeout=120)
    assert bad.returncode != 0 and "not a range name" in bad.stderr and len(bad.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "d").exists()
