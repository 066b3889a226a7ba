"""Benchmark of the net gallery: the studio's "Net → Generate" for the bundled queen.

Run ``python bench/bench_gallery.py [--nets N] [--sheet A4] [--runs R] [--pieces one|auto]``.  It builds
the queen from ``recipes/chess/queen.toml``, compiles the net kernels once (numba's cache; not timed),
then times :func:`voxfab.fabricate.netdraw.net_gallery` at the default face size (the smallest with
legible marks) and the studio's defaults (5 s per net), split into

* the search and validation (distinct nets by :func:`voxfab.unfold.unfold_many`, each fitted to the
  sheet and refolded by :func:`voxfab.unfold.validate`),
* the page's JSON (LAYOUT and PLACEMENT of every net, :func:`voxfab.fabricate.netdraw.gallery_json`),

and, for comparison, the face-by-face validation of the same nets (what validating cost before the
whole-array check of sound nets).
Goal: 8 queen nets in at most 3 s on the 2-core machine.
Medians over runs; on a shared, busy machine the figures move: say so when quoting them.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nets", type=int, default=8)
    ap.add_argument("--sheet", default="A4")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--pieces", default="one", choices=("one", "auto"))
    args = ap.parse_args()

    from voxfab.fabricate import netdraw
    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape
    from voxfab.unfold import _validate, unfold

    grid = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid
    unfold(grid, rng=0, timeout=300)  # compile or load the kernels: not part of a gallery
    net, drawing = netdraw.gallery_options({"sheet": args.sheet, "pieces": args.pieces},
                                           defaults={"timeout": 5.0, "budget": 180.0})
    rows = []
    for run in range(args.runs):
        t0 = time.perf_counter()
        gallery = netdraw.net_gallery(grid, net, drawing, count=args.nets, seed=run)
        t1 = time.perf_counter()
        body = json.dumps(netdraw.gallery_json(gallery, grid))
        t2 = time.perf_counter()
        for item in gallery.nets:
            _validate._check_piece_by_face(grid, _validate._exposed(grid), item.pieces[0], 0, {}, [], "")
        t3 = time.perf_counter()
        fits = sum(item.fit["fits"] for item in gallery.nets)
        rows.append((t1 - t0, t2 - t1, t2 - t0, t3 - t2))
        print(f"run {run + 1} (seed {run}): {len(gallery.nets)} nets, {fits} fit {args.sheet} at "
              f"{gallery.options.pitch:g} mm; search {t1 - t0:.2f} s, page JSON {t2 - t1:.2f} s "
              f"({len(body) / 1e6:.1f} MB), gallery {t2 - t0:.2f} s; face-by-face validation {t3 - t2:.2f} s")
    med = [statistics.median(col) for col in zip(*rows)]
    print(f"queen, {args.nets} nets on {args.sheet}, median of {args.runs}: gallery {med[2]:.2f} s "
          f"(search and validation {med[0]:.2f} s, JSON {med[1]:.2f} s); the face-by-face validation of the "
          f"same nets takes {med[3]:.2f} s")
    print("2-core machine shared with other jobs: figures are noisy")


if __name__ == "__main__":
    main()
