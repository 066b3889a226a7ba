"""Tests of listing by volume range, keyset paging, stats and rank counters."""

from __future__ import annotations

from pathlib import Path

import pytest

from voxfab.errors import RepositoryError
from voxfab.generate import growth
from voxfab.repo import Repository
from voxfab.shape import canonical_key


@pytest.fixture
def repo(tmp_path: Path) -> Repository:
    """30 grown shapes of volumes 30..34, a draft, and a removed shape."""
    r = Repository(tmp_path / "r.sqlite")
    grids = [growth(seed, 30 + seed % 5) for seed in range(30)]
    r.add_many(grids, symmetric=True)
    two = growth(99, 40)
    two[0, 0, 0] = two[24, 24, 12] = True  # stray voxels: more than one piece
    r.add(two, draft=True)
    r.remove(r.list(volume=(31, 31))[0].name)
    yield r
    r.close()


def test_volume_range_filter(repo: Repository) -> None:
    every = repo.list()
    assert len(every) == len(repo)
    for lo, hi in ((30, 30), (31, 33), (1, 29), (34, 50)):
        got = repo.list(volume=(lo, hi))
        assert got == [e for e in every if lo <= e.volume <= hi]
    assert [e for e in repo.list(drafts=False)] == [e for e in every if not e.draft]


def test_keyset_pages_cover_the_listing_once(repo: Repository) -> None:
    every = repo.list()
    for size in (1, 4, 7, 100):
        pages, after = [], None
        while True:
            page = repo.list(after=after, limit=size)
            pages += page
            if len(page) < size:
                break
            after = page[-1].name
        assert pages == every
    filtered = repo.list(volume=(32, 34))
    assert repo.list(volume=(32, 34), after=filtered[2].name, limit=3) == filtered[3:6]
    draft = [e for e in every if e.draft][0]
    assert repo.list(after=draft.name) == []


def test_paging_errors(repo: Repository) -> None:
    with pytest.raises(RepositoryError, match="no such shape"):
        repo.list(after="00777.001")
    with pytest.raises(RepositoryError, match="not a shape name"):
        repo.list(after="junk")
    with pytest.raises(RepositoryError, match="limit"):
        repo.list(limit=0)
    with pytest.raises(RepositoryError, match="empty"):
        repo.list(volume=(40, 30))


def test_stats_count_per_volume(repo: Repository) -> None:
    every = repo.list()
    info = repo.stats()
    assert info["shapes"] == sum(not e.draft for e in every) and info["drafts"] == 1
    for row in info["volumes"]:
        assert row["count"] == sum(e.volume == row["volume"] and not e.draft for e in every)
        assert row["last_rank"] >= row["count"]
    v31 = next(row for row in info["volumes"] if row["volume"] == 31)
    assert v31["last_rank"] == v31["count"] + 1  # one was removed, its rank is not given again
    part = repo.stats(volume=(32, 33))
    assert [row["volume"] for row in part["volumes"]] == [32, 33] and part["drafts"] == 0
    assert repo.last_ranks() == {row["volume"]: row["last_rank"] for row in info["volumes"]}


def test_precomputed_keys_are_used_and_checked(tmp_path: Path) -> None:
    grids = [growth(s, 50) for s in range(3)]
    keys = [canonical_key(g, symmetric=True) for g in grids]
    with Repository(tmp_path / "r.sqlite") as r:
        names = [x.name for x in r.add_many(grids, symmetric=True, keys=keys)]
        assert [r.find(g, symmetric=True) for g in grids] == names
        assert [r.show(n)["symmetric_key"] for n in names] == keys
        with pytest.raises(RepositoryError, match="keys: expected 3"):
            r.add_many(grids, keys=keys[:2])
