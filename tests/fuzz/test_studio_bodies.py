"""Hardening 3, classes 2 to 5 and issue 37's item 8: the studio's endpoints check their whole bodies.

Each case posts a real shape (the bundled queen, pawn, spinning top, a torus) with one
field spoiled, or with an option that must take effect, and checks the answer: a 400
with one line naming the field (never a 500), or a success whose files, measured
independently (trimesh, the plates' own report), show the option's effect.
"""

from __future__ import annotations

import io
import json
import string
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest
from _fuzz import HUGE_NUMBERS, JSON_VALUES
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import examples
from voxfab.studio._grid import centred, pack

RECIPES = Path(__file__).parents[2] / "recipes"
FUZZ = settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))


def _grid(name: str) -> np.ndarray:
    return centred(make_shape(load_recipe(RECIPES / f"{name}.toml")).grid)


@pytest.fixture(scope="module")
def pawn() -> np.ndarray:
    return _grid("chess/pawn")


@pytest.fixture(scope="module")
def queen() -> np.ndarray:
    return _grid("chess/queen")


def _refused(r, *words: str) -> str:
    assert r.status_code == 400, (r.status_code, r.text[:300])
    message = r.json()["error"]
    assert "\n" not in message and "Traceback" not in message and "internal error" not in message, message
    for w in words:
        assert w in message, (w, message)
    return message


def _wait(client, job: str, limit: float = 180.0) -> dict:
    end = time.monotonic() + limit
    while time.monotonic() < end:
        s = client.get(f"/api/jobs/{job}").json()
        if s["state"] not in ("queued", "running"):
            return s
        time.sleep(0.05)
    raise AssertionError(f"job {job} still running after {limit} s")


@pytest.fixture(scope="module")
def gallery(studio, pawn) -> str:
    """A one-net gallery of the pawn: the job that edits start from."""
    r = studio.post("/api/nets", json={"grid": pack(pawn), "count": 1,
                                       "options": {"sheet": "A0", "pieces": "auto", "timeout": 30}})
    assert r.status_code == 200, r.text
    done = _wait(studio, r.json()["job"])
    assert done["state"] == "done", done
    return r.json()["job"]


# --- class 2: a face normal of any type ------------------------------------------------------------

BAD_NORMALS = [["+z"], {"n": "+z"}, 3, None, True, "+w", "", 1.5, [], 10**400]


@pytest.mark.parametrize("normal", BAD_NORMALS, ids=[type(n).__name__ + str(i) for i, n in enumerate(BAD_NORMALS)])
def test_a_bad_normal_in_a_constraint_file_is_one_line(tmp_path: Path, normal: object) -> None:
    from _fuzz import refused

    np.save(tmp_path / "pawn.npy", make_shape(load_recipe(RECIPES / "chess/pawn.toml")).grid)
    (tmp_path / "c.json").write_text(json.dumps({"cut": [[[0, 0, 0, normal], [0, 0, 0, "+x"]]]}))
    line = refused(["net", tmp_path / "pawn.npy", "--constraints", tmp_path / "c.json", "-o", tmp_path / "n.json"])
    assert "cut edge 0: face normal must be one of" in line
    assert not (tmp_path / "n.json").exists()


@FUZZ
@given(st.sampled_from(["cut", "keep"]), st.integers(0, 4), JSON_VALUES)
def test_any_json_in_a_constraint_is_refused_by_name(key: str, where: int, value: object) -> None:
    from voxfab.errors import VoxfabError
    from voxfab.unfold import EdgeConstraints

    face: list = [1, 2, 3, "+z"]
    edge: list = [face, [1, 2, 3, "+x"]]
    if where < 4:
        face[where] = value
        data = {key: [edge]}
    else:
        data = {key: value}
    try:
        EdgeConstraints.from_dict(data)
    except VoxfabError as exc:
        assert "\n" not in str(exc) and len(str(exc)) < 400
        assert str(exc).startswith(key) or str(exc).startswith("edge constraints")


@pytest.mark.parametrize("normal", BAD_NORMALS[:5])
def test_a_bad_normal_is_a_400_on_the_gallery_and_the_edit(studio, pawn, gallery, normal) -> None:
    bad = {"cut": [[[12, 12, 0, normal], [12, 12, 0, "+x"]]]}
    _refused(studio.post("/api/nets", json={"grid": pack(pawn), "count": 1, "constraints": bad}), "face normal")
    _refused(studio.post("/api/nets/edit", json={"job": gallery, "cut": [[12, 12, 0, normal], [12, 12, 0, "+x"]]}),
             "face normal")
    _refused(studio.post("/api/nets/edit", json={"job": gallery, "undo": True, "marks": bad}), "face normal")


def test_unknown_constraint_keys_are_refused_as_the_cli_does(studio, pawn, gallery) -> None:
    for marks in ({"kep": []}, {"cut": [], "kep": [[[0, 0, 0, "+z"], [0, 0, 0, "+x"]]]}):
        _refused(studio.post("/api/nets", json={"grid": pack(pawn), "count": 1, "constraints": marks}), "'kep'")
        _refused(studio.post("/api/nets/edit", json={"job": gallery, "undo": True, "marks": marks}), "'kep'")


# --- class 3: numbers of any size ------------------------------------------------------------------

def _bodies(grid: dict, huge: object) -> list[tuple[str, dict, str]]:
    tube = {"maker": "tube", "profile": {"kind": "expr", "text": "x^2 + y^2 - 0.3"},
            "spine": {"kind": "expr", "x": "cos(2*pi*t)", "y": "sin(2*pi*t)", "z": "0"}, "radius": 0.3}
    focal = {"maker": "focal", "foci": [[0, 0, 0]], "radius": 2}
    return [
        ("/api/nets", {"grid": grid, "count": huge}, "count"),
        ("/api/nets", {"grid": grid, "seed": huge}, "seed"),
        ("/api/nets", {"grid": grid, "options": {"timeout": huge}}, "timeout"),
        ("/api/nets", {"grid": grid, "options": {"face_size": huge}}, "face_size"),
        ("/api/fits", {"grid": grid, "options": {"face_size": huge}}, "face_size"),
        ("/api/fits", {"grid": grid, "options": {"margin": huge}}, "margin"),
        ("/api/make", {"grid": grid, "artefact": "mesh.stl", "pitch": huge}, "pitch"),
        ("/api/make", {"grid": grid, "artefact": "mesh.stl", "options": {"infill": huge}}, "infill"),
        ("/api/make", {"grid": grid, "artefact": "mesh.stl", "options": {"hollow": huge}}, "hollow"),
        ("/api/make", {"grid": grid, "artefact": "plates.zip", "options": {"radial_plates": huge}}, "radial_plates"),
        ("/api/make", {"grid": grid, "artefact": "plates.zip", "options": {"thickness": huge}}, "thickness"),
        ("/api/make", {"grid": grid, "artefact": "net.svg", "options": {"tab_width": huge}}, "tab_width"),
        ("/api/recipe", {"shape": focal, "pitch": huge}, "pitch"),
        ("/api/animate", {"shape": tube, "steps": huge}, "steps"),
        ("/api/preview", {**focal, "radius": huge}, "radius"),
        ("/api/preview", {**tube, "radius": huge}, "radius"),
        ("/api/preview", {**tube, "arc": [0, huge]}, "arc"),
        ("/api/preview", {**tube, "twist": huge}, "twist"),
        ("/api/preview", {**focal, "foci": [[0, huge, 0]]}, "foci"),
        ("/api/preview", {**focal, "k": huge}, "k"),
    ]


@pytest.mark.parametrize("huge", HUGE_NUMBERS, ids=[str(h)[:6] + f"_{len(str(h))}" for h in HUGE_NUMBERS])
def test_numbers_out_of_every_range_are_400s_with_the_options_words(studio, pawn, huge) -> None:
    beyond_floats = abs(huge) > 1e308
    for path, body, field in _bodies(pack(pawn), huge):
        r = studio.post(path, json=body)
        if path == "/api/preview" and field != "k" and not beyond_floats:
            # a drawing's size has no declared bound: a far focus or a wide tube is scaled into 25³, or refused
            if r.status_code != 200:
                _refused(r)
            continue
        message = _refused(r, field)
        assert "expected" in message or "range" in message or "limit" in message or "over" in message, \
            (path, field, message)


@pytest.mark.parametrize("huge", [10**400, -(10**400), 2**64])
def test_placement_coordinates_of_any_size_are_400s(studio, pawn, gallery, huge) -> None:
    item = _wait(studio, gallery)["result"]["nets"][0]
    placement = json.loads(json.dumps(item["placement"]))
    placement["pieces"][0]["x"] = huge
    r = studio.post("/api/make", json={"grid": pack(pawn), "artefact": "net.svg",
                                       "net": {"job": gallery, "index": 0}, "placement": placement})
    if abs(huge) > 1e308:
        _refused(r, "placement.pieces[0].x")
    else:  # a number: the job checks it against the sheet, and says where it fails
        assert r.status_code == 200 and _wait(studio, r.json()["job"])["state"] == "error"
    placement["pieces"][0]["x"] = 0
    placement["pieces"][0]["turns"] = huge
    _refused(studio.post("/api/make", json={"grid": pack(pawn), "artefact": "net.svg",
                                            "net": {"job": gallery, "index": 0}, "placement": placement}),
             "placement.pieces[0].turns")
    _refused(studio.post("/api/make", json={"grid": pack(pawn), "artefact": "net.svg",
                                            "net": {"job": gallery, "index": huge}}), "net.index")
    _refused(studio.post("/api/nets/edit", json={"job": gallery, "index": huge, "undo": True}), "index")


def test_a_repository_page_of_any_size_is_a_400(studio) -> None:
    for limit in ("0", "501", "9" * 5000, "-1", "1e400", "x"):
        _refused(studio.get(f"/api/repo?limit={limit}"), "limit")


# --- class 4: nothing accepted and ignored ---------------------------------------------------------

ENDPOINT_FIELDS = {
    "/api/check": ("grid",), "/api/recipe": ("shape", "name", "pitch"), "/api/animate": ("shape", "steps"),
    "/api/repo": ("grid", "draft"), "/api/nets": ("grid", "seed", "count", "options", "constraints"),
    "/api/fits": ("grid", "options"), "/api/nets/edit": ("job", "index", "cut", "join", "undo", "split", "grid",
                                                         "marks"),
    "/api/make": ("grid", "artefact", "pitch", "title", "options", "net", "placement", "shape"),
}


@FUZZ
@given(st.sampled_from(sorted(ENDPOINT_FIELDS)), st.text(string.ascii_letters + "_", min_size=1, max_size=12),
       JSON_VALUES)
def test_an_unknown_field_is_refused_on_every_endpoint(studio, path: str, key: str, value: object) -> None:
    if key in ENDPOINT_FIELDS[path]:
        return
    body = {"grid": pack(examples.box(2, 2, 2)), "job": "0123456789abcdef", key: value}
    body = {k: v for k, v in body.items() if k in ENDPOINT_FIELDS[path] or k == key}
    _refused(studio.post(path, json=body), repr(key)[:30])


@FUZZ
@given(st.text(string.ascii_lowercase + "_", min_size=1, max_size=14), JSON_VALUES)
def test_an_unknown_shape_key_is_refused(studio, key: str, value: object) -> None:
    from voxfab.studio._specs import SHAPE_KEYS, form_keys

    focal = {"maker": "focal", "foci": [[0, 0, 0]], "radius": 2}
    if key in focal or key in SHAPE_KEYS["focal"] or key in form_keys("focal"):
        return
    _refused(studio.post("/api/preview", json={**focal, key: value}), repr(key)[:30])


@pytest.mark.parametrize(("artefact", "options", "field"), [
    ("mesh.3mf", {"infill": 101}, "infill"),
    ("mesh.stl", {"hollow": -1}, "hollow"),
    ("mesh.stl", {"thickness": 3.0}, "thickness"),  # a plates option: no effect on a mesh
    ("mesh.3mf", {"format": "stl"}, "format"),
    ("plates.zip", {"radial_plates": 1}, "radial_plates"),
    ("plates.zip", {"kerf": -0.1}, "kerf"),
    ("plates.zip", {"sheet": "A4", "plate_sheet": "A3"}, "plate_sheet"),
    ("net.svg", {"zipper": True}, "zipper"),
    ("net.svg", {"count": 2}, "count"),
    ("net.json", {"formats": ["svg"]}, "formats"),
    ("triptych.png", {"triptych": False}, "triptych"),
    ("triptych.png", {"infill": 20}, "infill"),
])
def test_make_refuses_options_its_output_does_not_take(studio, pawn, artefact, options, field) -> None:
    _refused(studio.post("/api/make", json={"grid": pack(pawn), "artefact": artefact, "options": options}), field)


def test_mesh_options_take_effect_on_the_download(studio, tmp_path: Path) -> None:
    import trimesh

    from voxfab.fabricate.mesh import hollow_out
    from voxfab.shape import crop

    top = _grid("spinning_top")
    volumes = {}
    for hollow in (0, 2):
        r = studio.post("/api/make", json={"grid": pack(top), "artefact": "mesh.stl", "pitch": 2.4, "title": "top",
                                           "options": {"hollow": hollow, "contacts": "split"}})
        assert r.status_code == 200, r.text
        assert _wait(studio, r.json()["job"])["state"] == "done"
        (tmp_path / "top.stl").write_bytes(studio.get(f"/api/files/{r.json()['job']}/0").content)
        mesh = trimesh.load(tmp_path / "top.stl", force="mesh")
        volumes[hollow] = mesh.volume
        assert np.allclose(mesh.bounds[1] - mesh.bounds[0], np.array(crop(top).shape) * 2.4, atol=1e-3)
    assert volumes[0] == pytest.approx(crop(top).sum() * 2.4**3, rel=1e-6)
    assert volumes[2] == pytest.approx(hollow_out(crop(top), 2).sum() * 2.4**3, rel=1e-6)


def test_plate_options_take_effect_on_the_download(studio, queen) -> None:
    counts = {}
    for n in (3, 5):
        r = studio.post("/api/make", json={"grid": pack(queen), "artefact": "plates.zip", "pitch": 2.0,
                                           "options": {"style": "radial", "radial_plates": n, "thickness": 1.0,
                                                       "plate_sheet": "900x600"}})
        assert r.status_code == 200, r.text
        assert _wait(studio, r.json()["job"])["state"] == "done"
        archive = zipfile.ZipFile(io.BytesIO(studio.get(f"/api/files/{r.json()['job']}/0").content))
        report = json.loads(archive.read("studio-plates-plates.json"))  # no title: the files are the studio's
        assert report["style"] == "radial" and report["thickness"] == 1.0
        counts[n] = report["plates"]
    assert counts[3] < counts[5] and counts[3] <= 3


def test_the_gallery_refuses_zipper_and_min_box_on_a_torus(studio) -> None:
    torus = pack(centred(examples.torus(6, 2)))
    for option in ("zipper", "min_box"):
        _refused(studio.post("/api/nets", json={"grid": torus, "count": 1,
                                                "options": {"strategy": "exact", option: True}}), option)


def test_fits_reads_its_options_and_refuses_the_old_top_level_body(studio) -> None:
    cube = pack(centred(np.ones((1, 1, 1), bool)))  # the README's cube: 6 faces
    _refused(studio.post("/api/fits", json={"grid": cube, "sheet": "30x30", "face_mm": 10}), "'face_mm'")
    _refused(studio.post("/api/fits", json={"grid": cube, "options": {"sheet": "30x30", "face_mm": 10}}), "face_mm")
    _refused(studio.post("/api/fits", json={"grid": cube, "options": {"pieces": "auto"}}), "pieces")
    _refused(studio.post("/api/fits", json={"grid": cube, "options": {"timeout": 121}}), "timeout")
    answers = {}
    for sheet in ("60x70", "60x90", "A4"):
        r = studio.post("/api/fits", json={"grid": cube, "options": {"sheet": sheet, "face_size": 10, "timeout": 20}})
        assert r.status_code == 200, r.text
        s = _wait(studio, r.json()["job"])
        assert s["state"] == "done", s
        assert s["result"]["sheet"] == sheet and s["result"]["face_size"] == 10
        answers[sheet] = s["result"]["answer"]
    assert answers == {"60x70": "no", "60x90": "yes", "A4": "yes"}  # the README's figures for the cube
    # a wider margin takes room: the 60 x 90 sheet no longer holds the 3x5 faces
    r = studio.post("/api/fits", json={"grid": cube, "options": {"sheet": "60x90", "face_size": 10, "margin": 15}})
    assert _wait(studio, r.json()["job"])["result"]["answer"] == "no"


# --- class 5: cancel stops the exact solver -----------------------------------------------------------

def test_cancel_stops_exact_fits_jobs_within_a_second(studio, queen) -> None:
    # A3 at 10.5 mm: 862 faces in a 25 x 36 box, a search that runs its whole timeout undecided
    body = {"grid": pack(queen), "options": {"sheet": "A3", "face_size": 10.5, "timeout": 100}}
    jobs = [studio.post("/api/fits", json=body).json()["job"] for _ in range(2)]
    end = time.monotonic() + 30
    while any(studio.get(f"/api/jobs/{j}").json()["state"] != "running" for j in jobs):
        assert time.monotonic() < end, "the two searches did not both start"
        time.sleep(0.05)
    time.sleep(2.0)  # well into the search: past the hint, inside CP-SAT
    for j in jobs:
        t0 = time.monotonic()
        studio.post(f"/api/jobs/{j}/cancel")
        s = _wait(studio, j, limit=10)
        assert s["state"] == "cancelled" and time.monotonic() - t0 < 1.0, (s, time.monotonic() - t0)
    # both workers are free again: a small question is answered at once
    small = studio.post("/api/fits", json={"grid": pack(centred(examples.box(2, 2, 2))),
                                           "options": {"sheet": "A4", "face_size": 10}}).json()["job"]
    assert _wait(studio, small, limit=30)["state"] == "done"


# --- issue 37, item 8: the edit refuses grids the editor cannot hold -----------------------------

@pytest.mark.parametrize("dims", [(26, 26, 26), (25, 25, 40), (1, 1, 300)])
def test_an_edit_refuses_an_oversized_grid(studio, gallery, dims) -> None:
    big = np.zeros(dims, bool)
    big[0, 0, 0] = True
    _refused(studio.post("/api/nets/edit", json={"job": gallery, "undo": True, "grid": pack(big)}),
             "larger than the studio's 25x25x25")


def test_an_edit_refuses_a_grid_that_is_not_its_nets(studio, gallery, queen) -> None:
    _refused(studio.post("/api/nets/edit", json={"job": gallery, "undo": True, "grid": pack(queen)}),
             "the shape changed")


@pytest.mark.parametrize("artefact", ["mesh.3mf", "plates.zip"])
def test_a_net_picked_for_an_output_made_from_the_shape_is_refused(studio, pawn, gallery, artefact) -> None:
    _refused(studio.post("/api/make", json={"grid": pack(pawn), "artefact": artefact,
                                            "net": {"job": gallery, "index": 0}}), "not from a chosen net")
