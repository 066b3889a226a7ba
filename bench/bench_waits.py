"""Benchmark of where the artist waits (issue 46), in CPU seconds, before and after side by side.

Run ``python bench/bench_waits.py [--base DIR] [--runs R] [--smoke] [--save]``.  Each row is measured in
child processes, so a run of the tree under test and one of ``--base`` (a checkout of another commit,
e.g. ``git worktree add /tmp/base BASE``) alternate on the same loaded machine; the figure is the
CPU time (``time.process_time`` in the child, or the child's whole ``resource`` usage), not the
wall clock, which a shared 2-core machine stretches.  Rows, by the issue's target:

* **floor** (1): ``voxfab net`` on a one-voxel cube, to JSON and to SVG, whole processes.  Goal: 0.3 s.
* **hopeless sheet** (2): the queen in pieces on a 60 x 60 mm sheet, refused, whole process.  Goal: the
  floor and 0.2 s.
* **gallery**: the studio's "Net → Generate" for the queen (``recipes/chess/queen.toml``), 8 nets in
  pieces on A4 at 8.6 mm, ``--timeout`` (60 s) per net (:func:`voxfab.fabricate.netdraw.net_gallery`,
  after the kernels are loaded).  Goal: at most 7 s of CPU for all eight.
* **edit**: a cut of a fold (the cut-off side a piece of its own) in the queen's net of 34 flat pieces
  on A5, and the new layout and packing the studio sends (:func:`voxfab.unfold.cut_edge`,
  :func:`voxfab.fabricate.netdraw.fit_and_placement` from the net's placement before the cut, as the
  studio lays an edited net out, where the tree has that; ``net_layout``): median CPU of 5 cuts, and
  median and maximum of 5 joins of two pieces (:func:`voxfab.unfold.join_edge`; every 7th pair of
  pieces that meet, a refused join skipped).  Goal: at most 0.3 s from click to screen.
* **one piece**: :func:`voxfab.unfold.unfold` (default strategy, seed 0) on balls, a torus, blobs
  and a vase of up to about 2700 faces (``bench_unfold``'s corpus): median and maximum per shape,
  and the whole ``voxfab net`` process on the largest blob.  Goal: median under 0.7 s, maximum under 1.5 s.

``--smoke``: one run of the gallery with 2 nets and the one-piece row on two balls.  ``--save`` keeps the
table as ``docs/data/bench/waits.json`` for the documentation.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from _table import Table, add_save_option

ROOT = Path(__file__).resolve().parents[1]

_GALLERY = """
import json, sys, time
from voxfab.fabricate import netdraw
from voxfab.recipe import load_recipe, make_shape
from voxfab.studio import warm_gallery_here
from voxfab.unfold import unfold
grid = make_shape(load_recipe(sys.argv[1])).grid
unfold(grid, rng=0, timeout=300)
warm_gallery_here()
net, drawing = netdraw.gallery_options({"sheet": "A4", "pieces": "auto", "face_size": 8.6},
                                       defaults={"timeout": float(sys.argv[4]), "budget": 600.0})
c0 = time.process_time()
g = netdraw.net_gallery(grid, net, drawing, count=int(sys.argv[2]), seed=int(sys.argv[3]))
print(json.dumps({"cpu": time.process_time() - c0, "nets": len(g.nets),
                  "sheets": [n.fit["sheets"] for n in g.nets]}))
"""

_EDIT = """
import json, sys, time
from voxfab.fabricate import netdraw
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import surface_graph
from voxfab.errors import UnfoldError
from voxfab.fabricate.netdraw._geometry import face_map
from voxfab.unfold import cut_edge, join_edge, unfold
grid = make_shape(load_recipe(sys.argv[1])).grid
pieces = list(unfold(grid, rng=1, fit=(9, 9), pieces="flat", timeout=120))
net, drawing = netdraw.gallery_options({"sheet": "A5", "pieces": "auto", "face_size": 8.6})
graph = surface_graph(grid)
_, shown = netdraw.fit_and_placement(pieces, drawing, graph)
try:  # a tree that lays an edited net out from its placement before the edit
    from voxfab.fabricate.netdraw._placement import Placement
    from voxfab.fabricate.netdraw._relayout import relayout
    before = {"before": (pieces, Placement.from_dict(shown))}
except ImportError:
    before = {}
names = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y", (0, 0, 1): "+z", (0, 0, -1): "-z"}
name = lambda net, i: (*net.voxel[i].tolist(), names[tuple(net.normal[i].tolist())])
big = max(pieces, key=lambda n: n.face_count)
out = []
for t in range(int(sys.argv[2])):
    i, j = big.folds[(t * 37 + 5) % len(big.folds)].tolist()
    c0 = time.process_time()
    cut = cut_edge(grid, pieces, name(big, i), name(big, j), split=True)
    netdraw.fit_and_placement(list(cut.pieces), drawing, graph, **before)
    netdraw.net_layout(grid, list(cut.pieces), graph=graph)
    out.append(time.process_time() - c0)
# Joins of two pieces along the seams between them, in the surface's order, every 7th pair of pieces.
owner = {int(f): (p, k) for p, n in enumerate(pieces) for k, f in enumerate(face_map(graph, n))}
pairs = sorted({tuple(sorted((owner[f][0], owner[int(g)][0]))): (f, int(g)) for f in range(graph.face_count)
                for g in graph.neighbor[f] if owner[f][0] != owner[int(g)][0]}.items())
joined = []
for _, (f, g) in pairs[::7]:
    (pa, ka), (pb, kb) = owner[f], owner[g]
    c0 = time.process_time()
    try:
        edit = join_edge(grid, pieces, name(pieces[pa], ka), name(pieces[pb], kb))
    except UnfoldError:
        continue
    netdraw.fit_and_placement(list(edit.pieces), drawing, graph, **before)
    netdraw.net_layout(grid, list(edit.pieces), graph=graph)
    joined.append(time.process_time() - c0)
    if len(joined) == int(sys.argv[2]):
        break
print(json.dumps({"cpu": sorted(out)[len(out) // 2], "pieces": len(cut.pieces),
                  "join": sorted(joined)[len(joined) // 2], "join_max": max(joined)}))
"""

_ONE_PIECE = """
import json, sys, time
sys.path.insert(0, sys.argv[1])
from bench_unfold import corpus
from voxfab.shape import examples
from voxfab.unfold import unfold
unfold(examples.ball(4), rng=0)
only = sys.argv[2:]
out = {}
for name, grid in corpus():
    if only and name not in only:
        continue
    c0 = time.process_time()
    unfold(grid, rng=0)
    out[name] = time.process_time() - c0
print(json.dumps(out))
"""


def _child(code: str, args: list[str], path: Path) -> dict:
    env = dict(os.environ, PYTHONPATH=str(path))
    # From a neutral directory: ``python -c`` and ``-m`` put the working directory before PYTHONPATH.
    done = subprocess.run([sys.executable, "-c", code, *args], env=env, capture_output=True, text=True, check=True,
                          cwd=tempfile.gettempdir())
    return json.loads(done.stdout.strip().splitlines()[-1])


def _process_cpu(cmd: list[str], path: Path, *, check: bool = True) -> float:
    """CPU seconds (user and system) of a whole child process (``check``: it must succeed)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, env=dict(os.environ, PYTHONPATH=str(path)), check=check, capture_output=True,
                   cwd=tempfile.gettempdir())
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--base", type=Path, help="a checkout of the commit to compare with")
    ap.add_argument("--runs", type=int, default=3)
    # The studio gives each net 5 s of the clock; on a loaded machine that clock ends the joins early and the
    # CPU looks small.  A long timeout measures the CPU an idle machine spends before its 5 s run out.
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per gallery net")
    ap.add_argument("--smoke", action="store_true", help="one run, 2 gallery nets, two balls")
    add_save_option(ap)
    args = ap.parse_args()
    nets, shapes = (2, ["ball r=4", "ball r=6"]) if args.smoke else (8, [])
    if args.smoke:
        args.runs = 1
    trees = [("after", ROOT)] + ([("before", args.base.resolve())] if args.base else [])
    queen = str(ROOT / "recipes" / "chess" / "queen.toml")

    gallery: dict[str, list[float]] = {name: [] for name, _ in trees}
    for run in range(args.runs):
        for name, path in trees:
            got = _child(_GALLERY, [queen, str(nets), str(run), str(args.timeout)], path)
            gallery[name].append(got["cpu"])
            print(f"gallery run {run + 1} ({name}, seed {run}): {got['nets']} nets, sheets {got['sheets']}, "
                  f"{got['cpu']:.2f} s CPU", flush=True)
    edit: dict[str, dict] = {}
    for name, path in trees:
        edit[name] = _child(_EDIT, [queen, "1" if args.smoke else "5"], path)
    one: dict[str, dict[str, float]] = {}
    for name, path in trees:
        one[name] = _child(_ONE_PIECE, [str(ROOT / "bench"), *shapes], path)
    cli: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        import numpy as np

        from voxfab.shape import examples

        shape = Path(tmp) / "blob.npy"
        np.save(shape, examples.ball(4) if args.smoke else examples.random_shape(1, side=18, fill=0.3))
        for name, path in trees:
            cmd = [sys.executable, "-m", "voxfab", "net", str(shape), "-o", str(Path(tmp) / f"{name}.json")]
            _process_cpu(cmd, path)  # numba's cache filled for this tree
            cli[name] = statistics.median(_process_cpu(cmd, path) for _ in range(args.runs))

    floor: dict[str, float] = {}
    drawn: dict[str, float] = {}
    hopeless: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        import numpy as np

        from voxfab.recipe import load_recipe, make_shape

        cube, queen_npy = Path(tmp) / "cube.npy", Path(tmp) / "queen.npy"
        np.save(cube, np.ones((1, 1, 1), dtype=bool))
        np.save(queen_npy, make_shape(load_recipe(queen)).grid)
        for name, path in trees:
            floor_cmd = [sys.executable, "-m", "voxfab", "net", str(cube), "-o", str(Path(tmp) / f"{name}-cube.json")]
            drawn_cmd = [*floor_cmd[:-1], str(Path(tmp) / f"{name}-cube.svg")]
            refused = [sys.executable, "-m", "voxfab", "net", str(queen_npy), "--pieces", "auto", "--sheet", "60x60",
                       "-o", str(Path(tmp) / f"{name}-q.pdf")]
            _process_cpu(floor_cmd, path)  # bytecode and numba's cache written for this tree
            floor[name] = statistics.median(_process_cpu(floor_cmd, path) for _ in range(args.runs))
            drawn[name] = statistics.median(_process_cpu(drawn_cmd, path) for _ in range(args.runs))
            hopeless[name] = statistics.median(_process_cpu(refused, path, check=False) for _ in range(args.runs))

    cols = [name for name, _ in trees]
    table = Table("waits", ["target", "row (CPU s)", *cols, "goal"])
    table.row(1, "`voxfab net` on a cube to JSON, whole process", *(f"{floor[c]:.2f}" for c in cols), "<= 0.3 s")
    table.row(1, "`voxfab net` on a cube to SVG, whole process", *(f"{drawn[c]:.2f}" for c in cols), "<= 0.3 s")
    table.row(2, "queen on a 60 x 60 sheet in pieces: refused, whole process",
              *(f"{hopeless[c]:.2f}" for c in cols), "floor + 0.2 s")
    table.row(3, f"gallery: {nets} queen nets in pieces, A4 (median of runs)",
              *(f"{statistics.median(gallery[c]):.2f}" for c in cols), "<= 7 s")
    table.row(4, f"edit: cut + re-layout, {edit[cols[0]]['pieces']} queen pieces, A5",
              *(f"{edit[c]['cpu']:.2f}" for c in cols), "<= 0.3 s")
    table.row(4, "edit: join of two pieces + re-layout (median, max)",
              *(f"{edit[c].get('join', float('nan')):.2f}, {edit[c].get('join_max', float('nan')):.2f}" for c in cols),
              "<= 0.3 s")
    table.row(6, f"one piece: `unfold` median, max of {len(one[cols[0]])} shapes",
              *(f"{statistics.median(one[c].values()):.2f}, {max(one[c].values()):.2f}" for c in cols),
              "< 0.7 s, < 1.5 s")
    table.row(6, "one piece: `voxfab net` on an 18-voxel blob, whole process", *(f"{cli[c]:.2f}" for c in cols), "")
    table.save(args.save)
    print("CPU seconds of child processes (a shared 2-core machine stretches the wall clock); target 5 is "
          "bench_pack.py's, target 7 bench_density.py's.")

if __name__ == "__main__":
    main()
