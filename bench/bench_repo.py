"""Benchmark of the shape repository: add and find at 10^4, 10^5 and 10^6 stored shapes.

Run ``python bench/bench_repo.py [--sizes 10000,100000,1000000]``.  Targets
(issue 16): with a million shapes, add under 5 ms and find under 1 ms; the bytes
per shape are printed.  The repository is filled by ``explore`` (growth shapes of
volume 25..1500, distinct up to the 48 cube symmetries, one transaction per 512
shapes), growing from one size to the next, so the largest size takes minutes.
The machine's load moves the figures: medians, and CPU time beside wall time.
``--smoke``: 300 shapes and 20 timed calls per row.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from voxfab.generate import candidate, explore
from voxfab.repo import Repository

VOLUME = (25, 1500)


def _time_each(fn: Callable[[np.ndarray], object], grids: list[np.ndarray]) -> tuple[float, float, float]:
    """Median wall ms, 95th percentile wall ms and median CPU ms of ``fn`` on each grid."""
    wall, cpu = [], []
    for g in grids:
        t, c = time.perf_counter(), time.process_time()
        fn(g)
        cpu.append((time.process_time() - c) * 1e3)
        wall.append((time.perf_counter() - t) * 1e3)
    return statistics.median(wall), float(np.percentile(wall, 95)), statistics.median(cpu)


def _fresh(seed: int, n: int) -> list[np.ndarray]:
    """Growth grids from a seed no fill uses (new to the repository, up to a rare coincidence)."""
    out = [candidate("growth", seed, i, volume=VOLUME) for i in range(n)]
    return [c.grid for c in out if c is not None]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="10000,100000,1000000", help="stored shapes at each measure")
    parser.add_argument("--samples", type=int, default=300, help="timed calls per row")
    parser.add_argument("--keep", type=Path, help="build the repository at this path (kept) instead of a temp dir")
    parser.add_argument("--smoke", action="store_true", help="300 shapes, 20 timed calls per row")
    args = parser.parse_args()
    if args.smoke:
        args.sizes, args.samples = "300", 20
    sizes = sorted(int(s) for s in args.sizes.split(","))

    with tempfile.TemporaryDirectory() as tmp:
        path = args.keep or Path(tmp) / "bench.sqlite"
        print(f"{'shapes':>9} {'fill s':>8} {'op (ms per call)':<26} {'median':>7} {'p95':>7} {'cpu med':>8}")
        with Repository(path) as repo:
            stage = 0
            for size in sizes:
                need = size - len(repo)
                t = time.perf_counter()
                if need > 0:
                    explore(repo, need, seed=1000 + stage, volume=VOLUME, max_attempts=3 * need + 2000)
                fill = time.perf_counter() - t
                stage += 1
                names = [e.name for e in repo.list(limit=args.samples, after=repo.list(limit=1 + size // 2)[-1].name)]
                stored = [repo.get(n) for n in names]
                fresh = _fresh(10_000 + stage, args.samples)
                rows = [
                    ("find, stored", _time_each(lambda g: repo.find(g, symmetric=True), stored)),
                    ("find, not stored", _time_each(lambda g: repo.find(g, symmetric=True), fresh)),
                    ("add, new (1 transaction)", _time_each(lambda g: repo.add(g, symmetric=True), fresh)),
                    ("add, existing", _time_each(lambda g: repo.add(g, symmetric=True), stored)),
                ]
                for i, (label, (med, p95, cpu)) in enumerate(rows):
                    head = f"{len(repo):>9} {fill:>8.1f}" if i == 0 else " " * 18
                    print(f"{head} {label:<26} {med:>7.3f} {p95:>7.3f} {cpu:>8.3f}", flush=True)
                info = repo.stats()
            problems = repo.check() if len(repo) <= 100_000 else "(skipped above 10^5 shapes)"
        import sqlite3

        raw = sqlite3.connect(path)
        raw.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        bits = raw.execute("SELECT avg(length(bits)), avg(length(coalesce(meta, ''))) FROM shapes").fetchone()
        raw.close()
        size_b = path.stat().st_size
        n = info["shapes"] + info["drafts"]
        print(f"file: {size_b / 1e6:.1f} MB for {n} shapes = {size_b / n:.0f} bytes per shape "
              f"(packed grid {bits[0]:.0f} B, metadata {bits[1]:.0f} B on average); "
              f"{len(info['volumes'])} volumes; check: {problems or 'ok'}")


if __name__ == "__main__":
    main()
