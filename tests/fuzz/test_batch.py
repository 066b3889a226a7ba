"""Hostile batch runs: tampered folders and records, bad options, servers that are not Dask schedulers.

Every refusal is one ``voxfab: error:`` line in bounded time and leaves no file
behind; a resumed batch rebuilds exactly the folders that do not match their
manifests.  Real Dask: a LocalCluster, and a scheduler with a worker that is
killed mid-run.
"""

from __future__ import annotations

import json
import os
import signal
import socketserver
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from _batch_fixtures import dask_process, free_port, make_repo, processes, write_outputs
from _fuzz import check_outcome, refused, run_cli

from voxfab.batch import run_batch
from voxfab.recipe import load_recipe
from voxfab.recipe._build import make_shape
from voxfab.repo import Repository

RECIPES = Path(__file__).resolve().parents[2] / "recipes"
MESH = 'pitch = 2.0\nseed = 4\n\n[outputs.mesh]\nformat = "stl"\n'


@pytest.fixture(scope="module")
def setup(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("batch_fuzz")
    make_repo(root / "r.sqlite")
    write_outputs(root / "outputs.toml", MESH)
    (root / "a_file").write_text("x")
    return root


def _batch(setup: Path, *args: object, out: Path | None = None) -> list[str]:
    given = [str(a) for a in args]
    base = {"--repo": setup / "r.sqlite", "--outputs": setup / "outputs.toml", "-o": out or setup / "new"}
    for key, value in base.items():
        if key not in given:
            given += [key, str(value)]
    quiet = [] if "--dashboard" in given else ["--no-dashboard"]
    return ["batch", *quiet, "--no-index", *given]


def _entries(root: Path) -> set[Path]:
    return set(root.rglob("*"))


# ---- resume checks every file ---------------------------------------------------------------------

def _rebuilt(out: Path, names: list[str]) -> dict[str, int]:
    return {n: (out / n / "manifest.json").stat().st_mtime_ns for n in names}


def test_resume_rebuilds_what_does_not_match_its_manifest(tmp_path: Path) -> None:
    names = make_repo(tmp_path / "r.sqlite")[:4]
    queen = make_shape(load_recipe(RECIPES / "chess" / "queen.toml")).grid
    with Repository(tmp_path / "r.sqlite") as repo:
        names.append(repo.add(queen).name)
    outputs = write_outputs(tmp_path / "outputs.toml", MESH)
    out = tmp_path / "out"
    select = f"{names[0]}:{names[-1]}"
    report = run_batch(tmp_path / "r.sqlite", outputs, out, names=select, workers=1, thumbnails=False)
    assert (report.built, report.skipped) == (6, 0)  # 4 columns, the edge-contact shape and the queen
    # The queen's print is the queen: its STL spans the queen's 25 voxels at 2 mm.
    import trimesh

    mesh = trimesh.load(out / names[-1] / "mesh.stl")
    assert mesh.is_watertight and mesh.extents.max() == pytest.approx(50.0, abs=0.01)

    damage = {
        names[0]: lambda: (out / names[0] / "mesh.stl").unlink(),
        names[1]: lambda: (out / names[1] / "mesh.stl").open("ab").write(b"garbage"),
        names[2]: lambda: (out / names[2] / "manifest.json").write_text("{"),
        names[3]: lambda: (out / "recipes" / f"{names[3]}.toml").unlink(),
        names[-1]: lambda: (out / "recipes" / f"{names[-1]}.toml").write_text(MESH + "# edited\n"),
    }
    untouched = "00028.001"
    before = _rebuilt(out, [untouched])
    for hurt in damage.values():
        hurt()
    # batch.json disagrees with the disk, as after Ctrl-C: the folders are the truth.
    record = json.loads((out / "batch.json").read_text())
    record["shapes"][untouched] = {"status": "failed", "seconds": 0.0, "worker": "lost", "error": "x"}
    (out / "batch.json").write_text(json.dumps(record))
    # A killed worker's temporary folder.
    stale = out / ".00026.001.999999999-abcdefgh.tmp"
    stale.mkdir()
    report = run_batch(tmp_path / "r.sqlite", outputs, out, names=select, workers=1, thumbnails=False)
    assert (report.built, report.skipped) == (5, 1)
    assert _rebuilt(out, [untouched]) == before
    assert not stale.exists()
    record = json.loads((out / "batch.json").read_text())["shapes"]
    assert {n: e["status"] for n, e in record.items()} == {n: "built" for n in [*names, untouched]}
    for name in names:
        assert (out / "recipes" / f"{name}.toml").read_text() == MESH + f'\n[source]\nfile = "{name}.npy"\n'
        manifest = json.loads((out / name / "manifest.json").read_text())
        assert (out / name / "mesh.stl").stat().st_size > 0 and manifest["files"]
    # Nothing left to do: a third run builds nothing.
    report = run_batch(tmp_path / "r.sqlite", outputs, out, names=select, workers=1, thumbnails=False)
    assert (report.built, report.skipped) == (0, 6)


def test_a_corrupt_row_fails_its_shape_and_is_never_built(tmp_path: Path) -> None:
    import sqlite3

    names = make_repo(tmp_path / "r.sqlite")
    with sqlite3.connect(tmp_path / "r.sqlite") as db:
        db.execute("UPDATE shapes SET bits = X'' WHERE name = ?", (names[1],))
        db.execute("UPDATE shapes SET bits = 'text' WHERE name = ?", (names[2],))
    outputs = write_outputs(tmp_path / "outputs.toml", MESH)
    out = tmp_path / "out"
    report = run_batch(tmp_path / "r.sqlite", outputs, out, names=f"{names[0]}:{names[2]}", workers=1,
                       thumbnails=False)
    assert (report.built, report.failed) == (1, 2)
    assert {n for n, _ in report.failures} == {names[1], names[2]}
    assert all("corrupt repository row" in why for _, why in report.failures)
    assert not (out / names[1]).exists() and not (out / names[2]).exists()
    assert not (out / "recipes" / f"{names[1]}.npy").exists()


# ---- refusals: one line, bounded time, nothing left behind ---------------------------------------

@pytest.mark.parametrize(("args", "message"), [
    (["--workers", "1000000"], "over the limit of 256"),
    (["--workers", "-2"], "--workers"),
    (["--connect-timeout", "nan"], "--connect-timeout: expected a positive number"),
    (["--connect-timeout", "inf"], "--connect-timeout: expected a positive number"),
    (["--connect-timeout", "1e300"], "over the limit of 3600"),
    (["--connect-timeout", "-5"], "--connect-timeout: expected a positive number of seconds, got -5"),
    (["--connect-timeout", "0"], "expected a positive number"),
    (["--dashboard", "notanaddr"], "--dashboard: expected [HOST]:PORT"),
    (["--dashboard", ":99999"], "--dashboard: expected [HOST]:PORT"),
    (["--outputs", "/dev/zero"], "not a regular file"),
    (["--outputs", "{root}/fifo"], "a FIFO"),
    (["--outputs", "{root}/anim.toml"], "outputs.animation: needs a tube source"),
    (["-o", "{root}/a_file/sub"], "is not a folder"),
    (["-o", "{root}/missing/a/b"], "does not exist"),
    (["-o", ""], "expected a path, got ''"),
    (["-o", "/proc/voxfab-batch"], "cannot"),
    (["-o", "{root}/recipes_file"], "recipes: exists and is not a folder"),
    (["--scheduler", "tcp://127.0.0.1:{closed}", "--connect-timeout", "3"], "cannot reach"),
    (["--limit", str(10**21)], None),
])
def test_bad_batch_options_are_refused_cleanly(setup: Path, args: list[str], message: str | None) -> None:
    fifo = setup / "fifo"
    if not fifo.exists():
        os.mkfifo(fifo)
    (setup / "anim.toml").write_text("pitch = 2.0\n[outputs.animation]\n")
    from voxfab.batch._task import outputs_sha256

    (setup / "recipes_file").mkdir(exist_ok=True)
    (setup / "recipes_file" / "recipes").write_text("x")
    sha = outputs_sha256((setup / "outputs.toml").read_text())
    (setup / "recipes_file" / "batch.json").write_text(
        json.dumps({"format": "voxfab-batch/1", "outputs_sha256": sha, "shapes": {}}))
    before = _entries(setup)
    argv = _batch(setup, *(a.format(root=setup, closed=free_port()) for a in args))
    if message is None:
        # A huge --limit lists the whole repository (no "datatype mismatch"); the run must end cleanly.
        line = refused([*argv, "--names", "00030.001:00040.001"])
        assert "no shape matches" in line
    else:
        o = check_outcome(run_cli(argv))  # one line, argparse's own refusals included
        assert o.code != 0 and len(o.error_lines) == 1 and message in o.error_lines[0], o.err
    assert _entries(setup) == before, "a refused batch left files behind"


@pytest.mark.parametrize("record", [
    '{"format": "voxfab-batch/1", "outputs_sha256": "S", "shapes": "x"}',
    '{"format": "voxfab-batch/1", "outputs_sha256": "S", "shapes": [1, 2]}',
    '{"format": "voxfab-batch/1", "outputs_sha256": "S", "shapes": {"00025.001": 3}}',
    "[" * 100_000 + "]" * 100_000,
    "{",
    "\xff\xfe",
])
def test_a_tampered_batch_record_is_refused(setup: Path, tmp_path: Path, record: str) -> None:
    from voxfab.batch._task import outputs_sha256

    out = tmp_path / "out"
    out.mkdir()
    sha = outputs_sha256((setup / "outputs.toml").read_text())
    (out / "batch.json").write_bytes(record.replace('"S"', f'"{sha}"').encode("utf-8", "surrogateescape"))
    before = _entries(tmp_path)
    line = refused(_batch(setup, "-o", out))
    assert "not a voxfab batch record" in line
    assert _entries(tmp_path) == before


# ---- servers that are not Dask schedulers ------------------------------------------------------------

class _Server(socketserver.ThreadingTCPServer):
    allow_reuse_address = True
    daemon_threads = True


def _serve(kind: str) -> Iterator[int]:
    class Handler(socketserver.BaseRequestHandler):
        def handle(self) -> None:
            try:
                if kind == "garbage":
                    rng = np.random.default_rng(0)
                    self.request.sendall(b"\xff" * 8 + rng.bytes(4096))
                elif kind == "http":
                    self.request.recv(1024)  # an HTTP server waits for the request line
                    self.request.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                time.sleep(20)  # "silent" says nothing at all
            except OSError:
                pass

    server = _Server(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield int(server.server_address[1])
    finally:
        server.shutdown()
        server.server_close()


@pytest.mark.parametrize(("kind", "message"), [
    ("garbage", "is not a Dask scheduler: it answered with something else"),
    ("silent", "is not a Dask scheduler: it sent nothing in 3 s"),
    ("http", "is not a Dask scheduler: it sent nothing in 3 s"),
])
def test_a_server_that_is_not_a_scheduler_is_named(setup: Path, kind: str, message: str) -> None:
    for port in _serve(kind):
        start = time.monotonic()
        line = refused(_batch(setup, "--scheduler", f"tcp://127.0.0.1:{port}", "--connect-timeout", "3"),
                       seconds=20)
        assert message in line and time.monotonic() - start < 10
    assert not (setup / "new").exists()


def test_losing_every_worker_stops_the_run_in_bounded_time(tmp_path: Path) -> None:
    """A real scheduler whose only worker is killed mid-run: the client says so instead of waiting."""
    from distributed import Client

    make_repo(tmp_path / "r.sqlite")
    # Slow enough per shape that the run is still going when the worker dies.
    outputs = write_outputs(tmp_path / "outputs.toml", MESH + '\n[outputs.pictures]\n')
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    with processes() as procs:
        procs.append(dask_process("scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard",
                                  log=tmp_path / "scheduler.log"))
        worker = dask_process("worker", address, "--host", "127.0.0.1", "--nthreads", "1", "--nworkers", "1",
                              "--no-dashboard", "--no-nanny", log=tmp_path / "worker.log")
        procs.append(worker)
        with Client(address, timeout=60) as client:
            client.wait_for_workers(1, timeout=60)
        run = subprocess.Popen(
            [sys.executable, "-m", "voxfab", "batch", "--repo", str(tmp_path / "r.sqlite"), "--outputs",
             str(outputs), "-o", str(tmp_path / "out"), "--scheduler", address, "--connect-timeout", "4",
             "--no-index"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        )
        procs.append(run)  # type: ignore[arg-type]
        assert run.stdout is not None
        first = run.stdout.readline()
        assert "shapes to build" in first, first
        worker.send_signal(signal.SIGKILL)
        start = time.monotonic()
        _, err = run.communicate(timeout=60)
        waited = time.monotonic() - start
    assert run.returncode != 0 and "Traceback" not in err
    assert err.strip().splitlines()[-1].startswith("voxfab: error: lost every worker: no worker for 4 s"), err
    assert waited < 30
    record = json.loads((tmp_path / "out" / "batch.json").read_text())["shapes"]
    built = {n for n, e in record.items() if e["status"] == "built"}
    assert built == {p.name for p in (tmp_path / "out").iterdir() if (p / "manifest.json").is_file()}


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_batch_stops_its_tasks_and_the_next_run_agrees_with_the_disk(tmp_path: Path, sig) -> None:
    names = make_repo(tmp_path / "r.sqlite")[:4]
    outputs = write_outputs(tmp_path / "outputs.toml", MESH + "\n[outputs.pictures]\n")
    out = tmp_path / "out"
    argv = [sys.executable, "-m", "voxfab", "batch", "--repo", str(tmp_path / "r.sqlite"), "--outputs",
            str(outputs), "-o", str(out), "--workers", "1", "--no-dashboard", "--no-index",
            "--names", f"{names[0]}:{names[-1]}"]
    run = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert run.stdout is not None
        assert "shapes to build" in run.stdout.readline()
        time.sleep(1.0)
        run.send_signal(sig)
        _, err = run.communicate(timeout=60)
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode in (130, 143) and "Traceback" not in err, err
    assert not list(out.glob(".*.tmp")), "a stopped build left its temporary folder"
    # Whatever finished, the next run counts it from the folders and builds only the rest.
    sound = sorted(p.name for p in out.iterdir() if (p / "manifest.json").is_file())
    report = run_batch(tmp_path / "r.sqlite", outputs, out, names=f"{names[0]}:{names[-1]}", workers=1,
                       thumbnails=False)
    assert (report.built, report.skipped) == (len(names) - len(sound), len(sound))
    record = json.loads((out / "batch.json").read_text())["shapes"]
    assert sorted(n for n, e in record.items() if e["status"] == "built") == names
