"""POST /api/nets/edit on the queen in pieces: after a cut the pieces it left alone stay on their sheet and spot,
/api/make draws the files as the editor laid them out, undo keeps them too, and "repack" packs afresh."""

from __future__ import annotations

import io
import re
import zipfile

import numpy as np

from voxfab.studio._grid import pack

from ._helpers import queen, wait_job

OPTIONS = {"sheet": "A5", "face_size": 12, "pieces": "auto", "label_height": 2.0}


def spots(net: dict) -> dict:
    """Every face's sheet and corners in mm, from the page's layout and placement: corner c of a piece lands
    at (x, y) + c turned * face size."""
    lay, place = net["layout"], net["placement"]
    corners = np.array(lay["corners"], dtype=float).reshape(-1, 4, 2)
    out = {}
    for k, face in enumerate(lay["faces"]):
        p = place["pieces"][lay["piece"][k]]
        c = corners[k]
        for _ in range(p["turns"]):
            c = np.stack([-c[:, 1], c[:, 0]], axis=1)
        out[tuple(face)] = (p["sheet"], np.array([p["x"], p["y"]]) + c * place["face_size"])
    return out


def pieces_of(net: dict) -> dict:
    """Each piece's faces, by piece."""
    out: dict[int, set] = {}
    for face, p in zip(net["layout"]["faces"], net["layout"]["piece"]):
        out.setdefault(p, set()).add(tuple(face))
    return {p: frozenset(f) for p, f in out.items()}


def made_sheets(client, job: str, placement: dict | None) -> list[bytes]:
    body = {"grid": pack(queen()), "artefact": "net.dxf", "title": "queen", "options": OPTIONS,
            "net": {"job": job, "index": 0}}
    if placement is not None:
        body["placement"] = placement
    m = client.post("/api/make", json=body)
    assert m.status_code == 200, m.text
    done = wait_job(client, m.json()["job"], 240)
    assert done["state"] == "done", done
    sheets = zipfile.ZipFile(io.BytesIO(client.get(f"/api/files/{m.json()['job']}/0").content))
    names = sorted(sheets.namelist(), key=lambda n: int(re.findall(r"\d+", n)[-1]))
    return [sheets.read(n) for n in names]


def outlines(sheet: bytes) -> list:
    import ezdxf
    from _dxf_read import closed_rings
    from _net_sheets import pieces_of as shells

    return shells(closed_rings(ezdxf.read(io.StringIO(sheet.decode()))))


def test_a_cut_keeps_the_other_pieces_in_place_and_the_files_are_the_layout_shown(client) -> None:
    import shapely

    r = client.post("/api/nets", json={"grid": pack(queen()), "seed": 1, "count": 1,
                                       "options": {**OPTIONS, "timeout": 20}})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["job"], 300)
    assert s["state"] == "done", s
    net = s["result"]["nets"][0]
    assert net["pieces"] > 15 and net["placement"] is not None
    lay = net["layout"]
    # A fold of the largest piece, cut off as a piece of its own.
    biggest = max(pieces_of(net).items(), key=lambda kv: len(kv[1]))[0]
    folds = [(i, j) for i, j in np.array(lay["folds"]).reshape(-1, 2).tolist() if lay["piece"][i] == biggest]
    i, j = folds[len(folds) // 2]
    e = client.post("/api/nets/edit", json={"job": r.json()["job"], "index": 0, "split": True,
                                            "cut": [lay["faces"][i], lay["faces"][j]]})
    assert e.status_code == 200, e.text
    cut = e.json()["net"]
    assert cut["pieces"] == net["pieces"] + 1 and cut["placement"]["sheets"] == cut["fit"]["sheets"]
    alone = set(pieces_of(net).values()) & set(pieces_of(cut).values())
    assert len(alone) == net["pieces"] - 1
    was, now = spots(net), spots(cut)
    for face in frozenset().union(*alone):
        assert was[face][0] == now[face][0] and np.allclose(was[face][1], now[face][1], atol=1e-6)
    # The files /api/make draws for the edited net, without a placement sent and with the one shown: the same
    # sheets, each face inside an outline of the sheet the editor shows it on, no two outlines over each other.
    kept = made_sheets(client, e.json()["job"], None)
    assert kept == made_sheets(client, e.json()["job"], cut["placement"])
    assert len(kept) == cut["placement"]["sheets"]
    shells = [outlines(sheet) for sheet in kept]
    assert sum(len(x) for x in shells) == cut["pieces"]
    for polygons in shells:
        for a_, b_ in ((a_, b_) for n, a_ in enumerate(polygons) for b_ in polygons[n + 1:]):
            assert a_.intersection(b_).area < 1e-6
    for sheet, corners in now.values():
        assert any(p.covers(shapely.Point(*corners.mean(axis=0))) for p in shells[sheet])
    # Undo: the net before the cut, its pieces where the page showed them.
    u = client.post("/api/nets/edit", json={"job": e.json()["job"], "index": 0, "undo": True})
    assert u.status_code == 200, u.text
    back = u.json()["net"]
    again = spots(back)
    for face in frozenset().union(*alone):
        assert again[face][0] == now[face][0] and np.allclose(again[face][1], now[face][1], atol=1e-6)
    # Packed afresh on request: the gallery's own packing of that net, the net unchanged.
    p = client.post("/api/nets/edit", json={"job": u.json()["job"], "index": 0, "repack": True})
    assert p.status_code == 200, p.text
    fresh = p.json()["net"]
    assert fresh["layout"] == net["layout"] and fresh["placement"] == net["placement"]
    assert fresh["undo"] == back["undo"] and fresh["edit"] == "repack"


def test_a_placement_sent_with_an_edit_is_checked(client) -> None:
    r = client.post("/api/nets", json={"grid": pack(queen()), "seed": 1, "count": 1,
                                       "options": {**OPTIONS, "timeout": 20}})
    s = wait_job(client, r.json()["job"], 300)
    lay = s["result"]["nets"][0]["layout"]
    i, j = np.array(lay["folds"]).reshape(-1, 2)[0].tolist()
    for placement, words in [("here", "placement: expected an object"),
                             ({"sheet": [210, 297]}, "placement.margin")]:
        e = client.post("/api/nets/edit", json={"job": r.json()["job"], "index": 0, "split": True,
                                                "cut": [lay["faces"][i], lay["faces"][j]], "placement": placement})
        assert e.status_code == 400 and words in e.json()["error"] and "\n" not in e.json()["error"]
    e = client.post("/api/nets/edit", json={"job": r.json()["job"], "index": 0, "repack": "yes"})
    assert e.status_code == 400 and "repack" in e.json()["error"]
