"""``census.json`` end to end: counts, every net refolded, serial and Dask alike, resume, the page, the CLI."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from voxfab.census import (
    CensusSettings,
    grid_of,
    net_page,
    run_census,
    tree_problem,
    verify_census,
    write_page,
)
from voxfab.census._certificate import check_certificate
from voxfab.errors import VoxfabWarning
from voxfab.unfold import Net, validate

from .test_unzip import _assert_one_path_through_corners

#: OEIS A000162 (one-sided: up to rotation, the polycubes the census lists) and A038119 (free: up to rotation
#: and reflection).
ONE_SIDED = [1, 1, 2, 8, 29]
FREE = [1, 1, 2, 7, 23]


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
    assert data["format"] == "voxfab-census/2" and data["complete"]
    rows = data["rows"]
    assert [r["n"] for r in rows] == [1, 2, 3, 4, 5]
    assert [r["one_sided"] for r in rows] == ONE_SIDED
    assert [r["free"] for r in rows] == FREE
    for r in rows:
        for key in ("unfold", "unzip"):
            assert {f"{key}_found", f"{key}_none", f"{key}_undecided"} <= set(r)
        assert r["censused"] == r["one_sided"]
        assert r["unfold_found"] + r["unfold_none"] + r["unfold_undecided"] == r["one_sided"]
        assert r["unzip_found"] + r["unzip_none"] + r["unzip_undecided"] == r["manifold"]
        assert r["manifold"] + r["edge_touching"] + r["vertex_touching"] + r["handle"] == r["one_sided"]
        assert isinstance(r["seconds"], float)
    assert rows[4]["edge_touching"] == 1  # the pentacube whose two end cubes meet along an edge
    assert len(data["shapes"]) == sum(ONE_SIDED)
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
    assert check.problems == () and check.nets == sum(ONE_SIDED) and check.unzippings == sum(ONE_SIDED) - 1
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
    with pytest.warns(VoxfabWarning, match="03-000002: nets/03-000002.unzip.json: No such file"):
        again = run_census(5, out, workers=0)
    assert (again.censused, again.kept) == (sum(ONE_SIDED) - 3, 3)
    assert _stable(out / "census.json") == _stable(serial / "census.json")
    with pytest.warns(VoxfabWarning, match="other settings .* 41 records are discarded"):
        other = run_census(3, out, workers=0, settings=CensusSettings(seed=1))  # other settings: nothing kept
    assert other.kept == 0


def test_a_smaller_census_keeps_the_larger_one(serial: Path, tmp_path: Path) -> None:
    out = tmp_path / "larger"
    shutil.copytree(serial, out)
    with pytest.warns(VoxfabWarning, match="census of 1..5 cubes: kept whole"):
        report = run_census(3, out, workers=0)
    assert (report.censused, report.kept) == (0, sum(ONE_SIDED))
    assert _stable(out / "census.json") == _stable(serial / "census.json")


def test_a_census_of_the_first_format_resumes_and_reads(serial: Path, tmp_path: Path) -> None:
    """voxfab-census/1 named the one-sided count free and the free count free_mirror: it still resumes and reads."""
    out = tmp_path / "old"
    shutil.copytree(serial, out)
    data = json.loads((out / "census.json").read_text())
    data["format"] = "voxfab-census/1"
    for row in data["rows"]:
        row["free"], row["free_mirror"] = row.pop("one_sided"), row.pop("free")
    (out / "census.json").write_text(json.dumps(data))
    page = write_page(out, data).read_text()
    assert ">29<" in page and ">23<" in page and "one sided" in page
    report = run_census(5, out, workers=0)
    assert (report.censused, report.kept) == (0, sum(ONE_SIDED))
    assert _stable(out / "census.json") == _stable(serial / "census.json")


def _independent_tree_check(net: Net, tree: list[list[int]]) -> None:
    """F - 1 folds, each a fold of the net joining two squares whose shared 3D edge lies at one 2D place in both,
    reaching every square from square 0 (so no cycle): folding along them puts every square in its place."""
    f = net.face_count
    assert len(tree) == f - 1
    folds = {tuple(sorted(p)) for p in net.folds.tolist()}
    c3, c2 = net.corners3d.tolist(), net.corners2d.tolist()
    links: dict[int, set[int]] = {i: set() for i in range(f)}
    for a, b in tree:
        assert (min(a, b), max(a, b)) in folds
        shared = [p for p in c3[a] if p in c3[b]]
        assert len(shared) == 2  # an edge, not a corner
        for p in shared:
            assert c2[a][c3[a].index(p)] == c2[b][c3[b].index(p)]
        links[a].add(b)
        links[b].add(a)
    seen, todo = {0}, [0]
    while todo:
        for b in links[todo.pop()] - seen:
            seen.add(b)
            todo.append(b)
    assert seen == set(range(f))


def test_every_stored_net_gives_its_fold_tree(serial: Path) -> None:
    """The folds of a net file close cycles (every edge whose squares meet in the plane); its tree has none."""
    data = json.loads((serial / "census.json").read_text())
    cycles = 0
    for rec in data["shapes"]:
        for key in ("net", "unzip_net"):
            if rec[key] is None:
                continue
            text = json.loads((serial / rec[key]).read_text())
            net = Net.from_dict(text)
            validate(grid_of(rec["cells"]), net)
            _independent_tree_check(net, text["tree"])
            cycles += net.folds.shape[0] > net.face_count - 1
    assert cycles > 0  # the folds alone are no tree: the tree is worth giving
    # A tree with a cycle, a missing fold or a fold that is none is caught by the census's own check.
    rec = next(r for r in data["shapes"] if r["n"] == 4)
    text = json.loads((serial / rec["net"]).read_text())
    net = Net.from_dict(text)
    extra = next(p for p in net.folds.tolist() if sorted(p) not in text["tree"])
    for bad in (text["tree"][:-1], text["tree"][:-1] + [extra], text["tree"][:-1] + [[0, 0]]):
        assert tree_problem(net, bad) is not None


def test_the_page_draws_its_pictures_through_the_drawing_model(serial: Path) -> None:
    """Each picture is a page of voxfab.drawing in its SVG backend's form: layers by name, XML that parses."""
    import re
    import xml.etree.ElementTree as ET

    page = (serial / "census.html").read_text()
    svgs = re.findall(r"<svg .*?</svg>", page, flags=re.S)
    assert len(svgs) >= 10
    layers = set()
    for svg in svgs:
        root = ET.fromstring(svg)
        groups = root.findall("{http://www.w3.org/2000/svg}g")
        assert groups and all(g.get("{http://www.inkscape.org/namespaces/inkscape}groupmode") == "layer"
                              for g in groups)
        layers |= {g.get("id") for g in groups}
    assert {"CUT", "GRID", "LABEL", "FILL"} <= layers
    net = json.loads((serial / "nets" / "04-000001.unzip.json").read_text())
    drawn = net_page(net)
    a, b = drawn.lines("CUT").segments()
    assert len(a) == 2 * (net["face_count"] * 4 // 2 - len(net["folds"]))  # both sides of each cut edge


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
