"""Studio jobs: the queue place, progress, and Cancel (a running net search stops within about a second)."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import numpy as np
import pytest

from voxfab._shared.progress import cancel_scope, check_cancelled
from voxfab.errors import CancelledError
from voxfab.recipe import load_recipe, make_shape
from voxfab.studio._grid import pack
from voxfab.studio._jobs import Jobs

from ._helpers import wait_job

QUEEN = Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml"


@pytest.fixture(scope="module")
def queen() -> np.ndarray:
    return make_shape(load_recipe(QUEEN)).grid


def _wait_state(client, job: str, states: tuple[str, ...], limit: float = 60.0) -> dict:
    end = time.monotonic() + limit
    while time.monotonic() < end:
        s = client.get(f"/api/jobs/{job}").json()
        if s["state"] in states:
            return s
        time.sleep(0.02)
    raise AssertionError(f"job {job} never reached {states}")


def test_check_cancelled_raises_only_inside_a_cancelled_scope():
    event = threading.Event()
    check_cancelled()  # no scope: never raises
    with cancel_scope(event):
        check_cancelled()
        event.set()
        with pytest.raises(CancelledError):
            check_cancelled()
    check_cancelled()  # the scope ended with the block


def test_queue_place_then_cancel_a_queued_job(tmp_path):
    """Two workers: the third job waits at place 1, and once cancelled it never runs."""
    jobs = Jobs(tmp_path, workers=2)
    release = threading.Event()
    ran = []

    def hold(job):
        ran.append(job.id)
        job.step(1, 3, "holding")
        release.wait(10)

    try:
        a, b = jobs.submit("nets", hold), jobs.submit("nets", hold)
        c, d = jobs.submit("nets", hold), jobs.submit("nets", hold)
        end = time.monotonic() + 5
        while len(ran) < 2 and time.monotonic() < end:
            time.sleep(0.01)
        assert {a.status()["state"], b.status()["state"]} == {"running"}
        assert a.status()["place"] == 0 and (a.status()["done"], a.status()["total"]) == (1, 3)
        assert (c.status()["state"], c.status()["place"]) == ("queued", 1)
        assert (d.status()["state"], d.status()["place"]) == ("queued", 2)
        jobs.cancel(c)
        assert c.status()["state"] == "cancelled"
        assert d.status()["place"] == 1  # moved up
        release.set()
        end = time.monotonic() + 5
        while not d.ended and time.monotonic() < end:
            time.sleep(0.01)
        assert d.state == "done" and c.state == "cancelled"
        assert c.id not in ran and len(ran) == 3
    finally:
        release.set()
        jobs.shutdown()


def test_cancel_stops_a_running_net_search_within_a_second(client, queen):
    """The queen's gallery (many seconds of search) stops about as soon as Cancel is pressed."""
    # 8.6 mm faces (legible marks): no one-piece net fits A4, so the search runs on for nets to show
    body = {"grid": pack(queen), "count": 12, "seed": 0, "options": {"timeout": 30.0, "face_size": 8.6}}
    r = client.post("/api/nets", json=body)
    assert r.status_code == 200, r.text
    job = r.json()["job"]
    # Once a first net is found the kernels are compiled (compiling cannot be cut short) and the search is
    # under way for the next ones.
    end = time.monotonic() + 120
    while (s := client.get(f"/api/jobs/{job}").json())["done"] < 1 and time.monotonic() < end:
        time.sleep(0.05)
    assert s["state"] == "running" and s["done"] >= 1, s
    t0 = time.monotonic()
    r = client.post(f"/api/jobs/{job}/cancel")
    assert r.status_code == 200 and r.json()["state"] in ("running", "cancelled")
    s = _wait_state(client, job, ("cancelled", "done", "error"), limit=10)
    latency = time.monotonic() - t0
    assert s["state"] == "cancelled", s
    assert latency < 1.0, f"cancel took {latency:.2f} s"
    # Cancelling again, or an ended job, is harmless; an unknown job is one line.
    assert client.post(f"/api/jobs/{job}/cancel").json()["state"] == "cancelled"
    r = client.post("/api/jobs/0123456789abcdef/cancel")
    assert r.status_code == 400 and "no job" in r.json()["error"]


def test_a_gallery_waiting_in_the_queue_shows_its_place(client, queen):
    """Three galleries on two workers: the third says it is first in the queue, and runs once one is cancelled."""
    # 8.6 mm faces (legible marks): no one-piece net fits A4, so the search runs on for nets to show
    body = {"grid": pack(queen), "count": 12, "seed": 0, "options": {"timeout": 30.0, "face_size": 8.6}}
    ids = [client.post("/api/nets", json=dict(body, seed=s)).json()["job"] for s in range(3)]
    try:
        s = client.get(f"/api/jobs/{ids[2]}").json()
        assert (s["state"], s["place"]) == ("queued", 1), s
        assert s["message"]
        client.post(f"/api/jobs/{ids[0]}/cancel")
        s = _wait_state(client, ids[2], ("running", "done"), limit=5)
        assert s["place"] == 0
    finally:
        for j in ids:
            client.post(f"/api/jobs/{j}/cancel")
        for j in ids:
            assert wait_job(client, j, limit=10)["state"] in ("cancelled", "done")


def test_a_job_without_steps_of_its_own_shows_the_librarys_progress(tmp_path, queen):
    """A job that counts nothing itself (one file to make) shows the library's outermost meter: the plates."""
    from voxfab._shared.progress import meter

    jobs = Jobs(tmp_path, workers=1)
    seen = []

    def work(job):
        job.step(0, 1, "making plates.zip")
        with meter(5, desc="plates") as bar:
            for _ in range(5):
                with meter(3, desc="inner") as inner:  # nested: not the job's figure
                    inner.update(3)
                bar.update()
                seen.append((job.done, job.total, job.message))

    try:
        job = jobs.submit("make", work)
        end = time.monotonic() + 10
        while not job.ended and time.monotonic() < end:
            time.sleep(0.01)
        assert job.state == "done"
        assert seen == [(i, 5, "plates") for i in range(1, 6)]
    finally:
        jobs.shutdown()


def test_a_job_counting_its_own_steps_keeps_them(tmp_path):
    from voxfab._shared.progress import meter

    jobs = Jobs(tmp_path, workers=1)

    def work(job):
        job.step(1, 8, "1 of 8 nets")
        with meter(100, desc="net: faces placed") as bar:
            bar.update(50)

    try:
        job = jobs.submit("nets", work)
        end = time.monotonic() + 10
        while not job.ended and time.monotonic() < end:
            time.sleep(0.01)
        assert (job.done, job.total, job.message) == (1, 8, "1 of 8 nets")
    finally:
        jobs.shutdown()
