"""The rotating-profile animation of a tube: library, recipe output ``animation`` and ``voxfab build``."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image, ImageSequence

from voxfab.cli._main import main
from voxfab.digitize import tube_rotations
from voxfab.errors import InvalidShapeError, RecipeError
from voxfab.recipe import build, load_recipe
from voxfab.render import animation_frames
from voxfab.render._animate import save_tube_animation, tube_frames

SPINE = ["cos(2*pi*t)", "sin(2*pi*t)", "0"]
TWO_DISKS = "min((x - 0.5)^2 + y^2 - 0.2, (x + 0.5)^2 + y^2 - 0.2)"


def gif_frames(path):
    with Image.open(path) as im:
        return [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(im)]


def test_tube_frames_are_the_library_rotations():
    frames = tube_frames(dict(spine=SPINE, profile=TWO_DISKS, radius=0.3, size=15), steps=4)
    ref = list(tube_rotations(SPINE, TWO_DISKS, steps=4, radius=0.3, size=15))
    assert len(frames) == 4
    assert all(np.array_equal(a, b) for a, b in zip(frames, ref))
    assert not np.array_equal(frames[0], frames[1])  # the profile turns


def test_tube_frames_refuse_phase_and_bad_steps():
    with pytest.raises(InvalidShapeError, match="phase"):
        tube_frames(dict(spine=SPINE, phase=10.0), steps=4)
    with pytest.raises(InvalidShapeError, match="frames"):
        tube_frames(dict(spine=SPINE), steps=0)
    with pytest.raises(InvalidShapeError, match="spine"):
        tube_frames({}, steps=3)


def test_save_tube_animation_writes_the_frames(tmp_path):
    n = save_tube_animation(tmp_path / "a.gif", dict(spine=SPINE, profile=TWO_DISKS, radius=0.3, size=21), steps=5,
                            size=64)
    assert n == 5
    pics = gif_frames(tmp_path / "a.gif")
    assert len(pics) == 5 and pics[0].shape == (64, 64, 3)
    assert not np.array_equal(pics[0], pics[2])
    # the GIF shows exactly the library's frames
    want = animation_frames(tube_frames(dict(spine=SPINE, profile=TWO_DISKS, radius=0.3, size=21), steps=5), size=64)
    assert np.array_equal(pics[1], np.asarray(want[1].convert("RGB")))


RECIPE = """
name = "braid"
[source]
maker = "tube"
spine = ["cos(2*pi*t)", "sin(2*pi*t)", "0"]
profile = "{profile}"
radius = 0.3
twist = 120.0
size = 21
[outputs.animation]
steps = 6
size = 80
"""


def test_recipe_output_animation_and_cli(tmp_path, capsys):
    path = tmp_path / "braid.toml"
    path.write_text(RECIPE.format(profile=TWO_DISKS))
    out = build(load_recipe(path), tmp_path / "out")
    pics = gif_frames(out / "animation.gif")
    assert len(pics) == 6 and pics[0].shape == (80, 80, 3)
    ref = tube_frames(dict(spine=SPINE, profile=TWO_DISKS, radius=0.3, twist=120.0, size=21), steps=6)
    want = animation_frames(ref, size=80)
    assert np.array_equal(pics[3], np.asarray(want[3].convert("RGB")))
    assert "animation.gif" in (out / "manifest.json").read_text()
    # the same from the command line
    assert main(["build", str(path), "-o", str(tmp_path / "cli")]) == 0
    assert (tmp_path / "cli" / "braid" / "animation.gif").read_bytes() == (out / "animation.gif").read_bytes()


def test_recipe_animation_errors(tmp_path):
    path = tmp_path / "r.toml"
    path.write_text(RECIPE.format(profile=TWO_DISKS) + "source = 1\n")
    with pytest.raises(RecipeError, match="outputs.animation.source: unknown key"):
        load_recipe(path)
    path.write_text('name = "egg"\n[source]\nmaker = "focal"\nfoci = [[0.0, 0.0, 0.0]]\nradius = 1.0\n'
                    "[outputs.animation]\n")
    with pytest.raises(RecipeError, match="needs a tube source"):
        build(load_recipe(path), tmp_path / "out")
