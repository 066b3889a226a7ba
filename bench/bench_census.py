"""Benchmark of ``voxfab census``: seconds per polycube and the scaling from 1 to 2 Dask workers.

Run ``python bench/bench_census.py [--n 6] [--smoke]`` (``--smoke``: up to 3 cubes).  It censuses every polycube of 1..n
cubes three times into fresh folders: serially in this process, then on a local
Dask cluster of 1 and of 2 worker processes.  It prints the wall-clock time of
each run, the CPU seconds of the searches (added over the shapes), the cost per
shape, and the scaling (1-worker wall time over 2-worker wall time).  Then the
machine's own ceiling: the same tasks in 1 and in 2 plain processes, no Dask,
timed after each process has warmed up (imports, numba caches), so the gap
between the two scalings is what Dask, the client and the warm-up cost.  The first
tasks of a fresh worker pay its imports and numba cache loads, as a real run
does.  On a shared, busy machine the wall-clock figures move with the load:
the CPU seconds do not; say which when quoting them.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import tempfile
import time
from pathlib import Path
from typing import Any


def _run(n: int, out: Path, workers: int) -> tuple[float, float, int]:
    """One census; return (wall seconds, search CPU seconds, shapes)."""
    from voxfab.census import run_census

    start = time.perf_counter()
    report = run_census(n, out, workers=workers)
    wall = time.perf_counter() - start
    rows = json.loads(report.path.read_text())["rows"]
    return wall, sum(r["cpu_seconds"] for r in rows), sum(r["one_sided"] for r in rows)


def _timed_tasks(tasks: list[Any], results: Any) -> None:
    """In a fresh process: warm up on one small polycube, then census ``tasks``; send (start, end)."""
    from voxfab.census import CensusSettings, census_shape, census_task

    census_shape("warm-up", [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]], None, CensusSettings())
    start = time.time()
    for task in tasks:
        census_task(task)
    results.put((start, time.time()))


def _plain(n: int, out: Path, processes: int) -> float:
    """Wall seconds of the census's own tasks, largest first, dealt to ``processes`` plain processes."""
    from voxfab.census import CensusSettings, CensusTask, polycubes, shape_id

    todo = sorted(((shape_id(k, i), k, tuple(map(tuple, cells.tolist()))) for k, i, cells in polycubes(n)),
                  key=lambda item: -item[1])
    out.mkdir()
    (out / "nets").mkdir()
    chunks = [CensusTask(tuple(todo[i:i + 24]), str(out), CensusSettings()) for i in range(0, len(todo), 24)]
    # One BLAS thread per process, as Dask's nanny gives its workers: a spare OpenBLAS thread spinning
    # after a call takes the core from the other process.
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[name] = "1"
    ctx = multiprocessing.get_context("spawn")
    results = ctx.Queue()
    procs = [ctx.Process(target=_timed_tasks, args=(chunks[k::processes], results)) for k in range(processes)]
    for proc in procs:
        proc.start()
    spans = [results.get(timeout=3600) for _ in procs]
    for proc in procs:
        proc.join()
    return max(end for _, end in spans) - min(start for start, _ in spans)


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
        plain = {k: _plain(args.n, Path(tmp) / f"plain-{k}", k) for k in (1, 2)}
        print(f"the same tasks in plain processes after warm-up: 1 process {plain[1]:.1f} s, 2 processes "
              f"{plain[2]:.1f} s: {plain[1] / plain[2]:.2f}x, the machine's ceiling for this work")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
