"""Hardening 3, seen besides the classes: odd sheets, tiny faces and boxes say what is wrong, and pictures stay bounded."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, refused, run_cli

from voxfab.drawing.png import MAX_PAGE_PIXELS, page_scale
from voxfab.shape import examples


@pytest.fixture()
def ball(tmp_path: Path) -> Path:
    np.save(tmp_path / "ball.npy", examples.ball(3))
    return tmp_path / "ball.npy"


def test_a_net_on_a_huge_sheet_draws_a_bounded_picture(tmp_path: Path, ball: Path) -> None:
    from PIL import Image

    out = tmp_path / "n.png"
    o = check_outcome(run_cli(["net", ball, "--pieces", "auto", "--sheet", "3000x3000", "--face-size", 10,
                               "-o", out], seconds=120), seconds=120)
    assert o.code == 0
    with Image.open(out) as im:
        assert im.width * im.height <= MAX_PAGE_PIXELS and im.width == im.height == 5000


@pytest.mark.parametrize(("w", "h", "scale"), [(210, 297, 4.0), (5000, 5000, 4.0), (1e5, 10, 4.0), (841, 1189, 10)])
def test_page_scale_keeps_small_pages_and_bounds_large_ones(w: float, h: float, scale: float) -> None:
    s = page_scale(w, h, scale)
    assert s <= scale and round(w * s) * round(h * s) <= MAX_PAGE_PIXELS * 1.001
    if w * h * scale * scale <= MAX_PAGE_PIXELS:
        assert s == scale


@pytest.mark.parametrize("box", ["5x5", "9.9x40", "40x3"])
def test_a_box_smaller_than_a_face_says_so_in_mm(tmp_path: Path, ball: Path, box: str) -> None:
    line = refused(["net", ball, "--box", box, "--face-size", 10, "-o", tmp_path / "n.json"])
    assert f"--fit: {box} mm holds no 10 mm face" in line and "0x0" not in line


def test_tiny_faces_without_marks_never_speak_of_a_fit_not_asked_for(tmp_path: Path, ball: Path) -> None:
    o = check_outcome(run_cli(["net", ball, "--face-size", "1e-6", "--no-numbers", "--no-tabs", "-o",
                               tmp_path / "n.svg"], seconds=120), seconds=120)
    assert "fit:" not in o.err
    assert o.code == 0 and (tmp_path / "n.svg").exists()
