import re
import zlib

import numpy as np
import pytest
from _handnets import tree_net

from voxfab.errors import UnfoldError
from voxfab.render import net_picture, pdf_bytes, png_bytes, render, slice_sheet, triptych, triptych_layout
from voxfab.render._triptych import make_net

BOX = np.ones((2, 1, 1), dtype=bool)


def parse_pdf(data):
    """Check the xref table against the bytes and return {object number: body}."""
    start = int(re.search(rb"startxref\n(\d+)\n%%EOF\n$", data).group(1))
    xref = data[start:].split(b"trailer")[0].split(b"\n")
    count = int(xref[1].split()[1])
    objects = {}
    for i in range(1, count):
        off = int(xref[2 + i].split()[0])
        assert data[off:].startswith(b"%d 0 obj\n" % i)
        objects[i] = data[off : data.index(b"\nendobj\n", off)]
    return objects


def test_triptych_holds_net_slices_and_3d_under_the_title():
    net = tree_net(BOX)
    img = triptych(BOX, name="two cubes", net=net, panel=300)
    lay = triptych_layout(300)
    assert img.size == (lay.width, lay.height)
    a = np.asarray(img)
    expected = [net_picture(net, BOX, size=300), slice_sheet(BOX, size=300, height=300), render(BOX, view="profile", size=300)]
    for pic, (left, top, right, bottom) in zip(expected, lay.panels):
        assert np.array_equal(a[top:bottom, left:right], np.asarray(pic))
    title = a[: lay.title_height]
    assert (title.sum(axis=-1) < 200).sum() > 50  # the name is written


def test_triptych_png_and_pdf_are_deterministic_and_the_pdf_is_sound():
    net = tree_net(BOX)
    img = triptych(BOX, name="two cubes", net=net, panel=200)
    assert png_bytes(img) == png_bytes(triptych(BOX, name="two cubes", net=net, panel=200))
    data = pdf_bytes(img, title="two cubes")
    assert data == pdf_bytes(triptych(BOX, name="two cubes", net=net, panel=200), title="two cubes")
    assert data.startswith(b"%PDF-1.4") and b"CreationDate" not in data and b"ModDate" not in data
    objs = parse_pdf(data)
    # The drawing PDF backend: catalog, pages, info, page, content, then the page's image.
    image_obj = objs[6]
    w, h = img.size
    assert b"/Width %d /Height %d" % (w, h) in image_obj
    stream = image_obj.split(b"stream\n", 1)[1].rsplit(b"\nendstream", 1)[0]
    assert int(re.search(rb"/Length (\d+)", image_obj).group(1)) == len(stream)
    assert zlib.decompress(stream) == img.convert("RGB").tobytes()
    assert b"(two cubes)" in objs[3]
    # 150 dpi: the page is the picture's size in mm (25.4 mm per 150 px), in points.
    box = re.search(rb"/MediaBox \[0 0 ([\d.]+) ([\d.]+)\]", objs[4]).groups()
    assert [float(v) for v in box] == pytest.approx([w * 72 / 150, h * 72 / 150], abs=1e-3)
    assert b"/Im0 6 0 R" in objs[4] and b"/Im0 Do" in zlib.decompress(objs[5].split(b"stream\n", 1)[1][:-10])


def test_without_a_net_engine_or_net_the_panel_says_why(monkeypatch):
    import voxfab.unfold as unfold

    def refuse(grid, *, rng):
        raise UnfoldError("shape: 1 enclosed cavity")

    monkeypatch.setattr(unfold, "unfold", refuse, raising=False)
    with pytest.raises(UnfoldError):
        make_net(BOX, rng=0)
    img = triptych(BOX, name="x", panel=200)
    lay = triptych_layout(200)
    left, top, right, bottom = lay.panels[0]
    panel = np.asarray(img)[top:bottom, left:right]
    assert (panel.sum(axis=-1) < 500).any()  # the message is written


def test_triptych_uses_the_engine_net_by_seed():
    unfold = pytest.importorskip("voxfab.unfold")
    if not hasattr(unfold, "unfold"):
        pytest.skip("voxfab.unfold.unfold not available")
    from voxfab.shape import examples

    g = examples.ball(2)
    a = png_bytes(triptych(g, name="ball", rng=3, panel=200))
    assert a == png_bytes(triptych(g, name="ball", rng=3, panel=200))
    assert a == png_bytes(triptych(g, name="ball", net=unfold.unfold(g, rng=3), panel=200))


def test_pdf_renders_in_poppler_like_the_png(tmp_path):
    import shutil
    import subprocess

    from PIL import Image

    if shutil.which("pdftoppm") is None:
        pytest.skip("poppler's pdftoppm is not installed")
    net = tree_net(BOX)
    img = triptych(BOX, name="two cubes", net=net, panel=160)
    (tmp_path / "t.pdf").write_bytes(pdf_bytes(img, title="two cubes", dpi=150))
    subprocess.run(["pdftoppm", "-r", "150", "-png", "-singlefile", str(tmp_path / "t.pdf"), str(tmp_path / "p")],
                   check=True, capture_output=True)
    with Image.open(tmp_path / "p.png") as im:
        back = np.asarray(im.convert("RGB")).astype(int)
    assert back.shape == np.asarray(img).shape
    assert np.abs(back - np.asarray(img).astype(int)).mean() < 12  # the same picture, resampled by poppler


def _paper_bits(panel: np.ndarray) -> list[int]:
    """Pixel areas of the separate bits of paper in a net panel above its legend strip, largest first."""
    from scipy import ndimage

    strip = max(18, panel.shape[0] // 22)
    paper = (255 * 3 - panel[: panel.shape[0] - strip].astype(int).sum(axis=-1)) > 30
    paper = ndimage.binary_closing(paper, iterations=2)  # a tab and its face are one bit of paper
    labels, _ = ndimage.label(paper, structure=np.ones((3, 3)))
    return sorted((int(a) for a in np.bincount(labels.ravel())[1:] if a > 100), reverse=True)


def test_a_net_in_pieces_is_drawn_piece_by_piece_each_with_its_outline():
    """The pawn split in pieces: the triptych's net panel shows each piece apart, its area as its faces'."""
    from pathlib import Path

    from voxfab.recipe import load_recipe, make_shape
    from voxfab.render._raster import parse_color
    from voxfab.shape import surface_graph
    from voxfab.unfold import unfold

    pawn = make_shape(load_recipe(Path(__file__).resolve().parents[2] / "recipes" / "chess" / "pawn.toml")).grid
    pieces = unfold(pawn, rng=0, fit=(20, 20), pieces="flat")
    assert len(pieces) > 1
    assert sum(p.face_count for p in pieces) == surface_graph(pawn).face_count
    img = triptych(pawn, name="pawn", net=pieces, panel=400)
    assert png_bytes(img) == png_bytes(triptych(pawn, name="pawn", net=list(pieces), panel=400))
    left, top, right, bottom = triptych_layout(400).panels[0]
    panel = np.asarray(img)[top:bottom, left:right]
    assert np.array_equal(panel, np.asarray(net_picture(pieces, pawn, size=400)))
    bits = _paper_bits(panel)
    assert len(bits) == len(pieces), bits
    faces = sorted((p.face_count for p in pieces), reverse=True)
    ratios = np.array(bits) / np.array(faces)
    assert ratios.max() < 2.0 * ratios.min(), (bits, faces)
    # The cut outlines are the drawing's red, round every piece.
    red = np.array(parse_color("#ff0000", name="cut"))
    assert (np.abs(panel.astype(int) - red).sum(axis=-1) < 60).sum() > 100 * len(pieces)
