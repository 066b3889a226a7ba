"""Benchmark: pictures of 25³ shapes (3D views, slice sheet, net, triptych, turntable).

Run: python bench/bench_render.py [--smoke]   (--smoke: 200 px pictures, two shapes, one run each, the nets of the small one)
Goals: a 25³ render under 1 s; a triptych under 3 s.
The triptych is timed drawing the net found once by the net engine
(``voxfab.unfold.unfold``, timed on its own row: its search time is the net
engine's budget, not rendering).
"""

from __future__ import annotations

import statistics
import sys
import time
from collections.abc import Callable

import numpy as np

from voxfab import render
from voxfab.shape import examples, exposed_faces


def timed(fn: Callable[[], object], runs: int) -> tuple[float, float]:
    fn()  # warm caches (font loading, first numpy allocations)
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), max(times)


def engine():  # noqa: ANN201 - the unfold function or None
    import voxfab.unfold as unfold

    return getattr(unfold, "unfold", None)


def main() -> None:
    smoke = "--smoke" in sys.argv[1:]
    px, runs, frames = (200, 1, 4) if smoke else (800, 5, 36)
    shapes = {
        "random 25^3 (seed 1)": examples.random_shape(1),
        "random 25^3 dense (seed 2)": examples.random_shape(2, fill=0.45),
        "ball r=12": examples.ball(12),
        "torus": examples.torus(9, 3.5),
        "vase": examples.vase(),
    }
    if smoke:
        shapes = {"random 25^3 (seed 1)": shapes["random 25^3 (seed 1)"], "ball r=4": examples.ball(4)}
    rows: list[tuple[str, str, float, float, str]] = []
    for label, g in shapes.items():
        info = f"{int(g.sum())} vox, {exposed_faces(g)} faces"
        med, worst = timed(lambda g=g: render.png_bytes(render.render(g, view="iso", size=px)), runs)
        rows.append((f"render iso {px}px + PNG: {label}", info, med, worst, "< 1 s"))
    g = shapes["random 25^3 (seed 1)"]
    med, worst = timed(lambda: render.render(g, view="z", size=px), runs)
    rows.append((f"render z {px}px: random 25^3", "", med, worst, "< 1 s"))
    med, worst = timed(lambda: render.slice_sheet(g, size=px), runs)
    rows.append((f"slice sheet {px}px: random 25^3", "", med, worst, ""))
    med, worst = timed(lambda: render.turntable_frames(g, frames=frames, size=px // 2), 1)
    rows.append((f"turntable {frames} x {px // 2}px: random 25^3", "", med, worst, ""))

    unfold = engine()
    if unfold is None:
        print("note: voxfab.unfold.unfold is not installed: the triptych is timed with the net panel's message")
    # The smoke run's nets: the small ball alone (unfolding the random 25^3 takes seconds).
    for label in ("ball r=4",) if smoke else ("random 25^3 (seed 1)", "ball r=12"):
        g = shapes[label]
        net = None
        if unfold is not None:
            t = time.perf_counter()
            net = unfold(g, rng=0)
            spent = time.perf_counter() - t
            rows.append((f"net engine unfold (once, not render): {label}", f"{net.face_count} faces", spent, spent,
                         ""))
            med, worst = timed(lambda g=g, net=net: render.net_picture(net, g, size=px), min(runs, 3))
            rows.append((f"net picture {px}px: {label}", f"{net.face_count} faces", med, worst, ""))

        def draw(g=g, net=net, label=label) -> None:
            img = render.triptych(g, name=label, net=net, rng=0, panel=px)
            render.png_bytes(img)
            render.pdf_bytes(img, title=label)

        med, worst = timed(draw, min(runs, 3))
        what = "given net" if net is not None else "no engine"
        rows.append((f"triptych 3x{px}px PNG+PDF ({what}): {label}", "", med, worst, "< 3 s"))

    width = max(len(r[0]) for r in rows)
    print(f"{'case':<{width}} {'shape':>24} {'median s':>9} {'max s':>7}  goal")
    for name, info, med, worst, goal in rows:
        print(f"{name:<{width}} {info:>24} {med:9.3f} {worst:7.3f}  {goal}")


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
