import numpy as np
import pytest
from PIL import Image, ImageSequence

from voxfab.errors import InvalidShapeError
from voxfab.render import animation_frames, save_animation, save_turntable, turntable_frames
from voxfab.shape import examples


def asym():
    g = np.zeros((4, 3, 2), dtype=bool)
    g[:, 0, 0] = True
    g[0, :, 0] = True
    g[0, 0, 1] = True
    return g


def test_turntable_gif_has_every_frame_at_the_requested_size(tmp_path):
    n = save_turntable(asym(), tmp_path / "t.gif", frames=12, size=96, duration_ms=50)
    assert n == 12
    with Image.open(tmp_path / "t.gif") as im:
        assert im.n_frames == 12 and im.size == (96, 96)
        assert im.info["loop"] == 0 and im.info["duration"] == 50
        frames = [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(im)]
    assert all((f != 255).any() for f in frames)  # none blank
    assert not np.array_equal(frames[0], frames[3])  # it turns


def test_turntable_is_deterministic_and_frame0_is_the_iso_view(tmp_path):
    save_turntable(asym(), tmp_path / "a.gif", frames=6, size=64)
    save_turntable(asym(), tmp_path / "b.gif", frames=6, size=64)
    assert (tmp_path / "a.gif").read_bytes() == (tmp_path / "b.gif").read_bytes()
    frames = turntable_frames(asym(), frames=4, size=64)
    assert all(f.mode == "P" and f.getpalette() == frames[0].getpalette() for f in frames)
    # A quarter turn of a 4-fold symmetric shape gives the same picture (up to rounding of one level).
    box = np.ones((3, 3, 2), dtype=bool)
    q0, q1 = (np.asarray(f).astype(int) for f in turntable_frames(box, frames=4, size=64)[:2])
    assert np.array_equal(q0 > 0, q1 > 0)
    assert np.abs(q0 - q1).max() <= 1


def test_antialiased_frames_keep_the_fixed_palette():
    plain = turntable_frames(asym(), frames=2, size=48, antialias=1)
    soft = turntable_frames(asym(), frames=2, size=48, antialias=3)
    assert soft[0].mode == "P" and soft[0].getpalette() == plain[0].getpalette()
    a, b = np.asarray(plain[0]), np.asarray(soft[0])
    assert ((a > 0) != (b > 0)).mean() < 0.05  # the same shape, softened at its outline only
    assert not np.array_equal(a, b)


def test_animation_of_a_grid_sequence(tmp_path):
    # A bar turning around z in the xy plane, as a tube helper would yield.
    grids = []
    for k in range(8):
        g = np.zeros((9, 9, 3), dtype=bool)
        t = np.linspace(-4, 4, 50)
        a = np.pi * k / 8
        g[np.rint(4 + t * np.cos(a)).astype(int), np.rint(4 + t * np.sin(a)).astype(int), 1] = True
        grids.append(g)
    frames = animation_frames(grids, view="z", size=90)
    assert len(frames) == 8 and {f.size for f in frames} == {(90, 90)}
    n = save_animation(iter(grids), tmp_path / "tube.gif", size=90, duration_ms=100)
    assert n == 8
    with Image.open(tmp_path / "tube.gif") as im:
        assert im.n_frames == 8


def test_an_empty_shape_in_a_sequence_is_a_blank_frame():
    g = np.zeros((4, 4, 4), dtype=bool)
    g[1, 1, 1] = True
    frames = animation_frames([g, np.zeros_like(g), g], size=32)
    assert [int(np.asarray(f).max() > 0) for f in frames] == [1, 0, 1]


def test_bad_animation_input():
    with pytest.raises(InvalidShapeError, match="frames"):
        turntable_frames(examples.ball(2), frames=0)
    with pytest.raises(InvalidShapeError, match="grids"):
        animation_frames([])
    with pytest.raises(InvalidShapeError, match="grids"):
        animation_frames([np.zeros((2, 2, 2), dtype=bool)])


def test_swept_tube_animation_from_the_digitize_helper(tmp_path):
    import voxfab.digitize as digitize

    if not hasattr(digitize, "tube_rotations"):
        pytest.skip("voxfab.digitize.tube_rotations not available")
    grids = list(digitize.tube_rotations(["3*cos(2*pi*t)", "3*sin(2*pi*t)", "0"], "x^2/4 + y^2 - 1",
                                         steps=4, turn=90.0, radius=1.2, size=15, samples=128))
    n = save_animation(grids, tmp_path / "tube.gif", size=96)
    assert n == 4
    with Image.open(tmp_path / "tube.gif") as im:
        assert im.n_frames == len({g.tobytes() for g in grids})  # one frame per distinct shape
        assert im.size == (96, 96)
