"""Benchmark: where the artist waits on the command line, interpreter start included.

Run: python bench/bench_cli.py [--smoke] [--before CHECKOUT] [--save]
(--smoke: one run of each command instead of 7; --before: a checkout of voxfab to measure side by side,
e.g. ``git worktree add /tmp/before COMMIT``; its runs alternate with this checkout's.)
Goals: ``voxfab net`` on a unit cube within 0.3 s (the CLI's floor: a command imports only what it
runs); a sheet hopeless for a net in pieces (the chess queen on 60x60 mm) refused within 0.2 s above
that floor, with a face size or without.  Each row is a whole ``python -m voxfab`` process, run from
this checkout (or the one given); wall and CPU seconds (user + system, the operating system's count)
are medians.  Without ``--before``, the columns "before" hold the figures recorded before issue #46.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _table import Table, add_save_option

from voxfab.recipe import load_recipe, make_shape

ROOT = Path(__file__).resolve().parents[1]

#: Median wall and CPU seconds before issue #46 (commit 27fbcf1), measured on the shared 2-core machine at a
#: load of about 5: wall side by side with the change (--before), CPU over 15 runs.
RECORDED_BEFORE = {"voxfab --version": (0.214, 0.150), "voxfab net cube -o cube.json": (0.308, 0.228),
                   "voxfab net cube -o cube.svg": (0.434, 0.328)}


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_once(cmd: list[str], cwd: Path, checkout: Path) -> tuple[float, float, int]:
    """Wall and CPU seconds of one run of ``cmd`` with ``checkout``'s voxfab, and its exit status.

    The modules' bytecode may be written (as an install compiles it): with PYTHONDONTWRITEBYTECODE set, a
    fresh checkout would compile every module it imports at every start, a tenth of a second.
    """
    env = {**os.environ, "PYTHONPATH": str(checkout)}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    cpu, t = _cpu(), time.perf_counter()
    status = subprocess.run(cmd, capture_output=True, cwd=cwd, env=env).returncode
    return time.perf_counter() - t, _cpu() - cpu, status


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true", help="one run of each command")
    parser.add_argument("--before", type=Path, metavar="CHECKOUT",
                        help="a checkout of voxfab (the folder holding voxfab/) to measure side by side")
    add_save_option(parser)
    args = parser.parse_args()
    runs = 1 if args.smoke else 7
    voxfab = [sys.executable, "-m", "voxfab"]
    with tempfile.TemporaryDirectory() as tmp:
        here = Path(tmp)
        np.save(here / "cube.npy", np.ones((1, 1, 1), dtype=bool))
        np.save(here / "queen.npy", make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid)
        hopeless = [*voxfab, "net", "queen.npy", "--pieces", "auto", "--sheet", "60x60", "-o", "q.pdf"]
        rows = [
            ("python -c pass (interpreter floor)", [sys.executable, "-c", "pass"], ""),
            ("voxfab --version", [*voxfab, "--version"], ""),
            ("voxfab net cube -o cube.json", [*voxfab, "net", "cube.npy", "-o", "cube.json"], "<= 0.3 s"),
            ("voxfab net cube -o cube.svg", [*voxfab, "net", "cube.npy", "-o", "cube.svg"], "<= 0.3 s"),
            ("queen, pieces, 60x60: refused", hopeless, "floor + 0.2 s"),
            ("queen, pieces, 60x60, 8.6 mm: refused", [*hopeless, "--face-size", "8.6"], "floor + 0.2 s"),
        ]
        recorded = "" if args.before else " (recorded)"
        table = Table("cli", ["command", f"before wall s{recorded}", "wall s", "max s", f"before cpu s{recorded}",
                              "cpu s", "exit", "goal"])
        for label, cmd, goal in rows:
            for checkout in filter(None, (args.before, ROOT)):
                run_once(cmd, here, checkout)  # not counted: the bytecode written, the files cached
            now, then = [], []
            for _ in range(runs):  # alternated, so a change in the machine's load falls on both
                if args.before:
                    then.append(run_once(cmd, here, args.before))
                now.append(run_once(cmd, here, ROOT))
            walls = [w for w, _, _ in now]
            if then:
                was = (f"{statistics.median(w for w, _, _ in then):.3f}", f"{statistics.median(c for _, c, _ in then):.3f}")
            else:
                was = tuple(f"{x:.3f}" for x in RECORDED_BEFORE.get(label, ())) or ("", "")
            table.row(label, was[0], f"{statistics.median(walls):.3f}", f"{max(walls):.3f}", was[1],
                      f"{statistics.median(c for _, c, _ in now):.3f}", now[-1][2], goal)
        print(f"medians of {runs} runs; the queen's refusals exit 6 (a sheet too small); 2-core machine shared "
              "with other jobs: wall figures are noisy, CPU seconds less so")
    table.save(args.save)


if __name__ == "__main__":
    main()
