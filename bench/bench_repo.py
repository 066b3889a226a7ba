"""Benchmark of the shape repository: add and find with 10,000 shapes stored.

Run ``python bench/bench_repo.py [--shapes N]``.  Target (issue 2): under 10 ms per
add or lookup with 10,000 shapes stored.  Figures depend on the machine's load.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from voxfab.repo import Repository
from voxfab.shape import GRID_SIDE, examples

# The 4 x 25 voxel positions beside a 1x1x25 column in the middle of a 3x3x25 grid.
_SIDES = np.array([(0, 1), (2, 1), (1, 0), (1, 2)])
_BESIDE = [(int(x), int(y), z) for x, y in _SIDES for z in range(GRID_SIDE)]


def column_shapes(n: int, *, rng: np.random.Generator | int) -> list[np.ndarray]:
    """``n`` well-formed shapes: a 1x1x25 column plus random voxels beside it.

    Volumes run over 25 + (3..42) so no volume needs more than 999 ranks; the
    shapes are drawn without repetition of the voxel sets (a few may still be equal
    up to translation; the repository tells).
    """
    gen = np.random.default_rng(rng)
    seen: set[bytes] = set()
    out = []
    while len(out) < n:
        k = len(out) % 40 + 3  # at least 3 extra voxels: C(100, 3) sets, plenty per volume
        pick = gen.choice(len(_BESIDE), size=k, replace=False)
        g = np.zeros((3, 3, GRID_SIDE), dtype=bool)
        g[1, 1, :] = True
        idx = np.array([_BESIDE[i] for i in pick])
        g[idx[:, 0], idx[:, 1], idx[:, 2]] = True
        b = np.packbits(g).tobytes()
        if b not in seen:
            seen.add(b)
            out.append(g)
    return out


def _time_each(fn: Callable[[np.ndarray], object], grids: list[np.ndarray]) -> tuple[list[float], list[float]]:
    """Wall-clock and CPU milliseconds of ``fn`` on each grid (CPU time is less noisy on a busy machine)."""
    wall, cpu = [], []
    for g in grids:
        t, c = time.perf_counter(), time.process_time()
        fn(g)
        cpu.append((time.process_time() - c) * 1e3)
        wall.append((time.perf_counter() - t) * 1e3)
    return wall, cpu


def _row(label: str, times: tuple[list[float], list[float]]) -> str:
    wall, cpu = times
    return (
        f"{label:<44} {len(wall):>6} {statistics.median(wall):>8.2f} {statistics.mean(wall):>8.2f} "
        f"{float(np.percentile(wall, 95)):>8.2f} {statistics.median(cpu):>9.2f} {statistics.mean(cpu):>9.2f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shapes", type=int, default=10_000, help="shapes stored before timing")
    parser.add_argument("--samples", type=int, default=200, help="timed calls per row")
    args = parser.parse_args()

    fill = column_shapes(args.shapes + args.samples, rng=0)
    stored, fresh = fill[: args.shapes], fill[args.shapes :]
    # Realistic 25-cube shapes: the cost of the canonical keys grows with the grid.
    big = [examples.random_shape(seed) for seed in range(20)]

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.sqlite"
        with Repository(path) as repo:
            t, c = time.perf_counter(), time.process_time()
            results = repo.add_many(stored)
            fill_s, fill_cpu = time.perf_counter() - t, time.process_time() - c
            created = sum(r.created for r in results)
            # Top up the few duplicates so that exactly args.shapes are stored.
            extra = iter(column_shapes(args.shapes, rng=1))
            while len(repo) < args.shapes:
                repo.add(next(extra))
            n = len(repo)

            rows = [
                _row("find, stored (column shapes)", _time_each(repo.find, stored[: args.samples])),
                _row("find, symmetric, stored", _time_each(lambda g: repo.find(g, symmetric=True),
                                                         stored[: args.samples])),
                _row("find, not stored", _time_each(repo.find, fresh)),
                _row("find, random 25^3 shapes (not stored)", _time_each(repo.find, big)),
                _row("add, new (column shapes, 1 transaction each)", _time_each(repo.add, fresh)),
                _row("add, existing (returns the name)", _time_each(repo.add, stored[: args.samples])),
                _row("add, symmetric, existing", _time_each(lambda g: repo.add(g, symmetric=True),
                                                          stored[args.samples : 2 * args.samples])),
                _row("add, new random 25^3 shapes", _time_each(repo.add, big)),
                _row("find, random 25^3 shapes (stored)", _time_each(repo.find, big)),
            ]
            total = len(repo)
            problems = repo.check()
        size_mb = path.stat().st_size / 1e6

    print(f"repository: {n} shapes stored ({created} of {len(stored)} created by one add_many in "
          f"{fill_s:.1f} s wall, {fill_cpu:.1f} s CPU, {fill_cpu / len(stored) * 1e3:.2f} ms CPU/shape); {total} at the end; "
          f"file {size_mb:.1f} MB; check: {'ok' if not problems else problems}")
    print(f"{'operation (ms per call)':<44} {'calls':>6} {'median':>8} {'mean':>8} {'p95':>8} "
          f"{'cpu med':>9} {'cpu mean':>9}")
    for row in rows:
        print(row)


if __name__ == "__main__":
    main()
