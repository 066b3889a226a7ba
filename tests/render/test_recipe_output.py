import numpy as np
import pytest
from PIL import Image

from voxfab._shared.options import OptionError
from voxfab.render import PictureOptions, png_bytes, render, render_pictures, view_filename
from voxfab.shape import VoxelShape, examples


def recipe_output(shape, folder, *, name, seed, **options):
    return render_pictures(shape, PictureOptions(**options), folder, name=name, seed=seed).files


def test_writes_views_slices_triptych_and_turntable(tmp_path):
    shape = VoxelShape(examples.torus(5, 2), pitch=2.0)
    files = recipe_output(shape, tmp_path, name="ring", seed=2, size=120, views=["iso", "-z"],
                          triptych=True, turntable=True, frames=4, slices=True)
    names = [f.path for f in files]
    assert names == ["render_iso.png", "render_neg_z.png", "slices.png", "triptych.png", "triptych.pdf",
                     "turntable.gif"]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(names)
    assert all(f.purpose for f in files)
    assert (tmp_path / "render_neg_z.png").read_bytes() == png_bytes(render(shape, view="-z", size=120))
    with Image.open(tmp_path / "turntable.gif") as im:
        assert im.n_frames == 4
    assert (tmp_path / "triptych.pdf").read_bytes().startswith(b"%PDF")
    # Deterministic: a second build gives the same bytes.
    again = tmp_path / "again"
    again.mkdir()
    recipe_output(shape, again, name="ring", seed=2, size=120, views=["iso", "-z"], triptych=True,
                  turntable=True, frames=4, slices=True)
    for n in names:
        assert (again / n).read_bytes() == (tmp_path / n).read_bytes(), n


def test_defaults_write_the_profile_view_and_triptych(tmp_path):
    files = recipe_output(VoxelShape(np.ones((2, 2, 2), dtype=bool)), tmp_path, name="cube", seed=0, size=100)
    assert [f.path for f in files] == ["render_profile.png", "triptych.png", "triptych.pdf"]


@pytest.mark.parametrize(("options", "text"), [({"views": ["top"]}, "top"), ({"size": 5}, "size"),
                                                ({"color": "nope"}, "color")])
def test_bad_options_are_refused(options, text):
    with pytest.raises(OptionError, match=text):
        PictureOptions(**options)


def test_view_filenames():
    assert [view_filename(v) for v in ("iso", "x", "-x", "-z", "profile")] == [
        "render_iso.png", "render_x.png", "render_neg_x.png", "render_neg_z.png", "render_profile.png"]
