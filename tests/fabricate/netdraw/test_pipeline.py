"""One net pipeline: `voxfab net`, a recipe's net output and the library give the same files."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from voxfab.errors import InvalidShapeError, UnknownFormatError
from voxfab.fabricate.netdraw import DrawingOptions, NetOptions, check_request, net_files, parse_box
from voxfab.shape import examples
from voxfab.unfold import Net, validate

SHAPE = examples.ball(2)
SEED = 3


def _cli(tmp_path: Path) -> dict[str, bytes]:
    out = tmp_path / "cli"
    out.mkdir()
    np.save(out / "ball.npy", SHAPE)
    r = subprocess.run([sys.executable, "-m", "voxfab", "net", "ball.npy", "--seed", str(SEED), "--face-size", "12",
                        "--sheet", "A3", "-o", "net.json", "-o", "net.svg", "-o", "net.dxf"],
                       capture_output=True, text=True, cwd=out, timeout=300)
    assert r.returncode == 0, r.stderr
    return {name: (out / name).read_bytes() for name in ("net.json", "net.svg", "net.dxf")}


def _recipe(tmp_path: Path) -> dict[str, bytes]:
    from voxfab.recipe import build, load_recipe

    src = tmp_path / "recipe"
    src.mkdir()
    np.save(src / "ball.npy", SHAPE)
    (src / "ball.toml").write_text(f'name = "ball"\nseed = {SEED}\n[source]\nfile = "ball.npy"\n[outputs.net]\n'
                                   'formats = ["svg", "dxf"]\nsheet = "A3"\nface_size = 12.0\n')
    folder = build(load_recipe(src / "ball.toml"), tmp_path / "recipe-out")
    return {name: (folder / name).read_bytes() for name in ("net.json", "net.svg", "net.dxf")}


def _library(tmp_path: Path) -> dict[str, bytes]:
    out = tmp_path / "lib"
    out.mkdir()
    paths = [out / n for n in ("net.json", "net.svg", "net.dxf")]
    made = net_files(SHAPE, NetOptions(face_size=12.0), DrawingOptions(pitch=12.0, sheet="A3"), paths,
                     title="ball", seed=SEED)
    assert made.written == [str(p) for p in paths] and made.nets[0]["seed"] == SEED
    return {p.name: p.read_bytes() for p in paths}


def test_cli_recipe_and_library_write_identical_net_files(tmp_path: Path) -> None:
    cli, recipe, library = _cli(tmp_path), _recipe(tmp_path), _library(tmp_path)
    for name in ("net.json", "net.svg", "net.dxf"):
        assert cli[name] == recipe[name] == library[name], name
    net = Net.from_json(cli["net.json"].decode())
    assert net.seed == SEED and validate(SHAPE, net).ok
    assert b"ball  FACES 12 MM  SEED 3" in cli["net.svg"]


def test_net_files_numbers_several_nets_and_refuses_bad_requests(tmp_path: Path) -> None:
    made = net_files(SHAPE, NetOptions(count=2, timeout=10), DrawingOptions(), [tmp_path / "n.json"], title="b",
                     seed=1)
    assert made.written == [str(tmp_path / "n-1.json"), str(tmp_path / "n-2.json")]
    nets = [Net.from_json((tmp_path / f"n-{i}.json").read_text()) for i in (1, 2)]
    assert nets[0].corners2d.tobytes() != nets[1].corners2d.tobytes() and all(validate(SHAPE, n).ok for n in nets)
    with pytest.raises(InvalidShapeError, match="--zipper"):
        check_request(NetOptions(zipper=True), [tmp_path / "n.svg"], box=False)
    with pytest.raises(InvalidShapeError, match="--count"):
        check_request(NetOptions(count=2, pieces="auto"), [tmp_path / "n.json"], box=False)
    with pytest.raises(InvalidShapeError, match="--fit"):
        check_request(NetOptions(), [tmp_path / "n.svg"], box=True)
    with pytest.raises(UnknownFormatError, match="n.txt"):
        check_request(NetOptions(), [tmp_path / "n.txt"], box=False)
    assert parse_box("60x40", 2.0) == (30, 20) and parse_box("7x5", None) == (7, 5) and parse_box(None, 1) is None
    with pytest.raises(InvalidShapeError, match="whole voxels"):
        parse_box("7.5x5", None)
