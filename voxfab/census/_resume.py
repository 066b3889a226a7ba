"""What a census keeps of an earlier run in its folder: read, checked, and said before anything is dropped.

``census.json`` is read whole and refused in one line when it is no census (not
JSON, nested past any census, a record without a census id): a file someone
else wrote is never overwritten unread.  An earlier census with other settings
is said to be discarded before anything is written; one with the same settings
and a larger N is kept whole (the run censuses up to the larger N).  Each
record is then kept only when :func:`._verify.record_problems` finds nothing:
its net files parse, are nets of its polycube, refold, hold their fold tree,
and its proofs hold; the others are censused again, said in one line.  Files of
the first format (``voxfab-census/1``, whose rows called the one-sided count
``free``) are read the same way.
"""

from __future__ import annotations

import dataclasses
import json
import warnings
from pathlib import Path
from typing import Any

from voxfab.errors import FormatError, VoxfabWarning

__all__ = ["CENSUS_FORMAT", "Earlier", "OLD_FORMATS", "kept_records", "read_earlier", "upgrade_rows"]

CENSUS_FORMAT = "voxfab-census/2"
#: Earlier formats read as well: ``/1`` named the one-sided count ``free`` and the free count ``free_mirror``.
OLD_FORMATS = ("voxfab-census/1",)
#: Problems named in the line that says which records are censused again.
_NAMED = 3


@dataclasses.dataclass(frozen=True)
class Earlier:
    """An earlier census in DIR: its N, its settings and its records by id."""

    n: int
    settings: dict[str, Any]
    records: dict[str, dict[str, Any]]


def upgrade_rows(data: dict[str, Any]) -> dict[str, Any]:
    """A census's data with rows of the current format (``one_sided`` and ``free``), whatever its format."""
    if data.get("format") not in OLD_FORMATS:
        return data
    rows = []
    for row in data.get("rows", []):
        row = dict(row)
        if "free_mirror" in row:
            row["one_sided"], row["free"] = row.pop("free"), row.pop("free_mirror")
        rows.append(row)
    return {**data, "rows": rows, "format": CENSUS_FORMAT}


def read_earlier(path: Path) -> Earlier | None:
    """The census in ``path`` (``DIR/census.json``), None when there is none.

    Raises
    ------
    FormatError
        The file is not a census: not JSON, nested too deep, not a census format,
        or a record without a census id.
    """
    from ._verify import SHAPE_ID

    if not path.exists():
        return None
    where = f"{path}: not a census file"
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except RecursionError:
        raise FormatError(f"{where}: nested too deep; remove it or choose another folder") from None
    except (OSError, ValueError) as exc:
        raise FormatError(f"{where} ({' '.join(str(exc).split())[:120]}); remove it or choose another folder") \
            from None
    if not isinstance(data, dict) or data.get("format") not in (CENSUS_FORMAT, *OLD_FORMATS):
        raise FormatError(f"{where} (no format {CENSUS_FORMAT}); remove it or choose another folder")
    n, settings, shapes = data.get("n"), data.get("settings"), data.get("shapes")
    if isinstance(n, bool) or not isinstance(n, int) or not isinstance(settings, dict) or not isinstance(shapes, list):
        raise FormatError(f"{where}: it needs n, settings and shapes; remove it or choose another folder")
    records: dict[str, dict[str, Any]] = {}
    for i, rec in enumerate(shapes):
        sid = rec.get("id") if isinstance(rec, dict) else None
        if not isinstance(sid, str) or not SHAPE_ID.fullmatch(sid):
            raise FormatError(f"{path}: record {i + 1} has the id {str(sid)[:40]!r}, not a census id (NN-NNNNNN); "
                              "remove the file or choose another folder")
        records[sid] = rec
    return Earlier(n, settings, records)


def _settings_text(settings: dict[str, Any]) -> str:
    return ", ".join(f"{k} {v}" for k, v in sorted(settings.items()))


def census_size(earlier: Earlier | None, n_max: int, settings: dict[str, Any], path: Path) -> int:
    """The N this run censuses to: the larger of ``n_max`` and a kept earlier census's; says what is discarded."""
    if earlier is None:
        return n_max
    if earlier.settings != settings:
        warnings.warn(f"{path} holds a census of 1..{earlier.n} cubes made with other settings "
                      f"({_settings_text(earlier.settings)}; now {_settings_text(settings)}): its "
                      f"{len(earlier.records)} records are discarded and censused again", VoxfabWarning, stacklevel=3)
        return n_max
    if earlier.n > n_max:
        warnings.warn(f"{path} holds a census of 1..{earlier.n} cubes: kept whole, not cut to {n_max}",
                      VoxfabWarning, stacklevel=3)
    return max(n_max, earlier.n)


def kept_records(earlier: Earlier | None, cells: dict[str, list[list[int]]], out: Path,
                 square_zipper: bool) -> dict[str, dict[str, Any]]:
    """The earlier records that name a polycube of this census and whose files and proofs check out.

    ``cells`` maps each id of this census to its polycube's cells.  Net files of an
    earlier version, without their fold tree, get it (the net is checked first).
    The records dropped are said in one line.
    """
    from ._verify import record_problems

    if earlier is None:
        return {}
    kept, dropped = {}, []
    for sid, rec in earlier.records.items():
        if sid not in cells:
            dropped.append(f"{sid}: no polycube of the census has this id")
            continue
        _add_missing_trees(out, rec)
        problems, _ = record_problems(out, rec, cells[sid], square_zipper)
        if problems:
            dropped.append(problems[0])
            _clear_net_paths(out, sid)
        else:
            kept[sid] = rec
    if dropped:
        more = f"; and {len(dropped) - _NAMED} more" if len(dropped) > _NAMED else ""
        warnings.warn(f"{len(dropped)} earlier record(s) in {out} are censused again: "
                      f"{'; '.join(dropped[:_NAMED])}{more}", VoxfabWarning, stacklevel=3)
    return kept


def _clear_net_paths(out: Path, sid: str) -> None:
    """Make room for a recomputed record's nets: an empty folder where a net file goes is removed.

    Raises
    ------
    OutputError
        A folder with files in it stands there: it is no census's, so it is left to its owner.
    """
    from voxfab.errors import OutputError

    from ._task import net_paths

    for name in net_paths(sid):
        path = out / name
        if path.is_dir() and not path.is_symlink():
            try:
                path.rmdir()
            except OSError:
                raise OutputError(f"{path}: a folder with files where the census writes a net; remove it") from None


def _add_missing_trees(out: Path, rec: dict[str, Any]) -> None:
    """Give a net file of an earlier version its fold tree, when it is a valid net of the record's cells."""
    from voxfab._shared.atomic import write_text
    from voxfab.errors import VoxfabError
    from voxfab.unfold import Net, validate

    from ._task import net_paths, net_text
    from ._topology import grid_of

    sid = rec["id"]
    for key, expected in zip(("net", "unzip_net"), net_paths(sid)):
        if rec.get(key) != expected:
            continue  # not the file this record should name: record_problems says so
        try:
            data = json.loads((out / expected).read_text())
            if not isinstance(data, dict) or "tree" in data:
                continue
            net = Net.from_dict(data)
            validate(grid_of(rec["cells"]), net)
        except (OSError, ValueError, TypeError, RecursionError, VoxfabError):
            continue
        write_text(out / expected, net_text(net))
