"""The documentation site: it builds with warnings as errors, its links resolve, its commands run, and its
generated reference holds every option of the code."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.glob("*.md"))
#: A page's commands that a test runs: ```console blocks, each command on a `$ ` line.
CONSOLE = re.compile(r"^```console\n(.*?)^```", re.S | re.M)
#: Commands shown but not run (a server, a cluster, a long build): ```sh blocks.
SHOWN = re.compile(r"^```sh\n(.*?)^```", re.S | re.M)
#: Seconds one page command may take: every one runs on a small shape.
COMMAND_SECONDS = 120


def _env() -> dict[str, str]:
    # This checkout's voxfab, also in the commands' own processes.
    return {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))}


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    pytest.importorskip("mkdocs", reason='the docs extra is not installed: pip install -e ".[docs]"')
    out = tmp_path_factory.mktemp("site")
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-f", str(ROOT / "mkdocs.yml"),
                        "-d", str(out)], cwd=ROOT, env=_env(), capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    return out


class _Links(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(a["id"])
        for key in ("href", "src"):
            if a.get(key) and tag in ("a", "img", "link", "script"):
                self.links.append(a[key])


def _parse(path: Path) -> _Links:
    p = _Links()
    p.feed(path.read_text(encoding="utf-8"))
    return p


def test_the_site_builds_strict_and_every_internal_link_resolves(site):
    pages = {path: _parse(path) for path in site.rglob("*.html")}
    assert (site / "first-hour" / "index.html") in pages and (site / "cli" / "index.html") in pages
    broken = []
    for path, parsed in pages.items():
        for link in parsed.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith(("mailto:", "javascript:")):
                continue
            base = site if parts.path.startswith("/") else path.parent  # 404.html links from the site's root
            target = (base / unquote(parts.path).lstrip("/")).resolve() if parts.path else path
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                broken.append(f"{path.relative_to(site)}: {link}")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _parse(target).ids
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{path.relative_to(site)}: {link} (no such anchor)")
    assert not broken, "\n".join(broken)
    # The generated parts are in the pages: a command's section, a table of options, the API.
    cli = (site / "cli" / "index.html").read_text(encoding="utf-8")
    assert 'id="voxfab-net"' in cli and "--face-size" in cli
    assert "--thickness" in (site / "plates" / "index.html").read_text(encoding="utf-8")
    assert "doc-function" in (site / "api" / "index.html").read_text(encoding="utf-8")


def _commands(page: Path) -> list[str]:
    return [line[2:] for block in CONSOLE.findall(page.read_text(encoding="utf-8"))
            for line in block.splitlines() if line.startswith("$ ")]


def _shown(page: Path) -> list[str]:
    return [line for block in SHOWN.findall(page.read_text(encoding="utf-8"))
            for line in block.splitlines() if line.startswith("voxfab ") or " voxfab " in line]


def _run_page(page: Path, folder: Path) -> list[str]:
    """Run a page's commands in order in a folder of its own holding the bundled recipes; the failures."""
    folder.mkdir()
    shutil.copytree(ROOT / "recipes", folder / "recipes")
    failures = []
    for command in _commands(page):
        argv = shlex.split(command)
        assert argv[0] == "voxfab", f"{page.name}: {command}: a page's command runs voxfab"
        try:
            r = subprocess.run([sys.executable, "-m", "voxfab", *argv[1:]], cwd=folder, env=_env(),
                               capture_output=True, text=True, timeout=COMMAND_SECONDS)
        except subprocess.TimeoutExpired:
            failures.append(f"{page.name}: {command}: over {COMMAND_SECONDS} s")
            break
        if r.returncode != 0 or "Traceback" in r.stderr:
            failures.append(f"{page.name}: {command}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
            break  # the page's later commands read what this one writes
    return failures


@pytest.mark.slow
def test_every_command_the_pages_show_in_console_blocks_runs(tmp_path):
    pages = [p for p in PAGES if _commands(p)]
    run = sum(len(_commands(p)) for p in PAGES)
    shown = sum(len(_shown(p)) for p in PAGES)
    # Most commands run; those only shown are servers, clusters and the full builds of the install.
    assert run >= 15 and run > 2 * shown, (run, shown)
    with ThreadPoolExecutor(2) as pool:
        failures = [f for found in pool.map(lambda p: _run_page(p, tmp_path / p.stem), pages) for f in found]
    assert not failures, "\n".join(failures)


def _filled() -> dict[str, str]:
    from voxfab.cli._reference import fill

    return {p.name: fill(p.read_text(encoding="utf-8"), DOCS / "data") for p in PAGES}


def test_every_option_appears_in_the_generated_reference():
    """Each options table, maker and command option is on a page: a new one without a place fails here."""
    from voxfab._shared.options import option_specs
    from voxfab.cli._main import build_parser
    from voxfab.cli._reference import _subcommands, option_tables
    from voxfab.digitize import MAKERS, maker_params
    from voxfab.fabricate import outputs
    from voxfab.fabricate._table import resolve
    from voxfab.shape import ShapeOptions

    pages = _filled()
    text = "\n".join(pages.values())
    missing = [name for name in option_tables() if f"<!-- gen:{name} -->" not in text]
    assert not missing, f"option tables on no page: {missing}"
    for row in outputs().values():
        assert f"[outputs.{row.name}]" in text, row.name
        for table in row.options:
            for spec in option_specs(resolve(table.cls)):
                if spec.name not in table.exclude:
                    assert f"`{spec.name}`" in text, (row.name, spec.name)
    assert all(f"`{s.name}`" in text for s in option_specs(ShapeOptions))
    for name in MAKERS:
        assert all(f"`{key}`" in text for key in maker_params(name)), name

    cli = pages["cli.md"]

    def walk(parser, words):
        for action in parser._actions:
            for flag in action.option_strings:
                assert flag in cli, (" ".join(words), flag)
        for name, sub in _subcommands(parser):
            assert f"voxfab {' '.join([*words, name])}\n" in cli, name
            walk(sub, [*words, name])

    walk(build_parser(), [])


def test_every_help_ends_with_its_reference():
    from voxfab.cli._main import build_parser
    from voxfab.cli._reference import _subcommands

    cli = _filled()["cli.md"]
    parser = build_parser()
    helps = [("", parser)] + [(name, sub) for name, sub in _subcommands(parser)]
    helps += [(f"repo {name}", sub) for name, sub in _subcommands(dict(_subcommands(parser))["repo"])]
    for command, p in helps:
        last = p.format_help().rstrip().splitlines()[-1]
        anchor = "voxfab" + "".join(f"-{w}" for w in command.split())
        assert last == f"Documentation: docs/cli.md#{anchor}", (command, last)
        heading = f"voxfab {command}".strip()
        assert re.search(rf"^#+ {re.escape(heading)}$", cli, re.M), heading


def test_benchmark_tables_are_the_benches_saved_output(tmp_path):
    """A bench's --save keeps the table it printed; the page's table is made from that file; every saved
    table is on a page."""
    from voxfab.cli._reference import bench_table

    r = subprocess.run([sys.executable, str(ROOT / "bench" / "bench_exact.py"), "--smoke", "--save", str(tmp_path)],
                       cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    printed = [line for line in r.stdout.splitlines() if line.startswith("|")]
    made = bench_table("exact", tmp_path)
    assert made.splitlines()[: len(printed)] == printed and len(printed) == 4  # header, rule, the cube's 2 questions
    assert "`python bench/bench_exact.py --smoke` wrote this table" in made
    text = "\n".join(p.read_text(encoding="utf-8") for p in PAGES)
    saved = sorted(p.stem for p in (DOCS / "data" / "bench").glob("*.json"))
    assert saved and all(f"<!-- gen:bench:{name} -->" in text for name in saved), saved
    assert set(re.findall(r"<!-- gen:bench:([\w-]+) -->", text)) == set(saved)


def test_the_readme_is_short_its_links_resolve_and_ci_runs_its_test_command():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) < 150
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", readme)
    assert len(links) >= 15 and not [link for link in links if not (ROOT / link).exists()]
    pictures = [ROOT / link for link in links if link.endswith(".png")]
    assert len(pictures) >= 5 and all(p.stat().st_size < 300_000 for p in pictures)
    commands = re.findall(r"^```sh\n(python -m venv .*)\n```", readme, re.M)
    assert len(commands) == 2 and "voxfab build recipes/chess/queen.toml -o output" in commands[0]
    assert commands[1] in (ROOT / ".ci" / "run").read_text(encoding="utf-8")


def test_the_census_results_are_a_census_json_as_voxfab_census_writes_it(tmp_path):
    """The page's census table is made from a census.json's rows: a run of 1..5 cubes now gives, in the same
    table, the first five rows the stored n = 9 run gave."""
    from voxfab.cli._reference import census_table

    r = subprocess.run([sys.executable, "-m", "voxfab", "census", "5", "-o", str(tmp_path / "c"), "--workers", "0"],
                       cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    now = census_table(tmp_path / "c" / "census.json").splitlines()
    stored = census_table(DOCS / "data" / "census" / "census-9.json").splitlines()
    assert len(now) == 2 + 5 and len(stored) == 2 + 9
    assert now == stored[:7]
    assert "<!-- gen:census:census-9 -->" in (DOCS / "open-questions.md").read_text(encoding="utf-8")


def test_a_run_table_keeps_the_other_runs_rows(tmp_path, capsys):
    """bench_hunt saves one row per run: a saved run of another name stays, one of the same name is replaced."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("bench_table", ROOT / "bench" / "_table.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for label, found in (("a", 1), ("b", 2), ("a", 3)):
        table = module.Table("hunt", ["run", "found"])
        table.row(label, found)
        table.save(tmp_path, merge=True)
    import json

    assert json.loads((tmp_path / "hunt.json").read_text())["rows"] == [{"run": "b", "found": "2"},
                                                                      {"run": "a", "found": "3"}]
    assert "| a | 3 |" in capsys.readouterr().out
