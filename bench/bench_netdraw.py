"""Benchmark: drawing large nets with tabs and numbers, and writing SVG, DXF and PDF.

Run: python bench/bench_netdraw.py
Goal: drawing a 3000-face net with tabs and numbers under 2 s (draw + SVG + DXF R12 + PDF).
Nets come from the net engine (voxfab.unfold.unfold); finding them is not timed.
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from voxfab.fabricate.netdraw import DrawingOptions, draw_net
from voxfab.fabricate.netdraw._writers import write
from voxfab.shape import examples


def timed(fn, *args, runs: int = 5, **kwargs) -> tuple[float, float]:
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn(*args, **kwargs)
        times.append(time.perf_counter() - t)
    return statistics.median(times), max(times)


def shapes() -> list[tuple[str, np.ndarray]]:
    # Digital balls are the net engine's hard family; r = 13 gives 3174 faces.
    return [("ball r=12", examples.ball(12)), ("ball r=13", examples.ball(13))]


def bench_one(name: str, grid: np.ndarray, net, tmp: Path) -> None:
    opts = DrawingOptions(pitch=5.0, sheet="1500x1500")
    opts2k = DrawingOptions(pitch=5.0, sheet="1500x1500", dxf_version="R2000")
    d = draw_net(grid, net, options=opts, name=name)
    t_draw = timed(draw_net, grid, net, options=opts, name=name)
    t = {ext: timed(write, d, tmp / f"n.{ext}", opts) for ext in ("svg", "dxf", "pdf")}
    t["dxf2k"] = timed(write, d, tmp / "n2k.dxf", opts2k, runs=1)
    total = t_draw[0] + t["svg"][0] + t["dxf"][0] + t["pdf"][0]
    print(f"{name:<14}{net.face_count:>7}{d.seams:>7}{int(d.tab_seams.sum()):>6}"
          f"{net.seams_without_tab_room:>7}{len(d.sheets):>7}"
          f"{t_draw[0]:>9.3f}{t['svg'][0]:>8.3f}{t['dxf'][0]:>9.3f}{t['dxf2k'][0]:>9.3f}"
          f"{t['pdf'][0]:>8.3f}{total:>9.3f}")
    # The A4 case: automatic pitch, split over sheets, as a user would run it.
    a4 = DrawingOptions()
    t_a4 = timed(draw_net, grid, net, options=a4, name=name, runs=3)
    da4 = draw_net(grid, net, options=a4, name=name)
    print(f"{'  on A4':<14}{'':>7}{da4.seams:>7}{int(da4.tab_seams.sum()):>6}{'':>7}{len(da4.sheets):>7}"
          f"{t_a4[0]:>9.3f}   (pitch {da4.pitch:g} mm)")


def main() -> None:
    try:
        from voxfab.unfold import unfold
    except ImportError:
        sys.exit("bench_netdraw: the net engine (voxfab.unfold.unfold) is not available")
    print(f"{'shape':<14}{'faces':>7}{'seams':>7}{'tabs':>6}{'noroom':>7}{'sheets':>7}{'draw s':>9}{'svg s':>8}"
          f"{'dxf12 s':>9}{'dxf2k s':>9}{'pdf s':>8}{'total s':>9}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, grid in shapes():
            bench_one(name, grid, unfold(grid, rng=1), Path(tmp))
    print("noroom: seams the engine left without tab room (they get a printed mark instead of a tab)")
    print("medians of 5 runs (R2000: 1 run); 2-core machine shared with other jobs, figures are noisy")


if __name__ == "__main__":
    main()
