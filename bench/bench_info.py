"""Benchmark: `voxfab info` wall time (interpreter start included) and import times.

Run: python bench/bench_info.py [--smoke]   (--smoke: one run of each command instead of 7)
Goal: `voxfab info` on a 25³ shape under 0.5 s wall.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from voxfab.shape import examples


def wall(cmd: list[str], runs: int = 7) -> tuple[float, float]:
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - t)
    return statistics.median(times), max(times)


def main() -> None:
    runs = 1 if "--smoke" in sys.argv[1:] else 7
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "shape.npy"
        np.save(path, examples.random_shape(1))
        rows = [
            ("python -c pass (interpreter floor)", [sys.executable, "-c", "pass"]),
            ("import voxfab", [sys.executable, "-c", "import voxfab"]),
            ("voxfab --version", [sys.executable, "-m", "voxfab", "--version"]),
            ("voxfab info 25^3", [sys.executable, "-m", "voxfab", "info", str(path)]),
            ("voxfab info 25^3 --json", [sys.executable, "-m", "voxfab", "info", str(path), "--json"]),
        ]
        print(f"{'command':<40} {'median s':>9} {'max s':>7}  goal")
        for label, cmd in rows:
            med, worst = wall(cmd, runs)
            goal = "< 0.5 s" if label.startswith("voxfab info") else ""
            print(f"{label:<40} {med:9.3f} {worst:7.3f}  {goal}")


if __name__ == "__main__":
    main()
