"""A batch run writes the net files `voxfab net` writes for the same shape, options and seed."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from voxfab.repo import Repository

ROOT = Path(__file__).resolve().parents[2]


def test_batch_and_cli_write_identical_net_files(tmp_path: Path) -> None:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    g = np.zeros((25, 25, 25), dtype=bool)
    g[10:14, 10:14, :] = True  # a 4 x 4 column the height of the grid
    with Repository(tmp_path / "r.sqlite") as repo:
        name = repo.add(g).name
    (tmp_path / "outputs.toml").write_text('seed = 3\n[outputs.net]\nformats = ["svg", "dxf"]\nsheet = "A2"\n'
                                           "face_size = 8.6\n")
    r = subprocess.run([sys.executable, "-m", "voxfab", "batch", "--repo", str(tmp_path / "r.sqlite"), "--outputs",
                        str(tmp_path / "outputs.toml"), "-o", str(tmp_path / "out"), "--workers", "1",
                        "--no-dashboard", "--no-index"], capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, r.stderr
    cli = tmp_path / "cli"
    cli.mkdir()
    r = subprocess.run([sys.executable, "-m", "voxfab", "net", name, "--repo", str(tmp_path / "r.sqlite"), "--seed",
                        "3", "--face-size", "8.6", "--sheet", "A2", "-o", "net.json", "-o", "net.svg", "-o",
                        "net.dxf"], capture_output=True, text=True, timeout=600, env=env, cwd=cli)
    assert r.returncode == 0, r.stderr
    for file in ("net.json", "net.svg", "net.dxf"):
        assert (tmp_path / "out" / name / file).read_bytes() == (cli / file).read_bytes(), file
