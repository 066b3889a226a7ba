"""The drawing model's print-then-cut parts: cutters' marks and areas, inks with halos, per-ring fills, nonzero fills."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from voxfab.drawing import Fill, Ink, Lines, Page, Polylines, cutter_area, registration_marks
from voxfab.drawing.pdf import page_content
from voxfab.drawing.png import page_image
from voxfab.drawing.svg import page_svg

SVG = "{http://www.w3.org/2000/svg}"


def square(x: float, y: float, s: float) -> np.ndarray:
    return np.array([(x, y), (x + s, y), (x + s, y + s), (x, y + s)], dtype=float)


def test_silhouette_type_1_marks_on_letter() -> None:
    w, h = 215.9, 279.4
    marks = registration_marks("silhouette", (w, h)).lines()
    assert len(marks) == 3
    sq, tr, bl = marks
    # y up: the square's top edge 10 mm under the sheet's top, its left edge 10 mm in.
    assert np.allclose(sq.min(axis=0), (10, h - 15)) and np.allclose(sq.max(axis=0), (15, h - 10))
    assert np.allclose(tr.min(axis=0), (w - 30, h - 30)) and np.allclose(tr.max(axis=0), (w - 10, h - 10))
    assert np.allclose(bl.min(axis=0), (10, 10)) and np.allclose(bl.max(axis=0), (30, 30))
    # An L of 0.5 mm lines: its area is two 20 x 0.5 arms less their shared corner.
    x, y = bl[:, 0], bl[:, 1]
    assert abs(abs((x * np.roll(y, -1) - np.roll(x, -1) * y).sum()) / 2 - (2 * 20 * 0.5 - 0.25)) < 1e-9
    assert cutter_area("silhouette", (w, h), 10.0) == (18.0, 18.0, w - 18.0, h - 18.0)
    assert cutter_area("none", (w, h), 10.0) == (10.0, 10.0, w - 10.0, h - 10.0)
    assert not len(registration_marks("none", (w, h)))


@pytest.mark.parametrize(("size", "landscape"), [((210.0, 297.0), False), ((215.9, 279.4), False),
                                                  ((297.0, 210.0), True)])
def test_cricut_area_is_its_print_then_cut_maximum_centred(size, landscape) -> None:
    w, h = size
    x0, y0, x1, y1 = cutter_area("cricut", size, 10.0)
    aw, ah = (234.95, 171.45) if landscape else (171.45, 234.95)
    assert np.allclose((x1 - x0, y1 - y0), (aw, ah)) and np.allclose((x0 + x1, y0 + y1), (w, h))
    marks = registration_marks("cricut", size, 10.0).lines()
    assert len(marks) == 4
    for m in marks:  # all on the page, none inside the area
        assert (m >= 0).all() and (m[:, 0] <= w).all() and (m[:, 1] <= h).all()
        assert not ((m[:, 0] > x0) & (m[:, 0] < x1) & (m[:, 1] > y0) & (m[:, 1] < y1)).any()


def test_a_small_sheet_shrinks_the_cricut_area_to_fit_its_marks() -> None:
    x0, y0, x1, y1 = cutter_area("cricut", (148.0, 210.0), 10.0)
    assert (x0, y0) >= (10.0, 10.0) and (x1, y1) <= (138.0, 200.0)
    marks = np.concatenate(registration_marks("cricut", (148.0, 210.0), 10.0).lines())
    assert marks.min() >= 0 and marks[:, 0].max() <= 148 and marks[:, 1].max() <= 210


def test_nonzero_fills_make_one_area_of_overlapping_rings() -> None:
    rings = Polylines.from_list([square(2, 2, 6), square(5, 5, 6)], [True, True])
    page = Page(20, 20, {}, fills=(Fill(rings, "#ff0000", nonzero=True),))
    px = np.asarray(page_image(page, scale=2.0))
    # The overlap (6..8, 6..8 mm; y up) is red, not a hole as even-odd would leave.
    assert tuple(px[int((20 - 7) * 2), int(7 * 2)]) == (255, 0, 0)
    even = np.asarray(page_image(Page(20, 20, {}, fills=(Fill(rings, "#ff0000"),)), scale=2.0))
    assert tuple(even[int((20 - 7) * 2), int(7 * 2)]) == (255, 255, 255)
    content = page_content(page).decode()
    assert "\nf\n" in content and "f*" not in content
    svg = ET.fromstring(page_svg(page, lines=Lines.PREVIEW))
    assert [p.get("fill-rule") for p in svg.iter(f"{SVG}path")] == ["nonzero"]
    assert not list(ET.fromstring(page_svg(page)).iter(f"{SVG}path"))  # a laser file: no fills


def test_rings_of_their_own_colours_and_ids() -> None:
    rings = Polylines.from_list([square(1, 1, 3), square(5, 1, 3), square(9, 1, 3)], [True] * 3)
    fill = Fill(rings, "#000000", colors=("#102030", "#a0b0c0", "#102030"), names=("face-0", "face-1", "face-2"))
    page = Page(20, 10, {}, fills=(fill,), artwork=True)
    paths = {p.get("id"): p.get("fill") for p in ET.fromstring(page_svg(page)).iter(f"{SVG}path")}
    assert paths == {"face-0": "#102030", "face-1": "#a0b0c0", "face-2": "#102030"}
    px = np.asarray(page_image(page, scale=2.0))
    assert [tuple(px[int((10 - 2.5) * 2), int(x * 2)]) for x in (2.5, 6.5, 10.5)] == \
        [(0x10, 0x20, 0x30), (0xA0, 0xB0, 0xC0), (0x10, 0x20, 0x30)]
    # The PDF sets each colour once, its rings in one path.
    content = page_content(page).decode()
    assert content.count(" rg\n") == 2


def test_inks_print_a_layer_in_their_colours_over_a_halo_and_dxf_keeps_the_layer(tmp_path) -> None:
    import ezdxf

    from voxfab.drawing import Drawing, write_drawing

    line = Polylines.from_segments([(2, 5)], [(18, 5)])
    page = Page(20, 10, {"MOUNTAIN": line}, inks=(Ink("MOUNTAIN", line, "#ffffff", "#000000"),),
                marks=Polylines.from_list([square(0.5, 0.5, 1)], [True]))
    svg = ET.fromstring(page_svg(page))
    groups = {g.get("id"): g for g in svg.iter(f"{SVG}g")}
    assert groups["MOUNTAIN-halo1"].get("stroke") == "#000000" and groups["MOUNTAIN-ink1"].get("stroke") == "#ffffff"
    assert float(groups["MOUNTAIN-halo1"].get("stroke-width")) > float(groups["MOUNTAIN-ink1"].get("stroke-width"))
    assert "MOUNTAIN" not in groups and groups["REGISTRATION"].get("fill") == "#000000"
    px = np.asarray(page_image(page, scale=10.0))
    assert tuple(px[50, 22]) == (255, 255, 255)  # the line's first dash, white
    assert tuple(px[52, 22]) == (0, 0, 0)  # its halo beside it
    assert tuple(px[100 - 10, 10]) == (0, 0, 0)  # the mark
    content = page_content(page).decode()
    assert content.index("0 0 0 RG") < content.index("1 1 1 RG")
    write_drawing(Drawing((page,)), tmp_path / "p.dxf")
    layers = {e.dxf.layer for e in ezdxf.readfile(tmp_path / "p.dxf").modelspace()}
    assert layers == {"MOUNTAIN"}


def test_select_keeps_polylines_in_order() -> None:
    lines = Polylines.from_list([square(0, 0, 1), np.array([(5.0, 5.0), (6.0, 6.0)]), square(2, 2, 1)],
                                [True, False, True])
    picked = lines.select([True, False, True])
    assert len(picked) == 2 and picked.closed.tolist() == [True, True]
    assert np.array_equal(picked.lines()[1], square(2, 2, 1))


def test_rings_in_their_colours_rasterise_as_each_ring_alone() -> None:
    from voxfab.drawing.png import even_odd_mask

    rng = np.random.default_rng(5)
    rings, colors = [], []
    for i in range(60):  # squares and tab-like trapezoids, some overlapping, at awkward positions
        x, y, s = rng.uniform(0, 40), rng.uniform(0, 30), rng.uniform(0.3, 9)
        ring = square(x, y, s) if i % 2 else np.array([(x, y), (x + s, y), (x + 0.7 * s, y - 0.4 * s),
                                                         (x + 0.3 * s, y - 0.4 * s)])
        rings.append(ring)
        colors.append(f"#{i:02x}{(7 * i) % 256:02x}80")
    page = Page(50, 40, {}, fills=(Fill(Polylines.from_list(rings, [True] * 60), "#000000", colors=tuple(colors)),),
                artwork=True)
    got = np.asarray(page_image(page, scale=3.3))
    want = np.full_like(got, 255)

    def to_px(xy: np.ndarray) -> np.ndarray:
        return np.stack([xy[:, 0] * 3.3, (40 - xy[:, 1]) * 3.3], axis=1)

    for ring, c in zip(rings, colors):
        mask = even_odd_mask(Polylines.from_list([ring], [True]), want.shape[1], want.shape[0], to_px)
        want[mask] = [int(c[i:i + 2], 16) for i in (1, 3, 5)]
    assert np.array_equal(got, want)
