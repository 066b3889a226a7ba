"""Ctrl-C during a CP-SAT search: the search stops at once and the interrupt goes on, as anywhere else.

Real processes stopped with SIGINT; every wait is bounded.  CP-SAT's own SIGINT
handler turned a Ctrl-C into "ran out of time" and, installed for good, made a
later Ctrl-C kill the process outright.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("ortools")

ROOT = Path(__file__).resolve().parents[2]
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))

#: A search that runs to its 60 s limit: ~60 distinct integers under an objective with no quick proof.
SCRIPT = textwrap.dedent("""
    import os, signal, threading, time
    from voxfab.unfold._cpsat import cp_model, one_worker_solver, solve
    m = cp_model().CpModel()
    xs = [m.new_int_var(0, 10**6, f"x{i}") for i in range(60)]
    for i in range(59):
        m.add(xs[i] * 7 + xs[i + 1] * 13 != 1000 + i)
    m.add_all_different(xs)
    m.maximize(sum(x * (i % 7 - 3) for i, x in enumerate(xs)))
    solver = one_worker_solver()
    solver.parameters.max_time_in_seconds = 60
    print("searching", flush=True)
    start = time.monotonic()
    try:
        solve(solver, m)
        print("returned", round(time.monotonic() - start, 1), flush=True)
    except KeyboardInterrupt:
        print("interrupted", round(time.monotonic() - start, 1), flush=True)
    # after a search, Ctrl-C is Python's again
    try:
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(2)
        print("no interrupt after the search", flush=True)
    except KeyboardInterrupt:
        print("interrupted again", flush=True)
""")


def test_ctrl_c_stops_the_search_raises_and_the_process_ends_cleanly():
    proc = subprocess.Popen([sys.executable, "-c", SCRIPT], env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        assert proc.stdout.readline().strip() == "searching"
        time.sleep(1.5)  # the search under way
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    lines = out.split()
    assert proc.returncode == 0 and "terminate" not in err, (proc.returncode, out, err[-1000:])
    assert lines[0] == "interrupted" and float(lines[1]) < 10, out
    assert lines[2:] == ["interrupted", "again"], out


def test_ctrl_c_during_net_strategy_exact_is_an_interrupt_not_a_timeout(tmp_path):
    from voxfab.recipe import load_recipe, make_shape

    np.save(tmp_path / "queen.npy", make_shape(load_recipe(ROOT / "recipes" / "chess" / "queen.toml")).grid)
    # --min-box on the queen's 862 faces: a search that runs to its 60 s limit.
    proc = subprocess.Popen([sys.executable, "-m", "voxfab", "net", "queen.npy", "-o", "q.json", "--strategy", "exact",
                             "--min-box", "--timeout", "60"], cwd=tmp_path, env=ENV, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(15)  # imports and the first boxes: the exact search is under way
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert time.monotonic() - t0 < 10
    assert proc.returncode == 130 and err.strip() == "voxfab: interrupted", (proc.returncode, err[-1000:])
    assert not (tmp_path / "q.json").exists()
