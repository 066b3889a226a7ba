"""Benchmark: where the artist waits on the command line, interpreter start included.

Run: python bench/bench_cli.py [--smoke]   (--smoke: one run of each command instead of 7)
Goals: ``voxfab net`` on a unit cube within 0.3 s (the CLI's floor: a command imports only what it
runs); a sheet hopeless for a net in pieces (the chess queen on 60x60 mm) refused within 0.2 s above
that floor, with a face size or without.  Each row is a whole ``python -m voxfab`` process.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from voxfab.recipe import load_recipe, make_shape

ROOT = Path(__file__).resolve().parents[1]


def wall(cmd: list[str], cwd: Path, runs: int) -> tuple[float, float, int]:
    """Median and largest wall seconds of ``cmd``, and its exit status."""
    times, status = [], 0
    for _ in range(runs):
        t = time.perf_counter()
        status = subprocess.run(cmd, capture_output=True, cwd=cwd).returncode
        times.append(time.perf_counter() - t)
    return statistics.median(times), max(times), status


def main() -> None:
    runs = 1 if "--smoke" in sys.argv[1:] else 7
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
        print(f"{'command':<40} {'median s':>9} {'max s':>7} {'exit':>5}  goal")
        for label, cmd, goal in rows:
            med, worst, status = wall(cmd, here, runs)
            print(f"{label:<40} {med:9.3f} {worst:7.3f} {status:>5}  {goal}")
        print(f"medians of {runs} runs; the queen's refusals exit 6 (a sheet too small); 2-core machine shared "
              "with other jobs, figures are noisy")


if __name__ == "__main__":
    main()
