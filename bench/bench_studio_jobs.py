"""Benchmark of the studio's jobs: how soon Cancel stops a net search, and how soon Ctrl-C stops the server.

Run ``python bench/bench_studio_jobs.py [--runs N] [--smoke]`` (``--smoke``: one run).  Each run starts a real ``voxfab studio`` on
127.0.0.1, fills both workers with galleries of the queen (12 nets each, a third waiting) and:

* cancel: POST ``/api/jobs/ID/cancel`` on a running gallery at a random moment of its search, then
  polls ``/api/jobs/ID`` every 5 ms until it says ``cancelled`` (the round trips are in the figure);
* Ctrl-C: sends SIGINT (once, then twice 50 ms apart) and times the process's exit.

Goals (issue 20): a cancelled search stops within about 1 s; the server within 2 s of Ctrl-C.
Medians and maxima over runs; on a shared, busy machine the figures move: say so when quoting them.
"""

from __future__ import annotations

import argparse
import os
import random
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench_studio import _get, _post  # the same small HTTP client

ROOT = Path(__file__).resolve().parents[1]


def _start(folder: Path) -> tuple[subprocess.Popen, str]:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.Popen([sys.executable, "-m", "voxfab", "studio", "--port", str(port), "--repo",
                             str(folder / "repo.sqlite"), "--no-browser"], env=env, cwd=folder,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    end = time.monotonic() + 60
    while True:
        try:
            _get(f"{url}/api/info")
            return proc, url
        except OSError:
            if proc.poll() is not None or time.monotonic() > end:
                proc.kill()
                raise SystemExit("the studio did not start") from None
            time.sleep(0.1)


def _busy(url: str, body: dict) -> list[str]:
    """Three galleries (two run, one waits); returns their ids once the first has found a net."""
    ids = [_post(f"{url}/api/nets", dict(body, seed=s))["job"] for s in range(3)]
    end = time.monotonic() + 120
    while _get(f"{url}/api/jobs/{ids[0]}")["done"] < 1 and time.monotonic() < end:
        time.sleep(0.05)
    return ids


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--smoke", action="store_true", help="one run")
    args = parser.parse_args()
    if args.smoke:
        args.runs = 1
    sys.path.insert(0, str(ROOT))
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.studio import pack

    queen = make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid
    body = {"grid": pack(queen), "count": 12, "options": {"timeout": 30.0}}
    if args.smoke:
        # In pieces: a one-piece queen net on A4 ends in an error when no compact one is found in time
        # (a loaded machine), and the run needs a search under way to cancel.
        body["options"]["pieces"] = "auto"
    rng = random.Random(0)
    cancel, stop = [], {1: [], 2: []}
    with tempfile.TemporaryDirectory() as tmp:
        for run in range(args.runs):
            for presses in (1, 2):
                proc, url = _start(Path(tmp))
                try:
                    ids = _busy(url, body)
                    if presses == 1:  # one cancel per run, on a search under way
                        time.sleep(rng.uniform(0.2, 2.0))
                        t0 = time.monotonic()
                        _post(f"{url}/api/jobs/{ids[1]}/cancel", {})
                        while (job := _get(f"{url}/api/jobs/{ids[1]}"))["state"] != "cancelled":
                            if job["state"] not in ("queued", "running") or time.monotonic() - t0 > 60:
                                raise SystemExit(f"the cancelled gallery ended {job['state']!r}, not cancelled: "
                                                 f"{job.get('message', '')}")
                            time.sleep(0.005)
                        cancel.append(time.monotonic() - t0)
                    t0 = time.monotonic()
                    for _ in range(presses):
                        proc.send_signal(signal.SIGINT)
                        time.sleep(0.05)
                    proc.wait(30)
                    stop[presses].append(time.monotonic() - t0)
                finally:
                    if proc.poll() is None:
                        proc.kill()
                        proc.wait(5)
            print(f"run {run + 1}: cancel {1000 * cancel[-1]:.0f} ms; Ctrl-C {stop[1][-1]:.2f} s, "
                  f"twice {stop[2][-1]:.2f} s", flush=True)

    def ms(xs: list[float]) -> str:
        return f"median {1000 * statistics.median(xs):.0f} ms, max {1000 * max(xs):.0f} ms"

    print(f"cancel of a running queen gallery: {ms(cancel)} over {len(cancel)} runs (goal about 1 s)")
    print(f"stop after Ctrl-C with 2 galleries running, 1 queued: {ms(stop[1])}; "
          f"after Ctrl-C twice: {ms(stop[2])} (goal 2 s)")


if __name__ == "__main__":
    main()
