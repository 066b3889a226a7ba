"""Ctrl-C on a census running on a local Dask cluster: one line, and nothing of the cluster left behind.

A real process group stopped with SIGINT as a terminal's Ctrl-C does (the client
and every worker process get it), in a temporary folder of its own (TMPDIR); the
cluster listens on 127.0.0.1 only; every wait is bounded.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("distributed")

ROOT = Path(__file__).resolve().parents[2]


def _group_alive(pgid: int) -> list[str]:
    return subprocess.run(["pgrep", "-g", str(pgid)], capture_output=True, text=True).stdout.split()


def test_ctrl_c_on_a_dask_census_is_one_line_and_leaves_no_scratch_space(tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp), PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.Popen([sys.executable, "-m", "voxfab", "census", "8", "-o", str(tmp_path / "c"), "--workers",
                             "2"], cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        # The workers are censusing once their first nets are written.
        nets = tmp_path / "c" / "nets"
        end = time.monotonic() + 240
        while not (nets.is_dir() and any(nets.iterdir())):
            assert proc.poll() is None and time.monotonic() < end, proc.communicate(timeout=10)[1][-2000:]
            time.sleep(0.2)
        assert any(p.name.startswith(("voxfab-dask-", "dask-scratch-space")) for p in tmp.iterdir())
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(10)
    end = time.monotonic() + 20
    while _group_alive(proc.pid) and time.monotonic() < end:
        time.sleep(0.2)
    # One line saying what was saved, then the interrupt: no traceback, no worker's noise.
    lines = err.splitlines()
    assert proc.returncode == 130 and lines[-1] == "voxfab: interrupted", (proc.returncode, err[-3000:])
    assert len(lines) <= 2 and all(line.startswith("voxfab: ") for line in lines), err[-3000:]
    assert not _group_alive(proc.pid)
    assert list(tmp.iterdir()) == []
