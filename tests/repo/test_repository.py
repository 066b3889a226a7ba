"""Tests of voxfab.repo.Repository: naming, duplicates, drafts, operations."""

from __future__ import annotations

import itertools
import json
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab import io
from voxfab.errors import InvalidShapeError, RepositoryError
from voxfab.repo import DEFAULT_PATH, AddResult, Entry, Repository
from voxfab.shape import (
    canonical_key,
    crop,
    examples,
    extents,
    mirror,
    rotations,
    symmetries,
    volume,
    well_formed_reasons,
)


@pytest.fixture(scope="module")
def shapes() -> list[np.ndarray]:
    """Three random well-formed 25-span shapes (none equal to another up to symmetry)."""
    out = [examples.random_shape(seed, fill=0.08) for seed in (1, 2, 3)]
    assert len({canonical_key(g, symmetric=True) for g in out}) == 3
    return out


def column(extra: tuple[int, ...] = ()) -> np.ndarray:
    """A 1x1x25 column at x=0 with extra voxels at x=1 at the heights ``extra`` (2x1x25 grid)."""
    g = np.zeros((2, 1, 25), dtype=bool)
    g[0, 0, :] = True
    g[1, 0, list(extra)] = True
    return g


def place(grid: np.ndarray, size: tuple[int, int, int], offset: tuple[int, int, int]) -> np.ndarray:
    """Put ``grid`` into an empty grid of ``size`` at ``offset``."""
    out = np.zeros(size, dtype=bool)
    sx, sy, sz = grid.shape
    ox, oy, oz = offset
    out[ox : ox + sx, oy : oy + sy, oz : oz + sz] = grid
    return out


@pytest.fixture
def repo(tmp_path: Path):
    with Repository(tmp_path / "r.sqlite") as r:
        yield r


# -- names and ranks ------------------------------------------------------------


def test_name_is_volume_and_rank_in_insertion_order(repo: Repository) -> None:
    a, b, c = column((3,)), column((7,)), column((3, 4))
    assert repo.add(a) == AddResult("00026.001", True, ())
    assert repo.add(c) == AddResult("00027.001", True, ())
    assert repo.add(b) == AddResult("00026.002", True, ())
    assert np.array_equal(repo.get("00026.001"), a)
    assert np.array_equal(repo.get("00026.002"), b)
    assert np.array_equal(repo.get("00027.001"), c)


def test_name_volume_is_the_voxel_count_of_real_shapes(repo: Repository, shapes) -> None:
    for g in shapes:
        result = repo.add(g)
        assert result.created
        vol, rank = result.name.split(".")
        assert int(vol) == volume(g) and len(vol) == 5
        assert rank == "001" or int(rank) > 1
        assert np.array_equal(repo.get(result.name), crop(g))


def test_stored_grid_is_cropped_and_metadata_recorded(repo: Repository, shapes) -> None:
    g = place(crop(shapes[0]), (30, 30, 30), (2, 3, 4))
    name = repo.add(g, meta={"seed": 1, "source": "random_shape"}).name
    info = repo.show(name)
    assert info["extents"] == list(extents(g))
    assert info["volume"] == volume(g)
    assert info["draft"] is False and info["reasons"] == []
    assert info["meta"] == {"seed": 1, "source": "random_shape"}
    assert info["key"] == canonical_key(g)
    assert info["symmetric_key"] == canonical_key(g, symmetric=True)
    assert json.loads(json.dumps(info)) == info


def test_removed_names_are_not_renumbered_nor_reused(repo: Repository) -> None:
    names = [repo.add(column((z,))).name for z in range(4)]
    assert names == ["00026.001", "00026.002", "00026.003", "00026.004"]
    repo.remove("00026.002")
    repo.remove("00026.004")
    assert [e.name for e in repo.list()] == ["00026.001", "00026.003"]
    assert np.array_equal(repo.get("00026.003"), column((2,)))
    # The removed shape comes back under a new rank; the old names stay unused.
    assert repo.add(column((1,))).name == "00026.005"
    assert repo.add(column((3,))).name == "00026.006"
    assert "00026.002" not in repo and "00026.004" not in repo
    assert repo.check() == []


def test_rank_overflow_is_a_clear_error(repo: Repository) -> None:
    # 999 distinct shapes of volume 27: the column plus two voxels on x=1, and two on y=1.
    pairs = list(itertools.combinations(range(25), 2))  # 300
    grids = [column(p) for p in pairs]
    for p in pairs:
        g = np.zeros((1, 2, 25), dtype=bool)
        g[0, 0, :] = True
        g[0, 1, list(p)] = True
        grids.append(g)
    for p in pairs:
        g = np.zeros((3, 1, 25), dtype=bool)  # extras on both sides
        g[1, 0, :] = True
        g[0, 0, p[0]] = g[2, 0, p[1]] = True
        grids.append(g)
    for p in pairs[:99]:
        g = np.zeros((1, 3, 25), dtype=bool)
        g[0, 1, :] = True
        g[0, 0, p[0]] = g[0, 2, p[1]] = True
        grids.append(g)
    assert len(grids) == 999 and {volume(g) for g in grids} == {27}
    results = repo.add_many(grids)
    assert [r.name for r in results] == [f"00027.{i:03d}" for i in range(1, 1000)]
    extra = np.zeros((1, 3, 25), dtype=bool)
    extra[0, 1, :] = True
    extra[0, 0, 20] = extra[0, 2, 21] = True
    with pytest.raises(RepositoryError, match=r"volume 27: all 999 ranks .* cannot name another"):
        repo.add(extra)
    # An existing shape is still found; other volumes still get names.
    assert repo.add(grids[5]) == AddResult("00027.006", False, ())
    assert repo.add(column((1,))).name == "00026.001"
    assert len(repo) == 1000


# -- duplicates -----------------------------------------------------------------


def test_duplicate_by_translation_returns_existing_name(repo: Repository, shapes) -> None:
    g = crop(shapes[1])
    first = repo.add(place(g, (28, 30, 26), (0, 0, 0)))
    assert first.created
    for offset in [(3, 1, 1), (1, 5, 0), (0, 0, 1)]:
        moved = place(g, (28, 30, 26), offset)
        assert repo.add(moved) == AddResult(first.name, False, ())
        assert repo.find(moved) == first.name
    assert len(repo) == 1


def test_duplicate_by_rotation_only_with_symmetric(repo: Repository, shapes) -> None:
    g = shapes[0]
    name = repo.add(g).name
    keys = {canonical_key(r) for r in rotations(g)}
    assert len(keys) == 24  # the random shape has no rotational symmetry
    for r in rotations(g)[1:]:
        assert repo.find(r) is None
        assert repo.find(r, symmetric=True) == name
        assert repo.add(r, symmetric=True) == AddResult(name, False, ())
    assert len(repo) == 1
    # Without the option a rotated copy is a new shape of the same volume.
    second = repo.add(rotations(g)[5])
    assert second.created and second.name == f"{volume(g):05d}.002"


def test_duplicate_by_reflection_only_with_symmetric(repo: Repository, shapes) -> None:
    g = shapes[2]
    name = repo.add(g).name
    for axis in "xyz":
        m = mirror(g, axis)
        assert canonical_key(m) != canonical_key(g)
        assert repo.add(m, symmetric=True) == AddResult(name, False, ())
        assert repo.find(m, symmetric=True) == name
        assert repo.find(m) is None
    other = repo.add(mirror(g, "y"))
    assert other.created
    # Both stored: a symmetric lookup returns the lowest rank.
    assert repo.find(mirror(g, "x"), symmetric=True) == name


def test_duplicate_stores_nothing_not_even_meta(repo: Repository) -> None:
    repo.add(column((5,)), meta={"seed": 1})
    again = repo.add(column((5,)), meta={"seed": 2})
    assert not again.created
    assert repo.show(again.name)["meta"] == {"seed": 1}


def test_add_many_dedups_within_the_batch(repo: Repository) -> None:
    results = repo.add_many([column((1,)), column((2,)), column((1,))], metas=[{"i": 0}, None, {"i": 2}])
    assert [(r.name, r.created) for r in results] == [
        ("00026.001", True), ("00026.002", True), ("00026.001", False)
    ]


def test_add_many_is_all_or_nothing(repo: Repository) -> None:
    with pytest.raises(RepositoryError, match="shape 1: not well formed"):
        repo.add_many([column((1,)), np.ones((3, 3, 3), bool)])
    with pytest.raises(RepositoryError, match="shape 2: the grid is empty"):
        repo.add_many([column((1,)), column((2,)), np.zeros((3, 3, 3), bool)])
    with pytest.raises(RepositoryError, match="metas: expected 2 entries, got 1"):
        repo.add_many([column((1,)), column((2,))], metas=[None])
    assert len(repo) == 0


# -- refusal and drafts ---------------------------------------------------------


def test_not_well_formed_is_refused_with_reasons(repo: Repository) -> None:
    two_pieces = np.zeros((3, 1, 25), dtype=bool)
    two_pieces[0, 0, :] = two_pieces[2, 0, :5] = True
    small = examples.ball(3)
    too_big = np.ones((1, 1, 26), dtype=bool)
    for g in (two_pieces, small, too_big):
        reasons = well_formed_reasons(g)
        assert reasons
        with pytest.raises(RepositoryError) as info:
            repo.add(g)
        for reason in reasons:
            assert reason in str(info.value)
        assert "\n" not in str(info.value)
    assert "2 6-connected pieces" in str(pytest.raises(RepositoryError, repo.add, two_pieces).value)
    assert len(repo) == 0


def test_empty_and_bad_grids(repo: Repository) -> None:
    with pytest.raises(RepositoryError, match="empty"):
        repo.add(np.zeros((3, 3, 3), bool), draft=True)
    with pytest.raises(InvalidShapeError, match="dtype"):
        repo.add(np.full((2, 2, 25), 0.5))
    with pytest.raises(RepositoryError, match="meta"):
        repo.add(column(), meta={"bad": object()})
    with pytest.raises(RepositoryError, match="meta"):
        repo.add(column(), meta=["not", "a", "mapping"])  # type: ignore[arg-type]
    assert len(repo) == 0


def test_drafts_are_stored_unnamed_and_deduplicated(repo: Repository) -> None:
    small = examples.ball(2)
    first = repo.add(small, draft=True, meta={"source": "ball"})
    assert first.created and first.draft
    assert first.name.startswith("draft-")
    assert first.reasons == tuple(well_formed_reasons(small))
    assert repo.add(small, draft=True) == AddResult(first.name, False, first.reasons)
    assert repo.find(small) == first.name
    # Stored as a draft or not, a shape that is not well formed needs draft=True.
    with pytest.raises(RepositoryError, match="not well formed"):
        repo.add(small)
    info = repo.show(first.name)
    assert info["draft"] is True and info["rank"] is None
    assert info["reasons"] == list(first.reasons)
    assert np.array_equal(repo.get(first.name), small)
    # A well-formed shape added with draft=True is named as usual.
    named = repo.add(column(), draft=True)
    assert named == AddResult("00025.001", True, ())
    second = repo.add(examples.ball(3), draft=True)
    assert second.name != first.name and second.draft
    assert repo.list() == [
        Entry("00025.001", 25, (1, 1, 25), False),
        Entry(first.name, volume(small), (5, 5, 5), True),
        Entry(second.name, volume(examples.ball(3)), (7, 7, 7), True),
    ]
    repo.remove(first.name)
    assert first.name not in repo
    assert repo.check() == []


# -- operations -----------------------------------------------------------------


def test_list_is_ordered_by_volume_then_rank(repo: Repository, shapes) -> None:
    grids = [shapes[0], column((2, 3)), column((4,)), shapes[1], column((1,)), column()]
    for g in grids:
        repo.add(g)
    entries = repo.list()
    keys = [(e.volume, int(e.name.split(".")[1])) for e in entries]
    assert keys == sorted(keys)
    assert [e.name for e in entries][:4] == ["00025.001", "00026.001", "00026.002", "00027.001"]
    assert list(repo) == [e.name for e in entries]
    assert len(repo) == len(grids)
    for e in entries:
        assert e.extents == extents(repo.get(e.name))
        assert e.volume == volume(repo.get(e.name))


@pytest.mark.parametrize("ext", [".npy", ".npz", ".txt"])
def test_export_round_trip(repo: Repository, shapes, tmp_path: Path, ext: str) -> None:
    name = repo.add(shapes[0]).name
    out = tmp_path / f"exported{ext}"
    assert repo.export(name, out) == out
    back = io.read(out).grid
    assert np.array_equal(back, crop(shapes[0]))
    assert repo.find(back) == name


def test_export_unknown_extension(repo: Repository, tmp_path: Path) -> None:
    repo.add(column())
    with pytest.raises(Exception, match=r"\.xyz"):
        repo.export("00025.001", tmp_path / "out.xyz")
    assert not (tmp_path / "out.xyz").exists()


def test_unknown_and_malformed_names(repo: Repository, tmp_path: Path) -> None:
    repo.add(column())
    for op in (repo.get, repo.show, repo.remove):
        with pytest.raises(RepositoryError, match=r"00025\.002: no such shape"):
            op("00025.002")
        with pytest.raises(RepositoryError, match="not a shape name"):
            op("shape-1")
        with pytest.raises(RepositoryError, match="no such shape"):
            op("draft-99")
    with pytest.raises(RepositoryError, match="not a shape name"):
        repo.export("25.1", tmp_path / "x.npy")
    assert 25 not in repo
    assert repo.find(column((3,))) is None


def test_closed_repository_refuses(tmp_path: Path) -> None:
    repo = Repository(tmp_path / "r.sqlite")
    repo.close()
    repo.close()
    with pytest.raises(RepositoryError, match="closed"):
        repo.add(column())
    with pytest.raises(RepositoryError, match="closed"):
        len(repo)


def test_data_persists_across_connections(tmp_path: Path, shapes) -> None:
    path = tmp_path / "sub" / "dir" / "r.sqlite"
    with Repository(path) as repo:
        name = repo.add(shapes[0], meta={"seed": 1}).name
    with Repository(path, create=False) as repo:
        assert np.array_equal(repo.get(name), crop(shapes[0]))
        assert repo.add(shapes[0]).created is False
        assert repo.show(name)["meta"] == {"seed": 1}


def test_default_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    assert DEFAULT_PATH == Path("output") / "repository.sqlite"
    with Repository() as repo:
        repo.add(column())
    assert (tmp_path / "output" / "repository.sqlite").is_file()


def _small_shapes() -> list[np.ndarray]:
    """Four asymmetric well-formed shapes in small grids (cheap to transform)."""
    out = []
    for seed in range(4):
        g = crop(examples.random_shape(seed, fill=0.02))
        assert len({canonical_key(s) for s in symmetries(g, reflections=True)}) == 48
        out.append(g)
    return out


_SMALL_SHAPES = _small_shapes()


@settings(max_examples=25, deadline=None)
@given(
    seed=st.integers(0, 3),
    turn=st.integers(0, 23),
    flip=st.sampled_from([None, "x", "y", "z"]),
    offset=st.tuples(st.integers(0, 4), st.integers(0, 4), st.integers(0, 4)),
)
def test_any_symmetry_and_translation_finds_the_stored_shape(seed, turn, flip, offset) -> None:
    g = _SMALL_SHAPES[seed]
    moved = rotations(g)[turn]
    if flip is not None:
        moved = mirror(moved, flip)
    moved = place(crop(moved), (30, 30, 30), offset)
    with tempfile.TemporaryDirectory() as tmp, Repository(Path(tmp) / "r.sqlite") as repo:
        names = [repo.add(s).name for s in _SMALL_SHAPES]
        assert repo.find(moved, symmetric=True) == names[seed]
        assert repo.add(moved, symmetric=True) == AddResult(names[seed], False, ())
        identity = turn == 0 and flip is None
        assert (repo.find(moved) == names[seed]) is identity
        assert len(repo) == len(_SMALL_SHAPES)
