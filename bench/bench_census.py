"""Benchmark of ``voxfab census``: seconds per polycube and the scaling from 1 to 2 Dask workers.

Run ``python bench/bench_census.py [--n 6] [--smoke]`` (``--smoke``: up to 3 cubes).  It censuses every polycube of 1..n
cubes three times into fresh folders: serially in this process, then on a local
Dask cluster of 1 and of 2 worker processes.  It prints the wall-clock time of
each run, the CPU seconds of the searches (added over the shapes), the cost per
shape, and the scaling (1-worker wall time over 2-worker wall time).  The first
tasks of a fresh worker pay its imports and numba cache loads, as a real run
does.  On a shared, busy machine the wall-clock figures move with the load:
the CPU seconds do not; say which when quoting them.
"""

from __future__ import annotations

import argparse
import json
import os
import tempfile
import time
from pathlib import Path


def _run(n: int, out: Path, workers: int) -> tuple[float, float, int]:
    """One census; return (wall seconds, search CPU seconds, shapes)."""
    from voxfab.census import run_census

    start = time.perf_counter()
    report = run_census(n, out, workers=workers)
    wall = time.perf_counter() - start
    rows = json.loads(report.path.read_text())["rows"]
    return wall, sum(r["cpu_seconds"] for r in rows), sum(r["free"] for r in rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=6, help="largest number of cubes (default 6)")
    parser.add_argument("--smoke", action="store_true", help="polycubes of up to 3 cubes")
    args = parser.parse_args()
    if args.smoke:
        args.n = 3
    print(f"load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp:
        walls = {}
        for label, workers in (("serial", 0), ("1 worker", 1), ("2 workers", 2)):
            wall, cpu, shapes = _run(args.n, Path(tmp) / label.replace(" ", "-"), workers)
            walls[workers] = wall
            print(f"{label:>10}: {shapes} polycubes in {wall:6.1f} s wall, {cpu:6.1f} s search CPU, "
                  f"{1000 * cpu / shapes:5.1f} ms CPU per polycube, {shapes / wall:6.1f} polycubes/s")
    print(f"scaling 1 -> 2 workers: {walls[1] / walls[2]:.2f}x (wall clock)")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
