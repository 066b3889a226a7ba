"""``voxfab census`` stopped by Ctrl-C: a real process and a real SIGINT, every wait bounded."""

from __future__ import annotations

import json
import selectors
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from voxfab.census import verify_census

#: Seconds from SIGINT to the census's line saying it stopped and saved what was done, at most.
_STOPS_WITHIN = 1.0
#: ... and to the process's end (the interpreter's own exit unloads numba, ortools and pandas).
_EXITS_WITHIN = 10.0


def _start(out: Path) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "voxfab", "census", "6", "-o", str(out), "--workers", "0"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


def _wait_for_searches(out: Path, proc: subprocess.Popen, deadline: float) -> None:
    """Until the first net file is written: the searches are under way."""
    while time.monotonic() < deadline:
        if (out / "nets").is_dir() and any((out / "nets").iterdir()):
            return
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.05)
    pytest.fail("the census wrote no net in 60 s")


@pytest.mark.parametrize("after", [0.1, 1.0, 3.0])
def test_ctrl_c_stops_a_serial_census_at_once_and_saves_what_is_done(tmp_path: Path, after: float) -> None:
    out = tmp_path / "c"
    proc = _start(out)
    try:
        _wait_for_searches(out, proc, time.monotonic() + 60)
        time.sleep(after)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        ready = selectors.DefaultSelector()
        ready.register(proc.stderr, selectors.EVENT_READ)
        assert ready.select(timeout=_EXITS_WITHIN), "no line after SIGINT"
        first = proc.stderr.readline()
        stopped = time.monotonic() - sent
        proc.wait(timeout=_EXITS_WITHIN)
        err = first + proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert proc.returncode == 130, err
    assert first.startswith("voxfab: census: stopped; what was done is saved in"), err
    assert f"({len(json.loads((out / 'census.json').read_text())['shapes'])} polycubes)" in first, first
    assert stopped < _STOPS_WITHIN, stopped
    assert "voxfab: interrupted" in err and "Traceback" not in err, err
    data = json.loads((out / "census.json").read_text())
    assert data["complete"] is False  # its shapes may be none yet: the first search was under way
    # An interrupted search is no answer: nothing undecided (every search of 6 cubes ends within its 10 s),
    # no error, and every record checks out.
    assert not [r["id"] for r in data["shapes"] if "undecided" in (r["unfold"], r["unzip"]) or "error" in r]
    assert verify_census(out).problems == ()
    saved = len(data["shapes"])
    again = subprocess.run([sys.executable, "-m", "voxfab", "census", "6", "-o", str(out), "--workers", "0"],
                           capture_output=True, text=True, timeout=600)
    assert again.returncode == 0, again.stderr
    assert f"{saved} kept from an earlier run" in again.stdout
    assert json.loads((out / "census.json").read_text())["complete"] is True
