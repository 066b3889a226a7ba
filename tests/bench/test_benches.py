"""Every script in ``bench/`` runs in its smoke mode, and reaches the library through public names only.

The smoke runs are real (see ``_bench_smoke``): half of them run here, the other half in
``test_benches_other_half.py``, so that each worker of pytest-xdist takes a half.  A bench that needs a
system tool that is missing (Chromium) says so in its output and goes on.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from _bench_smoke import BENCHES, HALVES, Run, check_smoke, smoke_all

ROOT = Path(__file__).resolve().parents[2]
#: Every module of bench/, the benches' helpers (``_peer.py``) included.
BENCH_MODULES = sorted(p.name for p in (ROOT / "bench").glob("*.py"))


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


@pytest.fixture(scope="module")
def smoke_runs() -> dict[str, Run]:
    """The smoke runs of the first half of the benches, started once for the module."""
    return smoke_all(HALVES[0])


@pytest.mark.parametrize("name", HALVES[0])
def test_bench_runs_in_smoke_mode(name: str, smoke_runs: dict[str, Run]) -> None:
    check_smoke(name, smoke_runs[name])
