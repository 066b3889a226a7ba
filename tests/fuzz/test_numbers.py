"""Numbers in text are ASCII digits, read one way (voxfab._shared.numbers) by the studio and the CLI.

``str.isdigit`` is true of '²' and '①', which ``int`` refuses; ``int`` and ``float``
take full-width and Arabic-Indic digits.  Each of these is a one-line refusal
naming the field, never a 500 or a number the user did not type.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from _fuzz import check_outcome, run_cli

from voxfab._shared.numbers import is_digits, parse_float, parse_int
from voxfab.repo import Repository
from voxfab.shape import examples
from voxfab.studio._grid import centred, pack

#: Digits that are not ASCII: superscript, circled, full-width, Arabic-Indic, Devanagari.
FOREIGN = ["²", "①", "３", "٣", "१२", "1²", "٣.5", "1_000", " 3", "3\n"]


@pytest.mark.parametrize("text", FOREIGN)
def test_the_helpers_take_ascii_digits_only(text):
    assert not is_digits(text)
    with pytest.raises(ValueError):
        parse_int(text)
    with pytest.raises(ValueError):
        parse_float(text)


def test_the_helpers_read_what_a_keyboard_types():
    assert [parse_int(t) for t in ("0", "-12", "+7", "007")] == [0, -12, 7, 7]
    assert [parse_float(t) for t in ("1", "-2.5", ".5", "1.", "1e3", "2.5E-1")] == [1, -2.5, 0.5, 1, 1000, 0.25]
    assert np.isnan(parse_float("nan")) and parse_float("-inf") == -np.inf
    with pytest.raises(ValueError):
        parse_int("1" * 10, max_digits=9)


@pytest.fixture(scope="module")
def job(studio) -> str:
    r = studio.post("/api/nets", json={"grid": pack(centred(examples.ball(2))), "count": 1,
                                       "options": {"sheet": "A4", "timeout": 5}})
    assert r.status_code == 200, r.text
    job = r.json()["job"]
    end = time.monotonic() + 120
    while studio.get(f"/api/jobs/{job}").json()["state"] in ("queued", "running"):
        assert time.monotonic() < end
        time.sleep(0.1)
    return job


@pytest.mark.parametrize("text", FOREIGN)
def test_since_in_foreign_digits_is_a_400(studio, job, text):
    r = studio.get(f"/api/jobs/{job}", params={"since": text})
    assert r.status_code == 400 and r.json()["error"].startswith("since:"), r.text
    assert studio.get(f"/api/jobs/{job}", params={"since": "0"}).status_code == 200


@pytest.mark.parametrize("text", FOREIGN)
def test_limit_in_foreign_digits_is_a_400(studio, text):
    r = studio.get("/api/repo", params={"limit": text})
    assert r.status_code == 400 and r.json()["error"].startswith("limit:"), r.text
    assert studio.get("/api/repo", params={"limit": "5"}).status_code == 200


@pytest.mark.parametrize("argv", [
    ["census", "３", "-o", "{d}/c", "--workers", "0"],
    ["census", "٣", "-o", "{d}/c", "--workers", "0"],
    ["census", "2", "-o", "{d}/c", "--workers", "٠"],
    ["census", "2", "-o", "{d}/c", "--workers", "0", "--connect-timeout", "３0"],
    ["repo", "list", "--limit", "３", "--repo", "{d}/r.sqlite"],
    ["repo", "list", "--volume", "３:9", "--repo", "{d}/r.sqlite"],
    ["studio", "--port", "８７６５", "--no-browser"],
    ["warmup", "--processes", "２"],
    ["net", "{d}/x.npy", "-o", "{d}/n.json", "--seed", "١"],
    ["mesh", "{d}/x.npy", "-o", "{d}/x.stl", "--pitch", "２"],
    ["net", "{d}/x.npy", "-o", "{d}/n.json", "--fit", "２0x30"],
])
def test_the_cli_refuses_numbers_in_foreign_digits(tmp_path, argv):
    np.save(tmp_path / "x.npy", examples.ball(2))
    Repository(tmp_path / "r.sqlite").close()
    before = sorted(p.name for p in tmp_path.iterdir())
    o = check_outcome(run_cli([a.format(d=tmp_path) for a in argv]))
    assert o.code != 0 and "expected" in o.error_lines[0], (o.code, o.err)
    assert sorted(p.name for p in tmp_path.iterdir()) == before
