"""Fuzz the command lines: random argument vectors over each command's real options."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from _fuzz import argv_for, check_outcome, run_cli
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab import io

#: Outputs a command line may name: usual ones, and ones that must be refused.
OUTPUT_NAMES = {
    "mesh": ["m.stl", "m.3mf", "m.obj", "m.glb", "m.ply", "missing/m.stl", "folder", "m"],
    "net": ["n.json", "n.svg", "n.pdf", "n.dxf", "n.png", "missing/n.json", "folder"],
    "slices": ["plates", "folder", "file.txt", "missing/plates"],
    "render": ["r.png", "r.pdf", "r.gif", "missing/r.png", "folder", "r.bmp"],
    "convert": ["c.npy", "c.npz", "c.txt", "c.vox", "c.binvox", "c.stl", "missing/c.npy", "folder"],
}


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    root = tmp_path_factory.mktemp("cli")
    grid = np.zeros((3, 3, 3), bool)
    grid[1, 1, :] = True
    io.write(grid, root / "bar.npy")
    (root / "folder").mkdir()
    (root / "folder" / "keep.txt").write_text("not an output")
    (root / "file.txt").write_text("not a folder")
    (root / "bad.npy").write_bytes(b"\x93NUMPY garbage")
    return root


def shapes(folder: Path) -> st.SearchStrategy[str]:
    good = st.just(str(folder / "bar.npy"))
    bad = st.sampled_from([str(folder / "bad.npy"), str(folder / "missing.npy"), str(folder / "folder"), "00001.001"])
    return st.one_of(good, good, bad)


def outputs(folder: Path, command: str) -> st.SearchStrategy[str]:
    names = [str(folder / "out" / name) if not name.startswith(("folder", "file")) else str(folder / name)
             for name in OUTPUT_NAMES[command]]
    return st.one_of(st.sampled_from(names[:2]), st.sampled_from(names))


# Options whose values keep a run short: net searches are bounded by time, a few nets at most.
BOUNDED = {"net": ("--timeout", "2"), "render": ()}


@pytest.mark.parametrize("command", ["info", "convert", "mesh", "net", "slices", "render"])
def test_random_command_lines(folder, command):
    (folder / "out").mkdir(exist_ok=True)
    positionals = {
        "shape": shapes(folder),
        "input": shapes(folder),
        "repo": st.just(str(folder / "repo.sqlite")),
        "recipes": st.just(str(folder / "none.toml")),
    }
    if command in OUTPUT_NAMES:
        positionals["output"] = outputs(folder, command)
        positionals["net"] = st.sampled_from([str(folder / "out" / "n.json"), str(folder / "missing.json")])
    counts = {"ok": 0, "refused": 0}

    @settings(max_examples=25 if command in ("net", "slices", "mesh") else 30, database=None)
    @given(argv=argv_for(command, positionals, fixed=BOUNDED.get(command, ())))
    def fuzz(argv):
        if command == "net":
            # --count N searches N nets with a per-net --timeout; its overall budget is not here yet.
            argv = [a for a in argv if not a.startswith("--count")]
        o = check_outcome(run_cli(argv))
        counts["ok" if o.code == 0 else "refused"] += 1
        if o.code == 0 and command in ("net", "slices") and o.out.strip():
            # Reports name only files that exist.
            report = json.loads(o.out)
            assert all(Path(p).exists() for p in report.get("written", report.get("files", [])))
        # No temporary is left behind by a finished run.
        assert not list((folder / "out").glob(".*.tmp")), argv

    fuzz()
    assert counts["refused"] > 0
