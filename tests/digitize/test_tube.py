"""Swept tubes: frames, holonomy, profiles, caps, rotation sequence."""

from __future__ import annotations

import math

import numpy as np
import pytest
from PIL import Image, ImageDraw
from scipy import ndimage

from voxfab.digitize import load_spine, solid, spine_frames, tube, tube_field, tube_rotations
from voxfab.digitize._tube import _profile
from voxfab.errors import InvalidShapeError
from voxfab.shape import well_formed_reasons

S_CURVE = ["4*t", "sin(2*pi*t)", "0"]  # planar, inflection at t = 1/2
TREFOIL = ["sin(2*pi*t) + 2*sin(4*pi*t)", "cos(2*pi*t) - 2*cos(4*pi*t)", "-sin(6*pi*t)"]


def test_rmf_does_not_flip_where_frenet_flips():
    pts, closed = load_spine(S_CURVE, samples=400)
    fr = spine_frames(pts, closed, "frenet")
    rmf = spine_frames(pts, closed, "rmf")
    fdots = np.sum(fr.normal[1:] * fr.normal[:-1], axis=1)
    rdots = np.sum(rmf.normal[1:] * rmf.normal[:-1], axis=1)
    assert fdots.min() < -0.9  # the Frenet normal jumps to -N at the inflection
    assert rdots.min() > 0.999
    # planar spine: one RMF axis stays the plane's normal, with one sign throughout
    nz = rmf.normal[:, 2] if abs(rmf.normal[0, 2]) > 0.5 else rmf.binormal[:, 2]
    assert np.all(np.abs(nz) > 0.999) and len(np.unique(np.sign(nz))) == 1
    for f in (fr, rmf):
        assert np.allclose(np.sum(f.normal * f.tangent, axis=1), 0, atol=1e-9)
        assert np.allclose(np.linalg.norm(f.normal, axis=1), 1)


def test_frenet_flip_shows_in_the_tube_and_rmf_does_not():
    # a profile that is not centrally symmetric: a disk off the spine on the +N side
    profile = "(x - 0.6)^2 + y^2 - 0.16"
    kw = dict(radius=0.5, size=31, k=0, mode="solid", samples=400)
    a = tube(S_CURVE, profile, frame="rmf", **kw)
    b = tube(S_CURVE, profile, frame="frenet", **kw)
    assert ndimage.label(a, structure=ndimage.generate_binary_structure(3, 1))[1] == 1
    assert ndimage.label(b, structure=ndimage.generate_binary_structure(3, 1))[1] >= 2


def test_closed_spine_holonomy_is_corrected():
    pts, closed = load_spine(TREFOIL, samples=2000)
    assert closed and len(pts) == 2000
    sp = spine_frames(pts, closed, "rmf")
    assert abs(sp.holonomy) > 0.05  # a knotted spine has holonomy
    # after the correction the frame closes up: the last sample's normal meets the first
    assert float(sp.normal[-1] @ sp.normal[0]) > 0.999
    steps = np.sum(sp.normal[1:] * sp.normal[:-1], axis=1)
    assert steps.min() > 0.99


def test_straight_tube_equals_a_cylinder():
    g = tube(["t", "0", "0"], "x^2 + y^2 - 1", radius=0.25, t_min=-1, t_max=1, cap="flat", scale=10.0, size=25, samples=64)
    ref = solid(lambda x, y, z: np.maximum(y * y + z * z - 0.0625, np.abs(x) - 1.0), (31, 31, 31), 0,
                origin=(-1.5, -1.5, -1.5), step=0.1)
    from voxfab.shape import crop

    assert np.array_equal(crop(g), crop(ref))


def test_round_caps_reach_beyond_flat_caps():
    kw = dict(radius=0.3, t_min=-1, t_max=1, scale=8.0, size=25, samples=64)
    flat = tube(["t", "0", "0"], **kw, cap="flat")
    round_ = tube(["t", "0", "0"], **kw, cap="round")
    from voxfab.shape import extents

    assert extents(round_)[0] >= extents(flat)[0] + 4
    assert flat.sum() < round_.sum()


@pytest.fixture()
def three_disks(tmp_path):
    im = Image.new("L", (60, 60), 255)
    dr = ImageDraw.Draw(im)
    for i in range(3):
        a = math.radians(90 + 120 * i)
        cx, cy = 30 + 17 * math.cos(a), 30 - 17 * math.sin(a)
        dr.ellipse((cx - 10, cy - 10, cx + 10, cy + 10), fill=0)
    im.save(tmp_path / "three.png")
    return tmp_path


def test_profile_with_three_components(three_disks):
    g = tube(["0", "0", "t"], "three.png", base_dir=three_disks, radius=1.0, t_min=0, t_max=2, scale=10.0, size=31)
    mid = g[:, :, 15]
    assert ndimage.label(mid)[1] == 3
    # twisted along a closed circle the three strands braid
    braid = tube(["cos(2*pi*t)", "sin(2*pi*t)", "0"], "three.png", base_dir=three_disks, radius=0.45, twist=120)
    assert braid.shape == (25, 25, 25) and braid.any()


def test_twist_rotates_the_profile():
    # a square profile twisted by 45 degrees: the end sections differ by 45 degrees
    pts, closed = load_spine(["0", "0", "t"], samples=64)
    sp = spine_frames(pts, closed)
    prof = _profile("max(abs(x), abs(y)) - 1", base_dir=None, threshold=0.5, stroke=None)
    fld = tube_field(sp, prof, radius=1.0, twist=45.0)
    # the square's corners point at 45° at the start and along the axes after a 45° twist
    assert fld.f(np.array(0.67), np.array(0.67), np.array(0.001)) < 0
    assert fld.f(np.array(0.95), np.array(0.0), np.array(0.001)) > 0
    assert fld.f(np.array(0.67), np.array(0.67), np.array(0.999)) > 0
    assert fld.f(np.array(0.95), np.array(0.0), np.array(0.999)) < 0


def test_rotation_sequence():
    frames = list(tube_rotations(S_CURVE, "(x - 0.5)^2 + y^2 - 0.25", steps=4, radius=0.5, samples=200))
    assert len(frames) == 4 and all(f.shape == (25, 25, 25) for f in frames)
    assert well_formed_reasons(frames[0]) == []
    assert not np.array_equal(frames[0], frames[1])
    # half a turn of an off-centre disk on a symmetric S: frames 0 and 2 are mirror images, same volume
    assert abs(int(frames[0].sum()) - int(frames[2].sum())) < 0.1 * frames[0].sum()


def test_rotations_take_the_tube_keywords_but_phase_and_scale():
    options = {"radius": 0.4, "twist": 90.0, "cap": "round", "samples": 200, "size": 17}
    (first,) = tube_rotations(S_CURVE, "(x - 0.5)^2 + y^2 - 0.25", steps=1, **options)
    # The first frame is the tube itself, cut to the same size.
    whole = tube(S_CURVE, "(x - 0.5)^2 + y^2 - 0.25", **options)
    assert first.shape == whole.shape == (17, 17, 17) and first.sum() == whole.sum()
    for bad in ({"phase": 10.0}, {"scale": 2.0}, {"radius_mm": 1.0}):
        with pytest.raises(TypeError, match=next(iter(bad))):
            next(tube_rotations(S_CURVE, steps=2, **bad))


def test_spine_from_points_file(tmp_path):
    t = np.linspace(0, 1, 50)
    np.savetxt(tmp_path / "spine.csv", np.stack([t * 5, np.sin(t * 6), np.cos(t * 3)], axis=1), delimiter=",")
    g = tube("spine.csv", base_dir=tmp_path, radius=0.4)
    assert well_formed_reasons(g) == []


def test_bad_inputs_name_the_input():
    with pytest.raises(InvalidShapeError, match=r"^spine y\(t\): unknown name 's'"):
        tube(["t", "s", "0"])
    with pytest.raises(InvalidShapeError, match="^spine: degenerate"):
        tube(["0", "0", "0"])
    with pytest.raises(InvalidShapeError, match="^radius"):
        tube(["t", "0", "0"], radius=-1.0)
    with pytest.raises(InvalidShapeError, match="^frame: unknown choice"):
        tube(["t", "0", "0"], frame="bishop")
    with pytest.raises(InvalidShapeError, match="^profile: syntax error"):
        tube(["t", "0", "0"], "x^2 + (y")


def test_open_profile_is_a_ribbon():
    # an open segment as profile becomes a band of width `stroke`: a flat ribbon along a straight spine
    g = tube(["t", "0", "0"], [[-1, 0], [1, 0]], stroke=0.4, radius=1.0, t_min=0, t_max=3, scale=8.0, size=31)
    from voxfab.shape import extents

    ex = extents(g)
    assert ex[0] == 25 and max(ex[1], ex[2]) >= 15 and min(ex[1], ex[2]) <= 4


TUBE_RECIPES = __import__("pathlib").Path(__file__).resolve().parents[2] / "recipes" / "tubes"


@pytest.mark.parametrize("k", [0, 1, 2])
@pytest.mark.parametrize(
    ("spine", "profile", "radius", "twist", "scale", "cuts"),
    [
        # the bundled interlaced tubes: three disks swept along a circle with 480° of twist
        (["cos(2*pi*t)", "sin(2*pi*t)", "0"], "three_disks.png", 0.42, 480.0, 8.0, (0, 180, 360)),
        # a round profile along a wavy closed spine, split off its symmetry axes
        (["3*cos(2*pi*t)", "3*sin(2*pi*t)", "0.5*sin(4*pi*t)"], "x^2 + y^2 - 1", 1.0, 0.0, 2.9, (20, 250, 380)),
    ],
)
def test_union_rule_open_profiles(k, spine, profile, radius, twist, scale, cuts):
    opts = dict(k=k, mode="surface", size=25, scale=scale, center=[0.01, -0.02, 0.03], radius=radius, twist=twist,
                base_dir=TUBE_RECIPES)
    whole = tube(spine, profile, **opts)
    first = tube(spine, profile, arc=cuts[:2], **opts)
    second = tube(spine, profile, arc=cuts[1:], **opts)
    assert whole.sum() > 500
    assert np.array_equal(first | second, whole), (k, int((whole ^ (first | second)).sum()))
    for part in (first, second):
        assert 0.2 * whole.sum() < part.sum() < 0.8 * whole.sum()


def test_ribbon_is_one_half_of_a_torus():
    # a planar spine circle keeps the profile's u axis in the spine's plane (radial), so the arc
    # [90, 270] is the half of the round profile on one side of the spine: the inner or the outer
    # half of the torus, within a voxel's flake of the spine circle on the other side
    grid = tube(["3*cos(2*pi*t)", "3*sin(2*pi*t)", "0"], "x^2 + y^2 - 1", arc=[90, 270], k=0, mode="surface",
                size=25, scale=2.9, center=[0.0, 0.0, 0.0])
    idx = np.argwhere(grid)
    r = np.hypot(idx[:, 0] - 12, idx[:, 1] - 12) / 2.9
    assert grid.sum() > 300
    assert (np.all(r <= 3.0 + 0.5 / 2.9 * 1.8) or np.all(r >= 3.0 - 0.5 / 2.9 * 1.8))


def test_ribbon_needs_surface_mode():
    with pytest.raises(InvalidShapeError, match="surface"):
        tube(["3*cos(2*pi*t)", "3*sin(2*pi*t)", "0"], arc=[0, 90], mode="solid", scale=2.9, center=[0, 0, 0])


@pytest.mark.parametrize("k", [0, 1, 2])
def test_a_drawn_open_profile_is_the_arc_of_the_closed_one(tmp_path, k):
    t = np.radians(np.linspace(0.0, 300.0, 601))
    (tmp_path / "arc.json").write_text(__import__("json").dumps(
        {"polylines": [{"points": np.c_[np.cos(t), np.sin(t)].tolist(), "closed": False}]}))
    spine = ["3*cos(2*pi*t)", "3*sin(2*pi*t)", "0.5*sin(4*pi*t)"]
    opts = dict(k=k, mode="surface", size=25, scale=2.9, center=[0.01, -0.02, 0.03], base_dir=tmp_path)
    drawn = tube(spine, "arc.json", profile_open=True, **opts)
    exact = tube(spine, "x^2 + y^2 - 1", arc=[0, 300], **opts)
    assert exact.sum() > 500
    assert np.array_equal(drawn, exact), int((drawn ^ exact).sum())
    with pytest.raises(InvalidShapeError, match="profile_open.*not both"):
        tube(spine, "arc.json", profile_open=True, arc=[0, 90], **opts)
