"""``voxfab batch`` errors through the real entry point: one line, non-zero exit, bounded time."""

from __future__ import annotations

import socket
import subprocess
import sys
from pathlib import Path

import pytest
from _batch_fixtures import make_repo, write_outputs


@pytest.fixture(scope="module")
def setup(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("batch_cli")
    make_repo(root / "r.sqlite")
    write_outputs(root / "outputs.toml")
    (root / "a_file").write_text("x")
    return root


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--repo", "{root}/none.sqlite"], "no repository at"),
        (["--outputs", "{root}/missing.toml"], "missing.toml: no such file"),
        (["--names", "25:26"], "not a shape name"),
        (["--names", "00030.001:00040.001"], "no shape matches the selection"),
        (["--limit", "0"], "--limit: expected at least 1"),
        (["--workers", "0"], "--workers: expected an integer >= 1"),
        (["-o", "{root}/a_file"], "exists and is not a folder"),
        (["--scheduler", "tcp://127.0.0.1:{port}", "--connect-timeout", "2"], "--scheduler: cannot reach"),
        (["--scheduler", "nonsense", "--connect-timeout", "2"], "expected tcp://HOST:PORT"),
    ],
)
def test_batch_errors(setup: Path, args: list[str], message: str) -> None:
    base = {"--repo": f"{setup}/r.sqlite", "--outputs": f"{setup}/outputs.toml", "-o": f"{setup}/out"}
    given = [a.format(root=setup, port=_closed_port()) for a in args]
    for key, value in base.items():
        if key not in given:
            given += [key, value]
    r = subprocess.run([sys.executable, "-m", "voxfab", "batch", *given], capture_output=True, text=True, timeout=120)
    assert r.returncode != 0
    assert r.stderr.strip().splitlines()[-1].startswith("voxfab: error: ") and message in r.stderr, r.stderr
    assert "Traceback" not in r.stderr
    assert not (setup / "out" / "00025.001").exists()
