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
