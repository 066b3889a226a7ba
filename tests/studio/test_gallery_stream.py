"""A gallery of nets in pieces streams: each net reaches the page as soon as it is made, and Cancel stops
any net job (a gallery, a pieces cut, a packing, a net file in pieces) within a second."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import numpy as np
import pytest

from voxfab.recipe import load_recipe, make_shape
from voxfab.studio._grid import pack

from ._helpers import wait_job

QUEEN = Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml"
A4_PIECES = {"sheet": "A4", "pieces": "auto", "timeout": 30.0}


@pytest.fixture(scope="module")
def queen() -> np.ndarray:
    return make_shape(load_recipe(QUEEN)).grid


def _poll(client, job: str, since: int) -> dict:
    r = client.get(f"/api/jobs/{job}?since={since}")
    assert r.status_code == 200, r.text
    return r.json()


def test_a_queen_gallery_in_pieces_gives_each_net_before_it_is_done(client, queen):
    """The items come one by one while the job runs; each is usable at once; the result repeats them."""
    from voxfab.unfold import Net, validate

    count = 3
    job = client.post("/api/nets", json={"grid": pack(queen), "count": count, "seed": 0,
                                         "options": A4_PIECES}).json()["job"]
    items: list[dict] = []
    early: dict | None = None  # the status that first gave an item while the job still ran
    end = time.monotonic() + 600
    while time.monotonic() < end:
        s = _poll(client, job, len(items))
        assert s["made"] == len(items) + len(s["items"]) and s["made"] <= count
        items += s["items"]
        if items and early is None and s["state"] == "running":
            early = s
            # The first net, while the gallery still cuts the others: its file refolds onto the queen.
            m = client.post("/api/make", json={"grid": pack(queen), "artefact": "net.json",
                                               "net": {"job": job, "index": 0}, "options": A4_PIECES})
            assert m.status_code == 200, m.text
            first_file = m.json()["job"]
        if s["state"] != "running" and s["state"] != "queued":
            break
        time.sleep(0.05)
    assert s["state"] == "done", s
    assert early is not None, "no item before the gallery was done"
    assert early["made"] < count and early["done"] < count  # progress counts what is really done
    assert [n["index"] for n in items] == list(range(count))
    assert s["result"]["nets"] == items and s["result"]["found"] == count
    # Both cuts of the first seed, each laid out once; every net fits A4 in pieces on its own sheets.
    assert {n["seed"] for n in items[:2]} == {0}
    assert items[0]["pieces"] != items[1]["pieces"]
    for n in items:
        assert n["pieces"] > 1 and n["fit"]["fits"] and n["placement"]["sheets"] == n["fit"]["sheets"]
        assert n["placement"]["sheet"] == [210.0, 297.0] and len(n["placement"]["pieces"]) == n["pieces"]
    made = wait_job(client, first_file, 300)
    assert made["state"] == "done", made
    names = [f["name"] for f in made["files"]]
    assert names and all(x.endswith((".json", ".zip")) for x in names)
    raw = client.get(f"/api/files/{first_file}/0").content
    if names[0].endswith(".zip"):
        import io
        import zipfile

        with zipfile.ZipFile(io.BytesIO(raw)) as zf:
            pieces = [Net.from_json(zf.read(x).decode()) for x in sorted(zf.namelist())]
    else:
        pieces = [Net.from_json(raw.decode())]
    assert len(pieces) == items[0]["pieces"]
    assert validate(queen, pieces).ok
    # a bad "since" is one line
    r = client.get(f"/api/jobs/{job}?since=-1")
    assert r.status_code == 400 and "since" in r.json()["error"]


def _cancel_latency(client, job: str) -> float:
    t0 = time.monotonic()
    r = client.post(f"/api/jobs/{job}/cancel")
    assert r.status_code == 200
    while (s := client.get(f"/api/jobs/{job}").json())["state"] not in ("cancelled", "done", "error"):
        assert time.monotonic() - t0 < 30, s
        time.sleep(0.01)
    assert s["state"] == "cancelled", s
    return time.monotonic() - t0


@pytest.mark.parametrize("when", ["first net shown", "cutting the first net"])
def test_cancel_stops_a_queen_pieces_gallery_within_a_second(client, queen, when):
    """Cancelled while it cuts (growth) or packs: the job ends in under a second."""
    job = client.post("/api/nets", json={"grid": pack(queen), "count": 8, "seed": 3,
                                         "options": A4_PIECES}).json()["job"]
    end = time.monotonic() + 600
    while time.monotonic() < end:
        s = client.get(f"/api/jobs/{job}").json()
        if s["state"] == "running" and (s["made"] >= 1 if when == "first net shown" else True):
            break
        assert s["state"] in ("queued", "running"), s
        time.sleep(0.02)
    if when == "cutting the first net":
        time.sleep(0.5)
    latency = _cancel_latency(client, job)
    assert latency < 1.0, f"cancel took {latency:.2f} s ({when})"


def test_cancel_stops_a_queen_net_file_in_pieces_within_a_second(client, queen):
    """`voxfab net --pieces auto` as a studio download (cut, pack, draw) stops within a second."""
    m = client.post("/api/make", json={"grid": pack(queen), "artefact": "net.svg", "title": "queen",
                                       "options": {"sheet": "A4", "pieces": "auto", "face_size": 8.6}})
    assert m.status_code == 200, m.text
    job = m.json()["job"]
    end = time.monotonic() + 120
    while client.get(f"/api/jobs/{job}").json()["state"] == "queued" and time.monotonic() < end:
        time.sleep(0.02)
    time.sleep(0.3)  # under way: the net is cut, packed and drawn in a second or two of CPU
    latency = _cancel_latency(client, job)
    assert latency < 1.0, f"cancel took {latency:.2f} s"


def test_the_packer_sees_the_cancel_scope(queen):
    """Packing the queen's pieces stops at once inside a cancelled scope, and runs whole outside one."""
    from voxfab._shared.progress import cancel_scope
    from voxfab.errors import CancelledError
    from voxfab.fabricate.netdraw import gallery_options
    from voxfab.fabricate.netdraw._drawing import sheet_plan
    from voxfab.fabricate.netdraw._sheets import sheet_cells
    from voxfab.shape import surface_graph
    from voxfab.unfold import unfold

    _, options = gallery_options({"sheet": "A4", "face_size": 8.6})
    # A seed no other test packs: the packer keeps the packings it made (in this process) and returns them.
    pieces = unfold(queen, rng=98765, fit=sheet_cells(options, 8.6), pieces="flat", timeout=60)
    graph = surface_graph(queen)
    assert len(pieces) > 1
    stop = threading.Event()
    stop.set()
    from voxfab.fabricate.netdraw import _sheets

    with _sheets._PACKED_LOCK:  # packings are remembered: pack again, not from memory
        _sheets._PACKED.clear()
    t0 = time.monotonic()
    with cancel_scope(stop), pytest.raises(CancelledError):
        sheet_plan(graph, pieces, options)
    assert time.monotonic() - t0 < 1.0
    # Packed first here, outside the scope (the packer keeps a packing it has made, never a cancelled one).
    assert sheet_plan(graph, pieces, options).count >= 2
