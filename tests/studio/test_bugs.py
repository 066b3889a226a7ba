"""Bugs an artist found in the studio (issue 20), checked through the API: each one stays fixed."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.digitize import revolution
from voxfab.studio._grid import InitialShape, pack, unpack
from voxfab.studio._words import explained, plain

CIRCLE = {"kind": "expr", "text": "x^2 + y^2 = 1"}
#: A hand stroke in the page's drawing units (axis at x = 20): from near the axis round a profile and back,
#: its ends a few pixels off the axis, as a hand draws them.
ROUND = [[24, 12], [80, 10], [92, 70], [70, 130], [55, 170], [75, 215], [60, 250], [23, 252]]


def _draw(points, closed, mode="solid"):
    return {"maker": "revolution", "k": 0, "mode": mode, "curve": CIRCLE, "axis": 20,
            "generatrix": {"kind": "drawn", "polylines": [{"points": points, "closed": closed}]}}


# --- hollow solid -------------------------------------------------------------------------------

@pytest.mark.parametrize("ends", [(24, 23), (20, 20), (26, 21)])
def test_an_open_stroke_from_the_axis_and_back_gives_the_solid(client, ends):
    """Open or closed, the same stroke gives the same solid: the axis column is filled, nothing is hollow."""
    pts = [[ends[0], 12], *ROUND[1:-1], [ends[1], 252]]
    open_ = client.post("/api/preview", json=_draw(pts, False)).json()
    closed = client.post("/api/preview", json=_draw(pts, True)).json()
    a, b = unpack(open_["grid"]), unpack(closed["grid"])
    assert (a == b).all(), (int(a.sum()), int(b.sum()))
    cx, cy = (int(round(c)) for c in np.argwhere(a).mean(axis=0)[:2])
    assert a[cx, cy, :].sum() >= 24  # the axis column, not a shell around an empty core
    # Independently: no cavity, and every voxel of the surface-only digitization is in the solid.
    from voxfab.shape import cavity_count

    assert cavity_count(a) == 0
    shell = unpack(client.post("/api/preview", json=_draw(pts, False, mode="surface")).json()["grid"])
    assert a.sum() > shell.sum() and not (shell & ~a).any()


def test_the_library_snaps_only_ends_near_the_axis():
    """An open generatrix ending well away from the axis keeps its hole (a pipe stays a pipe)."""
    pipe = [[0.3, 0.0], [1.0, 0.0], [1.0, 2.0], [0.3, 2.0]]  # ends 15% of the diameter off the axis
    near = [[0.05, 0.0], [1.0, 0.0], [1.0, 2.0], [0.05, 2.0]]  # ends 2.5%: on the axis
    on = [[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [0.0, 2.0]]
    g_pipe = revolution(lambda x, y: x * x + y * y - 1, pipe, axis=0.0)
    g_near = revolution(lambda x, y: x * x + y * y - 1, near, axis=0.0)
    g_on = revolution(lambda x, y: x * x + y * y - 1, on, axis=0.0)
    assert (g_near == g_on).all()
    c = np.argwhere(g_pipe).mean(axis=0).round().astype(int)
    assert not g_pipe[c[0], c[1], 5:-5].any() and g_on[c[0], c[1], :].all()


# --- oversized shapes and paths -----------------------------------------------------------------

@pytest.mark.parametrize("endpoint", ["/api/check", "/api/repo", "/api/nets", "/api/make"])
def test_grids_larger_than_the_page_opens_are_refused(client, endpoint):
    big = np.zeros((26, 25, 25), dtype=bool)
    big[:, 12, 12] = True
    body = {"grid": pack(big), **({"artefact": "mesh.stl"} if endpoint == "/api/make" else {})}
    r = client.post(endpoint, json=body)
    assert r.status_code == 400
    err = r.json()["error"]
    assert "26x25x25" in err and "25x25x25" in err and "\n" not in err
    ok = np.zeros((25, 25, 25), dtype=bool)
    ok[:, 12, 12] = True
    assert client.post("/api/check", json={"grid": pack(ok)}).status_code == 200


def test_nothing_oversized_reaches_the_repository(client, tmp_path):
    big = np.ones((40, 3, 3), dtype=bool)
    assert client.post("/api/repo", json={"grid": pack(big), "draft": True}).status_code == 400
    assert client.get("/api/repo").json()["shapes"] == []


def test_repository_errors_name_the_repository_not_its_folder(client, tmp_path):
    client.post("/api/repo", json={"grid": pack(np.pad(np.ones((3, 3, 25), bool), ((11, 11), (11, 11), (0, 0))))})
    for url in ("/api/repo/shape?name=99999.001", "/api/repo/thumb?name=99999.001"):
        r = client.get(url)
        assert r.status_code == 400
        body = r.json()
        assert "99999.001" in body["error"] and "repo.sqlite" in body["error"]
        assert str(tmp_path) not in body["error"] and str(tmp_path) not in body.get("detail", "")


def test_an_initial_shape_larger_than_the_editor_is_one_line():
    with pytest.raises(Exception) as info:
        InitialShape.of(np.ones((26, 2, 2), dtype=bool), label="big.npy")
    assert "25" in str(info.value) and "\n" not in str(info.value)


# --- jargon -------------------------------------------------------------------------------------

def test_well_formedness_reasons_are_in_plain_words_with_the_term_kept(client):
    g = np.zeros((25, 25, 25), dtype=bool)
    g[2:5, 2:5, 2:5] = True
    g[10:13, 10:13, 10:13] = True
    facts = client.post("/api/check", json={"grid": pack(g)}).json()["facts"]
    text = " ".join(facts["reasons"])
    assert "2 separate pieces" in text and "reach right across the 25-voxel box" in text
    assert "6-connected" not in text
    assert any("6-connected" in t for t in facts["terms"])  # the technical line for the tooltip


def test_refused_keep_says_how_in_the_pages_words(client):
    g = np.zeros((25, 25, 25), dtype=bool)
    g[2:5, 2:5, 2:5] = True
    body = client.post("/api/repo", json={"grid": pack(g)}).json()
    assert "draft=True" not in body["error"] and "as a draft if not well formed" in body["error"]
    assert "draft=True" in body["detail"]


def test_cli_options_in_messages_become_the_pages_choices():
    cli = ("net: 58x61 faces: it fits A4 at faces up to 1.5 mm, and A2 (--sheet); "
           "or split it into pieces (--pieces auto)")
    said = explained(cli)
    assert "--" not in said["text"] and "(choose sheet)" in said["text"]
    # the pieces menu's own words, not the CLI's value
    assert "(choose pieces: split into pieces if needed)" in said["text"] and "auto" not in said["text"]
    assert said["detail"] == cli
    engine = ("no one-piece net of the 1270-face surface in 30 s; raise the timeout, or allow several pieces "
              "(pieces='auto', CLI --pieces auto); fill the cavities (fill=True, CLI --fill)")
    words = plain(engine)
    assert "CLI" not in words and "'auto'" not in words and "=True" not in words
    assert "(choose pieces: split into pieces if needed)" in words and "(choose fill: on)" in words
    assert plain("a message without terms") == "a message without terms"
    assert "detail" not in explained("a message without terms")


def test_server_failures_and_the_complete_search_in_plain_words():
    said = explained("internal error (OSError): [Errno 28] No space left on device")
    assert "OSError" not in said["text"] and "Errno" not in said["text"] and "server" in said["text"]
    assert said["detail"] == "internal error (OSError): [Errno 28] No space left on device"  # the tooltip
    said = explained("undecided: the exact search ran out of time at the 40x52 box")
    assert "exact search" not in said["text"] and "complete search" in said["text"]
    assert "exact search" in said["detail"]


def test_a_job_that_fails_unexpectedly_says_so_plainly_with_the_exception_as_detail(client, monkeypatch):
    from voxfab.studio import _work

    from ._helpers import small_shape, wait_job

    def broken(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(_work, "make_files", broken)
    job = client.post("/api/make", json={"grid": pack(small_shape()), "artefact": "mesh.stl"}).json()["job"]
    status = wait_job(client, job)
    assert status["state"] == "error"
    assert "OSError" not in status["message"] and "server could not finish" in status["message"]
    assert "OSError" in status["detail"] and "No space left" in status["detail"]
