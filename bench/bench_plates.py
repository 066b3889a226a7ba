"""Benchmark: a 25³ shape to plates nested on sheets (DXF + SVG per sheet), without STEP.

Run ``python bench/bench_plates.py``.  The goal is under 2 s for the whole
path from voxels to written sheets.  "cold" is the first call in a fresh
process (lazy imports of shapely, scipy, rectpack and ezdxf included);
"warm" is the median of the following runs (three; one with ``--smoke``).
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

from voxfab.fabricate.plates import (
    make_plates,
    make_report,
    nest_plates,
    write_assembly_pdf,
    write_dxf,
    write_svg,
)
from voxfab.shape import VoxelShape, examples

GOAL_S = 2.0
RUNS = 3


def to_sheets(shape: VoxelShape, folder: Path, *, thickness: float) -> dict[str, float]:
    """Run the pipeline once; return the seconds of each stage."""
    times: dict[str, float] = {}
    t0 = time.perf_counter()
    stack = make_plates(shape.grid, pitch=shape.pitch, thickness=thickness)
    t1 = time.perf_counter()
    sheets = nest_plates(stack.plates, sheet="600x400", margin=5, spacing=2, kerf=0.15)
    make_report(stack, sheets, kerf=0.15)
    t2 = time.perf_counter()
    for sheet in sheets:
        write_dxf(sheet, folder / f"sheet-{sheet.index:02d}.dxf")
        write_svg(sheet, folder / f"sheet-{sheet.index:02d}.svg")
    t3 = time.perf_counter()
    times.update(plates=t1 - t0, nest=t2 - t1, write=t3 - t2, total=t3 - t0)
    times["n_plates"] = len(stack.plates)
    times["n_sheets"] = len(sheets)
    times["n_dowels"] = len(stack.dowels)
    return times


def main() -> None:
    warm_runs = 1 if "--smoke" in sys.argv[1:] else RUNS
    shape = VoxelShape(examples.random_shape(1), 3.0)
    print(f"shape: random_shape(1), {'x'.join(map(str, shape.grid.shape))}, {shape.volume} voxels, pitch 3 mm")
    print(f"{'case':<28}{'plates':>8}{'sheets':>8}{'dowels':>8}{'slice s':>9}{'nest s':>8}{'write s':>9}{'total s':>9}  goal")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for thickness, name in ((3.0, "3 mm plates (1/layer)"), (1.0, "1 mm plates (3/layer)")):
            runs = [to_sheets(shape, folder, thickness=thickness) for _ in range(warm_runs + 1)]
            for label, rows in (("cold", runs[:1]), ("warm", runs[1:])):
                med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
                ok = "ok" if med["total"] < GOAL_S else "SLOW"
                print(
                    f"{name + ', ' + label:<28}{int(med['n_plates']):>8}{int(med['n_sheets']):>8}{int(med['n_dowels']):>8}"
                    f"{med['plates']:>9.3f}{med['nest']:>8.3f}{med['write']:>9.3f}{med['total']:>9.3f}  {ok} (< {GOAL_S} s)"
                )
        stack = make_plates(shape.grid, pitch=shape.pitch, thickness=3.0)
        t = time.perf_counter()
        write_assembly_pdf(stack, folder / "assembly.pdf")
        first = time.perf_counter() - t
        t = time.perf_counter()
        write_assembly_pdf(stack, folder / "assembly.pdf")
        print(f"assembly PDF (25 layers): {first:.3f} s first call (matplotlib import), {time.perf_counter() - t:.3f} s after")


if __name__ == "__main__":
    main()
