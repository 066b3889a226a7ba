"""Named ranges: an ordered set of stored shapes under one name, each member named ``RANGE:MEMBER``.

A census stores its polycubes as a range (``polycubes-8:08-000001`` ...): the
shapes themselves are rows of ``shapes`` like any other (drafts, since a census
shape need not span the grid), and ``range_members`` ties each member name to
its row, in the order the range was stored.  These functions run inside the
caller's transaction on the repository's connection.
"""

from __future__ import annotations

import dataclasses
import sqlite3
from collections.abc import Sequence

from voxfab.errors import RepositoryError

from ._records import MEMBER_PATTERN

__all__ = ["RangeInfo", "split_member", "insert_members", "member_rows", "range_infos", "check_members"]


@dataclasses.dataclass(frozen=True)
class RangeInfo:
    """A stored range: its name and how many members it holds."""

    name: str
    count: int


def split_member(name: str) -> tuple[str, str] | None:
    """``(range, member)`` of a ``RANGE:MEMBER`` name, or None for any other name."""
    m = MEMBER_PATTERN.fullmatch(name)
    return None if m is None else (m.group(1), m.group(2))


def insert_members(db: sqlite3.Connection, range_name: str, members: Sequence[tuple[str, str]]) -> int:
    """Add ``(member, shape name)`` pairs to a range after its last member; return how many were new.

    A member already in the range with the same shape is kept as it is (a range
    can be stored again, or grown: a census of 9 after one of 8); the same
    member name for another shape is refused, and nothing is written.
    """
    top = db.execute("SELECT coalesce(max(position), 0) FROM range_members WHERE range = ?",
                     (range_name,)).fetchone()[0]
    added = 0
    for member, shape_name in members:
        shape_id = db.execute("SELECT id FROM shapes WHERE name = ?", (shape_name,)).fetchone()[0]
        held = db.execute("SELECT shape FROM range_members WHERE range = ? AND member = ?",
                          (range_name, member)).fetchone()
        if held is not None:
            if held[0] != shape_id:
                raise RepositoryError(
                    f"{range_name}:{member}: the range holds another shape under this name; "
                    f"remove the range first ('voxfab repo remove-range {range_name}')"
                )
            continue
        top += 1
        added += 1
        db.execute("INSERT INTO range_members (range, member, position, shape) VALUES (?, ?, ?, ?)",
                   (range_name, member, top, shape_id))
    return added


def member_rows(db: sqlite3.Connection, range_name: str, after: str | None,
                limit: int | None) -> list[tuple[str, int, int, int, int, int]]:
    """``(member, volume, nx, ny, nz, draft)`` of a range's members in stored order, after ``after``."""
    start = 0
    if after is not None:
        row = db.execute("SELECT position FROM range_members WHERE range = ? AND member = ?",
                         (range_name, after)).fetchone()
        if row is None:
            raise RepositoryError(f"{range_name}:{after}: no such member")
        start = int(row[0])
    sql = ("SELECT m.member, s.volume, s.nx, s.ny, s.nz, s.draft FROM range_members m"
           " JOIN shapes s ON s.id = m.shape WHERE m.range = ? AND m.position > ? ORDER BY m.position")
    if limit is not None:
        sql += f" LIMIT {int(limit)}"
    return db.execute(sql, (range_name, start)).fetchall()


def range_infos(db: sqlite3.Connection) -> list[RangeInfo]:
    """Every stored range with its member count, by name."""
    rows = db.execute("SELECT range, count(*) FROM range_members GROUP BY range ORDER BY range").fetchall()
    return [RangeInfo(name, int(n)) for name, n in rows]


def check_members(db: sqlite3.Connection) -> list[str]:
    """Problems of the range table: bad names, members pointing at no shape."""
    problems = []
    rows = db.execute("SELECT m.range, m.member, m.shape, s.id FROM range_members m"
                      " LEFT JOIN shapes s ON s.id = m.shape ORDER BY m.range, m.position").fetchall()
    for range_name, member, shape, found in rows:
        label = f"range member {range_name!r}:{member!r}"
        if not isinstance(range_name, str) or not isinstance(member, str) \
                or split_member(f"{range_name}:{member}") is None:
            problems.append(f"{label}: not a range member name")
        elif found is None:
            problems.append(f"{label}: points at row {shape}, which is not there")
    return problems
