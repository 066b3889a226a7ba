"""Benchmark: what colour costs a paper net, on the bundled queen painted in four colours.

Run: python bench/bench_colour_net.py [--smoke]
Goal: colour adds at most 10 % to ``voxfab net`` (search, validation, SVG and PDF written) on a
coloured queen, and nothing to an uncoloured one (the same grid with no colours takes the plain path).
Rows: the whole job (``net_files``, what ``voxfab net`` runs) on the uncoloured and the coloured queen,
then the drawing alone (the pieces found once: draw, SVG, PDF, PNG), where the colour work lives.
``--smoke``: a ball of radius 3 instead of the queen, one run each.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from voxfab.fabricate.netdraw import (
    DrawingOptions,
    NetOptions,
    draw_pieces,
    find_sheet_nets,
    net_files,
    save_drawing,
)
from voxfab.shape import VoxelShape, examples

#: Bands of colour up the shape, bottom to top (RGBA): a dark base, red, skin, a white crown.
BANDS = ((30, 40, 120, 255), (192, 48, 32, 255), (240, 190, 150, 255), (250, 250, 250, 255))


def painted(shape: VoxelShape) -> VoxelShape:
    """``shape`` in :data:`BANDS`, four equal bands of its height."""
    z = np.nonzero(shape.grid.any(axis=(0, 1)))[0]
    edges = np.linspace(z.min(), z.max() + 1, len(BANDS) + 1)
    zz = np.indices(shape.grid.shape)[2]
    for colour, lo in zip(BANDS, edges[:-1]):
        shape = shape.painted(colour, zz >= lo)
    return shape


def subject(smoke: bool) -> tuple[str, VoxelShape]:
    if smoke:
        return "ball r=3", VoxelShape(examples.ball(3), 1.0)
    from voxfab.recipe import load_recipe, make_shape

    shape = make_shape(load_recipe(Path(__file__).parents[1] / "recipes/chess/queen.toml"))
    return "queen", VoxelShape(shape.grid, shape.pitch)


def timed(plain, colour, runs: int) -> tuple[float, float]:  # noqa: ANN001
    """Fastest of ``runs`` runs of each, interleaved: load from other jobs on the machine hits both alike."""
    times: tuple[list[float], list[float]] = ([], [])
    for _ in range(runs):
        for fn, out in ((plain, times[0]), (colour, times[1])):
            t = time.perf_counter()
            fn()
            out.append(time.perf_counter() - t)
    return min(times[0]), min(times[1])


def main() -> None:
    smoke = "--smoke" in sys.argv[1:]
    runs = 1 if smoke else 5
    name, plain = subject(smoke)
    coloured = painted(plain)
    net = NetOptions(pieces="auto")
    drawing = DrawingOptions(pitch=10.0, sheet="A4")
    print(f"{'shape':<10}{'faces':>7}  {'step':<36}{'plain s':>9}{'colour s':>10}{'added %':>9}")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)

        def job(shape: VoxelShape, tag: str) -> None:
            net_files(shape, net, drawing, [folder / f"{tag}.svg", folder / f"{tag}.pdf"], title=name, seed=1)

        job(coloured, "warm")  # imports and first-call costs out of the figures
        t_plain, t_colour = timed(lambda: job(plain, "plain"), lambda: job(coloured, "colour"), runs)
        faces = plain.exposed_faces
        print(f"{name:<10}{faces:>7}  {'voxfab net (search + files)':<36}{t_plain:>9.3f}{t_colour:>10.3f}"
              f"{100 * (t_colour / t_plain - 1):>9.1f}")
        pieces = find_sheet_nets(plain.grid, drawing, rng=1, pieces="auto").nets[0]

        def draw(shape: VoxelShape, tag: str) -> None:
            d = draw_pieces(shape, pieces, options=drawing, name=name)
            for ext in ("svg", "pdf", "png"):
                save_drawing(d, folder / f"d-{tag}.{ext}", drawing)

        d_plain, d_colour = timed(lambda: draw(plain, "plain"), lambda: draw(coloured, "colour"), runs)
        print(f"{name:<10}{faces:>7}  {'drawing alone (draw + svg pdf png)':<36}{d_plain:>9.3f}{d_colour:>10.3f}"
              f"{100 * (d_colour / d_plain - 1):>9.1f}")
    print(f"fastest of {runs} interleaved runs; faces {drawing.pitch:g} mm on {drawing.sheet}, pieces auto, seed 1; 2-core "
          "machine shared with other jobs, figures are noisy")


if __name__ == "__main__":
    main()
