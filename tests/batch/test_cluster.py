"""Batch runs on real Dask clusters: a LocalCluster, and a scheduler with two worker processes."""

from __future__ import annotations

import json
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from _batch_fixtures import OUTPUTS, dask_process, free_port, make_repo, processes, write_outputs

from voxfab.batch import BATCH_FORMAT, run_batch
from voxfab.errors import RepositoryError
from voxfab.recipe import SHAPE_FILES


def _check_index(out: Path, built: list[str], failed: list[str]) -> None:
    """Read index.html with lxml and the contact sheet with PIL: every link and picture is there."""
    from lxml import html
    from PIL import Image

    page = html.parse(str(out / "index.html")).getroot()
    figures = page.findall(".//figure")
    assert [f.get("id") for f in figures] == built
    for f in figures:
        name = f.get("id")
        links = {a.get("href") for a in f.iter("a")}
        manifest = json.loads((out / name / "manifest.json").read_text())
        assert {f"{name}/{x['path']}" for x in manifest["files"]} | {f"{name}/manifest.json"} <= links
        srcs = [img.get("src") for img in f.iter("img")]
        assert srcs == [f"thumbs/{name}.png", f"thumbs/{name}-net.png"]
        for href in links | set(srcs):
            assert (out / href).exists(), href
    text = page.text_content()
    for name in failed:
        assert name in text and "edge-only" in text
    with Image.open(out / "contact_sheet.png") as sheet:
        pixels = np.asarray(sheet.convert("RGB"))
    # Two 160-px tiles per shape, pairs on a near-square grid: the first tiles are the thumbnails.
    with Image.open(out / "thumbs" / f"{built[0]}.png") as im:
        assert np.array_equal(pixels[:160, :160], np.asarray(im.convert("RGB")))
    with Image.open(out / "thumbs" / f"{built[0]}-net.png") as im:
        assert np.array_equal(pixels[:160, 160:320], np.asarray(im.convert("RGB")))
    assert pixels.shape[1] == 2 * 160 * int(np.ceil(np.sqrt(len(built))))


def test_local_cluster_batch_resume_and_failures(tmp_path: Path) -> None:
    names = make_repo(tmp_path / "r.sqlite")
    outputs = write_outputs(tmp_path / "outputs.toml")
    out = tmp_path / "out"
    seen = []
    pages: list[str] = []

    def start(count: int, skipped: int, link: str | None) -> None:
        # The dashboard (bokeh) serves its pages while the batch runs.
        assert (count, skipped) == (3, 0) and link is not None and link.startswith("http://127.0.0.1:")
        with urllib.request.urlopen(link, timeout=30) as response:
            pages.append(response.read().decode("utf-8", "replace"))

    report = run_batch(tmp_path / "r.sqlite", outputs, out, names="00025.001:00026.002", workers=2,
                       dashboard=":0", on_start=start, on_outcome=seen.append)
    assert (report.built, report.failed, report.skipped, report.workers) == (3, 0, 0, 2)
    assert len(pages) == 1 and "Dask" in pages[0]
    assert sorted(o.name for o in seen) == names[:3]
    record = json.loads((out / "batch.json").read_text())
    assert record["format"] == BATCH_FORMAT and record["outputs_file"] == "outputs.toml"
    assert sorted(record["shapes"]) == names[:3]
    for entry in record["shapes"].values():
        assert entry["status"] == "built" and entry["worker"].startswith("tcp://127.0.0.1:")
        assert entry["seconds"] > 0 and entry["files"] == 2 + len(SHAPE_FILES)

    # Resume with the whole repository: the three are skipped, the failing shape is reported, the rest built.
    before = {n: (out / n / "mesh.stl").stat().st_mtime_ns for n in names[:3]}
    report = run_batch(tmp_path / "r.sqlite", outputs, out, workers=1, dashboard=None)
    assert (report.built, report.failed, report.skipped) == (1, 1, 3)
    assert report.failures[0][0] == "00028.001" and "edge-only" in report.failures[0][1]
    assert {n: (out / n / "mesh.stl").stat().st_mtime_ns for n in names[:3]} == before
    record = json.loads((out / "batch.json").read_text())
    assert record["shapes"]["00028.001"]["status"] == "failed"
    assert [n for n in names if (out / n).is_dir()] == names[:4]
    _check_index(out, names[:4], ["00028.001"])

    # Other outputs in the same folder would mix two batches: refused before any work.
    other = write_outputs(tmp_path / "other.toml", OUTPUTS.replace("2.0", "3.0"))
    with pytest.raises(RepositoryError, match="built with other outputs"):
        run_batch(tmp_path / "r.sqlite", other, out, workers=1, dashboard=None)


def test_real_scheduler_with_two_worker_processes(tmp_path: Path) -> None:
    from distributed import Client

    make_repo(tmp_path / "r.sqlite")
    outputs = write_outputs(tmp_path / "outputs.toml")
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    with processes() as procs:
        procs.append(dask_process("scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard",
                           log=tmp_path / "scheduler.log"))
        for i in range(2):
            procs.append(dask_process("worker", address, "--host", "127.0.0.1", "--nthreads", "1", "--nworkers", "1",
                               "--no-dashboard", "--name", f"w{i}", log=tmp_path / f"worker{i}.log"))
        deadline = time.monotonic() + 60
        with Client(address, timeout=60) as client:
            client.wait_for_workers(2, timeout=max(1.0, deadline - time.monotonic()))
            workers = set(client.scheduler_info()["workers"])
        assert len(workers) == 2
        r = subprocess.run(
            [sys.executable, "-m", "voxfab", "batch", "--repo", str(tmp_path / "r.sqlite"), "--outputs",
             str(outputs), "-o", str(tmp_path / "out"), "--scheduler", address],
            capture_output=True, text=True, timeout=300,
        )
        assert all(p.poll() is None for p in procs), "a dask process died"
    # The failing shape makes the run exit non-zero with one error line, after building the others.
    assert r.returncode != 0
    assert r.stderr.strip().splitlines()[-1].startswith("voxfab: error: 1 of 5 shapes failed (first: 00028.001")
    assert "Traceback" not in r.stderr
    assert "4 built, 0 skipped (built before), 1 failed" in r.stdout and "on 2 workers" in r.stdout
    record = json.loads((tmp_path / "out" / "batch.json").read_text())["shapes"]
    assert {e["worker"] for e in record.values()} == workers  # both workers built shapes
    assert sorted(n for n, e in record.items() if e["status"] == "built") == [
        "00025.001", "00026.001", "00026.002", "00026.003"]
    _check_index(tmp_path / "out", sorted(n for n, e in record.items() if e["status"] == "built"), ["00028.001"])


def test_a_local_cluster_sends_tasks_to_its_workers_ahead() -> None:
    """The local scheduler shares the workers' cores: it queues no task of its own, each worker holds its next.

    With the default saturation a finished worker waits for the scheduler's process to get a core; here
    four slow tasks on one worker are all on that worker at once, and none waits on the scheduler.
    """
    import math

    from voxfab.batch._cluster import connect

    cl = connect(None, 1, None, 60.0)
    try:
        assert cl.client.run_on_scheduler(lambda dask_scheduler: dask_scheduler.WORKER_SATURATION) == math.inf
        futures = [cl.client.submit(time.sleep, 1.0, key=f"sleep-{i}", pure=False) for i in range(4)]
        deadline = time.monotonic() + 30
        held = 0
        while time.monotonic() < deadline and held < 4:
            held = sum(len(v) for v in cl.client.processing().values())
            time.sleep(0.05)
        assert held == 4
        assert cl.client.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.queued)) == 0
        cl.client.gather(futures)
    finally:
        cl.close()
