"""``voxfab slices`` through the real entry point."""

from __future__ import annotations

import json
import subprocess
import sys

import ezdxf
import numpy as np
import pytest
import shapely
from _dxf_read import closed_rings

from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import examples


def _run(*args: str, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "voxfab", "slices", *args], cwd=cwd, capture_output=True, text=True)


def test_cli_writes_sheets_and_prints_the_report(tmp_path) -> None:
    np.save(tmp_path / "vase.npy", examples.vase(8))
    out = tmp_path / "out"
    proc = _run("vase.npy", "-o", "out", "--axis", "x", "--pitch", "4", "--thickness", "2",
                "--sheet", "90x60", "--kerf", "0.1", "--dowel", "2", "--no-score", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    report = json.loads(proc.stdout)
    assert report["axis"] == "x" and report["plates_per_layer"] == 2 and report["kerf"] == 0.1
    assert report["sheets"] >= 1 and report["plates"] == 2 * report["pieces"]
    for f in report["files"]:
        assert (tmp_path / f).is_file()
    assert (out / "sheet-01.dxf").read_text().count("SCORE") == 1  # the layer table entry only
    assert not (out / "plates.step").exists()


def test_cli_reports_bad_input_as_a_voxfab_error(tmp_path, capsys, monkeypatch) -> None:
    from voxfab.cli import main

    np.save(tmp_path / "b.npy", examples.box(2, 2, 2))
    monkeypatch.chdir(tmp_path)
    assert main(["slices", "b.npy", "-o", "out", "--sheet", "big"]) == 3
    assert capsys.readouterr().err.startswith("voxfab: error: --sheet: expected A5, A4")
    assert main(["slices", "b.npy", "-o", "out", "--pitch", "3", "--sheet", "5x5", "--margin", "1"]) == 10
    assert "does not fit" in capsys.readouterr().err
    assert main(["slices", "b.npy", "-o", "out", "--thickness", "-1"]) == 3
    assert "thickness" in capsys.readouterr().err
    assert main(["slices", "b.npy", "-o", "out", "--pitch", "0"]) == 3
    assert "pitch" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def _plate_areas(doc) -> list[float]:
    """Material of each plate cut on a sheet: outlines less the holes inside them (dowel circles aside)."""
    rings = sorted((shapely.Polygon(r) for r in closed_rings(doc)), key=lambda r: -r.area)
    outer: list[list] = []
    for r in rings:
        host = [o for o in outer if o[0].contains(r)]
        if len(host) % 2 == 0:
            outer.append([r, r.area])
        else:
            host[-1][1] -= r.area
            outer.append([r, 0.0])
    return [a for _, a in outer if a > 0]


def test_queen_sheets_declare_millimetres_and_r12_on_request(tmp_path) -> None:
    """The queen's sheets are R2000 in mm by default; plate areas read back in mm² match plates.json; R12 on ask."""
    queen = make_shape(load_recipe("recipes/chess/queen.toml"))
    np.save(tmp_path / "queen.npy", queen.grid)
    found: dict[str, list[float]] = {}
    for version, code in (("", "AC1015"), ("R12", "AC1009")):
        out = f"out{version}"
        extra = ("--dxf-version", version) if version else ()
        proc = _run("queen.npy", "-o", out, "--pitch", "3.4", "--dowel", "0", *extra, cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
        report = json.loads((tmp_path / out / "plates.json").read_text())
        areas: list[float] = []
        for k in range(1, report["sheets"] + 1):
            doc = ezdxf.readfile(tmp_path / out / f"sheet-{k:02d}.dxf")
            assert doc.dxfversion == code
            auditor = doc.audit()
            assert not auditor.has_errors and not auditor.has_fixes
            if version == "R12":
                assert "$INSUNITS" not in doc.header
            else:
                assert doc.header["$INSUNITS"] == 4 and doc.header["$MEASUREMENT"] == 1
            areas += _plate_areas(doc)
            ext = np.array(doc.header["$EXTMAX"])[:2]
            assert (ext <= (report["sheet_width"], report["sheet_height"])).all()
        # every plate is cut at its size in mm: the queen's foot is 37.4 mm across (a disc of ~1100-1400 mm²)
        assert sorted(areas) == pytest.approx(sorted(p["area"] for p in report["plates_list"]), rel=1e-6)
        assert 1000 < max(areas) < 37.4 * 37.4
        found[code] = sorted(areas)
    assert found["AC1015"] == pytest.approx(found["AC1009"], rel=1e-9)


def test_radial_hub_wider_than_the_queens_neck_offers_ways_out_that_work(tmp_path) -> None:
    """Six radial plates of 6 mm need a 22.5 mm hub slot, wider than the queen's neck: no two plates hold each
    other there, and the command says so and names fewer or thinner plates; each way out keeps every plate
    whole."""
    import re

    import trimesh

    queen = make_shape(load_recipe("recipes/chess/queen.toml"))
    np.save(tmp_path / "queen.npy", queen.grid)
    asked = ("queen.npy", "--pitch", "3.4", "--style", "radial", "--radial-plates", "6", "--thickness", "6")
    proc = _run(*asked, "-o", "six", cwd=tmp_path)
    assert proc.returncode == 10 and not (tmp_path / "six").exists(), proc.stderr
    (line,) = proc.stderr.splitlines()
    assert "no two plates hold each other at the hub" in line
    assert "22.5 mm for 6 plates of 6 mm" in line and "wider than the solid's neck" in line
    fewer = int(re.search(r"--radial-plates (\d+)", line).group(1))
    thinner = float(re.search(r"--thickness ([0-9.]+), with 6 plates", line).group(1))
    assert 2 <= fewer < 6 and 0 < thinner < 6
    for plates, thickness, out in ((fewer, "6", "fewer"), (6, f"{thinner:g}", "thinner")):
        way = _run("queen.npy", "--pitch", "3.4", "--style", "radial", "--radial-plates", str(plates),
                   "--thickness", thickness, "--strict", "-o", out, cwd=tmp_path)
        assert way.returncode == 0, way.stderr
        got = json.loads((tmp_path / out / "plates.json").read_text())
        assert got["plates"] == plates and not got["trimmed"] and not got["left_out"] and not got["advice"]
        assert not got["weak"]
        scene = trimesh.load(tmp_path / out / "assembly.3mf", force="scene")
        assert len(scene.geometry) == plates
    strict = _run(*asked, "--strict", "-o", "strict", cwd=tmp_path)
    assert strict.returncode == 10 and "hub slot" in strict.stderr


def test_weak_radial_joints_warn_and_fail_strict(tmp_path) -> None:
    """The knight at 2.4 mm, radial: pairs that engage over less than half the shorter plate are dropped,
    listed as weak in plates.json and warned about; --strict exits 11."""
    knight = make_shape(load_recipe("recipes/chess/knight.toml"))
    np.save(tmp_path / "knight.npy", knight.grid)
    proc = _run("knight.npy", "--pitch", "2.4", "--style", "radial", "--strict", "-o", "k", cwd=tmp_path)
    assert proc.returncode == 11, proc.stderr
    weak = json.loads((tmp_path / "k" / "plates.json").read_text())["weak"]
    assert weak and all(pair.startswith("R") for pair in weak)
    (line,) = [x for x in proc.stderr.splitlines() if "crossing(s) dropped" in x]
    assert all(pair in line for pair in weak)


def test_cli_by_colour_cuts_each_colour_on_sheets_of_its_own(tmp_path) -> None:
    from _voxart import character

    from voxfab.io import write

    write(character().joined()[0], tmp_path / "hero.vox")
    proc = _run("hero.vox", "-o", "out", "--thickness", "2", "--sheet", "200x150", "--by-colour", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    report = json.loads((tmp_path / "out" / "plates.json").read_text())
    assert report["by_colour"] and len(report["colours"]) >= 4
    colour_of = {p["number"]: p["colour"]["hex"] for p in report["plates_list"]}
    for sheet in report["sheets_list"]:
        assert {colour_of[n] for n in sheet["plates"]} == {sheet["colour"]}
        assert sheet["file"] == f"sheet-{sheet['index']:02d}-{sheet['colour'][1:]}.dxf"
        doc = ezdxf.readfile(tmp_path / "out" / sheet["file"])
        assert len([r for r in closed_rings(doc) if shapely.Polygon(r).area > 0]) >= len(sheet["plates"])
        svg = (tmp_path / "out" / sheet["file"]).with_suffix(".svg").read_text()
        assert f"<title>sheet {sheet['index']}, {sheet['colour']}</title>" in svg
