"""Benchmark: the bundled recipes' nets in pieces on the sheets makers own, side by side with the peer.

Run: python bench/bench_pack.py [--sheets A4,Letter,mat12] [--shapes queen,pawn,egg,...] [--no-peer] [--smoke]
     [--repeat N]
(--smoke: the queen on A4, without the peer.)

Each recipe's shape (cavities filled) at 8.6 mm faces, the smallest with 2 mm labels and 3 mm tabs,
made as a new user makes it: ``voxfab net SHAPE.npy --pieces auto --sheet S --face-size 8.6 -o net.pdf``,
timed as a whole process (start-up and imports included).  Beside it, when ``blender`` is on the PATH,
the peer: Blender's Export Paper Model add-on on the same surface (one quad per voxel face), the same
sheet, margin and face size, also timed as a whole process (:mod:`_peer`).  The two run one after the
other for each row (``--repeat N``: N times each, alternately, medians printed), so both see the same
load on the shared machine; CPU time (user + system of the
process and its children) is printed beside the wall time, as it is the steadier of the two.

Goals per net: no more pages than the peer and no longer than the peer's whole process; then at most
ceil(1.25 A / U) pages, A the paper (faces and tabs, measured from the drawing) and U a sheet less its
margins and title band.  A goal to measure, not a test.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _peer import PEER_SHEETS, peer_available, run_peer  # noqa: E402

RECIPES = {"queen": "chess/queen", "king": "chess/king", "bishop": "chess/bishop", "spinning_top": "spinning_top",
           "pawn": "chess/pawn", "torus4d_slice": "torus4d_slice", "egg": "egg", "rook": "chess/rook",
           "vase": "vase"}
FACE = 8.6
ROOT = Path(__file__).parents[1]


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def voxfab_run(shape: Path, sheet: str, out: Path) -> tuple[dict, float, float]:
    """``voxfab net`` as a user runs it: its JSON summary, wall and CPU seconds."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    cmd = [sys.executable, "-m", "voxfab", "net", str(shape), "--pieces", "auto", "--sheet", sheet,
           "--face-size", f"{FACE:g}", "--label-height", "2", "-o", str(out / "net.pdf")]
    cpu, t = _children_cpu(), time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    wall, cpu = time.perf_counter() - t, _children_cpu() - cpu
    if done.returncode != 0:
        raise SystemExit(f"voxfab net failed on {shape}: {done.stderr.strip().splitlines()[-1:]}")
    return json.loads(done.stdout)["nets"][0], wall, cpu


def row(name: str, grid: np.ndarray, sheet: str, peer: bool, repeat: int = 1) -> str:
    from voxfab.fabricate.netdraw import DrawingOptions, drawable_area

    opts = DrawingOptions(pitch=FACE, sheet=sheet, label_height=2.0)
    with tempfile.TemporaryDirectory(prefix="voxfab-bench-") as tmp:
        d = Path(tmp)
        np.save(d / "shape.npy", grid)
        runs = []
        peer_runs = []
        for _ in range(repeat):  # alternately, so that both see the same load
            runs.append(voxfab_run(d / "shape.npy", sheet, d))
            if peer and sheet in PEER_SHEETS:
                cpu0 = _children_cpu()
                p = run_peer(grid, FACE, sheet)
                peer_runs.append((p, _children_cpu() - cpu0))
    got = runs[0][0]
    wall = float(np.median([r[1] for r in runs]))
    cpu = float(np.median([r[2] for r in runs]))
    w, h = opts.sheet_size
    x0, y0, x1, y1 = drawable_area(opts)
    usable = (x1 - x0) * (y1 - y0)
    pages = len(got["fill"])
    paper = sum(got["fill"]) * w * h
    text = (f"{name:<14}{got['faces']:>6}{got['pieces']:>7}{pages:>6}{math.ceil(1.25 * paper / usable):>6}"
            f"{100 * paper / (pages * usable):>6.0f}{got['seams_without_tab_room']:>7}{wall:>7.1f}{cpu:>6.1f}")
    if peer_runs:
        p = peer_runs[0][0]
        pwall = float(np.median([q.seconds for q, _ in peer_runs]))
        pcpu = float(np.median([c for _, c in peer_runs]))
        text += f"  {p.pages if p.pages else 'fail':>6}{pwall:>7.1f}{pcpu:>6.1f}" + (f"  {p.error}" if p.error else "")
    return text


def main() -> None:
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import fill_cavities

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sheets", default="A4,Letter,mat12")
    ap.add_argument("--shapes", default=",".join(RECIPES), help=f"of {', '.join(RECIPES)}")
    ap.add_argument("--no-peer", action="store_true", help="leave the peer out even when blender is installed")
    ap.add_argument("--repeat", type=int, default=1, help="runs of each side, alternately; the medians are printed")
    ap.add_argument("--smoke", action="store_true", help="the queen on A4 without the peer: the whole path in seconds")
    args = ap.parse_args()
    if args.smoke:
        args.sheets, args.shapes, args.no_peer = "A4", "queen", True
    peer = peer_available() and not args.no_peer
    grids = []
    for name in args.shapes.split(","):
        recipe = load_recipe(ROOT / "recipes" / f"{RECIPES[name]}.toml")
        grids.append((name, fill_cavities(make_shape(recipe).grid)))
    for sheet in args.sheets.split(","):
        print(f"\nsheet {sheet}, faces {FACE} mm" + ("" if peer else " (no peer: blender is not on the PATH)"))
        print(f"{'shape':<14}{'faces':>6}{'pieces':>7}{'pages':>6}{'bound':>6}{'fill%':>6}{'no tab':>7}{'wall s':>7}"
              f"{'cpu s':>6}" + (f"  {'peer pages':>6}{'wall s':>7}{'cpu s':>6}" if peer else ""))
        for name, grid in grids:
            print(row(name, grid, sheet, peer, max(args.repeat, 1)), flush=True)
    print("bound: ceil(1.25 A / U); fill: A over the pages' usable area; no tab: seams without room for a tab; "
          "wall and cpu: the whole process (start-up included), on a 2-core machine shared with others")


if __name__ == "__main__":
    main()
