"""Tests of one batch task, the outputs file and the selection, without a cluster."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
from _batch_fixtures import OUTPUTS, column, edge_contact, make_repo, write_outputs

from voxfab import io
from voxfab.batch import (
    BatchTask,
    build_task,
    load_outputs,
    parse_name_range,
    select_names,
    shape_file_recipe,
)
from voxfab.cli import main
from voxfab.errors import RecipeError, RepositoryError
from voxfab.recipe import SHAPE_FILES
from voxfab.repo import Repository, encode_bits


def _task(name: str, grid: np.ndarray, outdir: Path, outputs: str = OUTPUTS, thumbnails: bool = False) -> BatchTask:
    return BatchTask(name, encode_bits(grid), grid.shape, str(outdir), outputs, thumbnails)


def _digest(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def test_task_folder_equals_voxfab_build_of_the_same_recipe(tmp_path: Path) -> None:
    grid = column(3, 9)
    outcome = build_task(_task("00027.001", grid, tmp_path / "batch"))
    assert outcome.status == "built" and outcome.worker == "local" and outcome.files == 2 + len(SHAPE_FILES)
    assert outcome.error is None and outcome.seconds > 0

    # The same recipe written by hand and built by the command line in another folder.
    hand = tmp_path / "hand"
    hand.mkdir()
    io.write(grid, hand / "00027.001.npy")
    (hand / "00027.001.toml").write_text(OUTPUTS + '\n[source]\nfile = "00027.001.npy"\n')
    assert main(["build", str(hand / "00027.001.toml"), "-o", str(tmp_path / "built")]) == 0
    assert _digest(tmp_path / "batch" / "00027.001") == _digest(tmp_path / "built" / "00027.001")
    manifest = json.loads((tmp_path / "batch" / "00027.001" / "manifest.json").read_text())
    assert manifest["shape"]["volume"] == 27 and manifest["pitch_mm"] == 2.0 and manifest["seed"] == 4
    # The STL is the shape at 2 mm per voxel: 2 x 1 x 25 voxels.
    import trimesh

    mesh = trimesh.load(tmp_path / "batch" / "00027.001" / "mesh.stl")
    assert np.allclose(mesh.extents, [4.0, 2.0, 50.0])
    assert np.isclose(mesh.volume, 27 * 8.0)


def test_failing_shape_is_an_outcome_and_leaves_no_folder(tmp_path: Path) -> None:
    outcome = build_task(_task("00028.001", edge_contact(), tmp_path))
    assert outcome.status == "failed" and "edge-only" in (outcome.error or "")
    assert not (tmp_path / "00028.001").exists()
    assert outcome.to_json()["status"] == "failed" and "files" not in outcome.to_json()


def test_thumbnails_are_drawn(tmp_path: Path) -> None:
    from PIL import Image

    outcome = build_task(_task("00026.001", column(4), tmp_path, thumbnails=True))
    assert outcome.status == "built", outcome.error
    for suffix in ("", "-net"):
        with Image.open(tmp_path / "thumbs" / f"00026.001{suffix}.png") as im:
            assert im.size == (160, 160)
            assert len(np.unique(np.asarray(im.convert("RGB")).reshape(-1, 3), axis=0)) > 3  # not blank


def test_shape_file_recipe_keeps_the_lines_of_the_outputs() -> None:
    text = shape_file_recipe("seed = 1\n[outputs.mesh]", "00025.001")
    assert text.splitlines()[:2] == ["seed = 1", "[outputs.mesh]"]
    assert text.endswith('[source]\nfile = "00025.001.npy"\n')


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[outputs.mesh]\nformat = 3\n", r"outputs.toml:2: outputs.mesh.format: expected"),
        ('[outputs.nope]\n', "unknown output 'nope'"),
        ('name = "x"\n[outputs.mesh]\n', "name: unknown key; an outputs file accepts"),
        ('[source]\nmaker = "focal"\n', "source: unknown key"),
        ("pitch = 2.0\n", "no [outputs.*] table"),
        ("[outputs.mesh\n", "invalid TOML"),
        ("pitch = -1\n[outputs.mesh]\n", "pitch: expected a positive number"),
    ],
)
def test_outputs_file_errors(tmp_path: Path, text: str, message: str) -> None:
    path = write_outputs(tmp_path / "outputs.toml", text)
    with pytest.raises(RecipeError, match=message.replace("[", r"\[").replace("*", r"\*")
                       if "outputs.toml" not in message else message):
        load_outputs(path)


def test_outputs_file_is_read(tmp_path: Path) -> None:
    assert load_outputs(write_outputs(tmp_path / "o.toml")) == OUTPUTS
    with pytest.raises(RecipeError, match="no such file"):
        load_outputs(tmp_path / "missing.toml")


def test_selection_by_name_range_and_limit(tmp_path: Path) -> None:
    names = make_repo(tmp_path / "r.sqlite")
    with Repository(tmp_path / "r.sqlite") as repo:
        repo.add(column()[:, :, :10], draft=True)  # too short to be well formed; drafts are never selected
        assert select_names(repo) == names
        assert select_names(repo, limit=2) == names[:2]
        assert select_names(repo, names="00026.002:00028.001") == names[2:]
        assert select_names(repo, names="00026.001:00026.002") == names[1:3]
        assert select_names(repo, names=":00026.001") == names[:2]
        assert select_names(repo, names="00026.003:") == names[3:]
        assert select_names(repo, names="00026.002") == [names[2]]
        assert select_names(repo, names="00026.001:00099.999", limit=2) == names[1:3]
        assert select_names(repo, names="00030.001:00040.001") == []
        with pytest.raises(RepositoryError, match="empty"):
            select_names(repo, names="00026.003:00026.001")
        with pytest.raises(RepositoryError, match="not a shape name"):
            select_names(repo, names="26:27")
        with pytest.raises(RepositoryError, match="--limit"):
            select_names(repo, limit=0)
    assert parse_name_range("00001.002:00003.004") == ((1, 2), (3, 4))


@pytest.mark.parametrize(("outputs", "drawn"), [
    ('[outputs.net]\nformats = []\nsheet = "900x600"\n', ["net.json"]),
    ("[outputs.hunt]\nzipper_timeout = 2\n", ["hunt-zipper.json", "hunt-net.json"]),
])
def test_the_net_thumbnail_is_the_net_the_build_wrote(tmp_path: Path, outputs: str, drawn: list[str]) -> None:
    """The thumbnail draws the net the outputs made, handed over by the build (the net output's, else the
    hunt's zipper net, else its one-piece net), not one of its own."""
    from PIL import Image

    from voxfab.recipe import load_recipe, make_shape
    from voxfab.render import make_net, net_picture
    from voxfab.unfold import Net

    grid = make_shape(load_recipe(Path(__file__).parents[2] / "recipes" / "chess" / "pawn.toml")).grid
    outcome = build_task(_task("00555.001", grid, tmp_path, f"pitch = 8.6\nseed = 4\n{outputs}", thumbnails=True))
    assert outcome.status == "built", outcome.error
    written = next(tmp_path / "00555.001" / f for f in drawn if (tmp_path / "00555.001" / f).is_file())
    net = Net.from_json(written.read_text())

    def pixels(of: Net) -> np.ndarray:
        return np.asarray(net_picture(of, grid, size=160, legend=False, numbers=False).convert("RGB"))

    with Image.open(tmp_path / "thumbs" / "00555.001-net.png") as im:
        thumbnail = np.asarray(im.convert("RGB"))
    assert np.array_equal(thumbnail, pixels(net))
    assert not np.array_equal(thumbnail, pixels(make_net(grid, rng=4)))
