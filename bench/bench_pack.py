"""Benchmark: the bundled recipes' nets in pieces on the sheets makers own.

Run: python bench/bench_pack.py [SHEET ...] [--smoke]   (default: A4 Letter A3 mat12 laser; --smoke: the queen on A4)
Each recipe's shape (cavities filled) at 8.6 mm faces, the smallest with 2 mm labels and 3 mm tabs,
with ``pieces="auto"``, as a new user runs it.  Goal per net: at most ceil(1.25 A / U) sheets, where A
is the paper (faces and tabs, measured from the drawing) and U a sheet less its margins (and title
band); no seam without a tab; at most 10 s for a 3000-face shape on A4.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

from voxfab.fabricate.netdraw import DrawingOptions, draw_net, draw_pieces, drawable_area, find_sheet_nets
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import fill_cavities

RECIPES = ["chess/queen", "chess/king", "chess/bishop", "spinning_top", "chess/pawn", "torus4d_slice", "egg",
           "chess/rook", "vase"]
FACE = 8.6


def row(name: str, grid, sheet: str) -> str:
    opts = DrawingOptions(pitch=FACE, sheet=sheet, label_height=2.0)
    t = time.perf_counter()
    found = find_sheet_nets(grid, opts, rng=1, pieces="auto", fill=True, timeout=60.0)
    nets = found.nets[0]
    d = draw_pieces(grid, nets, options=found.options) if len(nets) > 1 else draw_net(grid, nets[0],
                                                                                        options=found.options)
    elapsed = time.perf_counter() - t
    w, h = opts.sheet_size
    x0, y0, x1, y1 = drawable_area(opts)
    paper = sum(s.fill for s in d.sheets) * w * h
    usable = (x1 - x0) * (y1 - y0)
    bound = math.ceil(1.25 * paper / usable)
    fill = 100 * paper / (len(d.sheets) * usable)
    untabbed = int((~d.tab_seams & ~d.tab_elsewhere).sum())
    sizes = [n.face_count for n in nets]
    return (f"{name:<14}{sum(sizes):>7}{len(nets):>7}{len(d.sheets):>7}{bound:>7}{math.ceil(paper / usable):>7}"
            f"{fill:>7.0f}{untabbed:>8}{min(sizes) / max(sizes):>7.2f}{elapsed:>8.1f}")


def main() -> None:
    smoke = "--smoke" in sys.argv[1:]
    sheets = [a for a in sys.argv[1:] if a != "--smoke"] or (["A4"] if smoke else ["A4", "Letter", "A3", "mat12", "laser"])
    root = Path(__file__).parents[1] / "recipes"
    grids = []
    for r in ["chess/queen"] if smoke else RECIPES:
        recipe = load_recipe(root / f"{r}.toml")
        grids.append((recipe.name, fill_cavities(make_shape(recipe).grid)))
    for sheet in sheets:
        print(f"\nsheet {sheet}, faces {FACE} mm")
        print(f"{'shape':<14}{'faces':>7}{'pieces':>7}{'sheets':>7}{'bound':>7}{'area':>7}{'fill%':>7}"
              f"{'no tab':>8}{'small':>7}{'time s':>8}")
        for name, grid in grids:
            print(row(name, grid, sheet), flush=True)
    print("bound: ceil(1.25 A / U); area: ceil(A / U); fill: A over the sheets' usable area; small: the smallest "
          "piece over the largest; time: search and drawing (2-core machine shared with others, noisy)")


if __name__ == "__main__":
    main()
