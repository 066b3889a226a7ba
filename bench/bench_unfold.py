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

``--base DIR`` (a checkout of another commit, e.g. ``git worktree add /tmp/base
BASE``) measures the default nets of both trees in child processes, shape by
shape in turn, so both meet the same load; the table then shows before and
after side by side (and skips the distinct nets and the floor).

Timings are wall-clock on a shared machine: noisy, so quote medians; the CPU
seconds beside them (``time.process_time``) stretch less under load.  The last
row holds the target of issue 46 (median under 0.7 s, maximum under 1.5 s)
beside the figures measured.
"""

from __future__ import annotations

import argparse
import json
import os
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


#: Issue 46's target for a default net: median and maximum wall seconds over the corpus.
TARGET_MEDIAN, TARGET_MAX = 0.7, 1.5


def _default_nets(grid: np.ndarray, seeds: int) -> dict:
    """Wall and CPU seconds of each seed's default net, seams left without tab room, nets refused."""
    wall, cpu, left, invalid, seams = [], [], 0, 0, []
    for seed in range(seeds):
        t, c = time.perf_counter(), time.process_time()
        net = unfold(grid, rng=seed)
        wall.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
        report = validate(grid, net)
        left = max(left, report.seams_without_tab_room)
        seams.append(report.seams_without_tab_room)
        invalid += not report.ok
    return {"wall": wall, "cpu": cpu, "left": left, "invalid": invalid, "seams": seams}


def _in_tree(tree: Path, name: str, seeds: int) -> dict:
    """:func:`_default_nets` of one corpus shape, run by ``tree``'s voxfab in a child process."""
    env = dict(os.environ, PYTHONPATH=str(tree))
    done = subprocess.run([sys.executable, __file__, "--child", name, "--seeds", str(seeds)], env=env,
                          capture_output=True, text=True, check=True, cwd=tempfile.gettempdir())
    return json.loads(done.stdout.strip().splitlines()[-1])


def _child(name: str, seeds: int) -> None:
    unfold(examples.ball(4), rng=0)  # kernels loaded (or compiled) before the clock starts
    print(json.dumps(_default_nets(dict(corpus())[name], seeds)))


def _target(label: str, everything: list[float]) -> str:
    median, most = statistics.median(everything), max(everything)
    met = "met" if median < TARGET_MEDIAN and most < TARGET_MAX else "NOT met"
    return (f"{label}: median {median:.2f} s, max {most:.2f} s | target median < {TARGET_MEDIAN} s, "
            f"max < {TARGET_MAX} s: {met}")


def _compare(base: Path, args: argparse.Namespace, smoke_shapes: tuple[str, ...]) -> None:
    """Default nets of ``base`` (before) and this tree (after), shape by shape in turn."""
    trees = {"before": base.resolve(), "after": Path(__file__).resolve().parents[1]}
    for tree in trees.values():
        _in_tree(tree, "ball r=4", 1)  # numba's cache filled for each tree
    header = (f"{'shape':<14}{'faces':>6} | " + " | ".join(
        f"{t + ' median':>13}{'max':>6}{'cpu max':>8}{'left':>5}" for t in trees))
    print(header)
    print("-" * len(header))
    got: dict[str, list[dict]] = {t: [] for t in trees}
    for name, grid in corpus():
        if (args.only and args.only not in name) or (args.smoke and name not in smoke_shapes):
            continue
        cells = []
        for t, tree in trees.items():
            r = _in_tree(tree, name, args.seeds)
            got[t].append(r)
            cells.append(f"{statistics.median(r['wall']):>13.2f}{max(r['wall']):>6.2f}{max(r['cpu']):>8.2f}"
                         f"{r['left']:>5}")
        print(f"{name:<14}{surface_graph(grid).face_count:>6} | " + " | ".join(cells), flush=True)
    for t, rows in got.items():
        print(_target(f"{t}: default nets, wall", [x for r in rows for x in r["wall"]]))
        seams = [x for r in rows for x in r["seams"]]
        print(f"{t}: CPU median {statistics.median(x for r in rows for x in r['cpu']):.2f} s, "
              f"max {max(x for r in rows for x in r['cpu']):.2f} s; seams without tab room {sum(seams)} "
              f"(most {max(seams)}), nets with tab room on every seam {seams.count(0)} of {len(seams)}, "
              f"nets the validator refused {sum(r['invalid'] for r in rows)}")


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
    parser.add_argument("--base", type=Path, help="a checkout to compare with (default nets only)")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        _child(args.child, args.seeds)
        return
    smoke_shapes = ("ball r=4", "tunnel cube 5")
    if args.smoke:
        args.seeds, args.count, args.budget, args.floor_runs = 1, 4, 2.0, 1
    if args.base:
        _compare(args.base, args, smoke_shapes)
        return

    floor = _floor(args.floor_runs)
    unfold(examples.ball(4), rng=0)  # compile (or load) the kernels before any net is timed
    print(f"floor: voxfab net on the 78-face ball, median {statistics.median(floor):.2f} s, "
          f"min {min(floor):.2f} s over {len(floor)} runs")
    header = (f"{'shape':<14}{'faces':>6} | {'median s':>9}{'max s':>8}{'cpu max':>8}{'no tab room':>12} | "
              f"{'distinct':>9}{'s':>6}")
    print(header)
    print("-" * len(header))
    everything, cpu = [], []
    for name, grid in corpus():
        if (args.only and args.only not in name) or (args.smoke and name not in smoke_shapes):
            continue
        faces = surface_graph(grid).face_count
        got = _default_nets(grid, args.seeds)
        times, left = got["wall"], got["left"]
        everything.extend(times)
        cpu.extend(got["cpu"])
        t = time.perf_counter()
        nets = unfold_many(grid, count=args.count, rng=0, budget=args.budget, tab_aware=False)
        dt = time.perf_counter() - t
        print(f"{name:<14}{faces:>6} | {statistics.median(times):>9.2f}{max(times):>8.2f}{max(got['cpu']):>8.2f}"
              f"{left:>12} | "
              f"{len(nets):>9}{dt:>6.1f}", flush=True)
    print(_target("default nets over all shapes, wall", everything))
    print(f"default nets over all shapes, CPU: median {statistics.median(cpu):.2f} s, max {max(cpu):.2f} s")


if __name__ == "__main__":
    main()
