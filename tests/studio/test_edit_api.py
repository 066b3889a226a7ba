"""POST /api/nets/edit: cut and join an edge of a gallery net, the marks kept, undo back to the net before."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.studio._grid import pack
from voxfab.unfold import EdgeConstraints, Net, validate
from voxfab.unfold._layout import count_without_tab_room

from ._helpers import small_shape, wait_job


def as_net(layout: dict) -> Net:
    """A Net rebuilt from the page's LAYOUT alone (one piece): the independent check validates it."""
    faces = layout["faces"]
    normal = {"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0), "+z": (0, 0, 1), "-z": (0, 0, -1)}
    folds = np.array(layout["folds"]).reshape(-1, 2)
    nb = np.array(layout["neighbor"]).reshape(-1, 4)
    kind = np.array(layout["fold_type"]).reshape(-1, 4)
    kinds = [int(kind[i][list(nb[i]).index(j)]) for i, j in folds.tolist()]
    return Net(voxel=[f[:3] for f in faces], normal=[normal[f[3]] for f in faces],
               corners3d=np.array(layout["corners3d"]).reshape(-1, 4, 3),
               corners2d=np.array(layout["corners"]).reshape(-1, 4, 2), folds=folds, seed=0, strategy="page",
               mountain=kinds.count(1), valley=kinds.count(-1), flat=kinds.count(0))


def checked(grid, layout: dict, marks: dict | None = None) -> Net:
    net = as_net(layout)
    import dataclasses

    net = dataclasses.replace(net, seams_without_tab_room=count_without_tab_room(grid, net))
    report = validate(grid, net, strict=False, constraints=EdgeConstraints.from_dict(marks) if marks else None)
    assert report.ok, report.problems[:3]
    return net


@pytest.fixture
def gallery(client):
    grid = small_shape()
    r = client.post("/api/nets", json={"grid": pack(grid), "count": 1, "seed": 3, "options": {"timeout": 10}})
    assert r.status_code == 200, r.text
    status = wait_job(client, r.json()["job"])
    assert status["state"] == "done", status
    return grid, r.json()["job"], status["result"]["nets"][0]["layout"]


def pair_faces(layout: dict, i: int, j: int) -> list:
    return [layout["faces"][i], layout["faces"][j]]


def test_cut_join_and_undo(client, gallery):
    grid, job, layout = gallery
    folds = np.array(layout["folds"]).reshape(-1, 2)
    cut = None
    for i, j in folds.tolist()[::-1]:  # the last folds lie towards the outline, where there is room
        r = client.post("/api/nets/edit", json={"job": job, "index": 0, "cut": pair_faces(layout, i, j),
                                                "grid": pack(grid)})
        if r.status_code == 200:
            cut = r.json()
            break
        assert r.json()["error"].startswith("no room to re-attach"), r.text
    assert cut is not None
    new = cut["net"]["layout"]
    assert cut["net"]["pieces"] == 1 and cut["net"]["undo"] == 1 and cut["net"]["moved"] >= 1
    assert [i, j] not in np.array(new["folds"]).reshape(-1, 2).tolist()
    assert cut["net"]["marks"] == {"cut": [sorted(pair_faces(layout, i, j))], "keep": []}
    checked(grid, new, cut["net"]["marks"])
    # the cut edge is a seam now, with a label for both its halves
    assert f"{min(i, j)}-{max(i, j)}" in new["labels"]
    assert sorted(set(new["piece"])) == [0] and new["parent"].count(-1) == 1
    # The edited net is the new job's net 0: the next edit starts from it and keeps the cut mark.
    nb = np.array(new["neighbor"]).reshape(-1, 4)
    folded = {tuple(p) for p in np.array(new["folds"]).reshape(-1, 2).tolist()}
    seams = [(a, int(b)) for a in range(nb.shape[0]) for b in nb[a] if a < b and (a, b) not in folded
             and {a, b} != {i, j}]
    joined = None
    for a, b in seams:
        r = client.post("/api/nets/edit", json={"job": cut["job"], "index": 0, "join": pair_faces(new, a, b)})
        if r.status_code == 200:
            joined = r.json()
            break
        assert r.json()["error"].startswith("no room to join"), r.text
    assert joined is not None
    after = joined["net"]["layout"]
    assert [a, b] in np.array(after["folds"]).reshape(-1, 2).tolist()
    marks = joined["net"]["marks"]
    assert marks["cut"] == cut["net"]["marks"]["cut"] and marks["keep"] == [sorted(pair_faces(new, a, b))]
    checked(grid, after, marks)
    # Undo twice: back to the cut net, then to the gallery's own net.
    back = client.post("/api/nets/edit", json={"job": joined["job"], "index": 0, "undo": True}).json()
    assert back["net"]["layout"] == new and back["net"]["marks"] == cut["net"]["marks"]
    first = client.post("/api/nets/edit", json={"job": back["job"], "index": 0, "undo": True}).json()
    assert first["net"]["layout"]["corners"] == layout["corners"] and first["net"]["marks"]["cut"] == []
    r = client.post("/api/nets/edit", json={"job": first["job"], "index": 0, "undo": True})
    assert r.status_code == 400 and "no edit" in r.json()["error"]


def test_edited_net_is_made_into_files(client, gallery):
    grid, job, layout = gallery
    folds = np.array(layout["folds"]).reshape(-1, 2)
    for i, j in folds.tolist()[::-1]:
        edited = client.post("/api/nets/edit", json={"job": job, "index": 0, "cut": pair_faces(layout, i, j),
                                                     "grid": pack(grid)}).json()
        if "net" in edited:
            break
    r = client.post("/api/make", json={"grid": pack(grid), "artefact": "net.json", "pitch": 10.0,
                                       "net": {"job": edited["job"], "index": 0}})
    assert r.status_code == 200, r.text
    status = wait_job(client, r.json()["job"])
    assert status["state"] == "done", status
    made = Net.from_json(client.get(f"/api/files/{r.json()['job']}/0").text)
    # the file is the edited net, face for face
    assert made.corners2d.reshape(-1).tolist() == edited["net"]["layout"]["corners"]


@pytest.mark.parametrize("body, words", [
    ({"job": "0" * 16, "index": 0, "undo": True}, "no job"),
    ({"index": 0, "undo": True}, "expected {"),
    ({"job": "JOB", "index": 5, "undo": True}, "index"),
    ({"job": "JOB", "index": 0}, "exactly one of"),
    ({"job": "JOB", "index": 0, "cut": [[0, 0, 0, "up"], [0, 0, 0, "+z"]]}, "normal"),
    ({"job": "JOB", "index": 0, "cut": "edge"}, "pair of faces"),
    ({"job": "JOB", "index": 0, "undo": True}, "no edit"),
    ({"job": "JOB", "index": 0, "join": "FOLD"}, "already a fold"),
])
def test_bad_edits_are_one_line(client, gallery, body, words):
    grid, job, layout = gallery
    body = dict(body, grid=pack(grid))
    if body.get("job") == "JOB":
        body["job"] = job
    if body.get("join") == "FOLD":
        i, j = layout["folds"][:2]
        body["join"] = pair_faces(layout, i, j)
    r = client.post("/api/nets/edit", json=body)
    assert r.status_code == 400, r.text
    assert words in r.json()["error"] and "\n" not in r.json()["error"]


def test_marks_from_the_page_start_a_fresh_nets_record(client, gallery):
    grid, job, layout = gallery
    folds = np.array(layout["folds"]).reshape(-1, 2)
    folded = {tuple(p) for p in folds.tolist()}
    nb = np.array(layout["neighbor"]).reshape(-1, 4)
    # a seam of the gallery net, marked cut on the page before any edit
    a, b = next((a, int(b)) for a in range(nb.shape[0]) for b in nb[a] if a < b and (a, b) not in folded)
    page_marks = {"cut": [sorted(pair_faces(layout, a, b))], "keep": []}
    for i, j in folds.tolist()[::-1]:
        r = client.post("/api/nets/edit", json={"job": job, "index": 0, "cut": pair_faces(layout, i, j),
                                                "marks": page_marks})
        if r.status_code == 200:
            break
    assert r.status_code == 200, r.text
    marks = r.json()["net"]["marks"]
    assert sorted(marks["cut"]) == sorted(page_marks["cut"] + [sorted(pair_faces(layout, i, j))])
    checked(grid, r.json()["net"]["layout"], marks)
