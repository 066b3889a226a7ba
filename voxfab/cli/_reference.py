"""The documentation's generated parts, made from the code they describe so they cannot drift.

The pages under ``docs/`` hold empty blocks ``<!-- gen:NAME -->`` ... ``<!-- /gen:NAME -->``;
``docs/_gen/hooks.py`` fills each one at ``mkdocs build`` time with :func:`block`. The tables are
never committed: the argparse parsers give the CLI reference, the one options declaration
(:func:`voxfab._shared.options.option_specs` through the outputs table) the option tables, the
makers table the makers' keys, ``voxfab/_shared/limits.py`` the limits, and the benches' saved
output (``docs/data/bench/*.json``) the benchmark tables, and a census's own ``census.json`` rows
(``docs/data/census/*.json``) the census results.
"""

from __future__ import annotations

import argparse
import ast
import json
import re
from collections.abc import Iterator
from pathlib import Path

#: Where the documentation lives, as the help of every command links to it (one place).
DOCS = "docs/"
#: The pages' generated blocks: ``<!-- gen:NAME -->`` up to ``<!-- /gen:NAME -->``.
BLOCK = re.compile(r"(<!-- gen:([\w:.-]+) -->\n).*?(<!-- /gen:\2 -->)", re.S)


def help_link(command: str) -> str:
    """The last line of a command's ``--help``: where its reference is."""
    anchor = "voxfab" + "".join(f"-{word}" for word in command.split())
    return f"Documentation: {DOCS}cli.md#{anchor}"


def _cell(text: object) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _subcommands(parser: argparse.ArgumentParser) -> Iterator[tuple[str, argparse.ArgumentParser]]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            yield from action.choices.items()


def _options_table(parser: argparse.ArgumentParser) -> list[str]:
    formatter = parser._get_formatter()
    rows = ["| argument | meaning |", "|---|---|"]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) or action.help == argparse.SUPPRESS:
            continue
        if action.option_strings:
            metavar = "" if action.nargs == 0 else " " + formatter._format_args(action, action.dest.upper())
            name = ", ".join(f"`{flag}{metavar}`" for flag in action.option_strings)
        else:
            name = f"`{formatter._format_args(action, action.dest.upper())}`"
        meaning = formatter._expand_help(action) if action.help else ""
        rows.append(f"| {_cell(name)} | {_cell(meaning)} |")
    return rows


def cli_reference(parser: argparse.ArgumentParser | None = None) -> str:
    """Every subcommand of ``voxfab`` (and of ``voxfab repo``): its usage and each option, from its parser."""
    from voxfab.cli._main import build_parser

    parser = parser or build_parser()
    lines: list[str] = []

    def walk(p: argparse.ArgumentParser, words: list[str], level: int) -> None:
        for name, sub in _subcommands(p):
            path = [*words, name]
            lines.extend([f"{'#' * level} voxfab {' '.join(path)}", "", _cell(sub.description or ""), ""])
            lines.extend(["```text", sub.format_usage().strip(), "```", ""])
            lines.extend([*_options_table(sub), ""])
            walk(sub, path, level + 1)

    lines.extend(["### voxfab", "", "```text", parser.format_usage().strip(), "```", "",
                  *_options_table(parser), ""])
    walk(parser, [], 3)
    return "\n".join(lines)


def option_tables() -> dict[str, str]:
    """The option tables by block name: the shape's, every output's, every maker's."""
    from voxfab._shared.options import markdown_table
    from voxfab.digitize import MAKERS, maker_markdown
    from voxfab.fabricate import outputs
    from voxfab.fabricate._table import resolve
    from voxfab.shape import ShapeOptions

    tables = {"options:shape": markdown_table(ShapeOptions)}
    for output in outputs().values():
        for t in output.options:
            tables[f"options:{t.readme}"] = markdown_table(resolve(t.cls), exclude=t.exclude)
    tables.update({f"options:maker-{name}": maker_markdown(name) for name in MAKERS})
    return tables


def makers_table() -> str:
    """One row per maker of the makers table: its name, what it makes, its keys."""
    from voxfab.digitize import MAKERS

    rows = ["| maker | what it makes | keys |", "|---|---|---|"]
    for maker in MAKERS.values():
        keys = ", ".join(f"`{p.name}`" for p in maker.params)
        rows.append(f"| `{maker.name}` | {_cell(maker.help)} | {keys} |")
    return "\n".join(rows)


def outputs_table() -> str:
    """One row per output of the outputs table: recipe table, command, the files it writes."""
    from voxfab.fabricate import outputs

    rows = ["| recipe table | command | files |", "|---|---|---|"]
    for row in outputs().values():
        command = f"`voxfab {row.command}`" if row.command else "-"
        files = ", ".join(f"`{f}`" for f in row.files)
        rows.append(f"| `[outputs.{row.name}]` | {command} | {files} |")
    return "\n".join(rows)


def limits_table() -> str:
    """Every ``MAX_*`` of ``voxfab/_shared/limits.py``: its value and the comment that says what it bounds."""
    from voxfab._shared import limits

    source = Path(limits.__file__).read_text(encoding="utf-8")
    lines = source.splitlines()
    rows = ["| limit | value | what it bounds |", "|---|---|---|"]
    for node in ast.parse(source).body:
        if not (isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)):
            continue
        name = node.targets[0].id
        if not name.startswith("MAX_"):
            continue
        comment: list[str] = []
        i = node.lineno - 2
        while i >= 0 and lines[i].startswith("#:"):
            comment.insert(0, lines[i][2:].strip())
            i -= 1
        value = getattr(limits, name)
        value = int(value) if float(value).is_integer() else value  # 3,600 s, not 3,600.0
        text = " ".join(comment).replace("``", "`")
        rows.append(f"| `{name}` | {value:,} | {_cell(text)} |")
    return "\n".join(rows)


def bench_table(name: str, folder: Path) -> str:
    """The table a bench saved with ``--save`` (``docs/data/bench/NAME.json``: columns and rows)."""
    data = json.loads((folder / f"{name}.json").read_text(encoding="utf-8"))
    columns = data["columns"]
    rows = ["| " + " | ".join(_cell(c) for c in columns) + " |", "|" + "---|" * len(columns)]
    rows += ["| " + " | ".join(_cell(row.get(c, "")) for c in columns) + " |" for row in data["rows"]]
    note = f"\n\n`{data['command']}` wrote this table" + (f" ({data['machine']})." if data.get("machine") else ".")
    return "\n".join(rows) + note


#: The census table's columns: heading, and the row keys whose counts it shows (found / none / undecided).
CENSUS_COLUMNS = (
    ("n", ("n",)),
    ("one-sided polycubes (A000162)", ("one_sided",)),
    ("up to reflection (A038119)", ("free",)),
    ("unfold: found / none / undecided", ("unfold_found", "unfold_none", "unfold_undecided")),
    ("manifold, genus 0", ("manifold",)),
    ("unzip: found / none / undecided", ("unzip_found", "unzip_none", "unzip_undecided")),
    ("edge touching", ("edge_touching",)),
    ("vertex touching", ("vertex_touching",)),
    ("handle", ("handle",)),
)


def census_table(path: Path) -> str:
    """The rows of a ``census.json`` (``voxfab-census/2``, as ``voxfab census`` writes it), one line per n."""
    rows = json.loads(path.read_text(encoding="utf-8"))["rows"]
    lines = ["| " + " | ".join(h for h, _ in CENSUS_COLUMNS) + " |", "|" + "---|" * len(CENSUS_COLUMNS)]
    for row in rows:
        cells = [" / ".join(f"{row[k]:,}" for k in keys) for _, keys in CENSUS_COLUMNS]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def block(name: str, data: Path) -> str:
    """The generated markdown of the block ``name`` (``data``: the folder of the benches' saved tables)."""
    if name == "cli":
        return cli_reference()
    if name == "makers":
        return makers_table()
    if name == "outputs":
        return outputs_table()
    if name == "limits":
        return limits_table()
    if name.startswith("census:"):
        return census_table(data / "census" / f"{name.partition(':')[2]}.json")
    if name.startswith("bench:"):
        return bench_table(name.partition(":")[2], data / "bench")
    tables = option_tables()
    if name in tables:
        return tables[name]
    raise KeyError(f"no generated block named {name!r}")


def fill(text: str, data: Path) -> str:
    """``text`` with every generated block filled in."""
    return BLOCK.sub(lambda m: m.group(1) + block(m.group(2), data).rstrip("\n") + "\n" + m.group(3), text)
