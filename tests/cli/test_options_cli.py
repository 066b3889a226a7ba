"""Every option is checked before any work: the option cases of the hardening issue."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.cli import main
from voxfab.cli._common import STRICT_EXIT
from voxfab.shape import examples


@pytest.fixture
def ball(tmp_path, monkeypatch):
    np.save(tmp_path / "ball.npy", examples.ball(12))
    monkeypatch.chdir(tmp_path)
    return "ball.npy"


def _one_error_line(capsys, *words: str) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("voxfab: error: "), err
    assert all(w in err[0] for w in words), err[0]
    assert len(err[0]) < 300
    return err[0]


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["mesh", "ball.npy", "-o", "m.stl", "--size", "1e300"], ["--size", "1e+300", "up to 10000"]),
        (["mesh", "ball.npy", "-o", "m.stl", "--size", "nan"], ["--size", "nan"]),
        (["mesh", "ball.npy", "-o", "m.stl", "--pitch", "inf"], ["--pitch", "inf"]),
        (["render", "ball.npy", "-o", "r.png", "--size", "0"], ["--size", "16 to 8192", "got 0"]),
        (["render", "ball.npy", "-o", "r.png", "--background", "x" * 5000], ["--background", "5002 characters"]),
        (["slices", "ball.npy", "-o", "out", "--thickness", "0.0001"], ["--thickness", "0.1 to 100"]),
        (["slices", "ball.npy", "-o", "out", "--dowel", "1000"], ["--dowel", "got 1000"]),
        (["slices", "ball.npy", "-o", "out", "--sheet", "1x1"], ["--sheet", "no room"]),
        (["slices", "ball.npy", "-o", "out", "--sheet", "1e9x1e9"], ["--sheet"]),
        (["net", "ball.npy", "-o", "n.svg", "--sheet", "1x1"], ["sheet", "1x1"]),
        (["net", "ball.npy", "-o", "n.svg", "--sheet", "1e9x1e9"], ["sheet", "1e9x1e9"]),
        (["net", "ball.npy", "-o", "n.svg", "--sheet", "9000x9000"], ["sheet", "at most 5000 mm"]),
        (["net", "ball.npy", "-o", "n.svg", "--tab-width", "-3"], ["tab-width", "-3"]),
        (["net", "ball.npy", "-o", "n.json", "--timeout", "0"], ["--timeout"]),
        (["net", "ball.npy", "-o", "n.json", "--count", "1000000000"], ["--count", "1 to 1000"]),
    ],
)
def test_bad_values_fail_before_any_work(ball, capsys, monkeypatch, argv, words):
    import voxfab.fabricate.plates as plates
    import voxfab.unfold as unfold

    def no_work(*args, **kwargs):
        raise AssertionError("the work started before the options were checked")

    for module, name in ((unfold, "unfold"), (unfold, "unfold_many"), (plates, "make_slices")):
        monkeypatch.setattr(module, name, no_work)
    assert main(argv) == 3
    _one_error_line(capsys, *words)
    assert not any(p.name != "ball.npy" for p in __import__("pathlib").Path().iterdir())


def test_contacts_error_refuses_a_print_in_two_parts(tmp_path, capsys):
    g = np.zeros((5, 2, 2), bool)
    g[:2, :, :] = g[3:, :, :] = True  # two cubes with a gap: no contact at all
    np.save(tmp_path / "two.npy", g)
    out = tmp_path / "two.3mf"
    assert main(["mesh", str(tmp_path / "two.npy"), "-o", str(out), "--contacts", "error"]) == 10
    _one_error_line(capsys, "2 separate parts")
    assert not out.exists()
    # the default (bridge) writes it, and says so at the end; --strict makes that a failure
    assert main(["mesh", str(tmp_path / "two.npy"), "-o", str(out)]) == 0
    assert "voxfab: warning: the print is 2 separate parts" in capsys.readouterr().err
    assert main(["mesh", str(tmp_path / "two.npy"), "-o", str(out), "--strict"]) == STRICT_EXIT


def test_slices_into_an_existing_file_is_a_clean_error(tmp_path, capsys):
    np.save(tmp_path / "b.npy", examples.box(3, 3, 3))
    (tmp_path / "existing.vox").write_bytes(b"keep")
    assert main(["slices", str(tmp_path / "b.npy"), "-o", str(tmp_path / "existing.vox")]) == 3
    _one_error_line(capsys, "existing.vox", "not a folder")
    assert (tmp_path / "existing.vox").read_bytes() == b"keep"


def test_big_dowels_are_a_warning_not_a_silent_success(tmp_path, capsys):
    np.save(tmp_path / "b.npy", examples.box(3, 3, 3))
    argv = ["slices", str(tmp_path / "b.npy"), "-o", str(tmp_path / "out"), "--pitch", "3", "--dowel", "50"]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "without dowels" in err and err.count("voxfab: warning:") >= 1
    assert main([*argv, "--strict"]) == STRICT_EXIT


def test_build_ends_with_the_warnings_and_strict_fails(tmp_path, capsys):
    np.save(tmp_path / "b.npy", examples.box(3, 3, 3))
    recipe = tmp_path / "b.toml"
    recipe.write_text('pitch = 3.0\n[source]\nfile = "b.npy"\n[outputs.slices]\ndowel = 0.0\n')
    assert main(["build", str(recipe), "-o", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err.splitlines()
    assert "voxfab: warning: b: slices: plates without dowels (dowel = 0): align the stack by the scored outlines" in err
    assert main(["build", str(recipe), "-o", str(tmp_path / "out"), "--strict"]) == STRICT_EXIT
    assert main(["build", str(recipe), "--check", "--strict"]) == 0  # checking builds nothing: no warnings
