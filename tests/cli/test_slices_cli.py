"""``voxfab slices`` through the real entry point."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np

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
