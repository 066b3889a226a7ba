"""voxfab net through the real entry point."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
import time

import numpy as np

from voxfab.shape import examples
from voxfab.unfold import Net, validate


def _run(*args, cwd):
    return subprocess.run([sys.executable, "-m", "voxfab", "net", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=300)


def test_net_json_is_valid_and_reproducible(tmp_path):
    grid = examples.ball(3)
    np.save(tmp_path / "ball.npy", grid)
    r = _run("ball.npy", "-o", "a.json", "--seed", "4", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r2 = _run("ball.npy", "-o", "b.json", "--seed", "4", cwd=tmp_path)
    assert r2.returncode == 0, r2.stderr
    text = (tmp_path / "a.json").read_text()
    assert text == (tmp_path / "b.json").read_text()
    data = json.loads(text)
    assert data["format"] == "voxfab-net/1" and data["seed"] == 4
    assert set(data["faces"][0]) == {"voxel", "normal", "corners3d", "corners2d"}
    assert {"mountain", "valley", "flat", "seams_without_tab_room", "folds"} <= set(data)
    assert validate(grid, Net.from_json(text)).ok
    summary = json.loads(r.stdout)
    assert summary["written"] == ["a.json"]


def test_net_count_writes_distinct_numbered_files(tmp_path):
    grid = examples.ball(2)
    np.save(tmp_path / "b.npy", grid)
    r = _run("b.npy", "-o", "net.json", "--count", "3", "--seed", "1", "--timeout", "20",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    texts = [(tmp_path / f"net-{i}.json").read_text() for i in (1, 2, 3)]
    nets = [Net.from_json(t) for t in texts]
    assert len({n.corners2d.tobytes() + n.folds.tobytes() for n in nets}) == 3
    for n in nets:
        assert validate(grid, n).ok


def test_net_fit_in_mm_and_paper_strategy(tmp_path):
    grid = examples.ball(2)
    np.save(tmp_path / "b.npy", grid)
    r = _run("b.npy", "-o", "n.json", "--fit", "60x40", "--pitch", "2", "--strategy", "paper",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    net = Net.from_json((tmp_path / "n.json").read_text())
    x0, y0, x1, y1 = net.bounds()
    assert x1 - x0 <= 30 and y1 - y0 <= 20 and net.strategy == "paper"


def test_net_cavity_error_and_fill(tmp_path):
    grid = examples.box(3, 3, 3)
    grid[1, 1, 1] = False
    np.save(tmp_path / "hollow.npy", grid)
    r = _run("hollow.npy", "-o", "n.json", cwd=tmp_path)
    assert r.returncode == 6
    assert r.stderr.startswith("voxfab: error:") and "--fill" in r.stderr
    assert not (tmp_path / "n.json").exists()
    r = _run("hollow.npy", "-o", "n.json", "--fill", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert validate(examples.box(3, 3, 3), Net.from_json((tmp_path / "n.json").read_text())).ok
    r = _run("hollow.npy", "-o", "p.json", "--pieces", "auto", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    pieces = [Net.from_json((tmp_path / f"p-piece{i}.json").read_text()) for i in (1, 2)]
    assert validate(grid, pieces).ok


def test_net_bad_fit_is_an_error(tmp_path):
    np.save(tmp_path / "b.npy", examples.ball(2))
    r = _run("b.npy", "-o", "n.json", "--fit", "big", cwd=tmp_path)
    assert r.returncode != 0 and "--fit" in r.stderr


def test_net_drawings_name_net_and_sheet_apart_and_report_warnings(tmp_path):
    np.save(tmp_path / "box.npy", np.ones((3, 3, 3), dtype=bool))
    # Two nets, each split into pieces on several A5 sheets at 40 mm faces.
    r = _run("box.npy", "-o", "net.svg", "--face-size", "40", "--sheet", "A5", "--pieces", "auto",
             "--timeout", "10", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    (record,) = summary["nets"]
    sheets = len(record["fill"])
    assert sheets > 1 and record["pieces"] > 1 and record["face_size"] == 40.0
    assert summary["written"] == [f"net.sheet-{i}.svg" for i in range(1, sheets + 1)]
    assert all(0 < f < 1 for f in record["fill"]) and "filled" in r.stderr
    assert any("net split into" in w for w in summary["warnings"])
    assert "voxfab: warning: net split into" in r.stderr
    # --strict turns the warnings into a failure
    r = _run("box.npy", "-o", "net.svg", "--face-size", "40", "--sheet", "A5", "--pieces", "auto",
             "--timeout", "10", "--strict", cwd=tmp_path)
    assert r.returncode != 0
    r = _run("box.npy", "-o", "n.svg", "--face-size", "20", "--sheet", "A3", "--count", "2", "--timeout", "10",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["written"] == ["n-1.svg", "n-2.svg"]
    np.save(tmp_path / "big.npy", examples.ball(3))
    r = _run("big.npy", "-o", "n.svg", "--face-size", "20", "--sheet", "A4", "--timeout", "10", cwd=tmp_path)
    assert r.returncode != 0 and r.stderr.count("\n") == 1
    assert "does not fit sheet A4 at 20 mm faces" in r.stderr and "it needs" in r.stderr


def test_net_refuses_faces_too_small_for_the_marks(tmp_path):
    np.save(tmp_path / "box.npy", np.ones((2, 2, 2), dtype=bool))
    r = _run("box.npy", "-o", "n.svg", "--face-size", "5", cwd=tmp_path)
    assert r.returncode != 0 and r.stderr.count("\n") == 1
    assert "what works: make the faces 7.5 mm (--face-size 7.5), or draw without seam labels and glue tabs " \
           "(--no-numbers --no-tabs)" in r.stderr
    assert not (tmp_path / "n.svg").exists()
    r = _run("box.npy", "-o", "n.svg", "--face-size", "5", "--no-numbers", "--no-tabs", cwd=tmp_path)
    assert r.returncode == 0, r.stderr


def test_count_stops_at_the_overall_budget(tmp_path):
    # 500 nets of a radius-8 ball (about 0.1 s of CPU each on an idle machine) cannot all be found in 6 s:
    # the run ends near the budget and says how many.
    np.save(tmp_path / "b.npy", examples.ball(8))
    start = time.perf_counter()
    r = _run("b.npy", "-o", "net.json", "--count", "500", "--timeout", "6", "--budget", "6", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert time.perf_counter() - start < 60
    found = json.loads(r.stdout)["nets"]
    assert 1 <= len(found) < 500
    assert f"{len(found)} distinct nets found of the 500 asked for" in r.stderr


def test_exact_strategy_alone_gives_the_queen_one_net_every_run(tmp_path):
    """--strategy exact with no box searches a box that holds any net: a one-piece net, the same whatever the seed."""
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import surface_graph
    from voxfab.unfold._exact import any_box

    grid = make_shape(load_recipe("recipes/chess/queen.toml")).grid
    np.save(tmp_path / "queen.npy", grid)
    texts = []
    for seed in (0, 7):
        r = _run("queen.npy", "-o", f"q{seed}.json", "--strategy", "exact", "--seed", seed, cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        texts.append((tmp_path / f"q{seed}.json").read_text())
    assert texts[0] == texts[1]
    net = Net.from_json(texts[0])
    faces = surface_graph(grid).face_count
    assert net.strategy == "exact" and len(net.voxel) == faces == 862
    report = validate(grid, net)  # refolded onto the queen, every face once, no overlap on the sheet
    assert report.ok, report
    w, h = np.ptp(net.corners2d.reshape(-1, 2), axis=0)
    assert min(w, h) <= any_box(faces)[0] and max(w, h) <= any_box(faces)[1]


def _recipe_grid(name: str) -> np.ndarray:
    from pathlib import Path

    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape

    return make_shape(load_recipe(Path(__file__).parents[2] / "recipes" / f"{name}.toml")).grid


def test_hopeless_sheets_for_pieces_are_refused_in_one_line_with_the_library_words(tmp_path):
    from voxfab.fabricate.netdraw import DrawingOptions, find_sheet_nets
    from voxfab.fabricate.netdraw._sheets import HopelessSheetError

    grid = _recipe_grid("chess/queen")
    np.save(tmp_path / "queen.npy", grid)
    for sheet in ("55x55", "40x297"):
        r = _run("queen.npy", "--pieces", "auto", "--sheet", sheet, "--face-size", "8.6", "-o", "q.pdf",
                 cwd=tmp_path)
        assert r.returncode != 0 and "Traceback" not in r.stderr
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("voxfab: error: sheet ")
        try:
            find_sheet_nets(grid, DrawingOptions(pitch=8.6, sheet=sheet), rng=0, pieces="auto")
        except HopelessSheetError as err:
            assert lines[0] == f"voxfab: error: {err}"
        else:
            raise AssertionError(f"{sheet} was not refused")
        assert not list(tmp_path.glob("q*.pdf"))
    r = _run("queen.npy", "--pieces", "auto", "--sheet", "20x20", "--face-size", "8.6", "-o", "q.pdf", cwd=tmp_path)
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert r.stderr.strip().splitlines() == ["voxfab: error: --sheet: 20x20 leaves no room inside a 10 mm margin"]


def test_printed_figures_agree_with_the_json_on_the_pawn(tmp_path):
    import re

    np.save(tmp_path / "pawn.npy", _recipe_grid("chess/pawn"))
    r = _run("pawn.npy", "--pieces", "auto", "--sheet", "A4", "--face-size", "8.6", "-o", "p.pdf", "-o", "p.svg",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    net = json.loads(r.stdout)["nets"][0]
    for name in ("p.pdf", "p.svg"):
        lines = [x.removeprefix(f"voxfab: {name}: ") for x in r.stderr.splitlines() if x.startswith(f"voxfab: {name}: ")]
        head = next(x for x in lines if x.startswith("faces "))
        m = re.match(r"faces ([\d.]+) mm, (\d+) sheets? of .* mm, filled (.*)$", head)
        assert float(m.group(1)) == net["face_size"]
        assert int(m.group(2)) == len(net["fill"])
        assert [int(f.rstrip(" %")) for f in m.group(3).split(", ")] == [round(100 * f) for f in net["fill"]]
        split = next(x for x in lines if x.startswith("net split into "))
        assert split.startswith(f"net split into {net['pieces']} pieces on {len(net['fill'])} sheets")
        untabbed = [int(x.split()[0]) for x in lines if " without room for a tab" in x]
        assert (untabbed or [0]) == [net["seams_without_tab_room"]]


#: What ``voxfab net`` never runs on a small shape: the pictures, the plates, the census, the other makers,
#: the net editor and hunter, the exact search and the pieces, the repository's database (the shape is a
#: file), recipes, the readers of other formats (and the .npz archive code), the heavy libraries of other
#: commands (and numba: a small surface runs the plain-Python kernels), nor what numpy loads on first use
#: of a part the search does without: numpy.ma (np.unique), numpy.random (a board's seed is hashed as
#: SeedSequence hashes it); nor hashlib (a shape's key).
NOT_RUN_BY_NET = ("voxfab.render", "voxfab.fabricate.plates", "voxfab.census", "voxfab.digitize",
                  "voxfab.studio", "voxfab.batch", "voxfab.generate", "voxfab.unfold._edit", "voxfab.unfold._hunt",
                  "voxfab.unfold._many", "voxfab.unfold._exact", "voxfab.unfold._cpsat", "voxfab.unfold._pieces",
                  "voxfab.unfold._patches", "voxfab.repo._repository", "voxfab.recipe", "sqlite3", "tomllib", "dask",
                  "distributed", "ortools", "build123d", "OCP", "numba", "trimesh", "matplotlib", "PIL", "scipy",
                  "ezdxf", "tqdm", "importlib.metadata", "numpy.ma", "numpy.random", "hashlib", "voxfab.io.mesh",
                  "voxfab.io.vox", "voxfab.io.png", "voxfab.io.text", "voxfab.io.binvox", "zipfile")
#: What a JSON net on a small shape never runs besides: the sheets, the search for a face size, the drawing
#: and its geometry (shapely).
NOT_RUN_BY_JSON_NET = ("voxfab.drawing._model", "voxfab.drawing._font", "voxfab.drawing._legend",
                       "voxfab.fabricate.netdraw._sheets", "voxfab.fabricate.netdraw._fit",
                       "voxfab.fabricate.netdraw._drawing", "voxfab.unfold._boxfit", "shapely")


def _modules_loaded(tmp_path, argv: list[str], names: tuple[str, ...]) -> tuple[int, list[str]]:
    """The exit status of ``voxfab`` run on ``argv`` in a fresh interpreter, and the modules of ``names``
    (each a module or a package) it loaded."""
    code = ("import sys\nfrom voxfab.cli import main\n"
            f"status = main({argv!r})\n"
            f"print(status, sorted(m for m in sys.modules if any(m == n or m.startswith(n + '.') for n in {names!r})))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    status, loaded = r.stdout.splitlines()[-1].split(" ", 1)
    return int(status), ast.literal_eval(loaded)


def test_net_on_a_cube_imports_only_what_it_runs(tmp_path):
    np.save(tmp_path / "cube.npy", np.ones((1, 1, 1), dtype=bool))
    assert _modules_loaded(tmp_path, ["net", "cube.npy", "-o", "cube.json", "-o", "cube.svg"],
                           NOT_RUN_BY_NET) == (0, [])
    assert Net.from_json((tmp_path / "cube.json").read_text()).face_count == 6
    assert _modules_loaded(tmp_path, ["net", "cube.npy", "-o", "cube.json"],
                           NOT_RUN_BY_NET + NOT_RUN_BY_JSON_NET) == (0, [])


def test_a_hopeless_sheet_for_pieces_is_refused_before_any_search_with_or_without_a_face_size(tmp_path):
    np.save(tmp_path / "queen.npy", _recipe_grid("chess/queen"))
    # The kernels of the net search: loaded (compiled, or their plain-Python copy) only when a search runs.
    search = ("numba", "voxfab.unfold._board", "voxfab.unfold._growth", "voxfab.unfold._tabroom",
              "voxfab.unfold._pure")
    lines = {}
    for size in ((), ("--face-size", "8.6")):
        argv = ["net", "queen.npy", "--pieces", "auto", "--sheet", "60x60", *size, "-o", "q.pdf"]
        code = (f"import sys\nfrom voxfab.cli import main\nstatus = main({argv!r})\n"
                f"print(status, sorted(m for m in sys.modules if m.startswith({search!r})))\n")
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=300)
        assert r.returncode == 0, r.stderr
        assert r.stdout.splitlines()[-1] == "6 []", size
        lines[size] = r.stderr.strip().splitlines()
        assert len(lines[size]) == 1 and lines[size][0].startswith("voxfab: error: sheet 60x60 is too small")
    # Without a face size, pieces take the smallest with legible marks (8.6 mm): the same refusal.
    assert lines[()] == lines[("--face-size", "8.6")]
    assert not list(tmp_path.glob("q*.pdf"))


def test_a_builds_shape_file_is_titled_by_its_recipe_and_a_refusal_gives_flags_that_work(tmp_path):
    """The queen at its recipe's scale (3.4 mm voxels) has faces too small for the marks: the refusal names
    each way out with the flags that take it, and the first way taken makes a net titled queen, not shape."""
    import re
    from pathlib import Path

    recipe = Path(__file__).parents[2] / "recipes" / "chess" / "queen.toml"
    r = subprocess.run([sys.executable, "-m", "voxfab", "build", str(recipe), "-o", "out"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    r = _run("out/queen/shape.npz", "-o", "q.svg", cwd=tmp_path)
    assert r.returncode != 0 and r.stderr.count("\n") == 1 and "Traceback" not in r.stderr
    assert "faces of 3.4 mm are too small" in r.stderr and "what works:" in r.stderr
    flags = re.findall(r"\((--[^)]*)\)", r.stderr.split("what works:")[1])
    assert flags and flags[0] == "--face-size 8.6 --pieces auto", r.stderr
    r = _run("out/queen/shape.npz", "-o", "q.svg", *flags[0].split(), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    sheets = sorted(tmp_path.glob("q*.svg"))  # one file a sheet
    assert sheets
    for sheet in sheets:
        svg = sheet.read_text(encoding="utf-8")
        assert "<title>queen " in svg and "<title>shape " not in svg, sheet.name
