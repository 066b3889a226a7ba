"""Every way of stopping ``voxfab studio`` removes what it made; the next studio clears what a dead one left.

Real processes on 127.0.0.1, each with its own temporary folder (TMPDIR), stopped
with SIGINT as a terminal's Ctrl-C would; every wait is bounded.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

from voxfab.shape import examples
from voxfab.studio._grid import centred, pack

from .conftest import start_studio


def _studio(folder: Path, tmp: Path) -> tuple[subprocess.Popen, str]:
    """``voxfab studio`` with TMPDIR=tmp, once it answers (the warm-up has just begun)."""
    return start_studio(folder, "--host", "127.0.0.1", tmpdir=tmp, apart=True)


def _interrupt(proc: subprocess.Popen, sig: int = signal.SIGINT) -> tuple[str, str]:
    """Ctrl-C (or another signal), and what the studio printed; it must end within 20 s."""
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
        raise AssertionError(f"still running 20 s after Ctrl-C: {proc.communicate()[1][-2000:]}") from None
    return out, err


def _json(url: str, body: dict | None = None) -> dict:
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(url, data=data, headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=30) as r:
        return json.loads(r.read())


def test_ctrl_c_after_a_finished_fits_job_stops_and_cleans_up(tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    proc, url = _studio(tmp_path, tmp)
    try:
        job = _json(f"{url}/api/fits", {"grid": pack(centred(examples.ball(2))),
                                         "options": {"sheet": "A4", "timeout": 10}})["job"]
        end = time.monotonic() + 120
        while (state := _json(f"{url}/api/jobs/{job}"))["state"] in ("queued", "running"):
            assert time.monotonic() < end, state
            time.sleep(0.1)
        assert state["state"] == "done" and state["result"]["answer"] == "yes", state
        assert any(p.name.startswith("voxfab-studio-") for p in tmp.iterdir())
    finally:
        out, err = _interrupt(proc)
    # Ended by its own hand (not killed by the signal), saying so, its folders gone.
    assert proc.returncode == 0 and "voxfab studio: stopped" in out, (proc.returncode, out, err[-2000:])
    assert list(tmp.iterdir()) == []


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_stopping_during_the_warm_up_leaves_no_folder(tmp_path, sig):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    proc, _ = _studio(tmp_path, tmp)
    try:
        # The warm-up compiles (or loads) kernel after kernel for seconds after the server answers;
        # its first group's scratch folder appears at once.
        end = time.monotonic() + 30
        while not list(tmp.rglob("voxfab-warmup-*")) and time.monotonic() < end:
            time.sleep(0.02)
        assert list(tmp.rglob("voxfab-warmup-*")), sorted(p.name for p in tmp.rglob("*"))
    finally:
        out, err = _interrupt(proc, sig)
    assert proc.returncode == 0 and "voxfab studio: stopped" in out, (proc.returncode, out, err[-2000:])
    assert list(tmp.iterdir()) == []


def test_the_next_studio_clears_what_dead_ones_left_and_only_that(tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True,
                          timeout=30)
    dead_pid = int(gone.stdout)
    dead = tmp / f"voxfab-studio-{dead_pid}-abc123"
    (dead / "jobs" / "0123456789abcdef").mkdir(parents=True)
    (dead / "jobs" / "0123456789abcdef" / "net.svg").write_text("<svg/>")
    alive = tmp / f"voxfab-studio-{os.getpid()}-def456"  # this test's own process runs: kept
    alive.mkdir()
    other = tmp / "voxfab-studio-notes"  # not a session's name: kept
    other.mkdir()
    proc, _ = _studio(tmp_path, tmp)
    try:
        assert not dead.exists()
        assert alive.is_dir() and other.is_dir()
    finally:
        out, _ = _interrupt(proc)
    assert "voxfab studio: stopped" in out
    assert sorted(p.name for p in tmp.iterdir()) == sorted([alive.name, other.name])
