"""Every script in ``bench/`` runs in its smoke mode, and reaches the library through public names only.

The smoke runs are real: each bench starts as a subprocess (``python bench/NAME.py --smoke``) and goes
through its whole path on the smallest real inputs, printing its table.  Two run at a time, one per
core.  A bench that needs a system tool that is missing (Chromium) says so in its output and goes on.
"""

from __future__ import annotations

import ast
import concurrent.futures
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BENCHES = sorted(p.name for p in (ROOT / "bench").glob("bench_*.py"))
#: Every module of bench/, the benches' helpers (``_peer.py``) included.
BENCH_MODULES = sorted(p.name for p in (ROOT / "bench").glob("*.py"))
#: Seconds one smoke run may take on a loaded 2-core machine; a smoke run takes a few seconds alone.
SMOKE_TIMEOUT = 300


def private_uses(source: str) -> list[str]:
    """The places where ``source`` reaches a private module or attribute of voxfab, as ``line: what``."""
    tree = ast.parse(source)
    found: list[str] = []
    bound: set[str] = set()  # names that hold voxfab modules or objects

    def private(name: str) -> bool:
        return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))

    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[0] != "voxfab":
                    continue
                if any(private(p) for p in parts):
                    found.append(f"{node.lineno}: import {alias.name}")
                bound.add(alias.asname or "voxfab")
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            parts = node.module.split(".")
            if parts[0] != "voxfab":
                continue
            if any(private(p) for p in parts):
                found.append(f"{node.lineno}: from {node.module} import ...")
            for alias in node.names:
                if private(alias.name):
                    found.append(f"{node.lineno}: from {node.module} import {alias.name}")
                bound.add(alias.asname or alias.name)
        elif isinstance(node, ast.Call) and isinstance(node.func, (ast.Name, ast.Attribute)):
            func = node.func.id if isinstance(node.func, ast.Name) else node.func.attr
            strings = [a.value for a in node.args if isinstance(a, ast.Constant) and isinstance(a.value, str)]
            if func in ("import_module", "__import__") and any(
                    s.split(".")[0] == "voxfab" and any(private(p) for p in s.split(".")) for s in strings):
                found.append(f"{node.lineno}: {func}({strings[0]!r})")
    for node in ast.walk(tree):
        root: ast.AST | None = None
        what = ""
        if isinstance(node, ast.Attribute) and private(node.attr):
            root, what = node.value, node.attr
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
              and node.func.id in ("getattr", "setattr", "delattr", "hasattr") and len(node.args) >= 2
              and isinstance(node.args[1], ast.Constant) and isinstance(node.args[1].value, str)
              and private(node.args[1].value)):
            root, what = node.args[0], node.args[1].value
        while isinstance(root, ast.Attribute):
            root = root.value
        if isinstance(root, ast.Name) and root.id in bound:
            found.append(f"{node.lineno}: {root.id}...{what}")
    return sorted(set(found), key=lambda s: int(s.split(":")[0]))


def test_the_private_check_finds_each_way_in() -> None:
    source = """
import voxfab.batch._run as run
from voxfab.recipe._build import make_shape
from voxfab.unfold import _validate, unfold
import voxfab.studio
import importlib
from voxfab import render
run._connect = None
voxfab.studio._grid.pack(1)
setattr(render, "_cache", {})
importlib.import_module("voxfab.cli._common")
"""
    assert [line.split(":")[0] for line in private_uses(source)] == ["2", "3", "4", "8", "9", "10", "11"]
    clean = "import voxfab\nfrom voxfab.unfold import unfold\nprint(voxfab.__version__, unfold.__doc__)\n"
    assert private_uses(clean) == []


def test_no_bench_reaches_into_private_names() -> None:
    assert len(BENCHES) >= 18
    uses = {name: private_uses((ROOT / "bench" / name).read_text(encoding="utf-8")) for name in BENCH_MODULES}
    assert {name: u for name, u in uses.items() if u} == {}


def _smoke(name: str) -> subprocess.CompletedProcess[str] | str:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    try:
        return subprocess.run([sys.executable, str(ROOT / "bench" / name), "--smoke"], capture_output=True,
                              text=True, cwd=ROOT, env=env, timeout=SMOKE_TIMEOUT, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired as exc:
        return f"over {SMOKE_TIMEOUT} s; its output so far:\n{exc.stdout or ''}\n{exc.stderr or ''}"


@pytest.fixture(scope="module")
def smoke_runs() -> dict[str, subprocess.CompletedProcess[str] | str]:
    """Every bench's smoke run, two at a time (one per core), started once for the module."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        return dict(zip(BENCHES, pool.map(_smoke, BENCHES)))


@pytest.mark.parametrize("name", BENCHES)
def test_bench_runs_in_smoke_mode(name: str, smoke_runs: dict[str, subprocess.CompletedProcess[str] | str]) -> None:
    run = smoke_runs[name]
    assert not isinstance(run, str), f"{name} --smoke: {run}"
    assert run.returncode == 0, f"{name} --smoke exited {run.returncode}:\n{run.stdout[-3000:]}\n{run.stderr[-3000:]}"
    assert "Traceback" not in run.stderr, run.stderr[-3000:]
    # A table: a header and at least one row of figures.
    lines = [line for line in run.stdout.splitlines() if line.strip()]
    assert len(lines) >= 2 and any(ch.isdigit() for ch in "".join(lines[1:])), run.stdout
