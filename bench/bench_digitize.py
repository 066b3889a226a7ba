"""Benchmarks of the shape makers (voxfab.digitize).

Run ``python bench/bench_digitize.py``. Each heavy case runs in its own
subprocess so that its peak RSS (``resource.ru_maxrss``) is its own; a second
run of the same case under ``tracemalloc`` gives the peak of traced (numpy)
allocations. Figures are wall-clock times on whatever machine runs it: noisy
on a shared machine.

Targets: every maker at 25³ under 50 ms after import; a surface of revolution
at 256³ under 3 s and 2 GB; a tube with a 1000-point spine at 128³ under 5 s.

``--smoke`` times each recipe's maker once and runs one revolution and one tube
case at 32³, each in its two subprocesses, in a few seconds.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RECIPES = ROOT / "recipes"


def _trefoil(n: int = 1000):
    import numpy as np

    s = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.stack([np.sin(s) + 2 * np.sin(2 * s), np.cos(s) - 2 * np.cos(2 * s), -np.sin(3 * s)], axis=1)


#: The heavy cases, named KIND_PARAM_SIDE_MODE (see :func:`_case`); ``--smoke`` runs two at 32³.
CASES = (
    "revolution_runs_256_scale", "revolution_runs_256_fit", "revolution_region_256_scale", "revolution_region_256_fit",
    "tube_1000_128_scale", "tube_1000_128_fit",
)
SMOKE_CASES = ("revolution_runs_32_scale", "tube_200_32_fit")


def _case(name: str):
    """Return a zero-argument callable running one heavy case (``KIND_PARAM_SIDE_MODE``)."""
    from voxfab.digitize import revolution, revolution_field, tube

    queen = dict(curve="x^2 + y^2 - 1", generatrix="queen_generatrix.svg", base_dir=RECIPES / "chess")
    region = dict(curve="x^2 + y^2 - 1", generatrix="(x - 2)^2 + y^2 - 1")

    def scale_for(kw, side):
        fld = revolution_field(kw["curve"], kw["generatrix"], base_dir=kw.get("base_dir"))
        return (side - 4) / float(max(fld.hi - fld.lo))

    kind, param, side_text, fit = name.split("_")
    side = int(side_text)
    if kind == "tube":
        scale = None if fit == "fit" else (side - 4) / 7.3
        return lambda: tube(_trefoil(int(param)), radius=0.4, size=side, scale=scale)
    kw = queen if param == "runs" else region
    scale = None if fit == "fit" else scale_for(kw, side)
    return lambda: revolution(**kw, size=side, mode="surface", scale=scale)


def run_case(name: str, trace: bool) -> dict:
    import resource
    import tracemalloc

    import numpy as np

    import voxfab.digitize  # noqa: F401  - import cost is not part of the figure

    fn = _case(name)
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    if trace:
        tracemalloc.start()
    t = time.perf_counter()
    grid = fn()
    dt = time.perf_counter() - t
    out = {"case": name, "seconds": dt, "voxels": int(np.count_nonzero(grid)), "shape": list(grid.shape)}
    if trace:
        out["traced_peak_mb"] = tracemalloc.get_traced_memory()[1] / 2**20
    else:
        out["rss_peak_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        out["rss_after_import_mb"] = base / 1024
    return out


def makers_25(runs: int = 5) -> list[tuple[str, str, float, float]]:
    from voxfab.digitize import get_maker

    rows = []
    for path in sorted(RECIPES.rglob("*.toml")):
        params = dict(tomllib.loads(path.read_text(encoding="utf-8"))["source"])
        if "maker" not in params:
            continue  # a shape drawn in a file (the swordsman): no maker to time
        maker_name = params.pop("maker")
        maker = get_maker(maker_name)
        t = time.perf_counter()
        maker(base_dir=path.parent, **params)
        first = time.perf_counter() - t
        times = []
        for _ in range(runs):
            t = time.perf_counter()
            maker(base_dir=path.parent, **params)
            times.append(time.perf_counter() - t)
        rows.append((path.stem, maker_name, first, statistics.median(times)))
    return rows


def main() -> None:
    if len(sys.argv) == 3 and sys.argv[1] == "--case":
        print(json.dumps(run_case(sys.argv[2], trace=False)))
        return
    if len(sys.argv) == 3 and sys.argv[1] == "--trace":
        print(json.dumps(run_case(sys.argv[2], trace=True)))
        return
    smoke = "--smoke" in sys.argv[1:]
    runs = 1 if smoke else 5
    t = time.perf_counter()
    import voxfab.digitize  # noqa: F401

    print(f"import voxfab.digitize: {1000 * (time.perf_counter() - t):.0f} ms\n")
    print(f"{'recipe (25³)':22s} {'maker':11s} {'first call':>11s} {f'median of {runs}':>12s}")
    for stem, maker, first, med in makers_25(runs):
        flag = "" if med < 0.05 else "  (over 50 ms)"
        print(f"{stem:22s} {maker:11s} {1000 * first:9.1f} ms {1000 * med:9.1f} ms{flag}")
    print()
    print(f"{'case':30s} {'seconds':>8s} {'peak RSS':>10s} {'traced peak':>12s} {'voxels':>9s}")
    for name in SMOKE_CASES if smoke else CASES:
        res = json.loads(subprocess.run(
            [sys.executable, __file__, "--case", name], check=True, capture_output=True, text=True
        ).stdout)
        tr = json.loads(subprocess.run(
            [sys.executable, __file__, "--trace", name], check=True, capture_output=True, text=True
        ).stdout)
        print(
            f"{name:30s} {res['seconds']:8.2f} {res['rss_peak_mb']:7.0f} MB {tr['traced_peak_mb']:9.0f} MB "
            f"{res['voxels']:9d}"
        )


if __name__ == "__main__":
    main()
