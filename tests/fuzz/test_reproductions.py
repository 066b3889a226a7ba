"""The reproductions of issue 14, each through the real CLI: a clean error or a correct result, in time."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, png_claiming, refused, run_cli

from voxfab import io
from voxfab.shape import examples


def recipe(folder: Path, name: str, body: str) -> Path:
    path = folder / name
    path.write_text(body)
    return path


REVOLVE_GENERATRIX = '[source]\nmaker = "revolution"\ncurve = "x^2 + y^2 - 1"\ngeneratrix = "{}"\n'
REVOLVE_CURVE = '[source]\nmaker = "revolution"\ncurve = "{}"\ngeneratrix = "x^2 + y^2 - 1"\n'
TUBE_PROFILE = '[source]\nmaker = "tube"\nspine = ["cos(2*pi*t)", "sin(2*pi*t)", "0"]\nprofile = "{}"\n'


def build(tmp_path: Path, path: Path, *extra: str) -> list[str]:
    return ["build", str(path), "-o", str(tmp_path / "out"), *extra]


# --- tracebacks ----------------------------------------------------------------------------------

@pytest.mark.parametrize("text", ["-" * 100000 + "x", "+".join(["x"] * 200000)], ids=["minus", "plus"])
def test_huge_expressions_are_refused_with_their_length(tmp_path, text):
    r = recipe(tmp_path, "r.toml", f'[source]\nmaker = "implicit"\nexpression = "{text}"\n')
    line = refused(build(tmp_path, r))
    assert f"expression of {len(text):,} characters is over the limit of 1,000" in line
    assert len(line) < 300  # the expression is quoted in 80 characters, not 100 KB


def test_deep_expression_within_the_length_is_refused_with_its_depth(tmp_path):
    r = recipe(tmp_path, "r.toml", f'[source]\nmaker = "implicit"\nexpression = "{"-" * 900}x^2 - 1"\n')
    assert "nested 90" in refused(build(tmp_path, r)) and "over the limit of 100" in refused(build(tmp_path, r))


@pytest.mark.parametrize("template", [REVOLVE_GENERATRIX, REVOLVE_CURVE], ids=["generatrix", "curve"])
def test_bitmap_whose_header_claims_60000_squared_pixels(tmp_path, template):
    (tmp_path / "bomb.png").write_bytes(png_claiming(60000, 60000))
    line = refused(build(tmp_path, recipe(tmp_path, "r.toml", template.format("bomb.png"))))
    assert "60000x60000 = 3,600,000,000 pixels is over the limit of 16,777,216 pixels" in line


@pytest.mark.parametrize("template", [REVOLVE_GENERATRIX, REVOLVE_CURVE, TUBE_PROFILE],
                         ids=["generatrix", "curve", "tube-profile"])
def test_json_drawing_nested_100000_deep(tmp_path, template):
    (tmp_path / "deep.json").write_text("[" * 100000)
    line = refused(build(tmp_path, recipe(tmp_path, "r.toml", template.format("deep.json"))))
    assert "JSON nested 100000 levels, over the limit of 64 levels" in line


def test_json_drawing_with_a_5000_digit_integer(tmp_path):
    (tmp_path / "big.json").write_text(f"[[0, 0], [1, {'9' * 5000}], [0, 1]]")
    line = refused(build(tmp_path, recipe(tmp_path, "r.toml", REVOLVE_GENERATRIX.format("big.json"))))
    assert "an integer of 5000 digits is over the limit of 30 digits" in line


def test_toml_recipe_nested_5000_deep(tmp_path):
    r = recipe(tmp_path, "r.toml", "a = " + "[" * 5000 + "]" * 5000 + "\n")
    assert "TOML nested 5000 levels, over the limit of 64 levels" in refused(build(tmp_path, r))
    dotted = recipe(tmp_path, "d.toml", "a" + ".a" * 5000 + " = 1\n")
    assert "nested deeper than the limit of 64 levels" in refused(build(tmp_path, dotted))


def test_tube_with_a_billion_samples(tmp_path):
    r = recipe(tmp_path, "r.toml", TUBE_PROFILE.format("x^2 + y^2 - 1") + "samples = 1000000000\n")
    assert "source.samples: expected an integer in 2..100000, got 1000000000" in refused(build(tmp_path, r), seconds=20)


# --- unbounded work ----------------------------------------------------------------------------------

def test_focal_maker_with_100000_foci(tmp_path):
    foci = ", ".join(f"[0, 0, {i}]" for i in range(100000))
    r = recipe(tmp_path, "r.toml", f'[source]\nmaker = "focal"\nfoci = [{foci}]\nradius = 1e12\n')
    assert "foci: 100,000 foci is over the limit of 256" in refused(build(tmp_path, r), seconds=20)


def sparse_stl(path: Path, triangles: int) -> Path:
    """A binary STL of ``triangles`` zero triangles, as a sparse file (instant, no disk used)."""
    with open(path, "wb") as fh:
        fh.write(b"\0" * 80 + triangles.to_bytes(4, "little"))
        fh.truncate(84 + 50 * triangles)
    return path


def test_info_on_a_2_million_triangle_stl(tmp_path):
    line = refused(["info", sparse_stl(tmp_path / "big.stl", 2_000_000)], seconds=10)
    assert "100,000,084 bytes is over the limit of 67,108,864 bytes for a mesh file" in line
    line = refused(["info", sparse_stl(tmp_path / "big.stl", 1_200_000)], seconds=10)
    assert "the STL header states 1,200,000 triangles, over the limit of 1,000,000" in line


def test_info_on_a_fifo_named_npy_does_not_block(tmp_path):
    fifo = tmp_path / "x.npy"
    os.mkfifo(fifo)
    # A subprocess: before the fix the reader blocks forever in open().
    r = subprocess.run([sys.executable, "-m", "voxfab", "info", str(fifo)], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode != 0
    assert r.stderr == f"voxfab: error: {fifo}: is a FIFO, not a regular file; only regular files are read as a .npy file\n"


# --- not atomic ----------------------------------------------------------------------------------

@pytest.fixture
def cube(tmp_path) -> Path:
    grid = np.zeros((3, 3, 3), bool)
    grid[1, 1, 1] = True
    io.write(grid, tmp_path / "cube.npy")
    return tmp_path / "cube.npy"


def test_slices_interrupted_mid_write_leaves_no_folder(tmp_path, monkeypatch):
    io.write(examples.ball(3), tmp_path / "ball.npy")
    from voxfab.fabricate import plates

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt  # as Ctrl-C between the sheets and plates.json

    monkeypatch.setattr(plates, "write_assembly_pdf", interrupted)
    o = run_cli(["slices", tmp_path / "ball.npy", "-o", tmp_path / "plates"])
    assert o.code == 130 and sorted(p.name for p in tmp_path.iterdir()) == ["ball.npy"]


def test_slices_folder_is_replaced_whole(tmp_path):
    io.write(examples.ball(3), tmp_path / "ball.npy")
    out = tmp_path / "plates"
    assert check_outcome(run_cli(["slices", tmp_path / "ball.npy", "-o", out])).code == 0
    (out / "sheet-99.svg").write_text("stale")
    o = check_outcome(run_cli(["slices", tmp_path / "ball.npy", "-o", out]))
    assert o.code == 0 and not (out / "sheet-99.svg").exists() and (out / "plates.json").exists()
    assert all(Path(f).exists() for f in json.loads(o.out)["files"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ball.npy", "plates"]


def test_net_rerun_onto_fewer_files_leaves_no_stale_file(tmp_path, cube):
    first = check_outcome(run_cli(["net", cube, "-o", tmp_path / "t.json", "--count", "3", "--timeout", "5"]))
    assert json.loads(first.out)["written"] == [str(tmp_path / f"t-{i}.json") for i in (1, 2, 3)]
    second = check_outcome(run_cli(["net", cube, "-o", tmp_path / "t.json", "--count", "2", "--timeout", "5"]))
    written = json.loads(second.out)["written"]
    assert written == [str(tmp_path / "t-1.json"), str(tmp_path / "t-2.json")]
    assert sorted(p.name for p in tmp_path.glob("t*")) == ["t-1.json", "t-2.json"]


def test_net_drawing_onto_fewer_sheets_leaves_no_stale_sheet(tmp_path):
    io.write(examples.ball(3), tmp_path / "ball.npy")
    # 30 mm faces do not fit A4 in one piece: pieces packed on several sheets.
    many = check_outcome(run_cli(["net", tmp_path / "ball.npy", "-o", tmp_path / "t.svg", "--pitch", "30",
                                  "--pieces", "auto", "--timeout", "10"]))
    assert len(json.loads(many.out)["written"]) > 3
    few = check_outcome(run_cli(["net", tmp_path / "ball.npy", "-o", tmp_path / "t.svg", "--pitch", "12",
                                 "--sheet", "A2"]))
    written = json.loads(few.out)["written"]
    # The report names exactly the sheets on disk: none missing, none left from the first run.
    assert sorted(written) == sorted(str(p) for p in tmp_path.glob("t*.svg"))
    assert len(written) < len(json.loads(many.out)["written"])


def test_next_run_sweeps_what_a_killed_build_left(tmp_path):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    out = tmp_path / "out"
    out.mkdir()
    left = out / f".ball.{dead}-abcd1234.tmp"
    left.mkdir()
    (left / "shape.npy").write_bytes(b"half")
    r = recipe(tmp_path, "ball.toml", '[source]\nmaker = "implicit"\nexpression = "x^2 + y^2 + z^2 - 1"\nsize = 5\n')
    assert check_outcome(run_cli(["build", r, "-o", out])).code == 0
    assert sorted(p.name for p in out.iterdir()) == ["ball"]


def test_net_into_a_missing_folder_creates_nothing(tmp_path, cube):
    target = tmp_path / "nonexistent" / "dir" / "x.json"
    line = refused(["net", cube, "-o", target])
    assert line == f"voxfab: error: {target}: the folder {target.parent} does not exist"
    assert not (tmp_path / "nonexistent").exists()


# --- not confined ----------------------------------------------------------------------------------

def test_recipe_cannot_reach_outside_its_folder(tmp_path):
    inner = tmp_path / "recipes"
    inner.mkdir()
    io.write(examples.ball(3), tmp_path / "outside.npy")
    escape = "../" * 12 + "etc/passwd"
    cases = {
        "file": f'[source]\nfile = "{escape}"\n',
        "generatrix": REVOLVE_GENERATRIX.format(escape + ".csv"),
        "curve": REVOLVE_CURVE.format(escape + ".json"),
        "profile": TUBE_PROFILE.format(escape + ".png"),
    }
    for key, body in cases.items():
        line = refused(build(tmp_path, recipe(inner, f"{key}.toml", body)))
        assert "is outside the recipe's folder" in line and "--allow-outside" in line, line
        assert "etc/passwd" in line
    near = recipe(inner, "near.toml", '[source]\nfile = "../outside.npy"\n')
    assert "outside the recipe's folder" in refused(build(tmp_path, near))
    assert "outside the recipe's folder" in refused(["build", near, "--check"])
    assert check_outcome(run_cli(build(tmp_path, near, "--allow-outside"))).code == 0


def test_symlink_out_of_the_recipe_folder_is_refused(tmp_path):
    inner = tmp_path / "recipes"
    inner.mkdir()
    io.write(examples.ball(3), tmp_path / "outside.npy")
    (inner / "link.npy").symlink_to(tmp_path / "outside.npy")
    r = recipe(inner, "r.toml", '[source]\nfile = "link.npy"\n')
    assert "outside the recipe's folder" in refused(build(tmp_path, r))


# --- messages ----------------------------------------------------------------------------------

def test_library_warnings_do_not_reach_the_terminal(tmp_path):
    # A subprocess: pytest itself captures warnings, the terminal would not.
    code = (
        "import sys, numpy as np\n"
        "from voxfab.cli import info, main\n"
        "from voxfab.errors import InvalidShapeError\n"
        "def noisy(args):\n"
        "    np.log(np.zeros(3))\n"
        "    np.float64(1e308) * 10\n"
        "    raise InvalidShapeError('the one line')\n"
        "info.run = noisy\n"
        "sys.exit(main(['info', 'x.npy']))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 3 and r.stderr == "voxfab: error: the one line\n"


def test_error_lines_do_not_repeat_a_10kb_input(tmp_path):
    text = "foo(x) + " + "x + " * 240 + "1"  # under the length limit, an unknown function
    r = recipe(tmp_path, "r.toml", f'[source]\nmaker = "implicit"\nexpression = "{text}"\n')
    line = refused(build(tmp_path, r))
    assert len(line) < 400 and "foo" in line


def test_3mf_with_no_model(tmp_path):
    with zipfile.ZipFile(tmp_path / "empty.3mf", "w") as zf:
        zf.writestr("[Content_Types].xml", '<?xml version="1.0"?><Types/>')
    line = refused(["info", tmp_path / "empty.3mf"])
    assert line == f"voxfab: error: {tmp_path / 'empty.3mf'}: the 3MF package holds no 3D model (no 3D/*.model part)"
