"""Benchmark: drawing large nets, writing SVG, DXF and PDF, and the bundled recipes' paper nets.

Run: python bench/bench_netdraw.py [--recipes] [--smoke]
Goal: drawing a 3000-face net with tabs and numbers under 2 s (draw + SVG + DXF R12 + PDF).
Nets come from the net engine (voxfab.unfold.unfold); finding them is not timed in the first table.
With ``--recipes``, each bundled recipe's net output runs as a build would (search included), and
the text height and tab depth are measured back from the DXF file it wrote.
``--smoke``: a ball of radius 3, one run of each step, and the recipes' table for the pawn only.
"""

from __future__ import annotations

import functools
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from voxfab.fabricate.netdraw import DrawingOptions, draw_net, save_drawing
from voxfab.shape import examples


def timed(fn, *args, runs: int = 5, **kwargs) -> tuple[float, float]:
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn(*args, **kwargs)
        times.append(time.perf_counter() - t)
    return statistics.median(times), max(times)


def shapes(smoke: bool = False) -> list[tuple[str, np.ndarray]]:
    # Digital balls are the net engine's hard family; r = 13 gives 3174 faces.
    radii = (3,) if smoke else (12, 13)
    return [(f"ball r={r}", examples.ball(r)) for r in radii]


def bench_one(name: str, grid: np.ndarray, net, tmp: Path, runs: int = 5) -> None:
    # 11 mm faces carry 2 mm seam labels of up to four characters; the sheet is a large laser bed.
    opts = DrawingOptions(pitch=11.0, sheet="2500x2500")
    opts2k = DrawingOptions(pitch=11.0, sheet="2500x2500", dxf_version="R2000")
    d = draw_net(grid, net, options=opts, name=name)
    t_draw = timed(draw_net, grid, net, options=opts, name=name, runs=runs)
    t = {ext: timed(save_drawing, d, tmp / f"n.{ext}", opts, runs=runs) for ext in ("svg", "dxf", "pdf")}
    t["dxf2k"] = timed(save_drawing, d, tmp / "n2k.dxf", opts2k, runs=1)
    total = t_draw[0] + t["svg"][0] + t["dxf"][0] + t["pdf"][0]
    print(f"{name:<14}{net.face_count:>7}{d.seams:>7}{int(d.tab_seams.sum()):>6}"
          f"{net.seams_without_tab_room:>7}{len(d.sheets):>7}"
          f"{t_draw[0]:>9.3f}{t['svg'][0]:>8.3f}{t['dxf'][0]:>9.3f}{t['dxf2k'][0]:>9.3f}"
          f"{t['pdf'][0]:>8.3f}{total:>9.3f}")


def _layers(path: Path) -> dict[str, list[np.ndarray]]:
    import ezdxf

    out: dict[str, list[np.ndarray]] = {}
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "LINE":
            pts = np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
        elif e.dxftype() == "LWPOLYLINE":
            pts = np.array([tuple(p)[:2] for p in e.get_points("xy")])
            pts = np.vstack([pts, pts[:1]]) if e.closed else pts
        else:
            pts = np.array([tuple(v.dxf.location)[:2] for v in e.vertices])
            pts = np.vstack([pts, pts[:1]]) if e.is_closed else pts
        out.setdefault(e.dxf.layer, []).append(pts)
    return out


def measured(path: Path, face: float) -> tuple[float, float]:
    """Median digit height and smallest tab depth in mm, read from a net's DXF."""
    import shapely

    layers = _layers(path)
    glyphs = shapely.union_all([shapely.LineString(p).buffer(0.01) for p in layers["LABEL"]])
    heights = [max(g.bounds[2] - g.bounds[0], g.bounds[3] - g.bounds[1]) - 0.02 for g in glyphs.geoms]
    rings = [shapely.Polygon(p) for p in layers["CUT"] if len(p) > 3 and np.allclose(p[0], p[-1])]
    # Even-odd: holes are rings inside rings.
    paper = functools.reduce(shapely.symmetric_difference, rings)
    depths = []
    for p in layers.get("MOUNTAIN", []) + layers.get("VALLEY", []):
        a, b = p[0], p[-1]
        n = np.linalg.norm(b - a) / face
        if abs(n - round(n)) < 1e-3:
            continue  # a fold between faces, not a tab's
        mid, d = (a + b) / 2, (b - a) / np.linalg.norm(b - a)
        ray = np.array([-d[1], d[0]]) * 2 * face
        hits = [paper.boundary.intersection(shapely.LineString([mid, mid + s * ray])) for s in (1, -1)]
        depths.append(min(shapely.Point(mid).distance(h) for h in hits if not h.is_empty))
    return float(np.median(heights)), float(min(depths)) if depths else 0.0


def bench_recipes(tmp: Path, only: str | None = None) -> None:
    from voxfab.fabricate import BuildContext, outputs
    from voxfab.recipe import load_recipe, make_shape

    kind = outputs()["net"]
    print(f"\n{'recipe':<18}{'faces':>7}{'face mm':>9}{'sheet':>10}{'pieces':>7}{'sheets':>7}{'fill %':>10}"
          f"{'text mm':>9}{'tab mm':>8}{'time s':>8}")
    for path in sorted((Path(__file__).parents[1] / "recipes").rglob("*.toml")):
        if only is not None and path.stem != only:
            continue
        recipe = load_recipe(path)
        spec = next((o for o in recipe.outputs if o.name == "net"), None)
        if spec is None:
            continue
        settings = kind.settings(dict(spec.options))
        settings = type(settings)(settings.net.replace(formats=("dxf",)), settings.drawing)
        shape = make_shape(recipe)
        out = tmp / recipe.name
        out.mkdir()
        t = time.perf_counter()
        made = kind.run(shape, settings, out, name=recipe.name, seed=recipe.seed, context=BuildContext())
        elapsed = time.perf_counter() - t
        r = made.report
        text, tab = measured(out / made.files[-1].path, r["face_size_mm"])
        text_col = f"{text:.2f}" if settings.drawing.numbers else "off"
        fill = " ".join(f"{100 * f:.0f}" for f in r["sheet_fill"])
        print(f"{recipe.name:<18}{r['faces']:>7}{r['face_size_mm']:>9g}{settings.drawing.sheet:>10}{r['pieces']:>7}"
              f"{r['sheets']:>7}{fill:>10}{text_col:>9}{tab:>8.2f}{elapsed:>8.1f}")


def main() -> None:
    try:
        from voxfab.unfold import unfold
    except ImportError:
        sys.exit("bench_netdraw: the net engine (voxfab.unfold.unfold) is not available")
    print(f"{'shape':<14}{'faces':>7}{'seams':>7}{'tabs':>6}{'noroom':>7}{'sheets':>7}{'draw s':>9}{'svg s':>8}"
          f"{'dxf12 s':>9}{'dxf2k s':>9}{'pdf s':>8}{'total s':>9}")
    smoke = "--smoke" in sys.argv[1:]
    runs = 1 if smoke else 5
    with tempfile.TemporaryDirectory() as tmp:
        for name, grid in shapes(smoke):
            bench_one(name, grid, unfold(grid, rng=1), Path(tmp), runs)
        print("noroom: seams the engine left without tab room (they get a printed mark instead of a tab)")
        print(f"medians of {runs} runs (R2000: 1 run); 2-core machine shared with other jobs, figures are noisy")
        if "--recipes" in sys.argv[1:] or smoke:
            bench_recipes(Path(tmp), "pawn" if smoke else None)
            print("text: median digit height, tab: smallest tab depth, both measured in the DXF; time: one "
                  "run of the net output (search, draw, write)")


if __name__ == "__main__":
    main()
