"""``POST /api/fits``: the studio's "does it fit this sheet?" on the exact strategy, and its net drawn by Make."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("ortools")

from voxfab.recipe import load_recipe, make_shape  # noqa: E402
from voxfab.studio._grid import pack  # noqa: E402
from voxfab.unfold import validate  # noqa: E402

from ._helpers import wait_job  # noqa: E402

QUEEN = Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml"


def _cube() -> np.ndarray:
    g = np.zeros((25, 25, 25), dtype=bool)
    g[12, 12, 12] = True
    return g


def test_the_cube_is_proved_not_to_fit_and_then_fits(client):
    r = client.post("/api/fits", json={"grid": pack(_cube()), "options": {"sheet": "60x70", "face_size": 10}})
    assert r.status_code == 200, r.text
    done = wait_job(client, r.json()["job"])
    assert done["state"] == "done", done
    assert done["result"]["answer"] == "no" and done["result"]["box"] == [3, 3]
    assert "(proved)" in done["result"]["message"] and "net" not in done["result"]

    r = client.post("/api/fits", json={"grid": pack(_cube()), "options": {"sheet": "60x90", "face_size": 10}})
    job = r.json()["job"]
    done = wait_job(client, job)
    res = done["result"]
    assert res["answer"] == "yes" and res["box"] == [3, 5] and res["faces"] == 6
    w, h = res["net"]["extent"]
    assert (w <= 3 and h <= 5) or (h <= 3 and w <= 5)
    # The net that fits is the job's net 0: Make draws that very net.
    made = client.post("/api/make", json={"grid": pack(_cube()), "artefact": "net.json", "pitch": 10.0,
                                          "title": "cube", "net": {"job": job, "index": 0},
                                          "options": {"face_size": 10, "sheet": "60x90"}})
    assert made.status_code == 200, made.text
    status = wait_job(client, made.json()["job"])
    assert status["state"] == "done", status
    from voxfab.unfold import Net

    got = client.get(f"/api/files/{made.json()['job']}/0")
    net = Net.from_json(got.text)
    assert validate(_cube(), net).ok
    x0, y0, x1, y1 = net.bounds()
    assert sorted((x1 - x0, y1 - y0)) == sorted((w, h))


def test_the_queen_fits_a2_at_10_mm(client):
    queen = make_shape(load_recipe(QUEEN)).grid
    r = client.post("/api/fits", json={"grid": pack(queen), "options": {"sheet": "A2", "face_size": 10, "timeout": 120}})
    done = wait_job(client, r.json()["job"], limit=300)
    res = done["result"]
    assert res["answer"] == "yes" and res["box"] == [39, 56] and res["faces"] == 862
    w, h = res["net"]["extent"]
    assert (w <= 39 and h <= 56) or (h <= 39 and w <= 56)
    assert len(res["net"]["layout"]["faces"]) == 862


@pytest.mark.parametrize(("body", "word"), [
    ({"sheet": "B99"}, "sheet"), ({"face_size": 0}, "face_size"), ({"timeout": 1e9}, "timeout"), ({"sheet": 4}, "sheet"),
])
def test_bad_requests_are_one_line_400s(client, body, word):
    r = client.post("/api/fits", json={"grid": pack(_cube()), "options": body})
    assert r.status_code == 400 and word in r.json()["error"]


def test_two_pieces_are_refused(client):
    g = _cube()
    g[0, 0, 0] = True
    r = client.post("/api/fits", json={"grid": pack(g)})
    assert r.status_code == 400 and "one piece" in r.json()["error"]
