import io

import numpy as np
import pytest
from PIL import Image

from voxfab.errors import InvalidShapeError
from voxfab.render import View, camera_for, fit_frame, orbit_camera, rasterize, render, render_raster
from voxfab.shape import VoxelShape, crop, examples

AXIS_VIEWS = ["x", "-x", "y", "-y", "z", "-z"]


def expected_projection(grid, view):
    """The shape's projection as a picture (rows top to bottom), from grid.any(axis=...)."""
    axis = {"x": 0, "y": 1, "z": 2}[view.lstrip("-")]
    p = grid.any(axis=axis).T  # rows: the later axis, columns: the earlier one
    # Picture rows run downwards; the right-hand screen directions of each view decide the flips.
    flips = {"z": (True, False), "-z": (False, False), "x": (True, False), "-x": (True, True),
             "y": (True, True), "-y": (True, False)}[view]
    if flips[0]:
        p = p[::-1, :]
    if flips[1]:
        p = p[:, ::-1]
    return p


def bbox_crop(mask):
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    return mask[rows[0] : rows[-1] + 1, cols[0] : cols[-1] + 1]


def coverage_of(image, background=(255, 255, 255)):
    a = np.asarray(image)
    return (a != np.array(background, dtype=np.uint8)).any(axis=2)


@pytest.mark.parametrize("view", ["iso", *AXIS_VIEWS])
def test_pictures_have_the_requested_size_and_are_not_blank(view):
    img = render(examples.torus(6, 2), view=view, size=123)
    assert img.size == (123, 123) and img.mode == "RGB"
    cov = coverage_of(img)
    assert 0.05 < cov.mean() < 0.95
    assert len(np.unique(np.asarray(img).reshape(-1, 3), axis=0)) > 3  # shading and edges, not a flat blob


@pytest.mark.parametrize("view", AXIS_VIEWS)
@pytest.mark.parametrize(("seed", "antialias"), [(3, 1), (11, 1), (3, 3), (11, None)])
def test_axis_view_silhouette_matches_the_projection_pixel_for_pixel(view, seed, antialias):
    g = examples.random_shape(seed)
    s = 6
    img = render(g, view=view, size=200, scale=s, antialias=antialias)
    expected = np.kron(crop(expected_projection(g, view)[None])[0], np.ones((s, s), dtype=bool))
    got = bbox_crop(coverage_of(img))
    assert got.shape == expected.shape
    assert np.array_equal(got, expected)


@pytest.mark.parametrize("view", AXIS_VIEWS)
def test_fitted_axis_views_use_whole_pixels_per_voxel(view):
    g = examples.vase()
    r = render_raster(g, view=view, size=300)
    s = r.frame.scale
    assert s == int(s) and s >= 1
    expected = np.kron(crop(expected_projection(g, view)[None])[0], np.ones((int(s), int(s)), dtype=bool))
    assert np.array_equal(bbox_crop(r.coverage), expected)
    # The image's non-background pixels are exactly the coverage (edges included, never background).
    img = render(g, view=view, size=300, background="black")
    assert np.array_equal(coverage_of(img, (0, 0, 0)), r.coverage)


def test_z_buffer_keeps_the_nearest_voxel():
    # Two voxels on one line of sight of the isometric camera: only the near one may show.
    cam = camera_for("iso")
    near = np.zeros((5, 5, 5), dtype=bool)
    near[3, 0, 3] = True
    both = near.copy()
    both[0, 3, 0] = True  # offset (-3, 3, -3) = away from the viewer at (1, -1, 1)
    frame = fit_frame((0, 0, 0), (5, 5, 5), cam, width=160, height=160)
    r_near = rasterize(near, cam, frame)
    r_both = rasterize(both, cam, frame)
    assert np.array_equal(r_near.coverage, r_both.coverage)
    assert np.array_equal(r_near.shade, r_both.shade)
    # Seen from the other side the far voxel is the visible one.
    back = orbit_camera(135.0, -35.26)
    far = np.zeros_like(near)
    far[0, 3, 0] = True
    fb = fit_frame((0, 0, 0), (5, 5, 5), back, width=160, height=160)
    assert np.array_equal(rasterize(both, back, fb).shade, rasterize(far, back, fb).shade)


def test_iso_view_shows_three_face_tones_with_dark_edges():
    r = render_raster(np.ones((3, 3, 3), dtype=bool), view="iso", size=240)
    # The top face is brighter than the two side faces; edges are darker than any face.
    inner = r.coverage & ~r.edge
    assert r.edge.any() and inner.any()
    assert r.shade[r.edge].max() < r.shade[inner].min()
    cy, cx = np.argwhere(inner).mean(axis=0)
    top = r.shade[: int(cy) - 20][inner[: int(cy) - 20]]
    bottom = r.shade[int(cy) + 20 :][inner[int(cy) + 20 :]]
    assert top.mean() > bottom.mean()


def test_small_pictures_are_antialiased_not_darkened():
    from voxfab.render import supersampling

    g = examples.random_shape(6)
    assert supersampling(g, size=100) > 1 and supersampling(g, size=800) == 1
    soft = np.asarray(render(g, size=100)).astype(float)
    hard = np.asarray(render(g, size=100, antialias=1)).astype(float)
    cov = coverage_of(hard) & coverage_of(soft)
    assert soft[cov].mean() > hard[cov].mean() + 10  # thin edges instead of every other pixel dark


def test_pictures_do_not_depend_on_where_the_shape_sits():
    g = examples.torus(5, 2)
    moved = np.zeros((40, 40, 40), dtype=bool)
    moved[7 : 7 + g.shape[0], 13 : 13 + g.shape[1], 2 : 2 + g.shape[2]] = g
    assert np.array_equal(np.asarray(render(g, size=90)), np.asarray(render(moved, size=90)))


def test_renders_are_deterministic():
    g = examples.random_shape(5)
    buf = []
    for _ in range(2):
        b = io.BytesIO()
        render(g, size=200).save(b, format="PNG")
        buf.append(b.getvalue())
    assert buf[0] == buf[1]
    from voxfab.render import png_bytes

    assert png_bytes(render(g, size=200)) == png_bytes(render(g, size=200))


def test_background_and_color_options():
    img = render(VoxelShape(examples.ball(3)), size=64, background="#102030", color=(200, 0, 0), antialias=1)
    a = np.asarray(img)
    assert tuple(a[0, 0]) == (16, 32, 48)
    cov = coverage_of(img, (16, 32, 48))
    assert (a[cov][:, 1] == 0).all() and (a[cov][:, 0] > 0).any()


def test_bad_input_names_the_parameter():
    g = examples.ball(2)
    with pytest.raises(InvalidShapeError, match="view"):
        render(g, view="top")
    with pytest.raises(InvalidShapeError, match="size"):
        render(g, size=3)
    with pytest.raises(InvalidShapeError, match="antialias"):
        render(g, antialias=0)
    with pytest.raises(InvalidShapeError, match="background"):
        render(g, background="not-a-colour")
    with pytest.raises(InvalidShapeError, match="empty"):
        render(np.zeros((3, 3, 3), dtype=bool))
    assert {v.value for v in View} == {"iso", "profile", *AXIS_VIEWS}
    with pytest.raises(InvalidShapeError, match="profile"):
        camera_for("profile")


def test_png_round_trips_through_pillow(tmp_path):
    from voxfab.render import save_render

    save_render(examples.box(2, 3, 4), tmp_path / "b.png", view="-y", size=90)
    with Image.open(tmp_path / "b.png") as im:
        assert im.size == (90, 90) and im.format == "PNG"
