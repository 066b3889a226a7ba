"""Benchmark: what colour costs a print, on the chess queen painted by expressions.

Run ``python bench/bench_colour_print.py [--smoke]``.  The queen recipe's shape is
painted in four colours by recipe ``paint`` operations (a black foot, a red
waist, a gold crown column over a beige body), then printed to 3MF:

* ``voxfab mesh`` wall time (interpreter start and imports included), the
  uncoloured queen's ``shape.npz`` against the coloured one's, runs interleaved;
* the print pipeline in process (:func:`fabricate_mesh`: build, check, write
  the 3MF and mesh.json), best of many runs, both ways.

Goal (issue 47, item 4): colour adds at most 10 % to ``voxfab mesh`` on the
coloured queen, and nothing on an uncoloured shape (whose code path is the one
it had: ``colours`` is None all the way).  ``--smoke`` runs each figure once
(after a warm-up call).
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAINT = """
[[operations]]
op = "paint"
colour = "#f0e0c0"
[[operations]]
op = "paint"
colour = "#c03020"
where = "(z - 9) * (z - 13)"
[[operations]]
op = "paint"
colour = "#d0a020"
where = "max((x - 12)^2 + (y - 12)^2 - 6, 17 - z)"
[[operations]]
op = "paint"
colour = "#202020"
where = "z - 2"
"""


def queens(folder: Path) -> tuple[Path, Path]:
    """``shape.npz`` of the queen and of the painted queen (the recipe with paint operations added)."""
    from voxfab import io
    from voxfab.recipe import load_recipe, make_shape

    recipe = (ROOT / "recipes" / "chess" / "queen.toml").read_text()
    source = ROOT / "recipes" / "chess" / "queen_generatrix.svg"
    painted = recipe.replace('generatrix = "queen_generatrix.svg"', f'generatrix = "{source.as_posix()}"')
    painted = painted.split("[outputs.mesh]")[0] + PAINT
    (folder / "painted.toml").write_text(painted)
    plain = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml"))
    coloured = make_shape(load_recipe(folder / "painted.toml", allow_outside=True))
    assert coloured.colours is not None and coloured.colours.count == 4
    assert (coloured.grid == plain.grid).all()
    io.write(plain, folder / "plain.npz")
    io.write(coloured, folder / "coloured.npz")
    return folder / "plain.npz", folder / "coloured.npz"


def command_times(plain: Path, coloured: Path, runs: int) -> dict[str, float]:
    """Median wall time of ``voxfab mesh`` on each shape, runs interleaved so load falls on both alike."""
    times: dict[str, list[float]] = {"plain": [], "coloured": []}
    for _ in range(runs):
        for key, path in (("plain", plain), ("coloured", coloured)):
            cmd = [sys.executable, "-m", "voxfab", "mesh", str(path), "-o", str(path.with_suffix(".3mf"))]
            t = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True)
            times[key].append(time.perf_counter() - t)
    return {k: statistics.median(v) for k, v in times.items()}


def pipeline_times(plain: Path, coloured: Path, runs: int) -> dict[str, float]:
    """Best in-process time of the print pipeline on each shape (interleaved)."""
    from voxfab import io
    from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh

    shapes = {"plain": io.read(plain).shape(), "coloured": io.read(coloured).shape()}
    times: dict[str, list[float]] = {k: [] for k in shapes}
    out = plain.parent / "pipeline"
    out.mkdir(exist_ok=True)
    for key, shape in shapes.items():  # warm-up: compiled kernels load on the first call
        fabricate_mesh(shape, MeshOptions(), out / f"{key}.3mf", name="queen", report_path=out / f"{key}.json")
    for _ in range(runs):
        for key, shape in shapes.items():
            t = time.perf_counter()
            fabricate_mesh(shape, MeshOptions(), out / f"{key}.3mf", name="queen", report_path=out / f"{key}.json")
            times[key].append(time.perf_counter() - t)
    return {k: min(v) for k, v in times.items()}


def main() -> None:
    smoke = "--smoke" in sys.argv[1:]
    with tempfile.TemporaryDirectory() as tmp:
        plain, coloured = queens(Path(tmp))
        wall = command_times(plain, coloured, 1 if smoke else 9)
        inproc = pipeline_times(plain, coloured, 1 if smoke else 60)
    print(f"{'queen, 3MF':<34}{'uncoloured':>12}{'4 colours':>12}{'added':>9}")
    for label, fig, unit, scale in (("voxfab mesh, wall (median)", wall, "s", 1.0),
                                    ("fabricate_mesh in process (best)", inproc, "ms", 1000.0)):
        added = fig["coloured"] / fig["plain"] - 1
        print(f"{label:<34}{fig['plain'] * scale:>10.3f}{unit:>2}{fig['coloured'] * scale:>10.3f}{unit:>2}"
              f"{added * 100:>8.1f}%")
    verdict = "met" if wall["coloured"] <= 1.10 * wall["plain"] else "NOT met"
    print(f"goal: colour adds at most 10 % to voxfab mesh: {verdict}")


if __name__ == "__main__":
    main()
