"""Benchmark of ``voxfab batch``: shapes per minute with 1 and 2 workers, memory per worker.

Run ``python bench/bench_batch.py [--shapes N]``.  It explores N growth shapes into a
fresh repository (the explore rate is printed too) and builds them twice, on a
local Dask cluster of 1 and then of 2 worker processes, with the outputs of
``--outputs`` (default: an STL mesh, a paper net and the pictures) plus the index.
Each worker's peak memory (resident set) is sampled through the scheduler.  The
first tasks of a fresh worker pay its imports and numba cache loads, as a real run
does.  On a shared, busy machine the figures move: say so when quoting them.
"""

from __future__ import annotations

import argparse
import tempfile
import threading
import time
from pathlib import Path

DEFAULT_OUTPUTS = """\
pitch = 2.0
seed = 1

[outputs.mesh]
format = "stl"

[outputs.net]
formats = ["svg"]
face_size = 11.0  # mm: paper faces that carry 2 mm seam labels (8.6 mm would do) and 3 mm tabs
sheet = "A1"
fill = true
pieces = "auto"

[outputs.pictures]
"""


def _batch(repo: Path, outputs: Path, out: Path, workers: int) -> tuple[float, int, float, float]:
    """Run one batch; return (seconds, shapes built, peak memory MB of the busiest worker, task seconds)."""
    from distributed import LocalCluster

    import voxfab.batch._run as run

    peaks: dict[str, float] = {}
    stop = threading.Event()
    connect = run._connect

    def sample(client: object) -> None:
        while not stop.wait(0.5):
            try:
                info = client.scheduler_info()["workers"]  # type: ignore[attr-defined]
            except Exception:  # noqa: BLE001 - the cluster is closing
                return
            for address, w in info.items():
                mb = w.get("metrics", {}).get("memory", 0) / 1e6
                peaks[address] = max(peaks.get(address, 0.0), mb)

    def connect_and_sample(*args: object, **kwargs: object) -> object:
        cl = connect(*args, **kwargs)  # type: ignore[arg-type]
        threading.Thread(target=sample, args=(cl.client,), daemon=True).start()
        return cl

    assert LocalCluster  # imported here so the timing excludes the import of distributed
    run._connect = connect_and_sample  # type: ignore[assignment]
    try:
        report = run.run_batch(repo, outputs, out, workers=workers, dashboard=None)
    finally:
        stop.set()
        run._connect = connect
    import json

    tasks = json.loads((out / "batch.json").read_text())["shapes"].values()
    busy = sum(t["seconds"] for t in tasks)
    return report.seconds, report.built, max(peaks.values(), default=0.0), busy


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shapes", type=int, default=40, help="shapes per batch")
    parser.add_argument("--outputs", type=Path, help="outputs file (default: mesh STL, net SVG, pictures)")
    parser.add_argument("--volume", default="40:300", help="volume range of the explored shapes")
    args = parser.parse_args()

    from voxfab.generate import explore, parse_volume_range
    from voxfab.repo import Repository

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        outputs = args.outputs or root / "outputs.toml"
        if args.outputs is None:
            outputs.write_text(DEFAULT_OUTPUTS)
        with Repository(root / "r.sqlite") as repo:
            t = time.perf_counter()
            explore(repo, args.shapes, seed=1, volume=parse_volume_range(args.volume))
            print(f"explore: {args.shapes} shapes in {time.perf_counter() - t:.2f} s")
        rates = {}
        for workers in (1, 2):
            seconds, built, peak, busy = _batch(root / "r.sqlite", outputs, root / f"out{workers}", workers)
            rates[workers] = 60.0 * built / seconds
            # Task seconds over wall seconds: how many builds ran at once on average.
            print(f"{workers} worker(s): {built} shapes in {seconds:.1f} s = {rates[workers]:.1f} shapes/min; "
                  f"{busy / built:.2f} s per task; {busy / seconds:.2f} tasks at once; "
                  f"peak worker memory {peak:.0f} MB")
        print(f"scaling 2 workers / 1 worker: {rates[2] / rates[1]:.2f} (2 cores, shared with other work)")


if __name__ == "__main__":
    main()
