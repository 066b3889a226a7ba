"""Benchmark of the net search on the unfolding corpus.

Run ``python bench/bench_unfold.py`` (``--help`` for options).  For each corpus
shape and each strategy, over ``--seeds`` seeds: success rate of a one-piece net
(plain search, ``tab_aware=False``), median and maximum time.  The ``tab`` column
runs the default tab-aware search once per shape up to ``--tab-faces`` faces and
reports the seams without tab room left and the time.  Every net is checked by
the independent validator.  Timings are wall-clock on a shared machine: noisy.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from voxfab.errors import UnfoldError
from voxfab.shape import examples, surface_graph
from voxfab.unfold import unfold, validate


def corpus() -> list[tuple[str, np.ndarray]]:
    """The benchmark shapes: balls r=2..12, tunnel cubes 5 and 9, a torus, a vase, blobs."""
    shapes = [(f"ball r={r}", examples.ball(r)) for r in range(2, 13)]
    shapes += [("tunnel cube 5", examples.tunnel_cube(5)), ("tunnel cube 9", examples.tunnel_cube(9))]
    shapes += [("torus 8/3", examples.torus(8, 3)), ("vase", examples.vase())]
    shapes += [(f"random {s}", examples.random_shape(s)) for s in range(3)]
    return shapes


def _run(grid, seed, strategy, timeout, tab_aware):
    t = time.perf_counter()
    try:
        net = unfold(grid, rng=seed, strategy=strategy, timeout=timeout, tab_aware=tab_aware)
    except UnfoldError:
        return None, time.perf_counter() - t
    dt = time.perf_counter() - t
    validate(grid, net)
    return net, dt


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--timeout", type=float, default=10.0, help="default strategy budget (s)")
    parser.add_argument("--paper-timeout", type=float, default=2.0, help="paper strategy cap (s)")
    parser.add_argument("--tab-timeout", type=float, default=30.0)
    parser.add_argument("--tab-faces", type=int, default=1500)
    parser.add_argument("--only", help="substring of the shape names to run")
    args = parser.parse_args()

    t = time.perf_counter()
    unfold(examples.ball(2), rng=0)  # compile or load the cached kernels
    print(f"first call (kernel compile or cache load): {time.perf_counter() - t:.1f} s")
    header = (f"{'shape':<14}{'faces':>6} | {'default ok':>10}{'med s':>8}{'max s':>8} | "
              f"{'paper ok':>9}{'med s':>8}{'max s':>8} | {'tab: left':>9}{'s':>7}")
    print(header)
    print("-" * len(header))
    all_default = []
    for name, grid in corpus():
        if args.only and args.only not in name:
            continue
        faces = surface_graph(grid).face_count
        cells = []
        for strategy, timeout in (("default", args.timeout), ("paper", args.paper_timeout)):
            runs = [_run(grid, s, strategy, timeout, False) for s in range(args.seeds)]
            ok = [dt for net, dt in runs if net is not None]
            times = [dt for _, dt in runs]
            if strategy == "default":
                all_default.extend(times)
            cells.append(f"{len(ok):>4}/{args.seeds:<5}{statistics.median(times):>8.3f}"
                         f"{max(times):>8.3f}")
        if faces <= args.tab_faces:
            net, dt = _run(grid, 0, "default", args.tab_timeout, True)
            tab = f"{'fail' if net is None else net.seams_without_tab_room:>9}{dt:>7.1f}"
        else:
            tab = f"{'-':>9}{'':>7}"
        print(f"{name:<14}{faces:>6} | {cells[0]} |  {cells[1]} | {tab}",
              flush=True)
    print(f"default strategy over all runs: median {statistics.median(all_default):.3f} s, "
          f"max {max(all_default):.3f} s")


if __name__ == "__main__":
    main()
