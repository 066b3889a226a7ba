"""Benchmark of the hunt over the Library: ``[outputs.hunt]`` over explored shapes on a local Dask cluster.

Run ``python bench/bench_hunt.py [--shapes N] [--workers W] [--zipper-timeout S]``.  It
explores N growth shapes of small volume (the smallest well-formed shapes span the
grid: 25 voxels, about 100 faces) into a fresh repository, then runs the batch of
``[outputs.hunt]`` on them: the random engine, the exact strategy on the shapes it
failed on, and the exact zipper search with a short time limit.  It prints the
outcomes (one-piece net found by the random engine, found only by the exact
strategy, proved none, undecided; zipper net found, proved none, undecided), the
faces, the time per search and the total time.  On a shared, busy machine the
times, and so the undecided counts, move: say so when quoting them.  ``--smoke``: 4 shapes on one
worker with 2 s budgets (0.5 s for the zipper).
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time
from pathlib import Path

from _table import Table, add_save_option


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shapes", type=int, default=2000, help="explored shapes to hunt")
    parser.add_argument("--volume", default="25:40", help="volume range of the explored shapes")
    parser.add_argument("--seed", type=int, default=0, help="explore seed")
    parser.add_argument("--workers", type=int, default=2, help="local Dask workers")
    parser.add_argument("--timeout", type=float, default=10.0, help="random engine's budget per shape, s")
    parser.add_argument("--exact-timeout", type=float, default=10.0, help="exact one-piece budget, s")
    parser.add_argument("--zipper-timeout", type=float, default=1.5, help="exact zipper budget per shape, s")
    parser.add_argument("--out", type=Path, help="keep the batch folder here (default: a temporary one)")
    parser.add_argument("--index", action="store_true", help="draw the thumbnails and write the index page")
    parser.add_argument("--smoke", action="store_true", help="4 shapes, 1 worker, short budgets")
    parser.add_argument("--label", help="the run's name in the saved table (default: its zipper limit)")
    add_save_option(parser)
    args = parser.parse_args()
    if args.smoke:
        args.shapes, args.workers, args.timeout, args.exact_timeout, args.zipper_timeout = 4, 1, 2.0, 2.0, 0.5

    from voxfab.batch import run_batch
    from voxfab.generate import explore, parse_volume_range
    from voxfab.repo import Repository

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        outputs = root / "hunt.toml"
        outputs.write_text(f"[outputs.hunt]\ntimeout = {args.timeout}\nexact_timeout = {args.exact_timeout}\n"
                           f"zipper_timeout = {args.zipper_timeout}\n")
        with Repository(root / "r.sqlite") as repo:
            t = time.perf_counter()
            explore(repo, args.shapes, seed=args.seed, volume=parse_volume_range(args.volume))
            print(f"explore: {args.shapes} shapes of volume {args.volume} in {time.perf_counter() - t:.1f} s",
                  flush=True)
        out = args.out or root / "out"
        t = time.perf_counter()
        report = run_batch(root / "r.sqlite", outputs, out, workers=args.workers, dashboard=None,
                           thumbnails=args.index)
        total = time.perf_counter() - t
        if report.hunt is None:
            raise SystemExit(f"no shape was hunted: {report.failed} failed ({report.failures[:1]})")
        records = [json.loads((out / n / "hunt.json").read_text()) for n in sorted(
            n for v in report.hunt.net.values() for n in v)]
        # Each task's time, from batch.json: the whole build of the shape's folder.
        tasks = [v["seconds"] for v in json.loads((out / "batch.json").read_text())["shapes"].values()
                 if v.get("status") == "built"]
    counts = report.hunt.counts()
    faces = [r["faces"] for r in records]
    net, zipper = counts["net"], counts["zipper"]
    print(f"hunted {report.hunt.shapes} shapes ({report.failed} failed), {min(faces)} to {max(faces)} faces "
          f"(median {statistics.median(faces):.0f}), on {report.workers} workers; zipper limit "
          f"{args.zipper_timeout:g} s")
    print(f"one-piece net: random engine {net['random']}, only exact {net['exact']}, proved none {net['none']}, "
          f"undecided {net['undecided']}")
    print(f"zipper net: found {zipper['found']}, proved none {zipper['none']}, undecided {zipper['undecided']}")
    print(f"total {total:.1f} s ({60 * report.hunt.shapes / total:.0f} shapes/min); per shape "
          f"{statistics.mean(tasks):.2f} s mean, {max(tasks):.2f} s max (the whole folder's build)")
    table = Table("hunt", ["run", "random engine", "only exact", "no net (proved)", "undecided", "zipper found",
                           "no zipper (proved)", "zipper undecided", "time"])
    table.row(args.label or f"zipper limit {args.zipper_timeout:g} s", net["random"], net["exact"], net["none"],
              net["undecided"], zipper["found"], zipper["none"], zipper["undecided"], f"{total:.0f} s")
    table.save(args.save, merge=True)


if __name__ == "__main__":
    main()
