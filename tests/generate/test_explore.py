"""Tests of voxfab.generate.explore on real repositories."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

import voxfab.repo
from voxfab.errors import InvalidShapeError, RepositoryError
from voxfab.generate import explore
from voxfab.repo import Repository
from voxfab.shape import canonical_key, crop, symmetries, well_formed_reasons


def _translation_keys(grid: np.ndarray) -> set[str]:
    """Keys up to translation of the 48 symmetric copies: computed from the plain key only."""
    return {canonical_key(s) for s in symmetries(crop(grid), reflections=True)}


def test_explore_stores_distinct_well_formed_shapes(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        report = explore(repo, 60, seed=1, generator="mix", volume=(25, 4000))
        assert len(report.added) == 60 and len(repo) == 60
        grids = {name: repo.get(name) for name, _ in report.added}
    for name, v in report.added:
        assert well_formed_reasons(grids[name]) == [] and int(grids[name].sum()) == v
        assert 25 <= v <= 4000 and name.startswith(f"{v:05d}.")
    # No two stored shapes are equal up to translation and the 48 symmetries.
    orbits = [_translation_keys(g) for g in grids.values()]
    for a, b in itertools.combinations(orbits, 2):
        assert not a & b


def test_rank_is_storage_order_and_names_never_change(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        first = explore(repo, 40, seed=2, volume=(30, 33)).added
        before = {name: repo.get(name) for name, _ in first}
        second = explore(repo, 40, seed=3, volume=(30, 33)).added
        for name, g in before.items():
            assert np.array_equal(repo.get(name), g)
        ranks: dict[int, list[int]] = {}
        for name, v in first + second:
            ranks.setdefault(v, []).append(int(name.split(".")[1]))
        for rs in ranks.values():
            assert rs == list(range(1, len(rs) + 1))
        assert {n for n, _ in first}.isdisjoint(n for n, _ in second)


def test_same_seed_gives_the_same_repository(tmp_path: Path) -> None:
    out = []
    for d in ("a", "b"):
        with Repository(tmp_path / d / "r.sqlite") as repo:
            report = explore(repo, 25, seed=7, generator="mix")
            out.append([(name, repo.get(name).tobytes(), repo.show(name)["meta"]) for name, _ in report.added])
    assert out[0] == out[1]


def test_the_same_seed_again_adds_other_shapes(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        first = explore(repo, 30, seed=4, volume=(25, 40))
        again = explore(repo, 30, seed=4, volume=(25, 40))
        assert again.duplicates >= 30  # the first 30 candidates are stored already
        assert len(repo) == 60
        orbits = [_translation_keys(repo.get(n)) for n, _ in first.added + again.added]
    for a, b in itertools.combinations(orbits, 2):
        assert not a & b


def test_exhausted_volume_range_is_a_clear_error(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        # Volume 25 spanning 25 voxels: only the straight column exists.
        with pytest.raises(RepositoryError, match=r"only 1 of 2 new shapes after 300 candidates"):
            explore(repo, 2, seed=0, volume=(25, 25), max_attempts=300)
        assert [e.name for e in repo.list()] == ["00025.001"]


def test_full_volumes_are_skipped(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(voxfab.repo, "MAX_RANK", 2)
    with Repository(tmp_path / "r.sqlite") as repo:
        report = explore(repo, 6, seed=5, volume=(40, 42))
        assert report.rejected > 0
        assert sorted(v for _, v in report.added) == [40, 40, 41, 41, 42, 42]
        with pytest.raises(RepositoryError, match="only 0 of 1"):
            explore(repo, 1, seed=6, volume=(40, 42), max_attempts=50)


def test_bad_arguments(tmp_path: Path) -> None:
    with Repository(tmp_path / "r.sqlite") as repo:
        for kwargs, match in (
            ({"count": 0, "seed": 1}, "count"),
            ({"count": 1, "seed": -1}, "seed"),
            ({"count": 1, "seed": 1, "generator": "magic"}, "generator"),
            ({"count": 1, "seed": 1, "volume": (5, 20)}, "MAX must be at least 25"),
        ):
            with pytest.raises(InvalidShapeError, match=match):
                explore(repo, **kwargs)
        assert len(repo) == 0
