"""Benchmark of the net engine: default nets, distinct nets, and the start-up floor.

Run ``python bench/bench_unfold.py`` (``--help`` for options).

* **Default net** of each corpus shape (up to about 3000 faces, inside 25³): one
  piece with tab room on every seam, as ``voxfab net`` makes it.  Over
  ``--seeds`` seeds: median and maximum wall time, and the most seams left
  without tab room.  Every net is checked by the independent validator.
* **Distinct nets**: how many nets with different outlines (up to the 8
  rotations and mirrors of the sheet) ``unfold_many`` finds within
  ``--budget`` seconds, asking for ``--count``.
* **Floor**: the wall time of a whole ``python -m voxfab net`` process on the
  78-face ball (kernels loaded from numba's cache), median of ``--floor-runs``.

The compiled kernels are loaded (or compiled, after a change) once before the
first timed net, so no shape's maximum holds numba's compile time.

``--smoke``: two small shapes, one seed, 4 distinct nets in 2 s, one floor run.

Timings are wall-clock on a shared machine: noisy, so quote medians.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from voxfab.shape import examples, surface_graph
from voxfab.unfold import unfold, unfold_many, validate


def corpus() -> list[tuple[str, np.ndarray]]:
    """Balls r=4..12, tunnel cubes 5 and 9, a torus, a vase, and blobs of 2300-2700 faces."""
    shapes = [(f"ball r={r}", examples.ball(r)) for r in (4, 6, 8, 10, 12)]
    shapes += [("tunnel cube 5", examples.tunnel_cube(5)), ("tunnel cube 9", examples.tunnel_cube(9))]
    shapes += [("torus 8/3", examples.torus(8, 3)), ("vase", examples.vase())]
    shapes += [(f"blob {s}", examples.random_shape(s, side=20)) for s in range(3)]
    shapes += [(f"dense blob {s}", examples.random_shape(s, side=18, fill=0.3)) for s in range(2)]
    return shapes


def _default_nets(grid: np.ndarray, seeds: int) -> tuple[list[float], int]:
    times, left = [], 0
    for seed in range(seeds):
        t = time.perf_counter()
        net = unfold(grid, rng=seed)
        times.append(time.perf_counter() - t)
        report = validate(grid, net)
        left = max(left, report.seams_without_tab_room)
    return times, left


def _floor(runs: int) -> list[float]:
    with tempfile.TemporaryDirectory() as tmp:
        shape = Path(tmp) / "ball.npy"
        np.save(shape, examples.ball(2))
        cmd = [sys.executable, "-m", "voxfab", "net", str(shape), "-o", str(Path(tmp) / "n.json")]
        subprocess.run(cmd, check=True, capture_output=True)  # fill numba's cache once
        out = []
        for _ in range(runs):
            t = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True)
            out.append(time.perf_counter() - t)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5, help="default nets per shape")
    parser.add_argument("--count", type=int, default=50, help="distinct nets asked per shape")
    parser.add_argument("--budget", type=float, default=10.0, help="seconds for the distinct nets")
    parser.add_argument("--floor-runs", type=int, default=5)
    parser.add_argument("--only", help="substring of the shape names to run")
    parser.add_argument("--smoke", action="store_true", help="ball r=4 and tunnel cube 5, one seed, 4 nets in 2 s")
    args = parser.parse_args()
    smoke_shapes = ("ball r=4", "tunnel cube 5")
    if args.smoke:
        args.seeds, args.count, args.budget, args.floor_runs = 1, 4, 2.0, 1

    floor = _floor(args.floor_runs)
    unfold(examples.ball(4), rng=0)  # compile (or load) the kernels before any net is timed
    print(f"floor: voxfab net on the 78-face ball, median {statistics.median(floor):.2f} s, "
          f"min {min(floor):.2f} s over {len(floor)} runs")
    header = (f"{'shape':<14}{'faces':>6} | {'median s':>9}{'max s':>8}{'no tab room':>12} | "
              f"{'distinct':>9}{'s':>6}")
    print(header)
    print("-" * len(header))
    everything = []
    for name, grid in corpus():
        if (args.only and args.only not in name) or (args.smoke and name not in smoke_shapes):
            continue
        faces = surface_graph(grid).face_count
        times, left = _default_nets(grid, args.seeds)
        everything.extend(times)
        t = time.perf_counter()
        nets = unfold_many(grid, count=args.count, rng=0, budget=args.budget, tab_aware=False)
        dt = time.perf_counter() - t
        print(f"{name:<14}{faces:>6} | {statistics.median(times):>9.2f}{max(times):>8.2f}{left:>12} | "
              f"{len(nets):>9}{dt:>6.1f}", flush=True)
    print(f"default nets over all shapes: median {statistics.median(everything):.2f} s, "
          f"max {max(everything):.2f} s")


if __name__ == "__main__":
    main()
