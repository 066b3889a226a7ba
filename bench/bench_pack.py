"""Benchmark: nets in pieces on the sheets makers own, side by side with the peer (Blender's Export Paper Model).

Run: python bench/bench_pack.py [--sheets A4,Letter,mat12] [--shapes queen,ball,torus,pawn,egg,...] [--no-peer]
     [--repeat N] [--smoke] [--save [FOLDER]]
(--smoke: the queen on A4, without the peer; --save: keep the table as docs/data/bench/pack.json.)

Each shape (cavities filled: a bundled recipe, or the ball and the torus of ``bench_density``) at 8.6 mm faces,
the smallest with 2 mm labels and 3 mm tabs, made as a new user makes it:
``voxfab net SHAPE.npy --pieces auto --sheet S --face-size 8.6 -o net.pdf``, timed as a whole process
(start-up and imports included, the modules' bytecode cached as an installed package has it).  Beside it,
when ``blender`` is on the PATH, the peer: Blender's Export Paper Model add-on on the same surface (one
quad per voxel face), the same sheet, margin and face size, also timed as a whole process (:mod:`_peer`).
Each side runs once untimed first (caches filled), then the two run one after the other for each row
(``--repeat N``: N times each, alternately, medians printed), so both see the same load on the shared
machine; CPU time (user + system of the process and its children) is printed beside the wall time, as it
is the steadier of the two.

The target per net: at most half the peer's whole process time (wall; the CPU ratio beside it) on fewer
pages.  Then at most ceil(1.25 A / U) pages, A the paper (faces and tabs, measured from the drawing) and
U a sheet less its margins and title band.  Goals to measure, not tests.
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
from _table import Table, add_save_option  # noqa: E402
from bench_density import shapes as density_shapes  # noqa: E402

RECIPES = {"queen": "chess/queen", "king": "chess/king", "bishop": "chess/bishop", "spinning_top": "spinning_top",
           "pawn": "chess/pawn", "torus4d_slice": "torus4d_slice", "egg": "egg", "rook": "chess/rook",
           "vase": "vase"}
#: Shapes made by code, not recipes (``bench_density``'s makers).
MADE = ("ball", "torus")
#: The target's shapes: the default run.
TARGET = "queen,ball,torus"
FACE = 8.6
#: The target: voxfab's whole process at most this share of the peer's, on fewer pages.
RATIO = 0.5
ROOT = Path(__file__).parents[1]


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def voxfab_run(shape: Path, sheet: str, out: Path) -> tuple[dict, float, float]:
    """``voxfab net`` as a user runs it: its JSON summary, wall and CPU seconds."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    # An installed package has its modules' bytecode cached (pip writes it), as Blender's Python has.
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    cmd = [sys.executable, "-m", "voxfab", "net", str(shape), "--pieces", "auto", "--sheet", sheet,
           "--face-size", f"{FACE:g}", "--label-height", "2", "-o", str(out / "net.pdf")]
    cpu, t = _children_cpu(), time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    wall, cpu = time.perf_counter() - t, _children_cpu() - cpu
    if done.returncode != 0:
        raise SystemExit(f"voxfab net failed on {shape}: {done.stderr.strip().splitlines()[-1:]}")
    return json.loads(done.stdout)["nets"][0], wall, cpu


def measure(grid: np.ndarray, sheet: str, peer: bool, repeat: int = 1) -> dict:
    """voxfab's and the peer's runs on ``grid``, ``repeat`` times each, alternately: the figures of a row."""
    from voxfab.fabricate.netdraw import DrawingOptions, drawable_area

    opts = DrawingOptions(pitch=FACE, sheet=sheet, label_height=2.0)
    peer = peer and sheet in PEER_SHEETS
    with tempfile.TemporaryDirectory(prefix="voxfab-bench-") as tmp:
        d = Path(tmp)
        np.save(d / "shape.npy", grid)
        runs, peer_runs = [], []
        for _ in range(repeat):  # alternately, so that both see the same load
            runs.append(voxfab_run(d / "shape.npy", sheet, d))
            if peer:
                cpu0 = _children_cpu()
                p = run_peer(grid, FACE, sheet)
                peer_runs.append((p, _children_cpu() - cpu0))
    got = runs[0][0]
    w, h = opts.sheet_size
    x0, y0, x1, y1 = drawable_area(opts)
    usable = (x1 - x0) * (y1 - y0)
    paper = sum(got["fill"]) * w * h
    m = {"faces": got["faces"], "pieces": got["pieces"], "pages": len(got["fill"]),
         "bound": math.ceil(1.25 * paper / usable), "fill": 100 * paper / (len(got["fill"]) * usable),
         "no_tab": got["seams_without_tab_room"],
         "wall": float(np.median([r[1] for r in runs])), "cpu": float(np.median([r[2] for r in runs]))}
    if peer_runs:
        m.update(peer_pages=peer_runs[0][0].pages, peer_error=peer_runs[0][0].error,
                 peer_wall=float(np.median([q.seconds for q, _ in peer_runs])),
                 peer_cpu=float(np.median([c for _, c in peer_runs])))
    return m


COLUMNS = ["shape", "sheet", "faces", "pieces", "pages", "bound", "fill", "no tab", "wall", "CPU",
           "peer pages", "peer wall", "peer CPU", "wall ratio", "CPU ratio", "target"]


def cells(name: str, sheet: str, m: dict) -> list[str]:
    """A row of the table: voxfab's figures, the peer's, their ratios, and whether the target is met."""
    row = [name, sheet, m["faces"], m["pieces"], m["pages"], m["bound"], f"{m['fill']:.0f} %", m["no_tab"],
           f"{m['wall']:.1f} s", f"{m['cpu']:.1f} s"]
    if "peer_pages" not in m:
        return [*row, "", "", "", "", "", "no peer"]
    if not m["peer_pages"]:
        return [*row, f"failed: {m['peer_error']}", "", "", "", "", "no peer"]
    wall, cpu = m["wall"] / m["peer_wall"], m["cpu"] / m["peer_cpu"]
    missed = [f"time {wall:.2f}x"] if wall > RATIO else []
    missed += ["pages"] if m["pages"] >= m["peer_pages"] else []
    return [*row, m["peer_pages"], f"{m['peer_wall']:.1f} s", f"{m['peer_cpu']:.1f} s", f"{wall:.2f}x",
            f"{cpu:.2f}x", "met" if not missed else "missed: " + ", ".join(missed)]


def shape_grids(names: list[str]) -> list[tuple[str, np.ndarray]]:
    """Each shape's grid, cavities filled."""
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import fill_cavities

    made = density_shapes()
    grids = []
    for name in names:
        if name in MADE:
            grid = np.asarray(made[name](), dtype=bool)
        else:
            grid = make_shape(load_recipe(ROOT / "recipes" / f"{RECIPES[name]}.toml")).grid
        grids.append((name, fill_cavities(grid)))
    return grids


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sheets", default="A4")
    ap.add_argument("--shapes", default=TARGET, help=f"of {', '.join([*RECIPES, *MADE])}")
    ap.add_argument("--no-peer", action="store_true", help="leave the peer out even when blender is installed")
    ap.add_argument("--repeat", type=int, default=1, help="runs of each side, alternately; the medians are printed")
    ap.add_argument("--smoke", action="store_true", help="the queen on A4 without the peer: the whole path in seconds")
    add_save_option(ap)
    args = ap.parse_args()
    if args.smoke:
        args.sheets, args.shapes, args.no_peer = "A4", "queen", True
    unknown = sorted(set(args.shapes.split(",")) - set(RECIPES) - set(MADE))
    if unknown:
        ap.error(f"--shapes: no shape named {', '.join(unknown)}")
    peer = peer_available() and not args.no_peer
    grids = shape_grids(args.shapes.split(","))
    sheets = args.sheets.split(",")
    if not args.smoke:  # once untimed each: the compiled kernels, the bytecode and the disk caches warm
        measure(grids[0][1], sheets[0], peer)
    why = "" if peer else " (without the peer: --no-peer)" if args.no_peer else " (no peer: blender is not on the PATH)"
    print(f"faces {FACE} mm{why}")
    table = Table("pack", COLUMNS)
    for sheet in sheets:
        for name, grid in grids:
            table.row(*cells(name, sheet, measure(grid, sheet, peer, max(args.repeat, 1))))
    print(f"bound: ceil(1.25 A / U); fill: A over the pages' usable area; no tab: seams without room for a tab; "
          f"wall and CPU: the whole process (start-up included), medians of {max(args.repeat, 1)}, on a 2-core "
          f"machine shared with others; target: at most {RATIO}x the peer's wall time, on fewer pages")
    table.save(args.save)


if __name__ == "__main__":
    main()
