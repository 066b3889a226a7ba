import json

import numpy as np
import pytest
from _handnets import tree_net
from PIL import Image

from voxfab.errors import InvalidShapeError, UnknownFormatError
from voxfab.render import (
    Picture,
    PictureKind,
    PictureOptions,
    net_picture,
    pictures_asked,
    png_bytes,
    render_pictures,
    slice_sheet,
)
from voxfab.shape import VoxelShape

BAR = VoxelShape(np.ones((2, 1, 1), dtype=bool))


def test_pictures_asked_follow_the_options_in_writing_order():
    asked = pictures_asked(PictureOptions(views=("z", "iso", "z"), slices=True, net_picture=True, turntable=True))
    assert [(p.kind, p.path) for p in asked] == [
        (PictureKind.VIEW, "render_z.png"), (PictureKind.VIEW, "render_iso.png"),
        (PictureKind.SLICES, "slices.png"), (PictureKind.TRIPTYCH, "triptych.png"),
        (PictureKind.TRIPTYCH, "triptych.pdf"), (PictureKind.NET, "net_picture.png"),
        (PictureKind.TURNTABLE, "turntable.gif")]
    assert asked[0].view == "z"


def test_given_pictures_are_written_at_their_paths_with_a_report(tmp_path):
    net = tree_net(BAR.grid)
    pics = (Picture(PictureKind.NET, "n.pdf", size=120), Picture(PictureKind.SLICES, "s.png"),
            Picture(PictureKind.TURNTABLE, "t.gif"))
    made = render_pictures(BAR, PictureOptions(size=130, frames=3), tmp_path, name="bar", seed=0, net=net,
                           pictures=pics)
    assert [f.path for f in made.files] == ["n.pdf", "s.png", "t.gif"]
    assert made.files[0].purpose.endswith("as a one-page PDF")
    report = made.report["pictures"]
    assert json.loads(json.dumps(report)) == report  # plain JSON values
    assert [r["kind"] for r in report] == ["net", "slices", "turntable"]
    assert (tmp_path / "n.pdf").read_bytes().startswith(b"%PDF")
    assert (tmp_path / "s.png").read_bytes() == png_bytes(slice_sheet(BAR, size=130))
    with Image.open(tmp_path / "s.png") as im:
        assert im.size == (report[1]["width"], report[1]["height"])
    # Without its own size the turntable is half the options' size, never below 64 px.
    assert report[2]["width"] == report[2]["height"] == 65 and report[2]["frames"] == 3


def test_the_net_picture_option_draws_the_given_net(tmp_path):
    net = tree_net(BAR.grid)
    made = render_pictures(BAR, PictureOptions(size=100, triptych=False, net_picture=True), tmp_path, name="bar",
                           seed=0, net=net)
    assert [f.path for f in made.files] == ["render_profile.png", "net_picture.png"]
    assert (tmp_path / "net_picture.png").read_bytes() == png_bytes(net_picture(net, BAR, size=100))


@pytest.mark.parametrize(("kind", "path"), [(PictureKind.VIEW, "v.pdf"), (PictureKind.TRIPTYCH, "t.gif"),
                                            (PictureKind.TURNTABLE, "t.png"), (PictureKind.SLICES, "s")])
def test_a_wrong_extension_is_refused_before_anything_is_written(tmp_path, kind, path):
    pics = (Picture(PictureKind.VIEW, "first.png"), Picture(kind, path))
    with pytest.raises(UnknownFormatError, match="can be written as"):
        render_pictures(BAR, PictureOptions(size=64), tmp_path, name="bar", seed=0, pictures=pics)
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize(("fields", "text"), [({"kind": "paint"}, "unknown kind 'paint'"),
                                              ({"view": "top"}, "unknown view 'top'"),
                                              ({"size": 8}, "size: expected"), ({"size": True}, "size: expected")])
def test_a_picture_refuses_what_cannot_be_drawn(fields, text):
    with pytest.raises(InvalidShapeError, match=text):
        Picture(**{"kind": "view", "path": "a.png", **fields})


def test_a_picture_named_by_string_is_the_same_kind():
    assert Picture("triptych", "t.pdf").kind is PictureKind.TRIPTYCH
    assert Picture("triptych", "t.pdf").purpose() == "net | slices | 3D as a one-page PDF"
