"""``voxfab studio`` as a real process: Ctrl-C stops it within 2 s, even while net searches run."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest

from voxfab.recipe import load_recipe, make_shape
from voxfab.studio._grid import pack

from .conftest import ROOT, free_port, start_studio

QUEEN = ROOT / "recipes" / "chess" / "queen.toml"


def _post(url: str, body: dict) -> dict:
    req = urllib.request.Request(url, data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=10) as r:
        return json.loads(r.read())


def _get(url: str) -> dict:
    with urllib.request.urlopen(url, timeout=10) as r:
        return json.loads(r.read())


@pytest.mark.parametrize("presses", [1, 2])
def test_ctrl_c_stops_the_server_within_two_seconds_while_nets_are_searched(tmp_path, presses):
    queen = make_shape(load_recipe(QUEEN)).grid
    proc, url = start_studio(tmp_path)
    try:
        body = {"grid": pack(queen), "count": 12, "options": {"timeout": 30.0, "sheet": "A4", "pieces": "auto"}}
        ids = [_post(f"{url}/api/nets", dict(body, seed=s))["job"] for s in range(3)]
        end = time.monotonic() + 120
        while _get(f"{url}/api/jobs/{ids[0]}")["done"] < 1 and time.monotonic() < end:
            time.sleep(0.1)  # a net found: the search is under way, kernels compiled
        states = [_get(f"{url}/api/jobs/{j}")["state"] for j in ids]
        assert states[:2] == ["running", "running"] and states[2] == "queued", states
        t0 = time.monotonic()
        for _ in range(presses):
            proc.send_signal(signal.SIGINT)
            time.sleep(0.05)
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            pass
        stopped = time.monotonic() - t0
        assert proc.returncode is not None, "still running 10 s after Ctrl-C"
        assert stopped < 2.0, f"stopped {stopped:.2f} s after Ctrl-C"
        out = proc.stdout.read().decode()
        assert "Traceback" not in out, out[-2000:]
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(5)


def _queen_file(folder: Path) -> tuple[Path, np.ndarray]:
    queen = make_shape(load_recipe(QUEEN)).grid
    path = folder / "queen.npy"
    np.save(path, queen)
    return path, queen


def test_studio_shape_file_opens_with_that_shape(tmp_path):
    from voxfab.shape import crop
    from voxfab.studio._grid import unpack

    path, queen = _queen_file(tmp_path)
    proc, url = start_studio(tmp_path, str(path))
    try:
        got = _get(f"{url}/api/initial")["shape"]
        assert got["label"] == "queen.npy" and got["name"] is None
        grid = unpack(got["grid"])
        assert grid.shape == (25, 25, 25)
        assert (crop(grid) == crop(queen)).all()  # the same voxels, centred in the editor
        assert got["facts"]["volume"] == int(queen.sum())
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(10)


def test_studio_repository_name_opens_that_shape(tmp_path):
    from voxfab.repo import Repository
    from voxfab.shape import crop
    from voxfab.studio._grid import unpack

    _, queen = _queen_file(tmp_path)
    with Repository(tmp_path / "repo.sqlite") as repo:
        name = repo.add(queen).name
    proc, url = start_studio(tmp_path, name)
    try:
        got = _get(f"{url}/api/initial")["shape"]
        assert (got["label"], got["name"]) == (name, name)
        assert (crop(unpack(got["grid"])) == crop(queen)).all()
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(10)


def test_studio_without_shape_opens_on_the_drawing(server):
    assert _get(f"{server['url']}/api/initial") == {"shape": None}


@pytest.mark.parametrize("what, words", [
    ("missing.npy", "missing.npy"),
    ("big.npy", "does not fit the 25³ editor"),
    ("empty.npy", "empty"),
    ("99999.001", "99999.001"),
])
def test_studio_shape_errors_are_one_line_before_serving(tmp_path, what, words):
    np.save(tmp_path / "big.npy", np.ones((30, 4, 4), dtype=bool))
    np.save(tmp_path / "empty.npy", np.zeros((5, 5, 5), dtype=bool))
    from voxfab.repo import Repository

    with Repository(tmp_path / "repo.sqlite") as repo:
        repo.add(np.ones((3, 3, 3), dtype=bool), draft=True)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, "-m", "voxfab", "studio", what, "--port", str(free_port()),
                        "--repo", str(tmp_path / "repo.sqlite"), "--no-browser"],
                       env=env, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert r.returncode != 0
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and words in lines[0] and "Traceback" not in r.stderr, r.stderr
