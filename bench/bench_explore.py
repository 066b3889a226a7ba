"""Benchmark of ``explore``: new well-formed shapes stored per second.

Run ``python bench/bench_explore.py [--count N]``.  Target (issue 16): 10,000 growth
shapes in under a minute on 2 cores.  The machine's load moves the figures: the
median of ``--repeat`` runs is printed.  ``--smoke``: 200 growth and 2 mix shapes, one run.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

from voxfab.generate import explore, growth
from voxfab.repo import Repository


def _run(count: int, generator: str, seed: int) -> tuple[float, float, int]:
    with tempfile.TemporaryDirectory() as tmp, Repository(Path(tmp) / "r.sqlite") as repo:
        t, c = time.perf_counter(), time.process_time()
        report = explore(repo, count, seed=seed, generator=generator)
        return time.perf_counter() - t, time.process_time() - c, report.attempts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=10_000, help="growth shapes per run")
    parser.add_argument("--mix", type=int, default=500, help="shapes of the mix generator per run")
    parser.add_argument("--repeat", type=int, default=3, help="runs per row")
    parser.add_argument("--smoke", action="store_true", help="200 growth and 2 mix shapes, one run")
    args = parser.parse_args()
    if args.smoke:
        args.count, args.mix, args.repeat = 200, 2, 1
    growth(0, 100)  # compile (or load from the numba cache) outside the timings
    print(f"{'generator':<10} {'shapes':>7} {'wall s (median)':>16} {'cpu s':>7} {'shapes/s':>9} {'candidates':>11}")
    for generator, count in (("growth", args.count), ("mix", args.mix)):
        if count <= 0:
            continue
        runs = [_run(count, generator, seed) for seed in range(args.repeat)]
        wall = statistics.median(r[0] for r in runs)
        cpu = statistics.median(r[1] for r in runs)
        print(f"{generator:<10} {count:>7} {wall:>16.2f} {cpu:>7.2f} {count / wall:>9.0f} "
              f"{int(statistics.median(r[2] for r in runs)):>11}")


if __name__ == "__main__":
    main()
