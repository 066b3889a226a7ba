"""Small repositories for the batch tests: quick shapes, one that a strict mesh refuses."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from voxfab.repo import Repository

#: Outputs that build fast; ``contacts = "error"`` makes the mesh refuse edge-only contacts.
OUTPUTS = 'pitch = 2.0\nseed = 4\n\n[outputs.mesh]\nformat = "stl"\ncontacts = "error"\n'


def column(*bumps: int) -> np.ndarray:
    """A 1x1x25 column with one voxel beside it at each height in ``bumps``."""
    g = np.zeros((2, 1, 25), dtype=bool)
    g[0, 0, :] = True
    for z in bumps:
        g[1, 0, z] = True
    return g


def edge_contact() -> np.ndarray:
    """A well-formed shape with two voxels touching along an edge only."""
    g = np.zeros((2, 2, 25), dtype=bool)
    g[0, 0, :] = True
    g[1, 0, 5] = g[0, 1, 6] = g[1, 1, 6] = True
    return g


def make_repo(path: Path) -> list[str]:
    """Store four buildable shapes and the edge-contact one; return their names in name order."""
    with Repository(path) as repo:
        names = [repo.add(g, symmetric=True).name for g in (column(), column(2), column(5), column(8))]
        names.append(repo.add(edge_contact(), symmetric=True).name)
    assert names == ["00025.001", "00026.001", "00026.002", "00026.003", "00028.001"]
    return names


def write_outputs(path: Path, text: str = OUTPUTS) -> Path:
    path.write_text(text)
    return path


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextlib.contextmanager
def processes() -> Iterator[list[subprocess.Popen[bytes]]]:
    procs: list[subprocess.Popen[bytes]] = []
    try:
        yield procs
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(timeout=10)


def dask_process(*args: str, log: Path) -> subprocess.Popen[bytes]:
    # The dask console script of this interpreter, run as a module so PATH does not matter.
    return subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_" + args[0], *args[1:]],
                            stdout=log.open("wb"), stderr=subprocess.STDOUT, env={**os.environ})
