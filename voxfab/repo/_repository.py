"""The shape repository: named voxel shapes in one SQLite file."""

from __future__ import annotations

import dataclasses
import json
import sqlite3
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy.typing as npt

from voxfab._shared.typing import BoolGrid, PathLike
from voxfab.errors import RepositoryError
from voxfab.shape import VoxelShape, canonical_key, well_formed_reasons

from ._ranges import (
    RangeInfo,
    check_members,
    claim_drafts,
    insert_members,
    member_rows,
    range_infos,
    remove_made_drafts,
    require_sound,
    split_member,
)
from ._records import (
    MAX_RANK,
    Record,
    check_grid,
    check_name,
    check_range_name,
    decode_colours,
    decode_meta,
    decode_reasons,
    decode_row,
    draft_name,
    encode_meta,
    format_name,
    prepare,
)
from ._sqlite import SCHEMA_OBJECTS, connect, immediate, sqlite_errors

__all__ = ["DEFAULT_PATH", "AddResult", "Entry", "Repository"]

#: Where the CLI keeps the repository unless told otherwise (relative to the working folder).
DEFAULT_PATH = Path("output") / "repository.sqlite"

_ORDER = "ORDER BY draft, volume, rank, id"


@dataclasses.dataclass(frozen=True)
class AddResult:
    """What :meth:`Repository.add` did.

    Attributes
    ----------
    name : str
        ``VVVVV.NNN``, or ``draft-N`` for a shape stored as a draft.
    created : bool
        False when an equal shape was already stored (``name`` is its name).
    reasons : tuple of str
        Why the shape is not well formed (non-empty only for drafts).
    """

    name: str
    created: bool
    reasons: tuple[str, ...] = ()

    @property
    def draft(self) -> bool:
        """Whether the name is a draft id."""
        return self.name.startswith("draft-")


@dataclasses.dataclass(frozen=True)
class Entry:
    """One row of :meth:`Repository.list`.

    Attributes
    ----------
    name : str
        ``VVVVV.NNN`` or ``draft-N``.
    volume : int
        Filled voxels.
    extents : (int, int, int)
        Bounding-box size along x, y, z in voxels.
    draft : bool
        Whether the shape is a draft (not well formed, unnamed).
    """

    name: str
    volume: int
    extents: tuple[int, int, int]
    draft: bool


class Repository:
    """Named voxel shapes stored in one SQLite file.

    A well-formed shape (see :func:`voxfab.shape.well_formed_reasons`) gets the name
    ``VVVVV.NNN``: its volume zero-padded to 5 digits, then its 3-digit rank among the
    shapes of that volume in insertion order (``001`` first).  Names are stable:
    :meth:`remove` does not renumber the other shapes and a removed name is never
    given again, so rank ``N`` means "the N-th shape of that volume ever added".

    Equal shapes are stored once: a shape is looked up by its canonical key
    (:func:`voxfab.shape.canonical_key`, indexed), up to translation or, with
    ``symmetric=True``, up to the 48 symmetries of the cube.

    Several processes may use the same file at once: each write runs in a
    ``BEGIN IMMEDIATE`` transaction and names are UNIQUE in the schema.

    Parameters
    ----------
    path : str or os.PathLike
        The database file (default ``output/repository.sqlite``).
    create : bool
        Create the file (and its folder) when missing.  Otherwise a missing file
        raises :class:`RepositoryError`.

    Raises
    ------
    RepositoryError
        No file with ``create=False``, or a file that is not a voxfab repository.

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> column = np.ones((1, 1, 25), bool)
    >>> with tempfile.TemporaryDirectory() as d, Repository(f"{d}/r.sqlite") as repo:
    ...     repo.add(column).name, repo.add(column).created
    ('00025.001', False)
    """

    def __init__(self, path: PathLike = DEFAULT_PATH, *, create: bool = True) -> None:
        self._path = Path(path)
        self._conn: sqlite3.Connection | None = connect(self._path, create=create)

    # -- life cycle -------------------------------------------------------------

    @property
    def path(self) -> Path:
        """The database file."""
        return self._path

    def close(self) -> None:
        """Close the connection (idempotent)."""
        if self._conn is not None:
            self._conn.close()
            self._conn = None

    def __enter__(self) -> Repository:
        return self

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "closed" if self._conn is None else "open"
        return f"Repository({str(self._path)!r}, {state})"

    @property
    def _db(self) -> sqlite3.Connection:
        if self._conn is None:
            raise RepositoryError(f"{self._path}: the repository is closed")
        return self._conn

    # -- adding -----------------------------------------------------------------

    def add(
        self,
        grid: npt.ArrayLike,
        *,
        symmetric: bool = False,
        draft: bool = False,
        meta: Mapping[str, Any] | None = None,
    ) -> AddResult:
        """Store a shape and name it, unless an equal shape is stored already.

        Parameters
        ----------
        grid : (X, Y, Z) bool array_like or VoxelShape
            The shape; only its cropped content is stored, with its colours when it has them.
        symmetric : bool
            Also treat rotated and mirrored copies (48 cube symmetries) as equal.
        draft : bool
            Store a shape that is not well formed as an unnamed draft (id
            ``draft-N``) instead of refusing it.  A well-formed shape is named as usual.
        meta : mapping, optional
            JSON-compatible metadata (seed, source, ...), shown by :meth:`show`.

        Returns
        -------
        AddResult
            The new name and ``created=True``, or the stored equal shape's name and
            ``created=False`` (then nothing is written, ``meta`` included).

        Raises
        ------
        RepositoryError
            A shape that is not well formed (without ``draft``; the message lists the
            reasons), an empty grid, bad ``meta``, or all 999 ranks of the volume used.
        InvalidShapeError
            A grid of a wrong dtype or over the size limit.
        """
        return self.add_many([grid], symmetric=symmetric, draft=draft, metas=[meta])[0]

    def add_many(
        self,
        grids: Iterable[npt.ArrayLike],
        *,
        symmetric: bool = False,
        draft: bool = False,
        metas: Sequence[Mapping[str, Any] | None] | None = None,
        keys: Sequence[str] | None = None,
        reasons: Sequence[Sequence[str]] | None = None,
    ) -> list[AddResult]:
        """Add several shapes in one transaction: all are stored, or none is.

        Same rules as :meth:`add` (a shape equal to an earlier one in the same call
        gets its name).  One transaction makes bulk loading much faster.

        Parameters
        ----------
        grids : iterable of (X, Y, Z) bool array_like
        symmetric, draft : bool
            As in :meth:`add`.
        metas : sequence of (mapping or None), optional
            One metadata mapping per grid.
        keys : sequence of str, optional
            The grids' :func:`voxfab.shape.canonical_key` (``symmetric`` as given),
            when the caller has computed them already.
        reasons : sequence of sequences of str, optional
            The grids' :func:`voxfab.shape.well_formed_reasons`, when the caller has
            computed them already (``explore`` knows its growth is well formed by
            construction); checking connectivity is most of the cost of an add.

        Returns
        -------
        list of AddResult
            In the order of ``grids``.
        """
        results, pending = self._prepare_many(grids, symmetric=symmetric, draft=draft, metas=metas, keys=keys,
                                              reasons=reasons)
        # A draft the artist adds that a range stored already becomes the artist's: removing the range keeps it.
        found_drafts = [r.name for r in results if r is not None and r.draft]
        if pending or found_drafts:
            db = self._db
            with sqlite_errors(self._path), immediate(db):
                self._insert_pending(db, results, pending, symmetric=symmetric)
                claim_drafts(db, found_drafts)
        return [r for r in results if r is not None]

    def _prepare_many(
        self,
        grids: Iterable[npt.ArrayLike],
        *,
        symmetric: bool,
        draft: bool,
        metas: Sequence[Mapping[str, Any] | None] | None,
        keys: Sequence[str] | None = None,
        reasons: Sequence[Sequence[str]] | None = None,
    ) -> tuple[list[AddResult | None], list[tuple[int, Record]]]:
        """The results known before any lock (shapes stored already) and the records still to insert."""
        grids = list(grids)
        if metas is None:
            metas = [None] * len(grids)
        if len(metas) != len(grids):
            raise RepositoryError(f"metas: expected {len(grids)} entries, got {len(metas)}")
        if keys is not None and len(keys) != len(grids):
            raise RepositoryError(f"keys: expected {len(grids)} entries, got {len(keys)}")
        if reasons is not None and len(reasons) != len(grids):
            raise RepositoryError(f"reasons: expected {len(grids)} entries, got {len(reasons)}")
        # Everything is computed before the write lock is taken, so the lock is held
        # only for the index lookups and the inserts.  A shape found by a first
        # lock-free lookup needs neither its other key nor its well-formedness
        # computed again: equal shapes share them.
        results: list[AddResult | None] = []
        pending: list[tuple[int, Record]] = []
        for i, (grid, m) in enumerate(zip(grids, metas)):
            label = "shape" if len(grids) == 1 else f"shape {i}"
            colours = getattr(grid, "colours", None)
            g = check_grid(getattr(grid, "grid", grid), name=label)
            meta = encode_meta(m)
            key = keys[i] if keys is not None else canonical_key(g, symmetric=symmetric, colours=colours)
            found = self._lookup(key, symmetric=symmetric)
            if found is not None:
                name, stored_reasons = found
                if stored_reasons and not draft:
                    raise _not_well_formed(label, stored_reasons)
                results.append(AddResult(name, False, stored_reasons))
                continue
            known = None if reasons is None else tuple(reasons[i])
            if symmetric:
                record = prepare(g, meta=meta, symmetric_key=key, reasons=known, colours=colours)
            else:
                record = prepare(g, meta=meta, key=key, reasons=known, colours=colours)
            if record.reasons and not draft:
                raise _not_well_formed(label, record.reasons)
            results.append(None)
            pending.append((i, record))
        return results, pending

    def _insert_pending(self, db: sqlite3.Connection, results: list[AddResult | None],
                        pending: list[tuple[int, Record]], *, symmetric: bool) -> None:
        """Insert the prepared records (inside the caller's transaction), filling in their results."""
        for i, record in pending:
            results[i] = self._insert(db, record, symmetric=symmetric)

    def add_range(self, range_name: str, members: Sequence[tuple[str, npt.ArrayLike]], *,
                  meta: Mapping[str, Any] | None = None) -> int:
        """Store shapes as the named range ``range_name``, in order, in one transaction.

        Each shape is stored as :meth:`add` with ``draft=True`` would (an equal
        shape stored already is shared), and named ``RANGE:MEMBER`` as well.  The
        shapes need not be well formed: a census's polycubes do not span the grid.

        Parameters
        ----------
        range_name : str
            Lowercase letters, digits, ``-`` and ``_``, starting with a letter (``polycubes-8``).
        members : sequence of (str, (X, Y, Z) bool array_like)
            Member names (``08-000001``: lowercase letters, digits, ``-``, ``_``) and their shapes.
            Members already in the range with the same shape are kept; the rest are
            added after the range's last member.
        meta : mapping, optional
            JSON-compatible metadata stored with each new shape.

        Returns
        -------
        int
            How many members were added.

        Raises
        ------
        RepositoryError
            A bad range or member name, a member name given twice, or a member
            name the range holds already for another shape (then nothing is written).
        """
        check_range_name(range_name)
        names = [m for m, _ in members]
        for m in names:
            check_name(f"{range_name}:{m}")
        if len(set(names)) != len(names):
            twice = next(m for i, m in enumerate(names) if m in names[:i])
            raise RepositoryError(f"{range_name}:{twice}: a member name given twice")
        results, pending = self._prepare_many([g for _, g in members], symmetric=False, draft=True,
                                              metas=[meta] * len(names))
        db = self._db
        with sqlite_errors(self._path), immediate(db):
            self._insert_pending(db, results, pending, symmetric=False)
            made = [r.name for r in (results[i] for i, _ in pending) if r is not None and r.created and r.draft]
            return insert_members(db, range_name, [(m, r.name) for m, r in zip(names, results) if r is not None],
                                  made)

    def ranges(self) -> list[RangeInfo]:
        """Every stored range, by name, with its number of members."""
        with sqlite_errors(self._path):
            return range_infos(self._db)

    def list_range(self, range_name: str, *, after: str | None = None, limit: int | None = None) -> list[Entry]:
        """The members of a range in stored order, named ``RANGE:MEMBER``.

        ``after`` (a member, with or without ``RANGE:``) and ``limit`` page as in :meth:`list`.

        Raises
        ------
        RepositoryError
            A bad range name, a range that holds nothing, an unknown ``after`` or a limit below 1.
        """
        check_range_name(range_name)
        if limit is not None and int(limit) < 1:
            raise RepositoryError(f"limit: expected at least 1, got {limit}")
        if after is not None and after.startswith(f"{range_name}:"):
            after = after[len(range_name) + 1:]
        with sqlite_errors(self._path):
            held = self._db.execute("SELECT 1 FROM range_members WHERE range = ? LIMIT 1", (range_name,)).fetchone()
            if held is None:  # one index probe, not a count of every range
                raise RepositoryError(f"{range_name}: no such range in {self._path}")
            rows = member_rows(self._db, range_name, after, None if limit is None else min(int(limit), 2**62))
        return [Entry(f"{range_name}:{m}", v, (nx, ny, nz), bool(d)) for m, v, nx, ny, nz, d in rows]

    def remove_range(self, range_name: str) -> int:
        """Delete a range: its members, and the drafts it stored itself that no other range holds.

        Named shapes (``VVVVV.NNN``) in the range stay stored, and so do the
        artist's own drafts (a census finds a stored draft equal to a polycube and
        shares it).  Returns the member count.
        """
        check_range_name(range_name)
        db = self._db
        with sqlite_errors(self._path), immediate(db):
            require_sound(db)
            shapes = [r[0] for r in db.execute("SELECT shape FROM range_members WHERE range = ?", (range_name,))]
            if not shapes:
                raise RepositoryError(f"{range_name}: no such range in {self._path}")
            db.execute("DELETE FROM range_members WHERE range = ?", (range_name,))
            remove_made_drafts(db, shapes)
        return len(shapes)

    def _lookup(self, key: str, *, symmetric: bool) -> tuple[str, tuple[str, ...]] | None:
        """Name and reasons of the first stored shape with this canonical key, or None."""
        column = "symmetric_key" if symmetric else "key"
        with sqlite_errors(self._path):
            row = self._db.execute(
                f"SELECT name, reasons FROM shapes WHERE {column} = ? {_ORDER} LIMIT 1", (bytes.fromhex(key),)
            ).fetchone()
        return None if row is None else (row[0], decode_reasons(row[0], row[1]))

    def _insert(self, db: sqlite3.Connection, r: Record, *, symmetric: bool) -> AddResult:
        column, key = ("symmetric_key", r.symmetric_key) if symmetric else ("key", r.key)
        row = db.execute(
            f"SELECT name FROM shapes WHERE {column} = ? {_ORDER} LIMIT 1", (bytes.fromhex(key),)
        ).fetchone()
        if row is not None:
            return AddResult(row[0], False, r.reasons)
        values = (r.volume, *r.extents, r.bits, bytes.fromhex(r.key), bytes.fromhex(r.symmetric_key),
                  json.dumps(list(r.reasons)), r.meta, r.colours)
        insert = (
            "INSERT INTO shapes (name, rank, draft, volume, nx, ny, nz, bits, key, symmetric_key, reasons, meta,"
            " colours) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)"
        )
        if r.reasons:
            row_id = db.execute(insert, (None, None, 1, *values)).lastrowid
            name = draft_name(int(row_id))
            db.execute("UPDATE shapes SET name = ? WHERE id = ?", (name, row_id))
            return AddResult(name, True, r.reasons)
        last = db.execute("SELECT last_rank FROM rank_counters WHERE volume = ?", (r.volume,)).fetchone()
        rank = (last[0] if last else 0) + 1
        if rank > MAX_RANK:
            raise RepositoryError(
                f"volume {r.volume}: all {MAX_RANK} ranks {r.volume:05d}.001-{r.volume:05d}.{MAX_RANK} "
                "have been given (removed names are not reused); cannot name another shape of this volume"
            )
        db.execute(
            "INSERT INTO rank_counters (volume, last_rank) VALUES (?, ?)"
            " ON CONFLICT (volume) DO UPDATE SET last_rank = excluded.last_rank",
            (r.volume, rank),
        )
        name = format_name(r.volume, rank)
        db.execute(insert, (name, rank, 0, *values))
        return AddResult(name, True, ())

    # -- reading ----------------------------------------------------------------

    def _row(self, name: str, columns: str) -> tuple[Any, ...]:
        check_name(name)
        member = split_member(name)
        with sqlite_errors(self._path):
            if member is None:
                row = self._db.execute(f"SELECT {columns} FROM shapes WHERE name = ?", (name,)).fetchone()
            else:  # the member's shape row (the range table's columns have other names than the shape's)
                row = self._db.execute(f"SELECT {columns} FROM shapes JOIN range_members ON shape = id"
                                       " WHERE range = ? AND member = ?", member).fetchone()
        if row is None:
            raise RepositoryError(f"{name}: no such shape in {self._path}")
        return tuple(row)

    def get(self, name: str) -> BoolGrid:
        """Return the stored (cropped) grid of ``name``.

        Returns
        -------
        (X, Y, Z) bool ndarray
            A new writable array the size of the shape's bounding box.

        Raises
        ------
        RepositoryError
            For a malformed or unknown name.
        """
        return decode_row(name, *self._grid_columns(name))

    def shape(self, name: str, pitch: float = 1.0) -> VoxelShape:
        """The stored shape ``name`` (cropped) in its colours, at ``pitch`` mm per voxel."""
        bits, extents, volume, key, skey, colours = self._grid_columns(name)
        grid = decode_row(name, bits, extents, volume, key, skey, colours)
        return VoxelShape(grid, pitch, decode_colours(name, colours, grid))

    def _grid_columns(self, name: str) -> tuple[Any, ...]:
        bits, nx, ny, nz, volume, key, skey, colours = self._row(
            name, f"{_BITS}, nx, ny, nz, volume, key, symmetric_key, colours")
        return bits, (nx, ny, nz), volume, key, skey, colours

    def packed(self, name: str) -> tuple[bytes, tuple[int, int, int]]:
        """Return the stored packed bits of ``name`` and its extents, without unpacking.

        ``voxfab.repo._records.decode_bits(bits, extents)`` gives the grid of :meth:`get`;
        a batch sends these few bytes to its workers.  The row is checked as by
        :meth:`get` first, so a worker never receives a corrupt shape.
        """
        bits, extents, volume, key, skey, colours = self._grid_columns(name)
        decode_row(name, bits, extents, volume, key, skey, colours)
        return bytes(bits), extents

    def find(self, grid: npt.ArrayLike, *, symmetric: bool = False) -> str | None:
        """Return the name of the stored shape equal to ``grid``, or None.

        Equal means the same voxels up to translation, and with ``symmetric`` up to
        the 48 cube symmetries.  Drafts are found too (their ``draft-N`` id).
        """
        key = canonical_key(getattr(grid, "grid", grid), symmetric=symmetric, colours=getattr(grid, "colours", None))
        found = self._lookup(key, symmetric=symmetric)
        return None if found is None else found[0]

    def list(
        self,
        *,
        volume: tuple[int, int] | None = None,
        after: str | None = None,
        limit: int | None = None,
        drafts: bool = True,
    ) -> list[Entry]:
        """Return stored shapes: named ones by volume then rank, then drafts by volume.

        Without arguments every shape is listed.  The filters run in the database
        on its ``(draft, volume, rank, id)`` index, so one page costs the same at
        any depth of a million-shape repository.

        Parameters
        ----------
        volume : (int, int), optional
            Keep the shapes whose volume is in ``[min, max]`` (inclusive).
        after : str, optional
            Start after this stored name or draft id (the last one of the previous
            page): keyset paging, which no insertion or removal elsewhere can shift.
        limit : int, optional
            At most this many entries (at least 1).
        drafts : bool
            Include the drafts.

        Raises
        ------
        RepositoryError
            For an unknown ``after`` name, an empty volume range or a limit below 1.
        """
        span: tuple[int, int] | None = None
        if volume is not None:
            span = (int(volume[0]), int(volume[1]))
            if span[0] > span[1] or span[1] < 1:
                raise RepositoryError(f"volume: the range {span[0]}:{span[1]} is empty")
        if limit is not None and int(limit) < 1:
            raise RepositoryError(f"limit: expected at least 1, got {limit}")
        if limit is not None:
            # SQLite's LIMIT is a 64-bit integer; no file holds more rows than that anyway.
            limit = min(int(limit), 2**62)
        start: tuple[int, int, int, int | None] | None = None
        if after is not None:
            row_id, d, v, r = self._row(after, "id, draft, volume, rank")
            start = (int(d), int(v), int(row_id), r)
        # Named shapes, then drafts: two queries, each a range seek on the
        # (draft, volume, rank, id) index, so a page deep in the listing costs no
        # more than the first one.  Drafts have no rank: they page by (volume, id).
        parts: list[tuple[str, list[Any]]] = []
        if start is None or start[0] == 0:
            where, params = ["draft = 0"], []
            if start is not None:
                where.append("(volume, rank) > (?, ?)")
                params += [start[1], start[3]]
            parts.append((" AND ".join(where), params))
        if drafts:
            # A range's drafts are listed with the range (list_range), not among the artist's drafts.
            where, params = ["draft = 1 AND id NOT IN (SELECT shape FROM range_made)"], []
            if start is not None and start[0] == 1:
                where.append("(volume, id) > (?, ?)")
                params += [start[1], start[2]]
            parts.append((" AND ".join(where), params))
        rows: list[tuple[Any, ...]] = []
        with sqlite_errors(self._path):
            for where, params in parts:
                if span is not None:
                    where += " AND volume BETWEEN ? AND ?"
                    params = [*params, *span]
                sql = f"SELECT name, volume, nx, ny, nz, draft FROM shapes WHERE {where} {_ORDER}"
                if limit is not None:
                    if len(rows) >= limit:
                        break
                    sql += f" LIMIT {int(limit) - len(rows)}"
                rows += self._db.execute(sql, params).fetchall()
        return [Entry(name, v, (nx, ny, nz), bool(d)) for name, v, nx, ny, nz, d in rows]

    def stats(self, *, volume: tuple[int, int] | None = None) -> dict[str, Any]:
        """Count the stored shapes per volume.

        Returns
        -------
        dict
            ``shapes`` (named shapes), ``drafts`` (outside ranges), ``named_ranges``
            (each range's ``name`` and ``count``), and ``volumes``: a list of
            ``{"volume", "count", "last_rank"}`` by volume, where ``last_rank`` is the
            highest rank ever given (removed names are not reused, so it can exceed
            ``count``).  ``volume`` = ``(min, max)`` restricts all three.
        """
        lo, hi = (1, 2**62) if volume is None else (int(volume[0]), int(volume[1]))
        with sqlite_errors(self._path):
            rows = self._db.execute(
                "SELECT s.volume, count(*), c.last_rank FROM shapes s"
                " LEFT JOIN rank_counters c ON c.volume = s.volume"
                " WHERE s.draft = 0 AND s.volume BETWEEN ? AND ? GROUP BY s.volume ORDER BY s.volume",
                (lo, hi),
            ).fetchall()
            drafts = self._db.execute(
                "SELECT count(*) FROM shapes WHERE draft = 1 AND volume BETWEEN ? AND ?"
                " AND id NOT IN (SELECT shape FROM range_made)", (lo, hi)
            ).fetchone()[0]
            ranges = range_infos(self._db)
        return {
            "shapes": sum(r[1] for r in rows),
            "drafts": int(drafts),
            "named_ranges": [{"name": r.name, "count": r.count} for r in ranges],
            "volumes": [{"volume": v, "count": n, "last_rank": last} for v, n, last in rows],
        }

    def last_ranks(self) -> dict[int, int]:
        """Return the highest rank ever given per volume (a volume is full at :data:`MAX_RANK`)."""
        with sqlite_errors(self._path):
            return dict(self._db.execute("SELECT volume, last_rank FROM rank_counters").fetchall())

    def show(self, name: str) -> dict[str, Any]:
        """Return what is known about ``name`` as a JSON-compatible dict.

        Keys: ``name``, ``volume``, ``rank`` (None for drafts), ``extents``,
        ``draft``, ``reasons`` (why a draft is not well formed), ``key`` and
        ``symmetric_key`` (canonical sha256 keys), ``meta`` (None if none stored),
        ``colours`` (distinct colours, 0 when uncoloured).
        """
        volume, rank, nx, ny, nz, d, reasons, key, skey, meta, bits, colours = self._row(
            name, f"volume, rank, nx, ny, nz, draft, reasons, key, symmetric_key, meta, {_BITS}, colours"
        )
        grid = decode_row(name, bits, (nx, ny, nz), volume, key, skey, colours)
        stored = decode_colours(name, colours, grid)
        return {
            "name": name,
            "volume": volume,
            "rank": rank,
            "extents": [nx, ny, nz],
            "draft": bool(d),
            "reasons": list(decode_reasons(name, reasons)),
            "key": key.hex(),
            "symmetric_key": skey.hex(),
            "meta": decode_meta(name, meta),
            "colours": 0 if stored is None else stored.count,
        }

    def export(self, name: str, path: PathLike) -> Path:
        """Write the shape ``name`` to ``path`` through :func:`voxfab.io.write` (format by extension).

        Returns
        -------
        Path
            ``path``.
        """
        from voxfab import io

        io.write(self.shape(name), path)
        return Path(path)

    # -- removing ---------------------------------------------------------------

    def remove(self, name: str) -> None:
        """Delete ``name``.  Other shapes keep their names and the name is not reused.

        A range member (``RANGE:MEMBER``) leaves its range, and its draft goes with
        it unless another range holds it; a shape that a range holds is refused.

        Raises
        ------
        RepositoryError
            For a malformed or unknown name.
        """
        check_name(name)
        member = split_member(name)
        db = self._db
        with sqlite_errors(self._path), immediate(db):
            if member is not None:  # the member, and its draft when no range holds it any more
                require_sound(db)
                row = db.execute("SELECT shape FROM range_members WHERE range = ? AND member = ?", member).fetchone()
                if row is None:
                    raise RepositoryError(f"{name}: no such shape in {self._path}")
                db.execute("DELETE FROM range_members WHERE range = ? AND member = ?", member)
                remove_made_drafts(db, [row[0]])
                return
            held = db.execute("SELECT m.range || ':' || m.member FROM range_members m JOIN shapes s"
                              " ON s.id = m.shape WHERE s.name = ? LIMIT 1", (name,)).fetchone()
            if held is not None:
                raise RepositoryError(f"{name}: the range member {held[0]} is this shape; remove the member "
                                      "or its range first")
            db.execute("DELETE FROM range_made WHERE shape IN (SELECT id FROM shapes WHERE name = ?)", (name,))
            deleted = db.execute("DELETE FROM shapes WHERE name = ?", (name,)).rowcount
        if deleted == 0:
            raise RepositoryError(f"{name}: no such shape in {self._path}")

    def check(self, *, rows: bool = True) -> list[str]:
        """Return the problems found in the file (an empty list when it is sound).

        Checks that every table and index of the schema is there, runs SQLite's
        ``PRAGMA integrity_check``, then checks every row as a read
        does (blob length against the box, column types, JSON of ``reasons`` and
        ``meta``, volume and both keys against the decoded voxels), that every name
        matches its row (``VVVVV.NNN`` from volume and rank, ``draft-N`` from the row
        id), that no rank exceeds its volume's counter, and that named shapes are
        well formed while drafts say why they are not; and every range member
        (names, positions, the row it points at).  With ``rows=False`` only the
        schema and the ranges are checked (what storing a range relies on: quick).
        """
        problems: list[str] = []
        with sqlite_errors(self._path):
            db = self._db
            present = {r[0] for r in db.execute("SELECT name FROM sqlite_master")}
            missing = {n for n in SCHEMA_OBJECTS if n not in present}
            problems += [f"the table or index {n} is missing" for n in SCHEMA_OBJECTS if n in missing]
            if rows:
                problems += [r[0] for r in db.execute("PRAGMA integrity_check") if r[0] != "ok"]
        if rows and not {"shapes", "rank_counters"} & missing:
            problems += self._row_problems()
        if not {"shapes", "range_members", "range_made"} & missing:
            with sqlite_errors(self._path):
                problems += check_members(self._db)
        return problems

    def _row_problems(self) -> list[str]:
        problems: list[str] = []
        with sqlite_errors(self._path):
            rows = self._db.execute(
                f"SELECT s.id, s.name, s.volume, s.rank, s.draft, s.nx, s.ny, s.nz, {_BITS}, s.key,"
                " s.symmetric_key, s.reasons, s.meta, c.last_rank, s.colours"
                " FROM shapes s LEFT JOIN rank_counters c ON c.volume = s.volume ORDER BY s.id"
            ).fetchall()
        for row_id, name, volume, rank, d, nx, ny, nz, bits, key, skey, reasons, meta, last, colours in rows:
            label = f"row {row_id} ({name})" if isinstance(name, str) else f"row {row_id}"
            try:
                grid = decode_row(label, bits, (nx, ny, nz), volume, key, skey, colours)
                why = decode_reasons(label, reasons)
                decode_meta(label, meta)
            except RepositoryError as exc:
                problems.append(str(exc).split("; 'voxfab repo check'")[0])
                continue
            if d not in (0, 1) or (not d and type(rank) is not int):
                problems.append(f"{label}: draft {d!r} and rank {rank!r} do not make a name")
                continue
            expected = draft_name(row_id) if d else format_name(volume, rank)
            if name != expected:
                problems.append(f"{label}: name {name!r}, expected {expected!r}")
            if not d and (last is None or rank > last):
                problems.append(f"{label}: rank {rank} beyond the counter {last} of volume {volume}")
            if not d and (why or well_formed_reasons(grid)):
                problems.append(f"{label}: a named shape that is not well formed")
            if d and not why:
                problems.append(f"{label}: a draft that gives no reason")
        return problems

    # -- container protocol -----------------------------------------------------

    def __len__(self) -> int:
        with sqlite_errors(self._path):
            return int(self._db.execute("SELECT count(*) FROM shapes").fetchone()[0])

    def __iter__(self) -> Iterator[str]:
        """Iterate over the names in :meth:`list` order (a snapshot)."""
        return iter([e.name for e in self.list()])

    def __contains__(self, name: object) -> bool:
        if not isinstance(name, str):
            return False
        member = split_member(name)
        with sqlite_errors(self._path):
            if member is not None:
                return self._db.execute("SELECT 1 FROM range_members WHERE range = ? AND member = ?",
                                        member).fetchone() is not None
            return self._db.execute("SELECT 1 FROM shapes WHERE name = ?", (name,)).fetchone() is not None


#: The ``bits`` column as read: a blob, or NULL when the row holds another type
#: (text or a number written over it), which the row checks then refuse.
_BITS = "CASE typeof(bits) WHEN 'blob' THEN bits END"


def _not_well_formed(label: str, reasons: Sequence[str]) -> RepositoryError:
    return RepositoryError(
        f"{label}: not well formed: {'; '.join(reasons)} (pass draft=True to store it as a draft)"
    )
