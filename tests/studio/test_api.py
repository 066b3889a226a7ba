"""The studio's HTTP API without a browser: every endpoint, good and bad input, and the security rules."""

from __future__ import annotations

import base64
import io
import json
import zipfile

import numpy as np
import pytest
from PIL import Image

from voxfab.digitize import revolution
from voxfab.recipe import load_recipe, make_shape
from voxfab.repo import Repository
from voxfab.shape import canonical_key
from voxfab.studio._grid import centred, pack, unpack

from ._helpers import png, small_shape, wait_job

CIRCLE = {"kind": "expr", "text": "x^2 + y^2 = 1"}
WAVY = {"kind": "expr", "text": "x = 0.6 + 0.3*sin(3*y)"}
SQUARE = {"kind": "drawn", "polylines": [{"points": [[0, 0], [100, 0], [100, 100], [0, 100]], "closed": True}]}
VASE = {"kind": "drawn", "polylines": [{"points": [[20, 0], [70, 0], [90, 60], [45, 140], [80, 250], [20, 255]],
                                        "closed": False}]}
DISK_PNG = png(lambda d: d.ellipse((10, 10, 90, 90), fill=0))
BAR_PNG = png(lambda d: d.rectangle((0, 5, 40, 95), fill=0))
DISK = {"kind": "bitmap", "data": base64.b64encode(DISK_PNG).decode()}
BAR = {"kind": "bitmap", "data": base64.b64encode(BAR_PNG).decode()}


def rev(curve, generatrix, **extra):
    spec = {"maker": "revolution", "k": 0, "mode": "solid", "curve": curve, "generatrix": generatrix}
    if generatrix.get("kind") == "drawn":
        spec["axis"] = 20
    spec.update(extra)
    return spec


def grid_of(answer) -> np.ndarray:
    return unpack(answer["grid"])


# --- page, static files, security -------------------------------------------------------------

def test_page_and_its_files(client):
    r = client.get("/")
    assert r.status_code == 200 and "voxfab studio" in r.text and 'src="/static/js/main.js"' in r.text
    assert "default-src 'self'" in r.headers["content-security-policy"]
    for name in ("studio.css", "js/main.js", "js/viewer.js", "js/grid.js", "js/draw.js", "js/editor.js", "js/nets.js",
                 "js/api.js"):
        r = client.get(f"/static/{name}")
        assert r.status_code == 200 and r.content, name
    assert client.get("/static/js/main.js").headers["content-type"].startswith("text/javascript")
    # no request path reaches the file system: only the packaged table answers
    for bad in ("/static/../_app.py", "/static/%2e%2e/_app.py", "/static/..%2f__init__.py", "/static/nope.js",
                "/static//etc/passwd"):
        assert client.get(bad).status_code == 404, bad


def test_foreign_host_and_origin_are_refused(client):
    assert client.get("/", headers={"host": "evil.example:8765"}).status_code == 403
    assert client.get("/api/info", headers={"host": "127.0.0.1.evil.example"}).status_code == 403
    r = client.post("/api/check", json={}, headers={"origin": "http://evil.example"})
    assert r.status_code == 403 and "other sites" in r.text
    ok = client.post("/api/check", json={"grid": pack(small_shape())}, headers={"origin": "http://testserver"})
    assert ok.status_code == 200


def test_allowed_hosts_are_the_servers_own_address():
    from voxfab.studio import allowed_hosts

    assert allowed_hosts("127.0.0.1", 8765) == {"127.0.0.1:8765", "localhost:8765", "[::1]:8765"}
    assert allowed_hosts("192.168.1.5", 9000) == {"192.168.1.5:9000"}
    assert "127.0.0.1:80" in allowed_hosts("0.0.0.0", 80) and "evil.example:80" not in allowed_hosts("0.0.0.0", 80)


def test_request_size_is_limited(client):
    from voxfab.studio._guard import MAX_BODY

    big = b"x" * (MAX_BODY + 1)
    r = client.post("/api/preview", content=big, headers={"content-type": "application/json"})
    assert r.status_code == 413 and "larger than" in r.json()["error"]

    def chunks():  # no Content-Length: the body is counted as it streams in
        for _ in range(MAX_BODY // 65536 + 2):
            yield b" " * 65536

    r = client.post("/api/preview", content=chunks(), headers={"content-type": "application/json"})
    assert r.status_code == 413


def test_unknown_endpoints_and_methods_answer_json(client):
    r = client.get("/api/nope")
    assert r.status_code == 404 and "no such endpoint" in r.json()["error"]
    r = client.get("/api/preview")
    assert r.status_code == 405 and r.json()["error"]


def test_unexpected_failure_is_one_line_not_a_traceback(client, monkeypatch):
    from voxfab.studio import _grid

    def boom(grid):
        raise RuntimeError("disk on fire\nTraceback (most recent call last):")

    monkeypatch.setattr(_grid, "facts", boom)
    r = client.post("/api/check", json={"grid": pack(small_shape())})
    assert r.status_code == 500
    # plain words for the page, the exception's one line as the tooltip
    assert r.json() == {"error": "the server could not finish this (the technical line is in the tooltip)",
                        "detail": "internal error (RuntimeError): disk on fire Traceback (most recent call last):"}


def test_info(client):
    info = client.get("/api/info").json()
    assert info["side"] == 25 and info["repository"] == "repo.sqlite" and "net.svg" in info["artefacts"]


# --- drawing ----------------------------------------------------------------------------------

CURVES = {"expr": CIRCLE, "drawn": SQUARE, "bitmap": DISK}
GENERATRICES = {"expr": WAVY, "drawn": VASE, "bitmap": BAR}


@pytest.mark.parametrize("g", sorted(GENERATRICES))
@pytest.mark.parametrize("c", sorted(CURVES))
def test_all_nine_combinations_match_the_library(client, tmp_path, c, g):
    spec = rev(CURVES[c], GENERATRICES[g])
    r = client.post("/api/preview", json=spec)
    assert r.status_code == 200, r.text
    got = grid_of(r.json())
    assert r.json()["facts"]["well_formed"], r.json()["facts"]
    # the same sources straight through the library
    sources = {}
    for role, src in (("curve", CURVES[c]), ("generatrix", GENERATRICES[g])):
        if src["kind"] == "expr":
            sources[role] = src["text"]
        elif src["kind"] == "drawn":
            (tmp_path / f"{role}.json").write_text(json.dumps({"polylines": src["polylines"]}))
            sources[role] = f"{role}.json"
        else:
            (tmp_path / f"{role}.png").write_bytes(base64.b64decode(src["data"]))
            sources[role] = f"{role}.png"
    want = revolution(sources["curve"], sources["generatrix"], base_dir=tmp_path,
                      axis=20.0 if g == "drawn" else None)
    assert np.array_equal(got, centred(want))


def test_several_components_and_open_closed_drawings(client):
    two = {"kind": "drawn", "polylines": [
        {"points": [[0, 0], [40, 0], [40, 40], [0, 40]], "closed": True},
        {"points": [[60, 60], [100, 60], [100, 100], [60, 100]], "closed": True}]}
    r = client.post("/api/preview", json=rev(two, WAVY, mode="surface"))
    assert r.status_code == 200, r.text
    # a closed drawn generatrix is a region; two open strokes are runs
    ring = {"kind": "drawn", "polylines": [{"points": [[40, 0], [80, 0], [80, 200], [40, 200]], "closed": True}]}
    assert client.post("/api/preview", json=rev(CIRCLE, ring)).status_code == 200
    strokes = {"kind": "drawn", "polylines": [VASE["polylines"][0],
                                              {"points": [[20, 300], [60, 320], [20, 340]], "closed": False}]}
    r = client.post("/api/preview", json=rev(CIRCLE, strokes, mode="surface"))
    assert r.status_code == 200, r.text


def test_explicit_generatrix_heights(client):
    a = grid_of(client.post("/api/preview", json=rev(CIRCLE, WAVY, z_range=[-1, 1])).json())
    b = grid_of(client.post("/api/preview", json=rev(CIRCLE, WAVY, z_range=[0, 3])).json())
    assert not np.array_equal(a, b)


@pytest.mark.parametrize(("spec", "message"), [
    ("not json", "not JSON"),
    ({"maker": "nope"}, "shape.maker: expected one of revolution, tube, focal, implicit"),
    (rev(CIRCLE, WAVY, k=7), "k: expected an integer in 0..2"),
    (rev(CIRCLE, WAVY, k="1"), "shape.k: expected int"),
    (rev(CIRCLE, WAVY, mode="hollow"), "mode"),
    (rev({"kind": "expr", "text": "x^^2"}, WAVY), "syntax error at column"),
    (rev({"kind": "expr", "text": "import os"}, WAVY), "curve"),
    (rev(CIRCLE, {"kind": "drawn", "polylines": []}), "generatrix: draw at least one stroke"),
    (rev(CIRCLE, {"kind": "drawn", "polylines": [{"points": [[1, 2, 3]]}]}), "expected 2 coordinates"),
    (rev(CIRCLE, {"kind": "drawn", "polylines": [{"points": [[1, "a"]]}]}), "expected a finite number"),
    (rev(CIRCLE, {"kind": "drawn", "polylines": [{"points": [[0, i] for i in range(20001)]}]}), "at most 20000"),
    (rev(CIRCLE, {"kind": "bitmap", "data": "bm90IGFuIGltYWdl"}), "not a PNG, GIF or BMP"),
    (rev(CIRCLE, {"kind": "bitmap", "data": "***"}), "not base64"),
    (rev(CIRCLE, {"kind": "wave"}), "generatrix.kind: expected 'expr', 'drawn' or 'bitmap'"),
    (rev(CIRCLE, {"kind": "drawn", "polylines": [{"points": [[0, 0], [50, 50]], "closed": False}]}),
     "crosses the axis"),
    (rev(CIRCLE, {"kind": "expr", "text": "x = -1"}), "never positive"),
    (rev(CIRCLE, WAVY, z_range=[2, 1]), "low < high"),
])
def test_bad_drawings_get_one_clear_line(client, spec, message):
    body = spec if isinstance(spec, str) else json.dumps(spec)
    r = client.post("/api/preview", content=body, headers={"content-type": "application/json"})
    assert r.status_code == 400, r.text
    error = r.json()["error"]
    assert message in error and "\n" not in error and "Traceback" not in error
    assert "/tmp" not in error and "draw-" not in error  # no scratch paths


def test_tube_focal_and_implicit_previews(client):
    tube = {"maker": "tube", "profile": {"kind": "expr", "text": "x^2 + y^2 - 1"},
            "spine": {"kind": "expr", "x": "cos(2*pi*t)", "y": "sin(2*pi*t)", "z": "0"},
            "frame": "frenet", "radius": 0.3, "twist": 0}
    r = client.post("/api/preview", json=tube)
    assert r.status_code == 200 and r.json()["facts"]["volume"] > 100, r.text
    drawn = dict(tube, spine={"kind": "drawn", "points": [[0, 0, 0], [1, 0, 0.2], [1, 1, 0.4], [0, 1, 0.6]],
                              "closed": False}, frame="rmf")
    assert client.post("/api/preview", json=drawn).status_code == 200
    bad = dict(tube, frame="wobbly")
    r = client.post("/api/preview", json=bad)
    assert r.status_code == 400 and "frame" in r.json()["error"]
    egg = {"maker": "focal", "foci": [[0, 0, 0], [0, 0, 1]], "weights": [1, 2], "radius": 3}
    r = client.post("/api/preview", json=egg)
    assert r.status_code == 200 and r.json()["facts"]["well_formed"]
    r = client.post("/api/preview", json=dict(egg, radius=0.5))
    assert r.status_code == 400 and "Fermat-Weber" in r.json()["error"]
    r = client.post("/api/preview", json=dict(egg, weights=[1]))
    assert r.status_code == 400 and "weights" in r.json()["error"]
    r = client.post("/api/preview", json={"maker": "implicit", "expression": "x^2 + y^2 + z^2 - 1"})
    assert r.status_code == 200 and r.json()["facts"]["well_formed"]


def test_check(client):
    g = small_shape()
    assert client.post("/api/check", json={"grid": pack(g)}).json()["facts"] == {
        "volume": int(g.sum()), "extents": [5, 3, 25], "well_formed": True, "reasons": [], "terms": []}
    g[0, 0, 0] = True
    facts = client.post("/api/check", json={"grid": pack(g)}).json()["facts"]
    assert not facts["well_formed"] and any("pieces" in r for r in facts["reasons"])
    for bad, message in [({}, "grid: expected"), ({"grid": {"dims": [2, 2], "bits": "AA=="}}, "dims"),
                         ({"grid": {"dims": [2, 2, 2], "bits": "AAAA"}}, "bytes of bits"),
                         ({"grid": {"dims": [999, 1, 1], "bits": ""}}, "dims"),
                         ({"grid": {"dims": [2, 2, 2], "bits": "!!"}}, "base64")]:
        r = client.post("/api/check", json=bad)
        assert r.status_code == 400 and message in r.json()["error"], bad


def test_recipe_builds_the_same_shape(client, tmp_path):
    from voxfab.cli._main import main

    spec = rev(CIRCLE, WAVY, z_range=[-1, 1], k=1)
    shown = grid_of(client.post("/api/preview", json=spec).json())
    r = client.post("/api/recipe", json={"shape": spec, "name": "wavy", "pitch": 2.0})
    assert r.status_code == 200 and r.headers["content-disposition"] == 'attachment; filename="wavy.toml"'
    (tmp_path / "wavy.toml").write_bytes(r.content)
    recipe = load_recipe(tmp_path / "wavy.toml")
    assert recipe.pitch == 2.0
    assert np.array_equal(centred(make_shape(recipe).grid), shown)
    assert main(["build", str(tmp_path / "wavy.toml"), "-o", str(tmp_path / "out")]) == 0
    assert np.array_equal(centred(np.load(tmp_path / "out" / "wavy" / "shape.npy")), shown)


def test_recipe_with_drawings_and_bitmaps_is_a_zip(client, tmp_path):
    spec = rev(DISK, VASE)
    shown = grid_of(client.post("/api/preview", json=spec).json())
    r = client.post("/api/recipe", json={"shape": spec, "name": "vase"})
    assert r.status_code == 200 and r.headers["content-disposition"] == 'attachment; filename="vase.zip"'
    zipfile.ZipFile(io.BytesIO(r.content)).extractall(tmp_path)
    assert sorted(p.name for p in (tmp_path / "vase").iterdir()) == ["curve.png", "generatrix.json", "vase.toml"]
    assert np.array_equal(centred(make_shape(load_recipe(tmp_path / "vase" / "vase.toml")).grid), shown)


def test_recipe_errors(client):
    assert client.post("/api/recipe", json={"shape": rev(CIRCLE, WAVY), "name": "../evil"}).status_code == 400
    r = client.post("/api/recipe", json={"shape": rev(CIRCLE, WAVY), "pitch": -1})
    assert r.status_code == 400 and "pitch" in r.json()["error"]
    assert client.post("/api/recipe", json=[1]).status_code == 400


def test_animate_tube(client):
    tube = {"maker": "tube", "profile": {"kind": "expr", "text": "min((x-0.5)^2 + y^2 - 0.2, (x+0.5)^2 + y^2 - 0.2)"},
            "spine": {"kind": "expr", "x": "cos(2*pi*t)", "y": "sin(2*pi*t)", "z": "0"}, "radius": 0.35}
    r = client.post("/api/animate", json={"shape": tube, "steps": 4})
    assert r.status_code == 200, r.text
    frames = [unpack(f) for f in r.json()["frames"]]
    assert len(frames) == 4 and not np.array_equal(frames[0], frames[1])
    r = client.post("/api/animate", json={"shape": rev(CIRCLE, WAVY), "steps": 4})
    assert r.status_code == 400 and "tube" in r.json()["error"]
    assert client.post("/api/animate", json={"shape": tube, "steps": 1000}).status_code == 400


# --- the repository ---------------------------------------------------------------------------

def test_repository_save_list_open_thumb(client, tmp_path):
    assert client.get("/api/repo").json() == {"shapes": [], "more": False}
    big = small_shape()
    small = np.zeros((25, 25, 25), dtype=bool)
    small[12, 12, :] = True
    a = client.post("/api/repo", json={"grid": pack(big)}).json()
    b = client.post("/api/repo", json={"grid": pack(small)}).json()
    assert a == {"name": f"{big.sum():05d}.001", "created": True, "draft": False, "reasons": []}
    assert b["name"] == "00025.001"
    assert client.post("/api/repo", json={"grid": pack(small)}).json()["created"] is False
    # by volume, smallest first, a page at a time
    assert [s["name"] for s in client.get("/api/repo").json()["shapes"]] == ["00025.001", a["name"]]
    page = client.get("/api/repo?limit=1").json()
    assert [s["name"] for s in page["shapes"]] == ["00025.001"] and page["more"]
    page = client.get("/api/repo?limit=1&after=00025.001").json()
    assert [s["name"] for s in page["shapes"]] == [a["name"]] and not page["more"]
    for bad in ("limit=0", "limit=x", "limit=501", "after=../x"):
        assert client.get(f"/api/repo?{bad}").status_code == 400, bad
    with Repository(tmp_path / "repo.sqlite", create=False) as repo:
        assert np.array_equal(centred(repo.get(a["name"])), big)
    opened = client.get(f"/api/repo/shape?name={a['name']}").json()
    assert np.array_equal(unpack(opened["grid"]), big) and opened["facts"]["well_formed"]
    r = client.get(f"/api/repo/thumb?name={a['name']}")
    assert r.status_code == 200 and r.headers["content-type"] == "image/png"
    with Image.open(io.BytesIO(r.content)) as im:
        assert im.size == (120, 120) and len(np.unique(np.asarray(im.convert("L")))) > 3


def test_repository_errors_and_drafts(client):
    two = small_shape()
    two[0, 0, 0] = True
    r = client.post("/api/repo", json={"grid": pack(two)})
    assert r.status_code == 400 and "pieces" in r.json()["error"]
    d = client.post("/api/repo", json={"grid": pack(two), "draft": True}).json()
    assert d["draft"] and d["name"].startswith("draft-") and d["reasons"]
    r = client.post("/api/repo", json={"grid": pack(np.zeros((25, 25, 25), bool))})
    assert r.status_code == 400 and "empty" in r.json()["error"]
    for q in ("name=../../etc", "name=", "name=12345.1234"):
        r = client.get(f"/api/repo/shape?{q}")
        assert r.status_code == 400 and "repository name" in r.json()["error"]
    r = client.get("/api/repo/thumb?name=99999.999")
    assert r.status_code == 400 and "99999.999" in r.json()["error"]


def test_a_census_range_member_opens_in_the_editor(client, tmp_path):
    from voxfab.census import grid_of, polycubes, shape_id

    members = [(shape_id(n, i), grid_of(cells)) for n, i, cells in polycubes(5)]
    with Repository(tmp_path / "repo.sqlite") as repo:
        repo.add_range("polycubes-5", members)
    opened = client.get("/api/repo/shape?name=polycubes-5:05-000007").json()
    grid = unpack(opened["grid"])
    assert grid.shape == (25, 25, 25) and grid.sum() == 5 and opened["name"] == "polycubes-5:05-000007"
    assert canonical_key(grid) == canonical_key(dict(members)["05-000007"])
    r = client.get("/api/repo/shape?name=polycubes-5:05-000099")
    assert r.status_code == 400 and "polycubes-5:05-000099" in r.json()["error"]


# --- nets and files ---------------------------------------------------------------------------

def test_net_gallery_distinct_valid_nets_then_files(client, tmp_path):
    from voxfab.unfold import Net, outline_key, validate

    g = small_shape()
    r = client.post("/api/nets", json={"grid": pack(g), "count": 3, "seed": 1,
                                       "options": {"timeout": 5, "sheet": "A3", "face_size": 10}})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "done", s
    nets = s["result"]["nets"]
    assert s["result"]["found"] == 3 == len(nets) and s["result"]["options"]["face_size"] == 10
    assert s["result"]["options"]["sheet"] == "A3" and s["result"]["options"]["timeout"] == 5
    for n in nets:
        lay = n["layout"]
        assert len(lay["corners"]) == 8 * len(lay["faces"]) == 8 * n["faces"]
        assert len(lay["corners3d"]) == 12 * n["faces"] and len(lay["neighbor"]) == 4 * n["faces"]
        assert lay["piece"] == [0] * n["faces"] and lay["parent"].count(-1) == 1
        w, h = n["fit"]["extent"]
        assert n["fit"]["fits"] and n["fit"]["sheets"] == 1 and n["placement"]["sheets"] == 1
        # On an A3 sheet (297 x 420 mm) with its 10 mm margin, at 10 mm faces.
        assert min(w, h) * 10 <= 277 and max(w, h) * 10 <= 400
    # ordered by fit: the mean fill never rises along the gallery (same sheets, same faces)
    fills = [sum(n["fit"]["fill"]) for n in nets]
    assert fills == sorted(fills, reverse=True)
    # each net downloads as JSON: it refolds onto the shape, and the outlines differ
    keys = set()
    for i in range(3):
        m = client.post("/api/make", json={"grid": pack(g), "artefact": "net.json",
                                           "net": {"job": r.json()["job"], "index": i}})
        done = wait_job(client, m.json()["job"])
        text = client.get(f"/api/files/{m.json()['job']}/0").text
        net = Net.from_json(text)
        assert validate(g, net).ok and net.seed == nets[i]["seed"]
        keys.add(outline_key(net))
        assert done["files"][0]["name"] == "studio-net.json"
    assert len(keys) == 3


def test_net_gallery_errors(client):
    g = small_shape()
    for body, message in [({"grid": pack(g), "count": 0}, "count"), ({"grid": pack(g), "count": 99}, "count"),
                          ({"grid": pack(g), "options": {"sheet": "B9"}}, "sheet"),
                          ({"grid": pack(g), "options": {"timeout": -1}}, "timeout"),
                          ({"grid": pack(g), "options": {"face_size": "big"}}, "face_size"),
                          ({"grid": pack(g), "options": {"face_size": 2000}}, "face_size"),
                          ({"grid": pack(g), "options": {"colour": "red"}}, "unknown option"),
                          ({"grid": pack(g), "options": [1]}, "options"),
                          ({"grid": pack(g), "face_mm": 10}, "face_mm")]:
        r = client.post("/api/nets", json=body)
        assert r.status_code == 400 and message in r.json()["error"], body
        assert "\n" not in r.json()["error"]
    # The same bound and words as the CLI's --face-size.
    from voxfab.fabricate.netdraw import NetOptions

    with pytest.raises(Exception) as cli:
        NetOptions(face_size=2000)
    r = client.post("/api/nets", json={"grid": pack(g), "options": {"face_size": 2000}})
    assert r.json()["error"] == str(cli.value)
    two = g.copy()
    two[0, 0, 0] = True
    r = client.post("/api/nets", json={"grid": pack(two)})
    assert r.status_code == 400 and "one piece" in r.json()["error"]
    r = client.post("/api/nets", json={"grid": pack(g), "constraints": {"cut": [[[0, 0, 0, "+q"], [0, 0, 0, "+x"]]]}})
    assert r.status_code == 400


def test_gallery_of_faces_too_small_has_ways_out(client):
    g = small_shape()
    r = client.post("/api/nets", json={"grid": pack(g), "count": 2, "options": {"face_size": 3}})
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "error" and "what works: make the faces" in s["message"]
    assert "\n" not in s["message"]


@pytest.mark.parametrize("artefact", ["mesh.3mf", "mesh.stl", "net.svg", "net.dxf", "net.pdf", "plates.zip",
                                      "triptych.png", "triptych.pdf"])
def test_make_files(client, tmp_path, artefact):
    g = small_shape()
    # each output's own options only: one of another output would have no effect, and is refused
    options = {"thickness": 2.0} if artefact == "plates.zip" else {"sheet": "A3"} if artefact.startswith("net") else {}
    r = client.post("/api/make", json={"grid": pack(g), "artefact": artefact, "pitch": 2.0, "title": "column",
                                       "options": options})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "done", s
    f = s["files"][0]
    got = client.get(f"/api/files/{r.json()['job']}/0")
    assert got.status_code == 200 and f'filename="{f["name"]}"' in got.headers["content-disposition"]
    path = tmp_path / f["name"]
    path.write_bytes(got.content)
    if artefact.startswith("mesh"):
        import trimesh

        mesh = trimesh.load(path, force="mesh")
        assert mesh.is_watertight and mesh.volume == pytest.approx(g.sum() * 8.0, rel=1e-6)
    elif artefact == "net.svg":
        from lxml import etree

        root = etree.parse(str(path)).getroot()
        # A3, not A4: a column's net is long, and on A4 its faces may come out too small for tabs
        assert root.get("width") == "297mm" and "column" in etree.tostring(root).decode()
    elif artefact == "net.dxf":
        import ezdxf

        assert not ezdxf.readfile(path).audit().has_errors
    elif artefact.endswith("pdf"):
        assert got.content.startswith(b"%PDF")
    elif artefact == "plates.zip":
        names = zipfile.ZipFile(path).namelist()
        assert any(n.endswith(".dxf") for n in names) and "column-plates-assembly.pdf" in names
    else:
        with Image.open(path) as im:
            assert im.width > 3 * im.height / 2


def test_make_animation_and_errors(client):
    g = small_shape()
    tube = {"maker": "tube", "profile": {"kind": "expr", "text": "min((x-0.5)^2 + y^2 - 0.2, (x+0.5)^2 + y^2 - 0.2)"},
            "spine": {"kind": "expr", "x": "cos(2*pi*t)", "y": "sin(2*pi*t)", "z": "0"}, "radius": 0.3}
    r = client.post("/api/make", json={"grid": pack(g), "artefact": "animation.gif", "shape": tube,
                                       "options": {"steps": 3}})
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "done", s
    with Image.open(io.BytesIO(client.get(f"/api/files/{r.json()['job']}/0").content)) as im:
        assert im.n_frames == 3
    for body, message in [
        ({"grid": pack(g), "artefact": "rm -rf"}, "artefact"),
        ({"grid": pack(np.zeros((25, 25, 25), bool)), "artefact": "mesh.stl"}, "empty"),
        ({"grid": pack(g), "artefact": "mesh.stl", "pitch": 0}, "pitch"),
        ({"grid": pack(g), "artefact": "mesh.stl", "title": "../x"}, "title"),
        ({"grid": pack(g), "artefact": "net.svg", "net": {"job": "0123456789abcdef", "index": 0}}, "no job"),
        ({"grid": pack(g), "artefact": "net.svg", "options": {"sheet": "huge"}}, "sheet"),
        ({"grid": pack(g), "artefact": "net.svg", "options": {"timeout": 0}}, "timeout"),
        ({"grid": pack(g), "artefact": "animation.gif", "shape": rev(CIRCLE, WAVY)}, "tube"),
    ]:
        r = client.post("/api/make", json=body)
        assert r.status_code == 400 and message in r.json()["error"], body


def test_jobs_and_files_errors(client):
    r = client.get("/api/jobs/../../etc")
    assert r.status_code in (400, 404)
    r = client.get("/api/jobs/0123456789abcdef")
    assert r.status_code == 400 and "no job" in r.json()["error"]
    m = client.post("/api/make", json={"grid": pack(small_shape()), "artefact": "net.json"})
    wait_job(client, m.json()["job"])
    r = client.get(f"/api/files/{m.json()['job']}/7")
    assert r.status_code == 400 and "no file 7" in r.json()["error"]
    # a failing job reports its error as one line
    two = small_shape()
    two[0, 0, 0] = True
    m = client.post("/api/make", json={"grid": pack(two), "artefact": "net.json"})
    s = wait_job(client, m.json()["job"])
    assert s["state"] == "error" and s["message"] and "\n" not in s["message"]


def _folds(layout) -> set[tuple[int, int]]:
    return {tuple(sorted(p)) for p in np.array(layout["folds"]).reshape(-1, 2).tolist()}


def test_marked_edges_are_honoured(client):
    g = small_shape()
    first = wait_job(client, client.post("/api/nets", json={"grid": pack(g), "count": 1, "options": {"timeout": 3}}).json()["job"])
    lay = first["result"]["nets"][0]["layout"]
    folds = _folds(lay)
    nb = np.array(lay["neighbor"]).reshape(-1, 4)
    fold = sorted(folds)[len(folds) // 2]
    cut = next((i, int(j)) for i in range(len(nb)) for j in nb[i] if tuple(sorted((i, int(j)))) not in folds)
    faces = lay["faces"]
    constraints = {"cut": [[faces[fold[0]], faces[fold[1]]]], "keep": [[faces[cut[0]], faces[cut[1]]]]}
    r = client.post("/api/nets", json={"grid": pack(g), "count": 2, "options": {"timeout": 3}, "constraints": constraints})
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "done", s
    for net in s["result"]["nets"]:
        got = _folds(net["layout"])
        assert tuple(sorted(fold)) not in got  # marked cut: never a fold
        assert tuple(sorted(cut)) in got  # marked keep: always a fold
    # the same edge cut and kept, or a face that is not on the surface: one clear line
    both = {"cut": constraints["cut"], "keep": constraints["cut"]}
    r = client.post("/api/nets", json={"grid": pack(g), "constraints": both})
    assert r.status_code == 400 and "both cut and kept" in r.json()["error"]
    away = {"cut": [[[0, 0, 0, "+x"], [0, 0, 0, "+y"]]]}
    r = client.post("/api/nets", json={"grid": pack(g), "count": 1, "options": {"timeout": 3}, "constraints": away})
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "error" and "\n" not in s["message"] and s["message"]


def test_a_seed_that_runs_out_of_time_is_skipped(client, monkeypatch):
    import voxfab.unfold._many as engine  # unfold_many's calls of unfold
    from voxfab.errors import UnfoldError

    real = engine.unfold
    calls = []

    def flaky(grid, *, rng, **options):
        calls.append(rng)
        if len(calls) == 2:
            raise UnfoldError("no one-piece net in 1 s")
        return real(grid, rng=rng, **options)

    monkeypatch.setattr(engine, "unfold", flaky)
    g = small_shape()
    body = {"grid": pack(g), "count": 2, "options": {"timeout": 5, "sheet": "A3", "face_size": 10}}
    s = wait_job(client, client.post("/api/nets", json=body).json()["job"])
    assert s["state"] == "done" and s["result"]["found"] == 2 and len(calls) >= 3

    def never(grid, *, rng, **options):
        raise UnfoldError("no one-piece net in 1 s")

    monkeypatch.setattr(engine, "unfold", never)
    s = wait_job(client, client.post("/api/nets", json=body).json()["job"])
    assert s["state"] == "error" and s["message"] == "no one-piece net in 1 s"


@pytest.mark.parametrize("style", ["interlocked", "radial"])
def test_make_plates_in_a_style_and_see_the_assembly(client, style):
    """The queen's plates in a slotted style: the zip is the CLI's, the 3D view gets every plate as assembled."""
    from pathlib import Path

    queen = make_shape(load_recipe(Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml")).grid
    r = client.post("/api/make", json={"grid": pack(queen), "artefact": "plates.zip", "pitch": 2.0, "title": "queen",
                                       # radial plates thin enough for a hub slot the queen's neck holds
                                       "options": {"thickness": 3.0 if style == "interlocked" else 1.5,
                                                   "style": style, "plate_sheet": "600x400"}})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["job"])
    assert s["state"] == "done", s
    archive = zipfile.ZipFile(io.BytesIO(client.get(f"/api/files/{r.json()['job']}/0").content))
    report = json.loads(archive.read("queen-plates-plates.json"))
    plates = s["result"]["assembly"]["plates"]
    assert "queen-plates-assembly.3mf" in archive.namelist()
    assert report["style"] == style and len(plates) == report["plates"] > 1
    assert sorted(p["name"] for p in plates) == sorted(p["label"] for p in report["plates_list"])
    # Every plate sits inside the queen's box (25 voxels at 2 mm) in the print's frame.
    corners = np.concatenate([np.reshape(p["triangles"], (-1, 3)) for p in plates])
    assert corners.min() >= -0.01 and corners.max() <= 50.01
    r = client.post("/api/make", json={"grid": pack(queen), "artefact": "plates.zip",
                                       "options": {"style": "woven"}})
    assert r.status_code == 400 and "style" in r.json()["error"]


def test_open_curve_of_revolution_in_the_studio(client):
    ring = {"kind": "expr", "text": "(x-2)^2 + y^2 - 0.64"}
    closed = grid_of(client.post("/api/preview", json=rev(CIRCLE, ring, mode="surface")).json())
    r = client.post("/api/preview", json=rev(CIRCLE, ring, mode="surface", arc=[0, 180]))
    assert r.status_code == 200, r.text
    half = grid_of(r.json())
    assert 0.3 * closed.sum() < half.sum() < 0.7 * closed.sum()
    r = client.post("/api/preview", json=rev(CIRCLE, ring, arc=[0, 180]))
    assert r.status_code == 400 and 'mode = "surface"' in r.json()["error"]
    r = client.post("/api/preview", json=rev(CIRCLE, ring, mode="surface", arc=[0, "a"]))
    assert r.status_code == 400 and "shape.arc" in r.json()["error"]


def _cli_net(tmp_path, grid, seed: int, *names: str) -> dict[str, bytes]:
    import subprocess
    import sys

    out = tmp_path / f"cli-{seed}"
    out.mkdir()
    np.save(out / "column.npy", grid)
    argv = [sys.executable, "-m", "voxfab", "net", "column.npy", "--seed", str(seed), "--face-size", "10",
            "--sheet", "A3"]
    for n in names:
        argv += ["-o", n]
    r = subprocess.run(argv, capture_output=True, text=True, cwd=out, timeout=300)
    assert r.returncode == 0, r.stderr
    return {n: (out / n).read_bytes() for n in names}


def test_studio_net_files_are_the_cli_files(client, tmp_path):
    """The studio's /api/make (with and without a gallery pick) writes the bytes `voxfab net` writes."""
    g = small_shape()
    options = {"face_size": 10, "sheet": "A3"}
    gallery = wait_job(client, client.post("/api/nets", json={"grid": pack(g), "count": 2, "seed": 5,
                                                              "options": options}).json()["job"])
    assert gallery["state"] == "done", gallery
    pick = gallery["result"]["nets"][1]
    for net, seed in ((None, 0), ({"job": gallery["id"], "index": 1}, pick["seed"])):
        want = _cli_net(tmp_path, g, seed, "column-net.json", "column-net.svg")
        for artefact in ("net.json", "net.svg"):
            body = {"grid": pack(g), "artefact": artefact, "title": "column", "options": options}
            if net is not None:
                body["net"] = net
            m = client.post("/api/make", json=body)
            assert m.status_code == 200, m.text
            s = wait_job(client, m.json()["job"])
            assert s["state"] == "done", s
            got = client.get(f"/api/files/{m.json()['job']}/0").content
            assert got == want[f"column-{artefact}"], (artefact, seed)
