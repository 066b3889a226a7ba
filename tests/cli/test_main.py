import json
import re
import subprocess
import sys

import numpy as np
import pytest

from voxfab.cli import main
from voxfab.shape import examples


def voxfab(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "voxfab", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def test_version_through_the_real_entry_point():
    r = voxfab("--version")
    assert r.returncode == 0
    assert r.stdout.startswith("voxfab ")


def test_version_loads_no_command_nor_numpy():
    # The version is a constant: neither the shapes (numpy) nor any command's module, nor the
    # installed distribution's metadata.
    code = ("import sys\nfrom voxfab.cli import main\ntry:\n    main(['--version'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('numpy', 'importlib_metadata')\n"
            "             or m.startswith(('voxfab.cli.', 'voxfab.shape', 'importlib.metadata'))))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    loaded = r.stdout.splitlines()[-1]
    assert loaded == str(["voxfab.cli._common", "voxfab.cli._main", "voxfab.cli._reference"])


def test_info_json_is_one_object_with_the_required_keys(tmp_path):
    g = examples.random_shape(2)
    np.save(tmp_path / "s.npy", g)
    r = voxfab("info", tmp_path / "s.npy", "--json")
    assert r.returncode == 0, r.stderr
    info = json.loads(r.stdout)
    assert {"volume", "extents", "components", "well_formed", "reasons", "surface_faces"} <= set(info)
    assert info["volume"] == int(g.sum())
    assert info["well_formed"] is True and info["reasons"] == []
    assert info["components"] == 1


def test_info_reports_reasons_for_a_bad_shape(tmp_path, capsys):
    g = np.zeros((25, 25, 25), bool)
    g[0, 0, :3] = g[5, 5, :] = True
    np.save(tmp_path / "s.npy", g)
    assert main(["info", str(tmp_path / "s.npy"), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["well_formed"] is False
    assert info["components"] == 2
    assert any("pieces" in r for r in info["reasons"])


@pytest.mark.parametrize(
    ("setup", "code"),
    [
        (lambda p: p.write_bytes(b"\x93NUMPY garbage"), 5),  # corrupt
        (lambda p: np.save(p, np.zeros((3, 3, 3), bool)), 3),  # empty grid
        (lambda p: np.save(p, np.ones((300, 2, 2), bool)), 3),  # oversize
        (lambda p: np.save(p, np.full((2, 2, 2), 7, np.int16)), 3),  # wrong values
        (lambda p: np.save(p, np.zeros((2, 2), bool)), 3),  # wrong dimension
    ],
)
def test_bad_input_gives_one_line_and_nonzero_exit(tmp_path, setup, code):
    p = tmp_path / "bad.npy"
    setup(p)
    r = voxfab("info", p)
    assert r.returncode == code
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("voxfab: error: ")
    assert "Traceback" not in r.stderr


def test_unknown_extension_and_debug_traceback(tmp_path):
    p = tmp_path / "shape.xyz"
    p.write_text("hello")
    r = voxfab("info", p)
    assert r.returncode == 4 and "unknown extension '.xyz'" in r.stderr
    r = voxfab("--debug", "info", p)
    assert "Traceback" in r.stderr


def test_build_cli_writes_the_folder(tmp_path):
    np.save(tmp_path / "s.npy", examples.random_shape(5))
    (tmp_path / "r.toml").write_text('name = "demo"\n[source]\nfile = "s.npy"\n')
    r = voxfab("build", tmp_path / "r.toml", "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "out" / "demo" / "manifest.json").exists()
    assert "print:" not in r.stdout  # no mesh asked
    (tmp_path / "m.toml").write_text('name = "m"\npitch = 2.0\n[source]\nfile = "s.npy"\n[outputs.mesh]\ninfill = 15\n')
    r = voxfab("build", tmp_path / "m.toml", "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    report = json.loads((tmp_path / "out" / "m" / "mesh.json").read_text())
    assert f"{report['mass_g']:.1f} g of PLA at 15 % infill, about {report['print_time']}" in r.stdout
    (tmp_path / "bad.toml").write_text('[source]\nfile = "s.npy"\nshade = 2\n')
    r = voxfab("build", tmp_path / "bad.toml", "-o", tmp_path / "out")
    assert r.returncode == 7
    assert "bad.toml:3: source.shade: unknown key" in r.stderr


@pytest.mark.parametrize(
    ("args", "pattern"),
    [
        (["net", "s.npy", "-o", "n.svg", "--count", "abc"], r"^voxfab: error: net: argument --count: .*'abc'"),
        (["frob"], r"^voxfab: error: argument COMMAND: invalid choice: 'frob'"),
        (["repo"], r"^voxfab: error: repo: the following arguments are required: ACTION"),
        (["info"], r"^voxfab: error: info: the following arguments are required: SHAPE"),
    ],
)
def test_usage_errors_are_one_line(args, pattern):
    # argparse's refusals read like every other error: one line, exit 2, the help named.
    r = voxfab(*args)
    assert r.returncode == 2
    assert len(r.stderr.splitlines()) == 1 and "usage:" not in r.stderr
    assert re.match(pattern, r.stderr) and r.stderr.rstrip().endswith("--help)")


def test_build_open_curves_of_revolution_join_into_the_closed_one(tmp_path):
    # two recipes with the two halves of the circle, same scale and center: their shapes join into the whole
    import shutil
    from pathlib import Path

    shutil.copy(Path(__file__).resolve().parents[2] / "recipes" / "vase_generatrix.png", tmp_path)
    keys = 'generatrix = "vase_generatrix.png"\nmode = "surface"\nk = 1\nscale = 0.2\ncenter = [0, 0, 59.5]\n'
    for name, arc in (("whole", ""), ("first", "arc = [0, 180]\n"), ("second", "arc = [180, 360]\n")):
        (tmp_path / f"{name}.toml").write_text(f'name = "{name}"\n[source]\nmaker = "revolution"\n{keys}{arc}')
    r = voxfab("build", *(tmp_path / f"{n}.toml" for n in ("whole", "first", "second")), "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    whole, first, second = (np.load(tmp_path / "out" / n / "shape.npy") for n in ("whole", "first", "second"))
    assert whole.sum() > 1000 and np.array_equal(first | second, whole) and not np.array_equal(first, whole)
    (tmp_path / "bad.toml").write_text(f'name = "bad"\n[source]\nmaker = "revolution"\n{keys}arc = [180, 90]\n')
    r = voxfab("build", tmp_path / "bad.toml", "-o", tmp_path / "out")
    assert r.returncode != 0 and r.stderr.startswith("voxfab: error: arc:") and r.stderr.count("\n") == 1
    assert not (tmp_path / "out" / "bad").exists()


def test_the_program_leaves_its_objects_to_the_exit_and_a_call_leaves_the_collector_as_it_was(tmp_path):
    """Run as the program, a command collects young objects every GC_YOUNG allocations, not every 700, and
    leaves what it made unscanned at the exit (numba's objects cost a net a third of a second to collect);
    called (tests, scripts), main puts the collector back as it found it and freezes nothing."""
    import gc

    from voxfab.cli._main import GC_YOUNG

    np.save(tmp_path / "s.npy", examples.ball(3))
    code = ("import gc, json, sys\nimport voxfab.cli.info as info\nfrom voxfab.cli import main\nseen = []\n"
            "run = info.run\ninfo.run = lambda args: seen.append(gc.get_threshold()) or run(args)\n"
            "sys.argv = ['voxfab', 'info', 's.npy', '--json']\nstatus = main()\n"
            "print(json.dumps([status, seen, gc.get_threshold(), gc.get_freeze_count() > 0]))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    status, seen, after, frozen = json.loads(r.stdout.splitlines()[-1])
    default = list(gc.get_threshold())
    assert status == 0 and seen == [[GC_YOUNG, *default[1:]]] and after == default and frozen
    frozen_before = gc.get_freeze_count()
    assert main(["info", str(tmp_path / "s.npy"), "--json"]) == 0
    assert list(gc.get_threshold()) == default and gc.get_freeze_count() == frozen_before


def test_an_interrupted_command_ends_its_process_at_once_though_a_thread_still_runs(tmp_path):
    """A thread a library leaves running when Ctrl-C stops a command (a solver's workers) must not hold the
    process at its exit, nor abort it: the process ends with 130 once its exit handlers ran."""
    np.save(tmp_path / "cube.npy", np.ones((1, 1, 1), dtype=bool))
    code = """
import atexit, sys, threading, time
import voxfab.repo
from voxfab.cli import main

threading.Thread(target=time.sleep, args=(60,)).start()  # not a daemon: the interpreter's exit waits for it
atexit.register(lambda: print("exit handlers ran", file=sys.stderr))

def interrupted(*args, **kwargs):
    raise KeyboardInterrupt

voxfab.repo.load_shape = interrupted
sys.argv = ["voxfab", "info", "cube.npy"]
sys.exit(main())
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=30)
    assert r.returncode == 130, r.stderr
    assert r.stderr.splitlines() == ["voxfab: interrupted", "exit handlers ran"]
