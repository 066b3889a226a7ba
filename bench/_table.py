"""A bench's table: printed row by row as it is measured, and kept as data for the documentation.

``--save`` writes the rows to ``docs/data/bench/NAME.json`` (or the folder given), which the docs build
turns into the page's table (``<!-- gen:bench:NAME -->``, through ``voxfab.cli._reference``), so the
pages show what the bench measured, never a copy typed by hand.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
from pathlib import Path

#: Where the pages' benchmark tables are kept.
DATA = Path(__file__).resolve().parents[1] / "docs" / "data" / "bench"


def add_save_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--save", nargs="?", const=DATA, type=Path, metavar="FOLDER",
                        help=f"keep the table as FOLDER/NAME.json for the docs (default folder {DATA})")


class Table:
    """Markdown rows under ``columns``, printed at once; :meth:`save` keeps them."""

    def __init__(self, name: str, columns: list[str]) -> None:
        self.name, self.columns, self.rows = name, columns, []
        print("| " + " | ".join(columns) + " |\n|" + "---|" * len(columns), flush=True)

    def row(self, *values: object) -> None:
        cells = [str(v) for v in values]
        self.rows.append(dict(zip(self.columns, cells, strict=True)))
        print("| " + " | ".join(cells) + " |", flush=True)

    def save(self, folder: Path | None, *, merge: bool = False) -> None:
        """Write the table to ``folder/NAME.json`` under a temporary name (nothing when ``folder`` is None).

        ``merge``: a table of one row per run (``bench_hunt``) keeps the saved rows of other runs, a row
        of the same first cell being replaced.
        """
        if folder is None:
            return
        folder.mkdir(parents=True, exist_ok=True)
        target = folder / f"{self.name}.json"
        if merge and target.exists():
            saved = json.loads(target.read_text(encoding="utf-8"))
            if saved["columns"] == self.columns:
                mine = {row[self.columns[0]] for row in self.rows}
                self.rows = [r for r in saved["rows"] if r[self.columns[0]] not in mine] + self.rows
        args, rest = [], iter(sys.argv[1:])
        for a in rest:  # the command that made the table, less where it was kept
            if a == "--save":
                folder_given = next(rest, "")
                if folder_given.startswith("-"):
                    args.append(folder_given)
            elif not a.startswith("--save="):
                args.append(a)
        data = {"command": " ".join(["python", "bench/" + Path(sys.argv[0]).name, *args]),
                "machine": f"{os.cpu_count()} cores, {platform.machine()}, Python {platform.python_version()}",
                "columns": self.columns, "rows": self.rows}
        tmp = target.with_name(f".{target.name}.{os.getpid()}.part")
        tmp.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        tmp.replace(target)
        print(f"saved {target}", file=sys.stderr)
