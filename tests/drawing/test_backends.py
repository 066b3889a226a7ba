"""The four backends on one page: read back with other libraries, measured in mm."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from _dxf_read import closed_rings

from voxfab.drawing import (
    FORMATS,
    LAYERS,
    Drawing,
    Fill,
    Lines,
    Page,
    PlacedImage,
    Polylines,
    WriteOptions,
    page_paths,
    text_polylines,
    write_drawing,
)
from voxfab.errors import InvalidShapeError, UnknownFormatError

SVG = "{http://www.w3.org/2000/svg}"


def sample_page() -> Page:
    """A 100 x 60 mm page: a square with a square hole, a dowel circle, folds, a score and text."""
    outer = np.array([[10.0, 10.0], [50.0, 10.0], [50.0, 50.0], [10.0, 50.0]])
    hole = np.array([[20.0, 20.0], [20.0, 30.0], [30.0, 30.0], [30.0, 20.0]])
    rings = Polylines.from_list([outer, hole], [True, True])
    return Page(
        100.0, 60.0,
        layers={
            "CUT": rings,
            "MOUNTAIN": Polylines.from_segments([(60.0, 10.0)], [(60.0, 50.0)]),
            "VALLEY": Polylines.from_segments([(70.0, 10.0)], [(70.0, 50.0)]),
            "SCORE": Polylines.from_list([np.array([[80.0, 10.0], [90.0, 10.0], [90.0, 50.0]])], [False]),
            "LABEL": text_polylines(["AB 12"], [(60.0, 54.0)], [(1.0, 0.0)], 4.0),
        },
        circles={"CUT": np.array([[40.0, 40.0, 3.0]])},
        fills=(Fill(rings, "#f2c48d"),),
        title="sample",
    )


def test_svg_in_mm_with_hairlines_for_lasers_and_visible_lines_for_people(tmp_path: Path) -> None:
    from lxml import etree

    from voxfab.drawing.svg import page_svg

    page = sample_page()
    laser = etree.fromstring(page_svg(page).encode())
    assert laser.get("width") == "100mm" and laser.get("height") == "60mm" and laser.get("viewBox") == "0 0 100 60"
    groups = {g.get("id"): g for g in laser.findall(f"{SVG}g")}
    assert list(groups) == page.used_layers()
    assert {g.get("stroke-width") for g in groups.values()} == {"0.01"}
    assert groups["CUT"].get("stroke") == "#ff0000"
    assert groups["MOUNTAIN"].get("stroke-dasharray") == "2 1"
    # y is flipped: the hole's corner (20, 20) is at 60 - 20 = 40.
    assert "M20.000,40.000 " in groups["CUT"].findall(f"{SVG}path")[1].get("d")
    (c,) = groups["CUT"].findall(f"{SVG}circle")
    assert (float(c.get("cx")), float(c.get("cy")), float(c.get("r"))) == (40.0, 20.0, 3.0)
    preview = etree.fromstring(page_svg(page, lines=Lines.PREVIEW).encode())
    groups = {g.get("id"): g for g in preview.findall(f"{SVG}g")}
    assert groups["FILL"].find(f"{SVG}path").get("fill") == "#f2c48d"
    assert float(groups["CUT"].get("stroke-width")) == LAYERS["CUT"].width >= 0.15


@pytest.mark.parametrize("version", ["R12", "R2000"])
def test_dxf_audits_clean_with_mm_units_extents_and_the_geometry(tmp_path: Path, version: str) -> None:
    import ezdxf
    import shapely

    page = sample_page()
    path = tmp_path / "p.dxf"
    write_drawing(Drawing((page,)), path, WriteOptions(dxf_version=version))
    doc = ezdxf.readfile(path)
    assert doc.dxfversion == {"R12": "AC1009", "R2000": "AC1015"}[version]
    auditor = doc.audit()
    assert not auditor.has_errors and not auditor.has_fixes
    if version == "R2000":
        assert doc.header["$INSUNITS"] == 4
    assert tuple(doc.header["$EXTMIN"])[:2] == pytest.approx((10.0, 10.0))
    assert tuple(doc.header["$EXTMAX"])[:2] == pytest.approx((90.0, 58.0), abs=0.01)
    layers = {layer.dxf.name: layer for layer in doc.layers}
    assert set(LAYERS) <= set(layers)
    assert layers["CUT"].dxf.color == 1 and layers["MOUNTAIN"].dxf.linetype == "DASHED"
    msp = doc.modelspace()
    rings = []
    for e in msp.query('POLYLINE LWPOLYLINE[layer=="CUT"]'):
        pts = [tuple(v.dxf.location)[:2] for v in e.vertices] if e.dxftype() == "POLYLINE" else \
            [tuple(p)[:2] for p in e.get_points()]
        assert e.closed if e.dxftype() == "LWPOLYLINE" else e.is_closed
        rings.append(shapely.Polygon(pts))
    # the square minus its hole, less the dowel circle: 40² - 10² - π·3²
    area = rings[0].area - rings[1].area - sum(np.pi * c.dxf.radius**2 for c in msp.query("CIRCLE"))
    assert area == pytest.approx(1600 - 100 - np.pi * 9)


def test_dxf_declares_millimetres_by_default_and_r12_is_an_option(tmp_path: Path) -> None:
    """Without a version the DXF is R2000 with $INSUNITS = 4 (mm) and $MEASUREMENT = 1, so no program reads inches."""
    import ezdxf

    page = sample_page()
    write_drawing(Drawing((page,)), tmp_path / "d.dxf")
    doc = ezdxf.readfile(tmp_path / "d.dxf")
    assert doc.dxfversion == "AC1015"
    assert doc.header["$INSUNITS"] == 4 and doc.header["$MEASUREMENT"] == 1
    assert not doc.audit().has_errors
    write_drawing(Drawing((page,)), tmp_path / "old.dxf", WriteOptions(dxf_version="R12"))
    old = ezdxf.readfile(tmp_path / "old.dxf")
    assert old.dxfversion == "AC1009" and "$INSUNITS" not in old.header
    # the same geometry in both: the square's outline and its hole, in mm
    rings = [sorted(map(tuple, np.round(r, 4).tolist())) for r in closed_rings(doc)]
    assert rings == [sorted(map(tuple, np.round(r, 4).tolist())) for r in closed_rings(old)]
    assert sorted(np.ptp(r, axis=0).tolist() for r in closed_rings(doc)) == [[10.0, 10.0], [40.0, 40.0]]


def test_pdf_pages_are_true_size_and_print_the_lines(tmp_path: Path) -> None:
    if not shutil.which("pdftoppm"):
        pytest.skip("pdftoppm (poppler-utils) is not installed")
    from PIL import Image

    page = sample_page()
    path = tmp_path / "p.pdf"
    write_drawing(Drawing((page, page), "two"), path)
    info = subprocess.run(["pdfinfo", str(path)], capture_output=True, text=True, check=True).stdout
    assert re.search(r"Pages:\s+2\n", info)
    assert re.search(r"Page size:\s+283.46\d* x 170.07\d* pts", info)  # 100 x 60 mm
    subprocess.run(["pdftoppm", "-r", "254", "-f", "1", "-l", "1", "-png", str(path), str(tmp_path / "r")],
                   check=True)
    img = np.asarray(Image.open(tmp_path / "r-1.png").convert("RGB")).astype(int)
    assert abs(img.shape[0] - 600) <= 1 and abs(img.shape[1] - 1000) <= 1  # 10 px per mm
    # the fill inside the square, the paper in its hole, red on the cut line (row of y = 10 mm)
    assert tuple(img[600 - 150, 150]) == (242, 196, 141)
    assert tuple(img[600 - 250, 250]) == (255, 255, 255)
    red = (img[600 - 101, 100:500, 0] > 200) & (img[600 - 101, 100:500, 1] < 80)
    assert red.mean() > 0.9


def test_png_fills_holes_even_odd_and_draws_visible_lines(tmp_path: Path) -> None:
    from PIL import Image

    page = sample_page()
    path = tmp_path / "p.png"
    write_drawing(Drawing((page,)), path, WriteOptions(png_scale=5.0))
    img = np.asarray(Image.open(path).convert("RGB"))
    assert img.shape == (300, 500, 3)
    fill = (img == (242, 196, 141)).all(axis=-1)
    # 40 x 40 mm less the 10 x 10 mm hole, less the lines, at 25 px per mm²
    assert 0.9 * 1500 * 25 < fill.sum() < 1500 * 25
    assert not fill[300 - 125, 125]
    # a solid 0.2 mm cut line at 5 px/mm is one pixel wide: the row y = 10 mm is red
    red = (img[:, :, 0] == 255) & (img[:, :, 1] == 0)
    assert red[300 - 50, 50:250].mean() > 0.95
    # the mountain fold is dashed: magenta pixels along x = 60 mm with gaps
    column = (img[25:250, 300, 2] == 255) & (img[25:250, 300, 0] == 255) & (img[25:250, 300, 1] == 0)
    assert 0.5 < column.mean() < 0.8


def test_dashes_follow_the_pattern() -> None:
    from voxfab.drawing import Polylines
    from voxfab.drawing.png import dashes

    lines = Polylines.from_segments([(0.0, 0.0)], [(30.0, 0.0)])
    d = dashes(lines, (2.0, 1.0))
    assert len(d) == 10 and d.length() == pytest.approx(20.0)


def test_writer_names_pages_and_refuses_unknown_formats(tmp_path: Path) -> None:
    assert FORMATS == (".dxf", ".pdf", ".png", ".svg")
    assert page_paths(tmp_path / "net-2.svg", 2) == [tmp_path / "net-2.sheet-1.svg", tmp_path / "net-2.sheet-2.svg"]
    page = sample_page()
    written = write_drawing(Drawing((page, page)), tmp_path / "x.svg")
    assert written == [str(tmp_path / "x.sheet-1.svg"), str(tmp_path / "x.sheet-2.svg")]
    with pytest.raises(UnknownFormatError, match="unknown drawing format"):
        write_drawing(Drawing((page,)), tmp_path / "x.eps")


def test_same_drawing_same_bytes(tmp_path: Path) -> None:
    page = sample_page()
    for ext in FORMATS:
        a = write_drawing(Drawing((page,)), tmp_path / f"a{ext}")
        b = write_drawing(Drawing((page,)), tmp_path / f"b{ext}")
        assert Path(a[0]).read_bytes() == Path(b[0]).read_bytes()


def image_page() -> Page:
    """A 40 x 20 mm page holding a 2 x 2 pixel picture stretched over the box (10, 5)-(30, 15) mm, and a cut line."""
    pixels = np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [255, 255, 0]]], dtype=np.uint8)
    return Page(40.0, 20.0, layers={"CUT": Polylines.from_segments([(0.0, 2.0)], [(40.0, 2.0)])},
                images=(PlacedImage(pixels, 10.0, 5.0, 20.0, 10.0),))


def quadrant_colours(img: np.ndarray, px_per_mm: float) -> np.ndarray:
    """Colours at the centres of the box's four quarters: top left, top right, bottom left, bottom right."""
    h = img.shape[0]
    at = [(15.0, 12.5), (25.0, 12.5), (15.0, 7.5), (25.0, 7.5)]
    return np.array([img[int(h - y * px_per_mm), int(x * px_per_mm)] for x, y in at], dtype=int)


def test_a_placed_image_fills_its_box_in_png_pdf_and_svg_and_stays_out_of_dxf(tmp_path: Path) -> None:
    from lxml import etree
    from PIL import Image

    from voxfab.drawing.svg import page_svg

    page = image_page()
    expected = np.array([(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0)])
    write_drawing(Drawing((page,)), tmp_path / "i.png", WriteOptions(png_scale=10.0))
    png = np.asarray(Image.open(tmp_path / "i.png").convert("RGB"))
    assert png.shape == (200, 400, 3)
    assert np.abs(quadrant_colours(png, 10.0) - expected).max() <= 8  # resampled to the box
    assert tuple(png[200 - 20 * 10 // 2, 5 * 10]) == (255, 255, 255)  # paper beside the box
    # SVG previews embed the picture with y flipped; laser files leave it out.
    root = etree.fromstring(page_svg(page, lines=Lines.PREVIEW).encode())
    (image,) = root.findall(f"{SVG}image")
    assert [image.get(k) for k in ("x", "y", "width", "height")] == ["10", "5", "20", "10"]
    assert image.get("href").startswith("data:image/png;base64,")
    assert not etree.fromstring(page_svg(page).encode()).findall(f"{SVG}image")
    write_drawing(Drawing((page,)), tmp_path / "i.dxf")
    assert "IMAGE" not in (tmp_path / "i.dxf").read_text()
    if not shutil.which("pdftoppm"):
        pytest.skip("pdftoppm (poppler-utils) is not installed")
    write_drawing(Drawing((page,)), tmp_path / "i.pdf")
    info = subprocess.run(["pdfinfo", str(tmp_path / "i.pdf")], capture_output=True, text=True, check=True).stdout
    assert re.search(r"Page size:\s+113.38\d* x 56.69\d* pts", info)  # 40 x 20 mm
    subprocess.run(["pdftoppm", "-r", "254", "-png", "-singlefile", str(tmp_path / "i.pdf"), str(tmp_path / "r")],
                   check=True)
    pdf = np.asarray(Image.open(tmp_path / "r.png").convert("RGB"))
    assert np.abs(quadrant_colours(pdf, 10.0) - expected).max() <= 8
    red = (pdf[200 - 20, :, 0] > 200) & (pdf[200 - 20, :, 1] < 80)  # the cut line at y = 2 mm, over the paper
    assert red.mean() > 0.9


def test_a_placed_image_moves_with_its_page_and_refuses_bad_pixels() -> None:
    page = image_page().shifted((3.0, 4.0), width=50.0, height=30.0)
    assert (page.images[0].x, page.images[0].y) == (13.0, 9.0)
    with pytest.raises(InvalidShapeError, match="uint8 RGB"):
        PlacedImage(np.zeros((2, 2), dtype=np.uint8), 0.0, 0.0, 1.0, 1.0)
    with pytest.raises(InvalidShapeError, match="positive size"):
        PlacedImage(np.zeros((1, 1, 3), dtype=np.uint8), 0.0, 0.0, 0.0, 1.0)
