"""Tests of the repository file: opening, schema version, WAL, locking, bad files."""

from __future__ import annotations

import sqlite3
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from voxfab.errors import RepositoryError
from voxfab.repo import SCHEMA_VERSION, Repository, _sqlite


def column(z: int | None = None) -> np.ndarray:
    g = np.zeros((2, 1, 25), dtype=bool)
    g[0, 0, :] = True
    if z is not None:
        g[1, 0, z] = True
    return g


def test_create_false_on_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "none.sqlite"
    with pytest.raises(RepositoryError, match=f"no repository at {path}"):
        Repository(path, create=False)
    assert not path.exists()


def test_new_file_schema_wal_and_timeout(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    with Repository(path) as repo:
        repo.add(column())
        db = repo._db
        assert db.execute("PRAGMA busy_timeout").fetchone()[0] == int(_sqlite.BUSY_TIMEOUT_S * 1000)
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        for column_name, index in (("key", "shapes_key"), ("symmetric_key", "shapes_symmetric_key")):
            plan = " ".join(
                str(r[-1]) for r in db.execute(f"EXPLAIN QUERY PLAN SELECT name FROM shapes WHERE {column_name} = ?", ("x",))
            )
            assert f"USING INDEX {index}" in plan
    raw = sqlite3.connect(path)
    try:
        assert raw.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION
        assert raw.execute("PRAGMA application_id").fetchone()[0] == _sqlite.APPLICATION_ID
        assert raw.execute("PRAGMA journal_mode").fetchone()[0] == "wal"  # persistent in the file
        assert raw.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        # UNIQUE names are enforced by the schema itself, not only by the code.
        with pytest.raises(sqlite3.IntegrityError):
            raw.execute(
                "INSERT INTO shapes (name, rank, draft, volume, nx, ny, nz, bits, key, symmetric_key)"
                " SELECT name, 2, 0, volume, nx, ny, nz, bits, key, symmetric_key FROM shapes"
            )
    finally:
        raw.close()


def test_reopen_with_create_false(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    Repository(path).close()
    with Repository(path, create=False) as repo:
        assert len(repo) == 0


def test_not_an_sqlite_file(tmp_path: Path) -> None:
    path = tmp_path / "junk.sqlite"
    path.write_bytes(b"this is not a database at all, just some text" * 100)
    for create in (True, False):
        with pytest.raises(RepositoryError, match="not a voxfab repository"):
            Repository(path, create=create)
    assert path.read_bytes().startswith(b"this is not")


def test_other_sqlite_database(tmp_path: Path) -> None:
    path = tmp_path / "other.sqlite"
    raw = sqlite3.connect(path)
    raw.execute("CREATE TABLE t (x)")
    raw.commit()
    raw.close()
    with pytest.raises(RepositoryError, match="not a voxfab repository"):
        Repository(path)
    with pytest.raises(RepositoryError, match="not a voxfab repository"):
        Repository(path, create=False)


def test_empty_file_without_create(tmp_path: Path) -> None:
    path = tmp_path / "empty.sqlite"
    path.touch()
    with pytest.raises(RepositoryError, match="not a voxfab repository"):
        Repository(path, create=False)
    with Repository(path) as repo:  # an empty file is an empty database: made a repository
        assert repo.add(column()).name == "00025.001"


def test_newer_schema_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    Repository(path).close()
    raw = sqlite3.connect(path)
    raw.execute(f"PRAGMA user_version = {SCHEMA_VERSION + 1}")
    raw.commit()
    raw.close()
    with pytest.raises(RepositoryError, match=f"schema {SCHEMA_VERSION + 1} is newer"):
        Repository(path)


def test_folder_is_refused(tmp_path: Path) -> None:
    with pytest.raises(RepositoryError, match="is a folder"):
        Repository(tmp_path)


def _hold_write_lock(path: Path) -> sqlite3.Connection:
    raw = sqlite3.connect(path, isolation_level=None, check_same_thread=False)
    raw.execute("BEGIN IMMEDIATE")
    return raw


def test_writer_waits_for_the_lock(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    with Repository(path) as repo:
        raw = _hold_write_lock(path)
        timer = threading.Timer(0.3, lambda: raw.execute("COMMIT"))
        timer.start()
        start = time.monotonic()
        assert repo.add(column()).name == "00025.001"
        assert time.monotonic() - start >= 0.25
        timer.join()
        raw.close()


def test_lock_timeout_is_a_repository_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_sqlite, "BUSY_TIMEOUT_S", 0.2)
    path = tmp_path / "r.sqlite"
    with Repository(path) as repo:
        raw = _hold_write_lock(path)
        try:
            with pytest.raises(RepositoryError, match="locked"):
                repo.add(column())
            # Readers are not blocked by a writer in WAL mode.
            assert len(repo) == 0
        finally:
            raw.execute("ROLLBACK")
            raw.close()
        assert repo.add(column()).created


def _schema_1_file(path: Path, grids: list[np.ndarray]) -> None:
    """A repository as schema 1 wrote it: hex-text keys, the last row removed."""
    from voxfab.repo._records import encode_bits
    from voxfab.shape import canonical_key, crop

    raw = sqlite3.connect(path)
    try:
        for statement in _sqlite._MIGRATIONS[0]:
            raw.execute(statement)
        for g in grids:
            c = crop(g)
            raw.execute(
                "INSERT INTO shapes (name, rank, draft, volume, nx, ny, nz, bits, key, symmetric_key)"
                " VALUES (?, 1, 0, ?, ?, ?, ?, ?, ?, ?)",
                (f"{int(c.sum()):05d}.001", int(c.sum()), *c.shape, encode_bits(c), canonical_key(c),
                 canonical_key(c, symmetric=True)),
            )
            raw.execute("INSERT INTO rank_counters VALUES (?, 1)", (int(c.sum()),))
        raw.execute("DELETE FROM shapes WHERE id = ?", (len(grids),))
        raw.execute(f"PRAGMA application_id = {_sqlite.APPLICATION_ID}")
        raw.execute("PRAGMA user_version = 1")
        raw.commit()
    finally:
        raw.close()


def test_schema_1_file_is_migrated(tmp_path: Path) -> None:
    from voxfab.generate import growth
    from voxfab.shape import canonical_key

    grids = [growth(s, 40 + s) for s in range(4)]
    path = tmp_path / "old.sqlite"
    _schema_1_file(path, grids)
    with Repository(path, create=False) as repo:
        assert [e.name for e in repo.list()] == ["00040.001", "00041.001", "00042.001"]
        for g, name in zip(grids, ("00040.001", "00041.001", "00042.001")):
            assert repo.find(g) == name and repo.find(g, symmetric=True) == name
            assert repo.show(name)["key"] == canonical_key(g)
        assert repo.check() == []
        # The removed row's id is not given again (draft ids are row ids).
        bad = grids[0].copy()
        bad[0, 0, 0] = bad[24, 24, 0] = True
        assert repo.add(bad, draft=True).name == "draft-5"
    raw = sqlite3.connect(path)
    try:
        assert raw.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION == 5
        assert {r[0] for r in raw.execute("SELECT typeof(key) || typeof(symmetric_key) FROM shapes")} == {"blobblob"}
        assert raw.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        names = {r[0] for r in raw.execute("SELECT name FROM sqlite_master")}
        assert {"shapes_key", "shapes_symmetric_key", "shapes_order"} <= names and "shapes_v2" not in names
        assert {"range_members", "range_members_shape", "range_made"} <= names
    finally:
        raw.close()
