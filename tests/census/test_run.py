"""``census.json`` end to end: counts, every net refolded, serial and Dask alike, resume, the page, the CLI."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from voxfab.census import CensusSettings, grid_of, run_census, verify_census
from voxfab.census._certificate import check_certificate
from voxfab.unfold import Net, validate

from .test_unzip import _assert_one_path_through_corners

FREE = [1, 1, 2, 8, 29]
FREE_MIRROR = [1, 1, 2, 7, 23]


def _stable(path: Path) -> dict:
    """census.json without what depends on the machine: the times and the workers."""
    data = json.loads(path.read_text())
    data.pop("run")
    for row in data["rows"]:
        row.pop("seconds")
        row.pop("cpu_seconds")
    return data


@pytest.fixture(scope="module")
def serial(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("census") / "serial"
    run_census(5, out, workers=0)
    return out


def test_rows_follow_the_contract_and_the_counts(serial: Path) -> None:
    data = json.loads((serial / "census.json").read_text())
    assert data["format"] == "voxfab-census/1" and data["complete"]
    rows = data["rows"]
    assert [r["n"] for r in rows] == [1, 2, 3, 4, 5]
    assert [r["free"] for r in rows] == FREE
    assert [r["free_mirror"] for r in rows] == FREE_MIRROR
    for r in rows:
        for key in ("unfold", "unzip"):
            assert {f"{key}_found", f"{key}_none", f"{key}_undecided"} <= set(r)
        assert r["censused"] == r["free"]
        assert r["unfold_found"] + r["unfold_none"] + r["unfold_undecided"] == r["free"]
        assert r["unzip_found"] + r["unzip_none"] + r["unzip_undecided"] == r["manifold"]
        assert r["manifold"] + r["edge_touching"] + r["vertex_touching"] + r["handle"] == r["free"]
        assert isinstance(r["seconds"], float)
    assert rows[4]["edge_touching"] == 1  # the pentacube whose two end cubes meet along an edge
    assert len(data["shapes"]) == sum(FREE)
    assert data["run"]["where"] == "serial"


def test_every_recorded_net_refolds_to_its_polycube(serial: Path) -> None:
    data = json.loads((serial / "census.json").read_text())
    for rec in data["shapes"]:
        g = grid_of(rec["cells"])
        assert len(rec["cells"]) == rec["n"]
        if rec["unfold"] == "found":
            net = Net.from_json((serial / rec["net"]).read_text())
            validate(g, net)
        if rec["unzip"] == "found":
            net = Net.from_json((serial / rec["unzip_net"]).read_text())
            validate(g, net)
            _assert_one_path_through_corners(g, net)
        if rec["unzip"] == "none":
            check_certificate(rec["cells"], rec["certificate"])
        if rec["surface"] != "manifold":
            assert rec["unzip"] is None and rec["unzip_net"] is None
    check = verify_census(serial)
    assert check.problems == () and check.nets == sum(FREE) and check.unzippings == sum(FREE) - 1
    # A net file swapped for another shape's is caught.
    one = serial / "nets" / "04-000001.unzip.json"
    kept = one.read_bytes()
    one.write_bytes((serial / "nets" / "04-000002.unzip.json").read_bytes())
    try:
        assert any(p.startswith("04-000001:") for p in verify_census(serial).problems)
    finally:
        one.write_bytes(kept)


def test_a_dask_run_writes_the_same_census_as_a_serial_run(serial: Path, tmp_path: Path) -> None:
    pytest.importorskip("distributed")
    report = run_census(5, tmp_path / "dask", workers=2)
    assert report.workers == 2
    assert _stable(tmp_path / "dask" / "census.json") == _stable(serial / "census.json")
    for rec in json.loads((serial / "census.json").read_text())["shapes"]:
        for key in ("net", "unzip_net"):
            if rec[key]:
                assert (tmp_path / "dask" / rec[key]).read_bytes() == (serial / rec[key]).read_bytes()


def test_a_census_resumes_where_an_earlier_one_stopped(serial: Path, tmp_path: Path) -> None:
    out = tmp_path / "resumed"
    first = run_census(3, out, workers=0)
    assert (first.censused, first.kept) == (4, 0)
    (out / "nets" / "03-000002.unzip.json").unlink()  # a lost file: that shape is censused again
    again = run_census(5, out, workers=0)
    assert (again.censused, again.kept) == (sum(FREE) - 3, 3)
    assert _stable(out / "census.json") == _stable(serial / "census.json")
    other = run_census(3, out, workers=0, settings=CensusSettings(seed=1))  # other settings: nothing kept
    assert other.kept == 0


def test_the_page_shows_the_table_and_pictures_in_chromium(serial: Path, tmp_path: Path) -> None:
    page = serial / "census.html"
    text = page.read_text()
    assert text.count("<svg") >= 5  # a net and a polycube per n at least
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        pytest.skip("chromium is not installed")
    dom = subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=120).stdout
    assert "<table>" in dom and "Polycube census, 1 to 5 cubes" in dom
    shot = tmp_path / "page.png"
    subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--window-size=1400,2400", f"--screenshot={shot}", page.as_uri()],
                   capture_output=True, timeout=120, check=True)
    from PIL import Image

    pixels = np.asarray(Image.open(shot).convert("RGB")).astype(int)
    red = (pixels[..., 0] > 150) & (pixels[..., 1] < 80) & (pixels[..., 2] < 80)
    blue = (pixels[..., 2] > 150) & (pixels[..., 0] < 160)
    assert red.sum() > 200 and blue.sum() > 200  # cut paths drawn red, cubes shaded blue


def test_the_cli_prints_the_table_and_refuses_bad_input_in_one_line(tmp_path: Path) -> None:
    ok = subprocess.run([sys.executable, "-m", "voxfab", "census", "3", "-o", str(tmp_path / "c"), "--workers", "0"],
                        capture_output=True, text=True, timeout=300)
    assert ok.returncode == 0, ok.stderr
    assert "4 polycubes censused" in ok.stdout and (tmp_path / "c" / "census.json").is_file()
    for args, words in ((["0"], "from 1 to 11"), (["3", "--timeout", "-1"], "--timeout: expected a positive number"),
                        (["3", "--timeout", "nan"], "--timeout: expected a positive number"),
                        (["3", "--seed", "-3"], "--seed: expected an integer")):
        bad = subprocess.run([sys.executable, "-m", "voxfab", "census", *args, "-o", str(tmp_path / "d"),
                              "--workers", "0"], capture_output=True, text=True, timeout=120)
        assert bad.returncode != 0 and words in bad.stderr, bad.stderr
        assert len(bad.stderr.strip().splitlines()) == 1 and "Traceback" not in bad.stderr
    missing = subprocess.run([sys.executable, "-m", "voxfab", "census", "2", "-o", str(tmp_path / "no" / "where" / "x")],
                             capture_output=True, text=True, timeout=120)
    assert missing.returncode != 0 and "does not exist" in missing.stderr
