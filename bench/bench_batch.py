"""Benchmark of ``voxfab batch``: shapes per minute with 1 and 2 workers, and where the time goes.

Run ``python bench/bench_batch.py [--shapes N] [--source explore|recipes] [--smoke]``.

* ``explore`` (the census, default): N growth shapes explored into a fresh repository (the explore
  rate is printed too);
* ``recipes``: the bundled recipes' shapes, stored in a fresh repository.

Each set is built twice with :func:`voxfab.batch.run_batch`, on a local Dask cluster of 1 and then
of 2 worker processes, with the outputs of ``--outputs`` (default: an STL mesh, a paper net and the
pictures) plus the index.  A fresh cluster's workers pay their imports and numba cache loads in their
first task, as a real run does (kernels missing from numba's cache are compiled first, untimed).
The bench uses only the library's public names and measures the rest from outside: the time to
the ``on_start`` callback (checks and cluster start), the outcomes as they arrive (the task's own
seconds, the worker that built it), the time after the last outcome (cluster stop, index), and
every worker process's resident memory (psutil, sampled).

Columns of the breakdown, in seconds of wall time:

* ``start``: options checked, repository read and the cluster started (``on_start``);
* ``tasks``: first outcome sent to last outcome back;
* ``idle``: the workers' time in that span not spent in a task (dispatch, a short last round);
* ``first``: the extra time of each worker's first task over the median task (imports, numba caches);
* ``end``: cluster stop, ``batch.json`` and the index after the last outcome;

and in CPU seconds (psutil): ``cpu wrk`` the worker processes, ``client`` this process (the client, and
the local cluster's scheduler and nannies).  CPU seconds do not depend on the machine's
load as wall seconds do.

``--smoke`` runs the whole path on 2 small explored shapes (mesh only, no index) in a few seconds.
On a shared, busy machine the figures move: the load average is printed, say so when quoting them.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import statistics
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

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

SMOKE_OUTPUTS = 'pitch = 2.0\nseed = 1\n\n[outputs.mesh]\nformat = "stl"\n'


@dataclasses.dataclass(frozen=True)
class Run:
    """One batch run, timed from outside."""

    workers: int
    built: int
    wall: float
    start: float
    tasks: float
    end: float
    busy: float
    idle: float
    first_extra: float
    median_task: float
    peak_mb: float
    cpu: dict[str, float]

    @property
    def rate(self) -> float:
        return 60.0 * self.built / self.wall


class ProcessSampler:
    """Every process below this one, sampled every 0.2 s: peak resident memory and CPU seconds by role.

    A local cluster's scheduler and nannies run in this process with the client; each nanny starts
    its worker as a child process.  Other children (multiprocessing's resource tracker) are helpers.
    """

    def __init__(self) -> None:
        import psutil

        self._me = psutil.Process()
        self._own = self._cpu(self._me)
        self.peak_mb = 0.0
        self._cpu_by_pid: dict[int, tuple[str, float]] = {}
        self._roles: dict[int, str] = {}
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, daemon=True)

    @staticmethod
    def _cpu(process: object) -> float:
        t = process.cpu_times()  # type: ignore[attr-defined]
        return t.user + t.system

    def _sample(self) -> None:
        import psutil

        for child in self._me.children(recursive=True):
            try:
                if child.pid not in self._roles:  # the command line once per process: psutil reads /proc
                    self._roles[child.pid] = "helper" if "resource_tracker" in " ".join(child.cmdline()) else "worker"
                role = self._roles[child.pid]
                self._cpu_by_pid[child.pid] = (role, self._cpu(child))
                if role == "worker":
                    self.peak_mb = max(self.peak_mb, child.memory_info().rss / 1e6)
            except psutil.Error:  # a process that ended between the listing and the read
                continue

    def _loop(self) -> None:
        while not self._stop.wait(0.2):
            self._sample()

    def cpu(self) -> dict[str, float]:
        """CPU seconds of the workers, the helpers, and this process (client, scheduler, nannies) so far."""
        out = {"worker": 0.0, "helper": 0.0}
        for role, seconds in self._cpu_by_pid.values():
            out[role] += seconds
        out["client"] = self._cpu(self._me) - self._own
        return out

    def __enter__(self) -> ProcessSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


def batch_run(repo: Path, outputs: Path, out: Path, workers: int, index: bool) -> Run:
    """Run one batch on a fresh local cluster and time its parts from the callbacks."""
    from voxfab.batch import run_batch

    marks: dict[str, float] = {}
    arrivals: list[tuple[float, object]] = []

    def on_start(todo: int, skipped: int, link: str | None) -> None:
        marks["start"] = time.perf_counter()

    def on_outcome(outcome: object) -> None:
        arrivals.append((time.perf_counter(), outcome))

    with ProcessSampler() as sampler:
        t0 = time.perf_counter()
        report = run_batch(repo, outputs, out, workers=workers, dashboard=None, thumbnails=index,
                           on_start=on_start, on_outcome=on_outcome)
        t_end = time.perf_counter()
    cpu = sampler.cpu()
    if report.failed:
        raise SystemExit(f"{report.failed} shapes failed, first: {report.failures[0]}")
    outcomes = [o for _, o in arrivals]
    seconds = [o.seconds for o in outcomes]  # type: ignore[attr-defined]
    median = statistics.median(seconds)
    span = arrivals[-1][0] - marks["start"]
    per_worker: dict[str, list[float]] = {}
    for o in outcomes:
        per_worker.setdefault(o.worker, []).append(o.seconds)  # type: ignore[attr-defined]
    first_extra = statistics.mean(max(0.0, s[0] - median) for s in per_worker.values())
    busy = sum(seconds)
    return Run(workers, report.built, t_end - t0, marks["start"] - t0, span, t_end - arrivals[-1][0], busy,
               max(0.0, workers * span - busy) / workers, first_extra, median, sampler.peak_mb, cpu)


def fill_repository(path: Path, source: str, shapes: int, volume: str) -> str:
    """Store the shapes to build; return a line saying what was stored."""
    from voxfab.repo import Repository

    with Repository(path) as repo:
        if source == "explore":
            from voxfab.generate import explore, parse_volume_range

            t = time.perf_counter()
            explore(repo, shapes, seed=1, volume=parse_volume_range(volume))
            return f"explore: {shapes} shapes of volume {volume} in {time.perf_counter() - t:.2f} s"
        from voxfab.recipe import load_recipe, make_shape

        paths = sorted((ROOT / "recipes").rglob("*.toml"))[:shapes]
        for p in paths:
            repo.add(make_shape(load_recipe(p)).grid, symmetric=True)
        return f"recipes: {len(repo)} bundled recipes' shapes ({', '.join(p.stem for p in paths)})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shapes", type=int, default=40, help="shapes per batch (recipes: at most all of them)")
    parser.add_argument("--source", choices=("explore", "recipes"), default="explore",
                        help="explored growth shapes (the census) or the bundled recipes' shapes")
    parser.add_argument("--outputs", type=Path, help="outputs file (default: mesh STL, net SVG, pictures)")
    parser.add_argument("--volume", default="40:300", help="volume range of the explored shapes")
    parser.add_argument("--no-index", action="store_true", help="no thumbnails and no index page")
    parser.add_argument("--repeat", type=int, default=1, help="runs of each worker count, alternated")
    parser.add_argument("--smoke", action="store_true", help="2 small shapes, mesh only, no index: seconds")
    args = parser.parse_args()
    if args.smoke:
        args.shapes, args.volume, args.no_index = 2, "25:30", True

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        outputs = args.outputs or root / "outputs.toml"
        if args.outputs is None:
            outputs.write_text(SMOKE_OUTPUTS if args.smoke else DEFAULT_OUTPUTS)
        print(fill_repository(root / "r.sqlite", args.source, args.shapes, args.volume))
        from voxfab.warmup import GROUPS, is_compiled, warm_up

        # A real run finds the kernels in numba's cache (`voxfab warmup`): compile any missing, untimed.  The
        # smoke run's outputs (a mesh) call the print kernels alone; its explore compiled the makers' already.
        cold = [g for g in (["print"] if args.smoke else GROUPS) if not is_compiled(g)]
        if cold:
            t = time.perf_counter()
            warm_up(cold)
            print(f"warm-up (not timed): compiled {', '.join(cold)} in {time.perf_counter() - t:.1f} s")
        print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())} on {os.cpu_count()} cores")
        print(f"{'workers':>7} {'shapes':>6} {'wall s':>7} {'shapes/min':>10} {'start':>6} {'tasks':>6} "
              f"{'idle':>6} {'first':>6} {'end':>6} {'task med':>8} {'busy s':>7} {'at once':>7} {'peak MB':>7} "
              f"{'cpu wrk':>7} {'client':>6}")
        rates: dict[int, list[float]] = {1: [], 2: []}
        spans: dict[int, list[float]] = {1: [], 2: []}
        for i in range(args.repeat):
            for workers in (1, 2):  # alternated, so a change of the machine's load hits both alike
                r = batch_run(root / "r.sqlite", outputs, root / f"out{workers}-{i}", workers, not args.no_index)
                rates[workers].append(r.rate)
                spans[workers].append(r.tasks)
                # Task seconds over the tasks' span: how many builds ran at once on average.
                print(f"{workers:>7} {r.built:>6} {r.wall:>7.1f} {r.rate:>10.1f} {r.start:>6.2f} {r.tasks:>6.2f} "
                      f"{r.idle:>6.2f} {r.first_extra:>6.2f} {r.end:>6.2f} {r.median_task:>8.3f} {r.busy:>7.1f} "
                      f"{r.busy / r.tasks:>7.2f} {r.peak_mb:>7.0f} {r.cpu['worker']:>7.1f} {r.cpu['client']:>6.1f}",
                      flush=True)
        # Same inputs, same files: the two runs' manifests list the same files with the same sha256.
        built = sorted(p.name for p in (root / "out1-0").iterdir() if (p / "manifest.json").is_file())
        for name in built:
            files = [json.loads((root / f"out{w}-0" / name / "manifest.json").read_text())["files"] for w in (1, 2)]
            if files[0] != files[1]:
                raise SystemExit(f"{name}: the 1- and 2-worker runs wrote different files")
        med = {w: statistics.median(v) for w, v in rates.items()}
        print(f"scaling 2 workers / 1 worker: {med[2] / med[1]:.2f} (median of {args.repeat}); tasks alone "
              f"{statistics.median(spans[1]) / statistics.median(spans[2]):.2f}")
        print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())} (a shared machine: noisy)")


if __name__ == "__main__":
    main()
