"""The studio shows the library's automatic face size and its words (issue #44, item 1): the queen on A2, one
piece, no face size, gets the largest at which a one-piece net was found, and a refusal names that face size."""

from __future__ import annotations

import re

import pytest

from voxfab.studio._grid import pack

from ._helpers import queen, wait_job

pytestmark = pytest.mark.slow


def _gallery(client, options: dict) -> dict:
    r = client.post("/api/nets", json={"grid": pack(queen()), "count": 1, "seed": 0, "options": options})
    assert r.status_code == 200, r.text
    return wait_job(client, r.json()["job"], limit=600)


def test_the_queen_on_a2_gets_the_largest_face_size_and_a_refusal_names_it(client):
    done = _gallery(client, {"sheet": "A2", "pieces": "one", "timeout": 60})
    assert done["state"] == "done", done
    face = done["result"]["options"]["face_size"]
    assert face >= 12.5  # 10.8, 11.5 and 12.5 mm each give a one-piece net on A2
    (net,) = done["result"]["nets"]
    assert net["fit"]["fits"] and net["fit"]["face_size"] == face and net["fit"]["sheets"] == 1
    refused = _gallery(client, {"sheet": "A2", "pieces": "one", "timeout": 60, "face_size": 14})
    shown = refused["result"]["nets"][0]["fit"] if refused["state"] == "done" else None
    message = shown["message"] if shown else refused["message"]
    said = re.search(r"faces up to ([\d.]+) mm", message)
    assert said is not None and float(said.group(1)) == face, message
    ways = shown["ways_out"] if shown else refused["ways_out"]
    assert {"face_size": face} in [w["options"] for w in ways]
