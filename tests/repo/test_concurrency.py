"""Several processes adding to one repository at the same time."""

from __future__ import annotations

import json
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np

from voxfab.repo import Repository
from voxfab.shape import crop, examples, volume

WORKER = Path(__file__).with_name("_concurrent_worker.py")
PROCESSES = 4
PER_PROCESS = 25


def test_concurrent_processes_get_distinct_names(tmp_path: Path) -> None:
    db = tmp_path / "shared.sqlite"  # not created yet: the workers race to create it too
    procs = [
        subprocess.Popen(
            [sys.executable, str(WORKER), str(db), str(w), str(PER_PROCESS)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        )
        for w in range(PROCESSES)
    ]
    try:
        for p in procs:  # every worker has imported everything before any starts
            assert p.stdout.readline().strip() == "ready", p.stderr.read()
        for p in procs:
            p.stdin.write("go\n")
            p.stdin.flush()
        outputs = []
        for p in procs:
            out, err = p.communicate(timeout=120)
            assert p.returncode == 0, err
            outputs.append([tuple(json.loads(line)) for line in out.splitlines()])
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()

    # The shared shape: exactly one process created it, all got the same name.
    shared = [r for out in outputs for r in (out[0], out[-1])]
    assert len({name for name, _ in shared}) == 1
    assert sum(created for _, created in shared) == 1
    shared_name = shared[0][0]
    assert shared_name == f"{volume(examples.vase()):05d}.001"

    # The distinct shapes: all created, names 00027.001..00027.100 each given once.
    own = [r for out in outputs for r in out[1:-1]]
    assert len(own) == PROCESSES * PER_PROCESS
    assert all(created for _, created in own)
    assert sorted(name for name, _ in own) == [f"00027.{i:03d}" for i in range(1, PROCESSES * PER_PROCESS + 1)]
    # Each process saw its own ranks increase (insertion order within a process).
    for out in outputs:
        ranks = [int(name[-3:]) for name, _ in out[1:-1]]
        assert ranks == sorted(ranks)

    with Repository(db, create=False) as repo:
        assert len(repo) == PROCESSES * PER_PROCESS + 1
        assert repo.check() == []
        for out_index, out in enumerate(outputs):
            for i, (name, _) in enumerate(out[1:-1]):
                assert repo.show(name)["meta"] == {"worker": out_index, "i": i}
                g = repo.get(name)
                assert g.shape == (2, 1, 25) and g[0, 0].all() and g[1, 0].sum() == 2
        assert np.array_equal(repo.get(shared_name), crop(examples.vase()))
    raw = sqlite3.connect(db)
    try:
        assert raw.execute("PRAGMA integrity_check").fetchall() == [("ok",)]
        assert raw.execute("SELECT count(DISTINCT name), count(*) FROM shapes").fetchone() == (101, 101)
    finally:
        raw.close()
