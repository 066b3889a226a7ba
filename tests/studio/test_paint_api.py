"""The studio's shape in colour on the server: opened, edited, joined, kept, saved and made with its colours."""

from __future__ import annotations

import base64
import sys
from pathlib import Path

import numpy as np
import pytest

from voxfab.shape import VoxelShape, default_palette
from voxfab.studio._grid import InitialShape, centred_shape, pack, pack_shape, unpack_shape

from ._helpers import small_shape, wait_job

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _voxart import CHARACTER_COLOURS, character, read_vox_independently  # noqa: E402


def rgba_by_voxel(shape: VoxelShape) -> dict[tuple[int, int, int], tuple[int, ...]]:
    """Each filled voxel of the shape cut to its box, with its RGBA."""
    c = shape.crop()
    return {tuple(int(v) for v in p): tuple(int(v) for v in c.colours.rgba[tuple(p)]) for p in np.argwhere(c.grid)}


def open_character(client, tmp_path) -> dict:
    from voxfab import io as vio

    path = tmp_path / "character.vox"
    vio.write(character(), path)
    r = client.post("/api/shape/open?name=character.vox", content=path.read_bytes())
    assert r.status_code == 200, r.text
    return r.json()


def test_the_wire_form_carries_colours_and_an_uncoloured_shape_pays_nothing():
    shape = centred_shape(character(pitch=1.0))
    wire = pack_shape(shape)
    assert unpack_shape(wire) == shape
    assert set(pack(shape.grid)) == {"dims", "bits"} and unpack_shape(pack(shape.grid)).colours is None


def test_a_voxel_the_page_left_without_colour_takes_its_nearest_one(client):
    shape = centred_shape(character(pitch=1.0))
    wire = pack_shape(shape)
    index = bytearray(base64.b64decode(wire["colours"]))
    # a voxel inside the shirt (bits in C order, as np.argwhere lists them) loses its colour
    shirt = np.all(shape.colours.rgba == CHARACTER_COLOURS["shirt"], axis=-1)
    voxels = np.argwhere(shape.grid)
    inside = next(k for k, (x, y, z) in enumerate(voxels) if shirt[x - 1:x + 2, y - 1:y + 2, z - 1:z + 2].all())
    index[inside] = 0
    r = client.post("/api/paint/fit", json={"grid": {**wire, "colours": base64.b64encode(bytes(index)).decode()}})
    assert r.status_code == 200, r.text
    fitted = unpack_shape(r.json()["grid"])
    assert fitted == shape  # the shirt's colour again: its neighbours are all shirt


def test_bad_colours_are_refused_in_one_line(client):
    wire = pack_shape(centred_shape(character(pitch=1.0)))
    for bad in ({"colours": "AAAA"}, {"palette": "AAAA"}, {"colours": "not base64!"}, {"colours": None}):
        r = client.post("/api/paint/fit", json={"grid": {**wire, **bad}})
        assert r.status_code == 400 and "\n" not in r.json()["error"], (bad, r.text)


def test_opening_a_vox_keeps_its_colours(client, tmp_path):
    got = open_character(client, tmp_path)
    assert got["label"] == "character.vox" and got["facts"]["volume"] == int(character().grid.sum())
    opened = unpack_shape(got["grid"])
    assert opened.grid.shape == (25, 25, 25)
    assert rgba_by_voxel(opened) == rgba_by_voxel(character())


def test_opening_an_npz_keeps_its_scale_and_colours(client, tmp_path):
    from voxfab import io as vio

    path = tmp_path / "character.npz"
    vio.write(character(pitch=1.5), path)
    r = client.post("/api/shape/open?name=character.npz", content=path.read_bytes())
    assert r.status_code == 200, r.text
    assert r.json()["pitch"] == 1.5 and rgba_by_voxel(unpack_shape(r.json()["grid"])) == rgba_by_voxel(character())


@pytest.mark.parametrize(("name", "body", "words"), [
    ("shape.stl", b"solid x", "opens .vox, .npz, .npy"),
    ("../../etc/passwd.vox", b"VOX ", "opens .vox"),
    ("broken.vox", b"VOX \x96\x00\x00\x00garbage", "broken.vox"),
    ("empty.vox", b"", "empty"),
])
def test_opening_a_bad_file_says_so_in_one_line(client, name, body, words):
    r = client.post(f"/api/shape/open?name={name}", content=body)
    assert r.status_code == 400 and words in r.json()["error"] and "\n" not in r.json()["error"]
    assert "open-" not in r.json()["error"] and "work" not in r.json()["error"]


def test_saving_as_vox_keeps_every_colour_read_independently(client, tmp_path):
    opened = open_character(client, tmp_path)
    r = client.post("/api/shape/file", json={"grid": opened["grid"], "format": "vox", "title": "hero"})
    assert r.status_code == 200, r.text
    assert 'filename="hero.vox"' in r.headers["content-disposition"]
    (tmp_path / "hero.vox").write_bytes(r.content)
    size, voxels = read_vox_independently(tmp_path / "hero.vox")
    assert size == (19, 7, 20) and voxels == rgba_by_voxel(character())


def test_saving_as_npz_keeps_scale_and_colours(client, tmp_path):
    from voxfab import io as vio

    opened = open_character(client, tmp_path)
    r = client.post("/api/shape/file", json={"grid": opened["grid"], "format": "npz", "title": "hero", "pitch": 3})
    assert r.status_code == 200, r.text
    (tmp_path / "hero.npz").write_bytes(r.content)
    back = vio.read(tmp_path / "hero.npz")
    assert back.pitch == 3.0 and rgba_by_voxel(back.shape()) == rgba_by_voxel(character())
    r = client.post("/api/shape/file", json={"grid": opened["grid"], "format": "stl"})
    assert r.status_code == 400 and "vox, npz" in r.json()["error"]


def test_join_adds_voxels_in_a_neighbours_colour_and_says_where(client, tmp_path):
    opened = open_character(client, tmp_path)
    r = client.post("/api/join", json={"grid": opened["grid"]})
    assert r.status_code == 200, r.text
    got = r.json()
    joined = unpack_shape(got["grid"])
    before = unpack_shape(opened["grid"])
    assert joined.components == 1 and before.components == 5
    added = [tuple(v) for j in got["joins"] for v in j["added"]]
    assert len(got["joins"]) == 4 and all(j["words"].startswith("joined the part of") for j in got["joins"])
    assert sorted(map(tuple, np.argwhere(joined.grid & ~before.grid))) == sorted(added)
    # each added voxel in a colour of the character's own, the old voxels as they were
    colours = set(CHARACTER_COLOURS.values())
    assert all(tuple(int(v) for v in joined.colours.rgba[p]) in colours for p in added)
    assert np.array_equal(joined.colours.rgba[before.grid], before.colours.rgba[before.grid])
    assert got["facts"]["volume"] == int(joined.grid.sum())


def test_a_painted_shape_is_kept_and_opened_in_its_colours(client, tmp_path):
    opened = open_character(client, tmp_path)
    r = client.post("/api/repo", json={"grid": opened["grid"], "draft": True})
    assert r.status_code == 200 and r.json()["created"], r.text
    name = r.json()["name"]
    back = client.get("/api/repo/shape", params={"name": name})
    assert back.status_code == 200, back.text
    kept, sent = unpack_shape(back.json()["grid"]), unpack_shape(opened["grid"])
    # The same voxels in the same colours (the editor centres a kept shape in its grid).
    assert kept.crop() == sent.crop()
    # The same voxels in other colours are another shape.
    other = sent.painted((0, 0, 0, 255), sent.grid)
    r = client.post("/api/repo", json={"grid": pack(other.grid, other.colours), "draft": True})
    assert r.status_code == 200 and r.json()["created"] and r.json()["name"] != name


def test_made_files_get_the_shape_in_its_colours_and_scale(client, monkeypatch):
    from voxfab.studio import _work

    made = []
    monkeypatch.setattr(_work, "make_files", lambda job, shape, **kw: made.append(shape))
    red = VoxelShape(small_shape(), 2.5).painted((220, 20, 20, 255))
    for grid in (pack_shape(red), pack(small_shape())):
        r = client.post("/api/make", json={"grid": grid, "artefact": "mesh.3mf", "pitch": 2.5, "title": "c"})
        assert wait_job(client, r.json()["job"])["state"] == "done"
    assert made == [red, VoxelShape(small_shape(), 2.5)]


def test_the_palette_is_magicavoxels_default(client):
    assert np.array_equal(np.array(client.get("/api/palette").json()["palette"]), default_palette())


def test_studio_command_opens_a_vox_in_its_colours_and_joins_it(tmp_path, capsys):
    from voxfab import io as vio
    from voxfab.cli._main import build_parser
    from voxfab.cli.studio import _initial

    vio.write(character(), tmp_path / "character.vox")
    args = build_parser().parse_args(["studio", str(tmp_path / "character.vox"), "--repo", str(tmp_path / "r.sqlite")])
    first = _initial(args)
    assert isinstance(first, InitialShape) and first.colours is not None
    assert rgba_by_voxel(unpack_shape(first.answer()["grid"])) == rgba_by_voxel(character())
    args = build_parser().parse_args(["studio", str(tmp_path / "character.vox"), "--join"])
    joined = unpack_shape(_initial(args).answer()["grid"])
    assert joined.components == 1 and joined.colours is not None
    assert capsys.readouterr().err.count("joined the part of") == 4
