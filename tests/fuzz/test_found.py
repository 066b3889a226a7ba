"""Faults the fuzz tests found, kept as regressions: each was a traceback or a hang."""

from __future__ import annotations

import os

import pytest
from _fuzz import refused

from voxfab import io
from voxfab.shape import examples


@pytest.fixture
def ball(tmp_path):
    io.write(examples.ball(2), tmp_path / "ball.npy")
    return tmp_path / "ball.npy"


def test_npy_header_that_numpy_cannot_tokenize(tmp_path):
    # A header whose dict is cut inside another header: numpy raised tokenize.TokenError.
    header = b"{\x93NUMPY\x01\x00v\x00{'descr': '|b1', 'fortran_order': False, 'shape': (7, 7, 7), }"
    (tmp_path / "x.npy").write_bytes(b"\x93NUMPY\x01\x00v\x00" + header.ljust(118) + b"\n" + bytes(343))
    assert "not a valid .npy header" in refused(["info", tmp_path / "x.npy"])


def test_option_value_of_two_dashes(ball, tmp_path, capsys):
    # argparse gave [] for "--magnet=--", skipping its type check: an IndexError followed.
    with pytest.raises(SystemExit) as info:
        from voxfab.cli import main

        main(["mesh", str(ball), "-o", str(tmp_path / "m.stl"), "--magnet=--"])
    assert info.value.code == 2
    assert "argument --magnet: expected a value, got '--'" in capsys.readouterr().err


@pytest.mark.parametrize("content", [bytes(range(256)), None], ids=["binary", "fifo"])
def test_render_net_file_that_is_binary_or_a_fifo(ball, tmp_path, content):
    net = tmp_path / "n.json"
    if content is None:
        os.mkfifo(net)  # reading it blocked forever
    else:
        net.write_bytes(content)  # a UnicodeDecodeError escaped
    line = refused(["render", ball, "-o", tmp_path / "r.png", "--net", net], seconds=20)
    assert "is a FIFO" in line if content is None else "not UTF-8" in line
    assert not (tmp_path / "r.png").exists()


def test_library_log_records_do_not_reach_the_terminal(tmp_path):
    # trimesh logs a traceback when an ASCII STL's normals do not parse, then reads the mesh;
    # Python printed that record on stderr, a traceback on a run that succeeded.
    import subprocess
    import sys

    import trimesh

    text = trimesh.exchange.stl.export_stl_ascii(trimesh.creation.icosphere(subdivisions=1, radius=2.0))
    bad = text.replace("facet normal", "facet normal x y z", 1)
    (tmp_path / "normals.stl").write_text(bad)
    r = subprocess.run([sys.executable, "-m", "voxfab", "info", str(tmp_path / "normals.stl")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "Traceback" not in r.stderr and "failed to extract" not in r.stderr, r.stderr


def test_tube_whose_spine_dwarfs_its_profile(tmp_path):
    # The tube's search grid was sized from the spine's box over the profile radius:
    # numpy refused a negative or gigantic array with a ValueError.
    (tmp_path / "spine.json").write_text("[[0, 0, 0], [1e300, 0, 0], [0, 1e300, 0]]")
    r = tmp_path / "r.toml"
    r.write_text('[source]\nmaker = "tube"\nspine = "spine.json"\nprofile = "x^2 + y^2 - 1"\nsize = 8\n')
    line = refused(["build", r, "-o", tmp_path / "out"], seconds=20)
    assert "search grid would need countless cells, over the limit of 16,777,216" in line
