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

from ._records import MEMBER_PATTERN, RANGE_PATTERN

__all__ = ["RangeInfo", "split_member", "insert_members", "member_rows", "range_infos", "check_members",
           "require_sound", "claim_drafts", "remove_made_drafts"]


@dataclasses.dataclass(frozen=True)
class RangeInfo:
    """A stored range: its name and how many members it holds."""

    name: str
    count: int


def split_member(name: str) -> tuple[str, str] | None:
    """``(range, member)`` of a ``RANGE:MEMBER`` name, or None for any other name."""
    m = MEMBER_PATTERN.fullmatch(name)
    return None if m is None else (m.group(1), m.group(2))


def _corrupt(detail: str) -> RepositoryError:
    return RepositoryError(f"corrupt range table ({detail}); 'voxfab repo check' lists every bad row")


def require_sound(db: sqlite3.Connection) -> None:
    """Refuse to use a range table :func:`check_members` finds fault with (its first problem, in one line)."""
    problems = check_members(db)
    if problems:
        more = f" and {len(problems) - 1} more" if len(problems) > 1 else ""
        raise _corrupt(f"{problems[0]}{more}")


def insert_members(db: sqlite3.Connection, range_name: str, members: Sequence[tuple[str, str]],
                   made: Sequence[str] = ()) -> int:
    """Add ``(member, shape name)`` pairs to a range after its last member; return how many were new.

    A member already in the range with the same shape is kept as it is (a range
    can be stored again, or grown: a census of 9 after one of 8); the same
    member name for another shape is refused, and nothing is written.  ``made``
    names the drafts this call stored itself: the range's own, which removing
    it removes.
    """
    require_sound(db)
    db.executemany("INSERT OR IGNORE INTO range_made (shape) SELECT id FROM shapes WHERE name = ? AND draft = 1",
                   [(name,) for name in made])
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
        if type(row[0]) is not int:
            raise _corrupt(f"{range_name}:{after}: position stored as {type(row[0]).__name__}")
        start = row[0]
    sql = ("SELECT m.member, s.volume, s.nx, s.ny, s.nz, s.draft FROM range_members m"
           " JOIN shapes s ON s.id = m.shape WHERE m.range = ? AND m.position > ? ORDER BY m.position")
    if limit is not None:
        sql += f" LIMIT {int(limit)}"
    rows = db.execute(sql, (range_name, start)).fetchall()
    for row in rows:
        if not isinstance(row[0], str) or not all(type(v) is int for v in row[1:]):
            raise _corrupt(f"{range_name}:{row[0]!r}: a member or its shape stored with wrong types")
    return rows


def range_infos(db: sqlite3.Connection) -> list[RangeInfo]:
    """Every stored range with its member count, by name."""
    rows = db.execute("SELECT range, count(*) FROM range_members GROUP BY range ORDER BY range").fetchall()
    for name, _ in rows:
        if not isinstance(name, str) or not RANGE_PATTERN.fullmatch(name):
            raise _corrupt(f"a range named {name!r:.60}")
    return [RangeInfo(name, int(n)) for name, n in rows]


def claim_drafts(db: sqlite3.Connection, names: Sequence[str]) -> None:
    """The artist added these drafts (found stored by a range already): they are the artist's from now on."""
    db.executemany("DELETE FROM range_made WHERE shape = (SELECT id FROM shapes WHERE name = ?)",
                   [(name,) for name in names])


def remove_made_drafts(db: sqlite3.Connection, ids: Sequence[int]) -> None:
    """Delete those of the shapes ``ids`` that a range made and no range holds any more."""
    orphans = "SELECT shape FROM range_made WHERE shape IN ({}) AND shape NOT IN (SELECT shape FROM range_members)"
    for i in range(0, len(ids), 500):  # SQLite's limit on parameters
        part = list(ids[i:i + 500])
        marks = ",".join("?" * len(part))
        gone = [r[0] for r in db.execute(orphans.format(marks), part)]
        db.executemany("DELETE FROM shapes WHERE id = ? AND draft = 1", [(g,) for g in gone])
        db.executemany("DELETE FROM range_made WHERE shape = ?", [(g,) for g in gone])


def check_members(db: sqlite3.Connection) -> list[str]:
    """Problems of the range tables: bad names and positions, members pointing at no shape, made drafts astray."""
    problems = []
    rows = db.execute("SELECT m.range, m.member, m.position, m.shape, s.id FROM range_members m"
                      " LEFT JOIN shapes s ON s.id = m.shape ORDER BY m.rowid").fetchall()
    for range_name, member, position, shape, found in rows:
        label = f"range member {range_name!r:.60}:{member!r:.60}"
        if not isinstance(range_name, str) or not isinstance(member, str) \
                or split_member(f"{range_name}:{member}") is None:
            problems.append(f"{label}: not a range member name")
        elif type(position) is not int or position < 1:
            problems.append(f"{label}: position {position!r:.40} is not a whole number from 1")
        elif type(shape) is not int or found is None:
            problems.append(f"{label}: points at row {shape!r:.40}, which is not there")
    made = db.execute("SELECT r.shape, s.draft, (SELECT 1 FROM range_members m WHERE m.shape = r.shape)"
                      " FROM range_made r LEFT JOIN shapes s ON s.id = r.shape ORDER BY r.shape").fetchall()
    for shape, draft, held in made:
        if draft != 1 or held is None:
            problems.append(f"range draft row {shape!r:.40}: {'not a stored draft' if draft != 1 else 'in no range'}")
    return problems
