"""Benchmark: how densely nets in pieces fill their sheets, cut by flat patches, as bands and as large pieces, side by side.

Run: python bench/bench_density.py [--sheet A4] [--face-size 8.6] [--shapes queen,ball,torus,blob,vase,column]
[--smoke] [--save]
(--smoke: the ball alone; --save: the table kept as docs/data/bench/density.json for the documentation.)

Each shape (cavities filled) is cut as ``voxfab net SHAPE --pieces auto --sheet A4 --face-size 8.6``
cuts it, in the box of the sheet's cells: once from flat patches (``pieces="flat"``), once as bands
round the shape (``pieces="bands"``: straight strips of the rows of faces across an axis, stacked where
they line up), once as the few large pieces of ``pieces="auto"``, then as the pipeline cuts it by default
(the flat patches or the bands, whichever packs on fewer sheets, its last sheet then emptied into the gaps
of the others when that saves a sheet: :func:`voxfab.fabricate.netdraw._nesting.nest_last_sheet`).  Each cut is refolded
(:func:`voxfab.unfold.validate`) and packed as the drawing packs them (:func:`sheets_needed`).  Per cut:
the sheets, the fill (paper of faces and tabs over the sheets' usable area), the pieces, the seams (cut
edges glued shut) and those without room for a tab, and the seconds the cut took.  ``nest`` is what
that last step changed: sheets, pieces and seams of the default against the better of the flat and band cuts
(packed as the pipeline ranks them).  ``goal`` is
``ceil(1.25 A / U)`` of the flat cut, A the paper and U a sheet's drawable area.  A goal to measure,
not a test.

Measured (A4, 8.6 mm; default sheets before -> after the last sheet is emptied): queen 3 -> 3, ball 3 -> 3,
torus 4 -> 4, blob 5 -> 5, vase 15 -> 14 (+11 pieces, +95 seams), column 3 -> 3; on A5 the torus 9 -> 8.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
from _table import Table, add_save_option

ROOT = Path(__file__).parents[1]
CUTS = ("flat", "bands", "auto", "default")


def _blob() -> np.ndarray:
    """Three overlapping balls of different sizes: a lumpy solid with no flat side to speak of."""
    x, y, z = np.ogrid[:25, :25, :25]
    g = np.zeros((25, 25, 25), dtype=bool)
    for (cx, cy, cz), r in (((10, 11, 9), 6.5), ((15, 13, 14), 5.5), ((9, 14, 16), 4.5)):
        g |= (x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2 <= r * r
    return g


def _column() -> np.ndarray:
    """A round column 20 voxels high: a wall that goes straight on, the bands' best case."""
    x, y, z = np.ogrid[:25, :25, :25]
    return ((x - 12) ** 2 + (y - 12) ** 2 <= 36) & (z >= 2) & (z < 22)


def shapes() -> dict[str, object]:
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import examples

    return {"queen": lambda: make_shape(load_recipe(ROOT / "recipes/chess/queen.toml")).grid,
            "ball": lambda: examples.ball(7),
            "torus": lambda: examples.torus(7.0, 3.0),
            "blob": _blob,
            "vase": lambda: make_shape(load_recipe(ROOT / "recipes/vase.toml")).grid,
            "column": _column}


def measure(grid: np.ndarray, cut: str, face: float, sheet: str, seed: int = 0) -> dict[str, float]:
    """One cut of ``grid`` packed on ``sheet``: sheets, goal, fill, pieces, seams, untabbed, seconds.

    ``cut`` "default" is the cut ``voxfab net --pieces auto`` makes (:func:`find_sheet_nets`); "flat",
    "bands" and "auto" are :func:`voxfab.unfold.unfold`'s, in a box of the sheet's cells less a face for the tabs.
    """
    from voxfab.fabricate.netdraw import DrawingOptions, draw_pieces, drawable_area, find_sheet_nets
    from voxfab.unfold import unfold, validate

    opts = DrawingOptions(pitch=face, sheet=sheet, label_height=2.0)
    x0, y0, x1, y1 = drawable_area(opts)
    t = time.perf_counter()
    if cut == "default":
        pieces = list(find_sheet_nets(grid, opts, rng=seed, pieces="auto").nets[0])
    else:
        fit = (max(1, int((x1 - x0) // face) - 1), max(1, int((y1 - y0) // face) - 1))
        pieces = list(unfold(grid, rng=seed, fit=fit, pieces=cut, timeout=60.0))
    seconds = time.perf_counter() - t
    validate(grid, pieces if len(pieces) > 1 else pieces[0])
    faces = sum(p.face_count for p in pieces)
    # Each face has four edges; a fold joins two of them inside a piece, a seam two across a cut.
    seams = (4 * faces - 2 * sum(len(p.folds) for p in pieces)) // 2
    untabbed = sum(int(p.seams_without_tab_room) for p in pieces)
    count = len(draw_pieces(grid, pieces, options=opts).sheets)
    # The paper: the faces, and a 3 mm tab of about three quarters of a face's edge per tabbed seam.
    paper = faces * face * face + (seams - untabbed) * 0.75 * face * 3.0
    usable = (x1 - x0) * (y1 - y0)
    return {"sheets": count, "goal": math.ceil(1.25 * paper / usable), "fill": 100 * paper / (count * usable),
            "pieces": len(pieces), "seams": seams, "untabbed": untabbed, "seconds": seconds, "faces": faces}


def main() -> None:
    from voxfab.shape import fill_cavities

    makers = shapes()
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sheet", default="A4")
    ap.add_argument("--face-size", type=float, default=8.6)
    ap.add_argument("--shapes", default=",".join(makers), help=f"of {', '.join(makers)}")
    ap.add_argument("--smoke", action="store_true", help="the ball alone: the whole path in seconds")
    add_save_option(ap)
    args = ap.parse_args()
    names = ["ball"] if args.smoke else args.shapes.split(",")
    print(f"sheet {args.sheet}, faces {args.face_size:g} mm; per cut: sheets (fill %), pieces, seams, seams without "
          f"tab room, seconds to cut")
    table = Table("density", ["shape", "faces", "goal", *CUTS, "nest: sheets / pieces / seams"])
    for name in names:
        grid = fill_cavities(np.asarray(makers[name](), dtype=bool))
        got = [measure(grid, cut, args.face_size, args.sheet) for cut in CUTS]
        cut = min(got[:2], key=lambda m: (m["sheets"], m["untabbed"], m["seams"]))
        table.row(name, got[0]["faces"], got[0]["goal"], *(_cell(m) for m in got),
                  " / ".join(f"{got[3][k] - cut[k]:+d}" for k in ("sheets", "pieces", "seams")))
    table.save(args.save)
    print("goal: ceil(1.25 A / U) of the flat cut; fill: faces and tabs over the sheets' usable area")


def _cell(m: dict[str, float]) -> str:
    """One cut in a cell: sheets (fill), pieces, seams, seams without tab room (when any), seconds."""
    untabbed = f", {m['untabbed']} untabbed" if m["untabbed"] else ""
    return f"{m['sheets']} ({m['fill']:.0f} %), {m['pieces']} pcs, {m['seams']} seams{untabbed}, {m['seconds']:.0f} s"

if __name__ == "__main__":
    main()
