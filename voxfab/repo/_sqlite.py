"""SQLite storage of the repository: connection settings, versioned schema, transactions.

This module (with the rest of ``voxfab.repo``) is the only code in voxfab that
touches :mod:`sqlite3`.

The schema version lives in ``PRAGMA user_version`` and the file is marked as a
voxfab repository by ``PRAGMA application_id``.  ``_MIGRATIONS[v]`` holds the
statements that take a file from version ``v`` to ``v + 1``; opening a file
applies the missing ones inside one ``BEGIN IMMEDIATE`` transaction, so several
processes may open (and create) the same file at the same time.

Schema 2 stores the two canonical keys as 32-byte blobs instead of 64-character
hex text: with a million shapes the keys and their two indexes are most of the
file, and halving them halves the pages a lookup touches.

Schema 3 adds named ranges (``range_members``): an ordered set of stored shapes
under one name, such as the polycubes of a census, each member named
``RANGE:MEMBER``.  Most members are drafts (a census shape need not span the
grid); the drafts of a range stay out of the plain listing.

Schema 4 records which drafts a range stored itself (``range_made``): removing a
range removes those, never a draft the artist added (even one a census later
found equal to one of its polycubes).  A file of schema 3 counts every draft a
range holds as the range's own, as schema 3 did.
"""

from __future__ import annotations

import contextlib
import sqlite3
import time
from collections.abc import Iterator
from pathlib import Path

from voxfab.errors import RepositoryError

__all__ = ["SCHEMA_VERSION", "SCHEMA_OBJECTS", "APPLICATION_ID", "BUSY_TIMEOUT_S", "connect", "immediate", "sqlite_errors"]

#: Version of the schema written by this code (``PRAGMA user_version``).
SCHEMA_VERSION = 5
#: ``PRAGMA application_id`` of a voxfab repository: the bytes "VXFB".
APPLICATION_ID = 0x56584642
#: How long a writer waits for another process's write lock before giving up.
BUSY_TIMEOUT_S = 60.0

_MIGRATIONS: tuple[tuple[str, ...], ...] = (
    # 0 -> 1: shapes with their canonical keys; per-volume rank counters.
    (
        """
        CREATE TABLE shapes (
            id INTEGER PRIMARY KEY AUTOINCREMENT,
            name TEXT UNIQUE,
            volume INTEGER NOT NULL CHECK (volume > 0),
            rank INTEGER CHECK (rank BETWEEN 1 AND 999),
            nx INTEGER NOT NULL CHECK (nx > 0),
            ny INTEGER NOT NULL CHECK (ny > 0),
            nz INTEGER NOT NULL CHECK (nz > 0),
            bits BLOB NOT NULL,
            key TEXT NOT NULL,
            symmetric_key TEXT NOT NULL,
            draft INTEGER NOT NULL CHECK (draft IN (0, 1)),
            reasons TEXT NOT NULL DEFAULT '[]',
            meta TEXT,
            UNIQUE (volume, rank),
            CHECK ((draft = 1) = (rank IS NULL))
        )
        """,
        "CREATE INDEX shapes_key ON shapes (key)",
        "CREATE INDEX shapes_symmetric_key ON shapes (symmetric_key)",
        "CREATE INDEX shapes_order ON shapes (draft, volume, rank, id)",
        # The last rank ever given per volume: removed names are never given again.
        """
        CREATE TABLE rank_counters (
            volume INTEGER PRIMARY KEY,
            last_rank INTEGER NOT NULL CHECK (last_rank BETWEEN 1 AND 999)
        )
        """,
    ),
    # 1 -> 2: keys as 32-byte blobs.  SQLite cannot change a column's type in place,
    # so the table is rebuilt (ids kept: draft ids are row ids) and the AUTOINCREMENT
    # counter carried over, so that no draft id is ever given twice.
    (
        """
        CREATE TABLE shapes_v2 (
            id INTEGER PRIMARY KEY AUTOINCREMENT,
            name TEXT UNIQUE,
            volume INTEGER NOT NULL CHECK (volume > 0),
            rank INTEGER CHECK (rank BETWEEN 1 AND 999),
            nx INTEGER NOT NULL CHECK (nx > 0),
            ny INTEGER NOT NULL CHECK (ny > 0),
            nz INTEGER NOT NULL CHECK (nz > 0),
            bits BLOB NOT NULL,
            key BLOB NOT NULL CHECK (length(key) = 32),
            symmetric_key BLOB NOT NULL CHECK (length(symmetric_key) = 32),
            draft INTEGER NOT NULL CHECK (draft IN (0, 1)),
            reasons TEXT NOT NULL DEFAULT '[]',
            meta TEXT,
            UNIQUE (volume, rank),
            CHECK ((draft = 1) = (rank IS NULL))
        )
        """,
        "INSERT INTO shapes_v2 (id, name, volume, rank, nx, ny, nz, bits, key, symmetric_key, draft, reasons, meta)"
        " SELECT id, name, volume, rank, nx, ny, nz, bits, voxfab_unhex(key), voxfab_unhex(symmetric_key),"
        " draft, reasons, meta FROM shapes ORDER BY id",
        "INSERT INTO sqlite_sequence (name, seq) SELECT 'shapes_v2', seq FROM sqlite_sequence"
        " WHERE name = 'shapes' AND NOT EXISTS (SELECT 1 FROM sqlite_sequence WHERE name = 'shapes_v2')",
        "UPDATE sqlite_sequence SET seq = max(seq, (SELECT coalesce(max(seq), 0) FROM sqlite_sequence"
        " WHERE name = 'shapes')) WHERE name = 'shapes_v2'",
        "DROP TABLE shapes",
        "ALTER TABLE shapes_v2 RENAME TO shapes",
        "CREATE INDEX shapes_key ON shapes (key)",
        "CREATE INDEX shapes_symmetric_key ON shapes (symmetric_key)",
        "CREATE INDEX shapes_order ON shapes (draft, volume, rank, id)",
    ),
    # 2 -> 3: named ranges.  A member points at its shape's row; ``position`` keeps the
    # range in the order it was stored (a census's fixed order).
    (
        """
        CREATE TABLE range_members (
            range TEXT NOT NULL,
            member TEXT NOT NULL,
            position INTEGER NOT NULL CHECK (position > 0),
            shape INTEGER NOT NULL REFERENCES shapes (id),
            PRIMARY KEY (range, member),
            UNIQUE (range, position)
        )
        """,
        "CREATE INDEX range_members_shape ON range_members (shape)",
    ),
    # 3 -> 4: the drafts ranges stored themselves (the only shapes removing a range removes).
    (
        "CREATE TABLE range_made (shape INTEGER PRIMARY KEY REFERENCES shapes (id))",
        "INSERT INTO range_made (shape) SELECT DISTINCT m.shape FROM range_members m JOIN shapes s ON s.id = m.shape"
        " WHERE s.draft = 1",
    ),
    # 4 -> 5: colours.  The RGBA of each voxel of the stored (cropped) grid, in C order; NULL for an
    # uncoloured shape, so every shape stored before reads as it did.
    (
        "ALTER TABLE shapes ADD COLUMN colours BLOB CHECK (colours IS NULL OR length(colours) = 4 * volume)",
    ),
)
#: The tables and indexes of the current schema: a file missing one is damaged (``Repository.check``).
SCHEMA_OBJECTS = ("shapes", "rank_counters", "range_members", "range_made", "shapes_key", "shapes_symmetric_key",
                  "shapes_order", "range_members_shape")
assert len(_MIGRATIONS) == SCHEMA_VERSION


def _unhex(text: str | bytes) -> bytes:
    """SQL function of the 1 -> 2 migration (SQLite before 3.41 has no ``unhex``)."""
    return text if isinstance(text, bytes) else bytes.fromhex(text)


@contextlib.contextmanager
def sqlite_errors(path: Path) -> Iterator[None]:
    """Turn :class:`sqlite3.Error` into a one-line :class:`RepositoryError` naming ``path``."""
    try:
        yield
    except sqlite3.Error as exc:
        detail = " ".join(str(exc).split())
        if isinstance(exc, sqlite3.OperationalError) and "locked" in detail:
            detail += f" (another process kept it busy; waited up to {BUSY_TIMEOUT_S:g} s)"
        raise RepositoryError(f"{path}: {detail}") from exc


@contextlib.contextmanager
def immediate(conn: sqlite3.Connection) -> Iterator[sqlite3.Connection]:
    """Run the block in a ``BEGIN IMMEDIATE`` transaction: committed on success, rolled back on error.

    ``IMMEDIATE`` takes the write lock before the first read, so a read-then-write
    (such as allocating the next rank) cannot interleave with another writer.
    """
    conn.execute("BEGIN IMMEDIATE")
    try:
        yield conn
    except BaseException:
        with contextlib.suppress(sqlite3.Error):
            conn.execute("ROLLBACK")
        raise
    conn.execute("COMMIT")


def _pragma(conn: sqlite3.Connection, name: str) -> int:
    return int(conn.execute(f"PRAGMA {name}").fetchone()[0])


def _check_header(path: Path, version: int, app: int) -> None:
    if version > 0 and app != APPLICATION_ID:
        raise RepositoryError(f"{path}: an SQLite file that is not a voxfab repository")
    if version > SCHEMA_VERSION:
        raise RepositoryError(
            f"{path}: repository schema {version} is newer than this voxfab supports ({SCHEMA_VERSION})"
        )


def _migrate(conn: sqlite3.Connection, path: Path, *, create: bool) -> None:
    version, app = _pragma(conn, "user_version"), _pragma(conn, "application_id")
    _check_header(path, version, app)
    if version == SCHEMA_VERSION:
        return
    if version == 0 and not create:
        raise RepositoryError(f"{path}: not a voxfab repository (no schema)")
    with immediate(conn):
        # Read again under the write lock: another process may have migrated meanwhile.
        version, app = _pragma(conn, "user_version"), _pragma(conn, "application_id")
        _check_header(path, version, app)
        if version == 0:
            if conn.execute("SELECT count(*) FROM sqlite_master").fetchone()[0]:
                raise RepositoryError(f"{path}: an SQLite file that is not a voxfab repository")
            conn.execute(f"PRAGMA application_id = {APPLICATION_ID}")
        for step in _MIGRATIONS[version:]:
            for statement in step:
                conn.execute(statement)
        conn.execute(f"PRAGMA user_version = {SCHEMA_VERSION}")


def _use_wal(conn: sqlite3.Connection) -> None:
    """Put the file in WAL mode (kept in the file, so usually already done).

    Switching needs an exclusive lock, and SQLite reports "locked" at once,
    without its busy handler, while another process opens the new file: retry.
    """
    deadline = time.monotonic() + BUSY_TIMEOUT_S
    while True:
        try:
            if str(conn.execute("PRAGMA journal_mode").fetchone()[0]).lower() != "wal":
                conn.execute("PRAGMA journal_mode = WAL")
            return
        except sqlite3.OperationalError as exc:
            if "locked" not in str(exc) or time.monotonic() > deadline:
                raise
            time.sleep(0.01)


def _text(data: bytes) -> str | bytes:
    """Text columns as str; text that is not UTF-8 (a damaged row) as its bytes, for the row checks."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data


def connect(path: Path, *, create: bool) -> sqlite3.Connection:
    """Open (and with ``create`` make or upgrade) the repository file at ``path``.

    The connection is in autocommit mode: writers use :func:`immediate`.  The file
    is put in WAL mode (readers never block the writer) with ``synchronous=NORMAL``:
    a crashed process cannot corrupt it; a power cut may lose the last commits.

    Raises
    ------
    RepositoryError
        If ``create`` is false and there is no file, or the file is not a voxfab
        repository (or a newer schema).
    """
    if path.is_dir():
        raise RepositoryError(f"{path}: is a folder, not a repository file")
    if not path.exists():
        if not create:
            raise RepositoryError(f"no repository at {path}")
        path.parent.mkdir(parents=True, exist_ok=True)
    uri = f"{path.resolve().as_uri()}?mode={'rwc' if create else 'rw'}"
    with sqlite_errors(path):
        conn = sqlite3.connect(uri, uri=True, timeout=BUSY_TIMEOUT_S, isolation_level=None)
        conn.text_factory = _text
    try:
        with sqlite_errors(path):
            conn.execute(f"PRAGMA busy_timeout = {int(BUSY_TIMEOUT_S * 1000)}")
            conn.create_function("voxfab_unhex", 1, _unhex, deterministic=True)
            try:
                _migrate(conn, path, create=create)
            except sqlite3.DatabaseError as exc:
                if "not a database" in str(exc):
                    raise RepositoryError(f"{path}: not a voxfab repository (not an SQLite file)") from exc
                raise
            _use_wal(conn)
            conn.execute("PRAGMA synchronous = NORMAL")
    except BaseException:
        conn.close()
        raise
    return conn
