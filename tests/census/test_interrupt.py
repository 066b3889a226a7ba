"""SIGINT while a serial census searches in native code (CP-SAT): the search stops at once, with no outcome.

CP-SAT catches SIGINT by default and ends its search as if its time ran out, so
an interrupted unzipping came back ``undecided``, stored as an answer.  Here a
search CP-SAT needs far more than a minute for (random 3-SAT at the threshold,
400 variables) runs in the census's interrupt scope: a real process, a real
signal, bounded waits.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path

_SCRIPT = """
import random
from voxfab._shared.progress import cancel_scope
from voxfab.census._run import _interrupts
from voxfab.unfold._cpsat import cp_model, one_worker_solver, solve

rnd = random.Random(1)
m = cp_model().CpModel()
x = [m.new_bool_var(f"x{i}") for i in range(400)]
for _ in range(1704):
    m.add_bool_or([x[v] if rnd.random() < 0.5 else ~x[v] for v in rnd.sample(range(400), 3)])
solver = one_worker_solver()
solver.parameters.max_time_in_seconds = 60
try:
    with _interrupts() as event, cancel_scope(event):
        print("START", flush=True)
        status = solve(solver, m)
    print("RESULT", solver.status_name(status), flush=True)
except KeyboardInterrupt:
    print("INTERRUPTED", flush=True)
"""


def test_sigint_stops_a_solver_search_and_gives_no_outcome(tmp_path: Path) -> None:
    script = tmp_path / "solve.py"  # a file, as the CLI's code is: source text run by -c is exec'd text
    script.write_text(_SCRIPT)
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        assert proc.stdout.readline().strip() == "START", proc.communicate(timeout=60)
        time.sleep(1.0)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
        took = time.monotonic() - sent
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert out.strip() == "INTERRUPTED", (out, err)
    assert took < 1.0, took
