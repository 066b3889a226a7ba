"""Benchmark: one edge edit of the queen's net (cut a fold, join a seam), local repair and validation included.

Run: python bench/bench_edit.py [--edits N] [--smoke]   (--smoke: one edit of each kind on the pawn)
Goal: each edit of the queen (recipes/chess/queen.toml, 1270 faces) in at most 1 s, where regenerating
the net with the marks takes about 22 s.  The net is ``unfold(queen, rng=1)``; finding it is not timed.
Folds and seams are taken at evenly spaced places in the net's lists, so every run edits the same edges.
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import numpy as np

from voxfab.errors import UnfoldError
from voxfab.recipe import load_recipe, make_shape
from voxfab.unfold import cut_edge, join_edge, seam_pairs, unfold

ROOT = Path(__file__).resolve().parents[1]
_NORMALS = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y", (0, 0, 1): "+z", (0, 0, -1): "-z"}


def name(net, i: int) -> tuple:
    return (*net.voxel[i].tolist(), _NORMALS[tuple(net.normal[i].tolist())])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=8, help="cuts and joins each (default 8)")
    parser.add_argument("--smoke", action="store_true", help="one cut and one join of the pawn's net")
    args = parser.parse_args()
    piece = "pawn" if args.smoke else "queen"
    edits = 1 if args.smoke else args.edits
    grid = make_shape(load_recipe(ROOT / "recipes" / "chess" / f"{piece}.toml")).grid
    net = unfold(grid, rng=1)
    print(f"{piece}: {net.face_count} faces")
    results: dict[str, list[float]] = {"cut": [], "join": []}
    refused = {"cut": 0, "join": 0}
    moved: dict[str, list[int]] = {"cut": [], "join": []}
    seams = seam_pairs(grid, net)
    for t in range(edits):
        i, j = net.folds[(t * 157 + 11) % len(net.folds)].tolist()
        s = seams[(t * 131 + 7) % len(seams)]
        edges = {"cut": (cut_edge, name(net, i), name(net, j)),
                 "join": (join_edge, name(net, int(s[0, 0])), name(net, int(s[1, 0])))}
        for kind, (edit, a, b) in edges.items():
            start = time.perf_counter()
            try:
                r = edit(grid, net, a, b)
                moved[kind].append(r.moved)
            except UnfoldError:
                refused[kind] += 1
            results[kind].append(time.perf_counter() - start)
    for kind, times in results.items():
        print(f"{kind:5s} median {statistics.median(times):.3f} s  max {max(times):.3f} s  "
              f"({len(times) - refused[kind]} done, {refused[kind]} refused, "
              f"faces moved median {int(np.median(moved[kind] or [0]))}, max {max(moved[kind] or [0])})")


if __name__ == "__main__":
    main()
