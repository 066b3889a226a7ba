"""The studio's net gallery for a sheet (the contract of issue 20): options, pieces, placement, ways out."""

from __future__ import annotations

import io
import zipfile

import numpy as np
import pytest

from voxfab.shape import examples, surface_graph
from voxfab.studio._grid import pack

from ._helpers import small_shape, wait_job


def _ball() -> np.ndarray:
    g = np.zeros((25, 25, 25), dtype=bool)
    b = examples.ball(6)
    g[6:6 + b.shape[0], 6:6 + b.shape[1], 6:6 + b.shape[2]] = b
    return g


def test_info_names_the_cli_sheets(client):
    from voxfab.fabricate.netdraw import SHEETS

    info = client.get("/api/info").json()
    assert info["sheets"] == {k: list(v) for k, v in SHEETS.items()}


def test_a_net_in_pieces_with_its_placement_then_files_where_the_pieces_were_moved(client):
    import ezdxf

    from voxfab.unfold import Net, validate

    g = _ball()
    # One net: the placement and the moved files below are of the gallery's first net only.
    r = client.post("/api/nets", json={"grid": pack(g), "seed": 1, "count": 1,
                                       "options": {"sheet": "A4", "face_size": 10, "pieces": "auto",
                                                   "label_height": 2.0, "timeout": 60}})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["job"], 240)
    assert s["state"] == "done", s
    net = s["result"]["nets"][0]
    assert net["pieces"] > 1 and s["result"]["options"]["face_size"] == 10
    lay, place = net["layout"], net["placement"]
    sg = surface_graph(g)
    assert len(lay["faces"]) == sg.face_count == net["faces"] and len(lay["corners"]) == 8 * sg.face_count
    assert sorted(set(lay["piece"])) == list(range(net["pieces"]))
    assert place["sheet"] == [210.0, 297.0] and len(place["pieces"]) == net["pieces"]
    assert net["fit"]["sheets"] == place["sheets"]
    # Move a piece onto a sheet of its own: a piece that shared its sheet adds one (a piece alone
    # leaves its old sheet empty, which is dropped); the pieces still refold.
    shared = [p["piece"] for p in place["pieces"] if sum(q["sheet"] == p["sheet"] for q in place["pieces"]) > 1]
    mover = shared[-1] if shared else net["pieces"] - 1
    moved = dict(place, sheets=place["sheets"] + 1,
                 pieces=[dict(p, sheet=place["sheets"]) if p["piece"] == mover else p for p in place["pieces"]])
    files = {}
    for artefact in ("net.dxf", "net.json"):
        m = client.post("/api/make", json={"grid": pack(g), "artefact": artefact, "title": "ball",
                                           "options": {"sheet": "A4", "face_size": 10, "label_height": 2.0},
                                           "net": {"job": r.json()["job"], "index": 0}, "placement": moved})
        done = wait_job(client, m.json()["job"], 120)
        assert done["state"] == "done", done
        files[artefact] = client.get(f"/api/files/{m.json()['job']}/0").content
    sheets = zipfile.ZipFile(io.BytesIO(files["net.dxf"]))
    assert len(sheets.namelist()) == place["sheets"] + (1 if shared else 0)
    for name in sheets.namelist():
        doc = ezdxf.read(io.StringIO(sheets.read(name).decode()))
        assert not doc.audit().has_errors
    pieces = zipfile.ZipFile(io.BytesIO(files["net.json"]))
    assert validate(g, [Net.from_json(pieces.read(n).decode()) for n in sorted(pieces.namelist())]).ok
    # Two pieces on top of each other: one line, no files.
    first = place["pieces"][0]
    over = dict(place, pieces=[dict(p, sheet=first["sheet"], x=first["x"], y=first["y"], turns=first["turns"])
                               if p["piece"] == 1 else p for p in place["pieces"]])
    m = client.post("/api/make", json={"grid": pack(g), "artefact": "net.svg", "title": "ball",
                                       "options": {"sheet": "A4", "face_size": 10, "label_height": 2.0},
                                       "net": {"job": r.json()["job"], "index": 0}, "placement": over})
    done = wait_job(client, m.json()["job"], 120)
    assert done["state"] == "error" and "pieces 1 and 2" in done["message"] and "\n" not in done["message"]


@pytest.mark.parametrize("count", [1, 3])
def test_a_net_that_does_not_fit_offers_its_ways_out(client, count):
    g = _ball()
    r = client.post("/api/nets", json={"grid": pack(g), "count": count,
                                       "options": {"sheet": "A5", "face_size": 12, "timeout": 3}})
    s = wait_job(client, r.json()["job"], 240)
    assert s["state"] == "error" and "does not fit sheet A5" in s["message"], s
    ways = {tuple(w["options"].items())[0] for w in s["ways_out"]}
    assert ("pieces", "auto") in ways and any(k == "sheet" for k, _ in ways)
    assert all("--" not in w["label"] for w in s["ways_out"])


def test_bad_gallery_options_get_the_cli_words(client):
    g = small_shape()
    for options, words in [({"sheet": "B9"}, "sheet: expected A5, A4"), ({"face_size": -1}, "face_size"),
                           ({"pieces": "many"}, "pieces"), ({"wobble": 1}, "wobble")]:
        r = client.post("/api/nets", json={"grid": pack(g), "options": options})
        assert r.status_code == 400 and words in r.json()["error"], (options, r.text)
    r = client.post("/api/nets", json={"grid": pack(g), "options": "A4"})
    assert r.status_code == 400 and "options" in r.json()["error"]


def test_the_page_carries_the_contract_test_ids(client):
    import re

    html = client.get("/").text
    ids = set(re.findall(r'data-testid="([a-z0-9-]+)"', html))
    wanted = {"tab-draw", "tab-edit", "tab-keep", "tab-net", "tab-make", "net-sheet", "net-sheet-custom",
              "net-face-size", "net-pieces", "net-generate", "net-2d", "view-3d", "download-net-svg",
              "download-net-dxf", "download-net-pdf", "download-net-json", "status"}
    assert wanted <= ids, wanted - ids
    # The gallery items and the sheet views are made by the page's scripts, with the same attribute.
    main = client.get("/static/js/main.js").text
    sheets = client.get("/static/js/sheets.js").text
    assert "'net-gallery-item'" in main and "'net-sheet-view'" in sheets


def test_a_placement_needs_a_chosen_net(client):
    r = client.post("/api/make", json={"grid": pack(small_shape()), "artefact": "net.svg",
                                       "placement": {"sheet": [210, 297]}})
    assert r.status_code == 400 and "pick a net first" in r.json()["error"]
