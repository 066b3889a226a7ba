"""The studio's colours on the wire and its shape files, under random and hostile input.

Any coloured shape goes to the page and back unchanged; a spoiled colour field, file
format or title, and any bytes sent as a file to open, get a 400 with one line (or,
for a file that reads, its shape), never a 500 or a traceback.
"""

from __future__ import annotations

import base64

import numpy as np
from _fuzz import JSON_VALUES
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from voxfab.shape import VoxelColours, VoxelShape
from voxfab.studio._grid import pack_shape, unpack_shape

FUZZ = settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))


def _one_line(r) -> None:
    assert r.status_code in (200, 400), (r.status_code, r.text[:300])
    if r.status_code == 400:
        message = r.json()["error"]
        assert "\n" not in message and "Traceback" not in message and "internal error" not in message, message


@FUZZ
@given(st.data())
def test_any_coloured_shape_goes_to_the_page_and_back_unchanged(data):
    dims = data.draw(st.tuples(*[st.integers(1, 25)] * 3))
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))
    grid = rng.random(dims) < data.draw(st.floats(0.0, 1.0))
    index = np.where(grid, rng.integers(1, 256, dims), 0)
    palette = rng.integers(0, 256, (256, 4))
    shape = VoxelShape(grid, 1.0, VoxelColours(index, palette))
    assert unpack_shape(pack_shape(shape)) == shape


@FUZZ
@given(field=st.sampled_from(["colours", "palette"]), value=st.one_of(JSON_VALUES, st.binary(max_size=1100)))
def test_a_spoiled_colour_field_is_refused_in_one_line(studio, field, value):
    grid = np.zeros((25, 25, 25), dtype=bool)
    grid[10:14, 10:12, 3:9] = True
    grid[16, 16, 9] = True
    wire = pack_shape(VoxelShape(grid).painted((200, 10, 10, 255)))
    spoiled = base64.b64encode(value).decode() if isinstance(value, bytes) else value
    for url in ("/api/paint/fit", "/api/join", "/api/shape/file", "/api/make", "/api/repo"):
        body = {"grid": {**wire, field: spoiled}}
        if url == "/api/make":
            body["artefact"] = "mesh.stl"
        _one_line(studio.post(url, json=body))


@FUZZ
@given(fmt=st.one_of(JSON_VALUES, st.sampled_from(["vox", "npz", "VOX", ".vox", "stl"])),
       title=st.one_of(JSON_VALUES, st.text(max_size=80)))
def test_any_format_and_title_of_a_saved_shape_is_refused_or_saved(studio, fmt, title):
    grid = np.zeros((25, 25, 25), dtype=bool)
    grid[3:6, 3:6, 3:6] = True
    _one_line(studio.post("/api/shape/file", json={"grid": pack_shape(VoxelShape(grid)), "format": fmt,
                                                   "title": title}))


@FUZZ
@given(name=st.one_of(st.sampled_from(["a.vox", "a.npz", "a.npy", "a.VOX", "a", ".vox", "a b.npz"]),
                      st.text(max_size=90)),
       raw=st.one_of(st.binary(max_size=2000), st.sampled_from([b"VOX \x96\x00\x00\x00", b"\x93NUMPY", b"PK\x03\x04"])))
def test_any_bytes_opened_as_a_file_are_read_or_refused_in_one_line(studio, name, raw):
    r = studio.post("/api/shape/open", params={"name": name}, content=raw)
    _one_line(r)
    if r.status_code == 400:
        assert "open-" not in r.json()["error"]
