"""The smoke runs of the scripts in ``bench/``, shared by the test files that run them.

Each bench starts as a subprocess (``python bench/NAME.py --smoke``) and goes through its whole path on the
smallest real inputs, printing its table.  The runs are split over two test files, so that pytest-xdist (a
file per worker) puts half on each worker; a file run on its own starts two at a time, one per core.
"""

from __future__ import annotations

import concurrent.futures
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BENCHES = sorted(p.name for p in (ROOT / "bench").glob("bench_*.py"))
#: The two halves, one a test file; every other bench in name order, so both hold slow and quick ones.
HALVES = (BENCHES[0::2], BENCHES[1::2])
#: Seconds one smoke run may take on a loaded 2-core machine; a smoke run takes a few seconds alone.
SMOKE_TIMEOUT = 300

Run = subprocess.CompletedProcess[str] | str


def _smoke(name: str) -> Run:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    try:
        return subprocess.run([sys.executable, str(ROOT / "bench" / name), "--smoke"], capture_output=True,
                              text=True, cwd=ROOT, env=env, timeout=SMOKE_TIMEOUT, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired as exc:
        return f"over {SMOKE_TIMEOUT} s; its output so far:\n{exc.stdout or ''}\n{exc.stderr or ''}"


def smoke_all(names: list[str]) -> dict[str, Run]:
    """The smoke runs of ``names``: one at a time under pytest-xdist (the other worker has the other core), else
    two at a time."""
    at_once = 1 if int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1")) > 1 else 2
    with concurrent.futures.ThreadPoolExecutor(max_workers=at_once) as pool:
        return dict(zip(names, pool.map(_smoke, names)))


def check_smoke(name: str, run: Run) -> None:
    """The run exited 0 with no traceback and printed a table: a header and at least one row of figures."""
    assert not isinstance(run, str), f"{name} --smoke: {run}"
    assert run.returncode == 0, f"{name} --smoke exited {run.returncode}:\n{run.stdout[-3000:]}\n{run.stderr[-3000:]}"
    assert "Traceback" not in run.stderr, run.stderr[-3000:]
    lines = [line for line in run.stdout.splitlines() if line.strip()]
    assert len(lines) >= 2 and any(ch.isdigit() for ch in "".join(lines[1:])), run.stdout
