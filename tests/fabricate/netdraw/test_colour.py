"""Coloured nets, checked from the files: face fills against the voxels, a PDF rendered by pdftoppm,
legible marks, tinted tabs, the bleed, and print-then-cut files in register."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from _voxart import CHARACTER_COLOURS, character
from scipy import ndimage

from voxfab.fabricate.netdraw import DrawingOptions, NetOptions, fabricate_net
from voxfab.fabricate.netdraw._paint import TINT
from voxfab.shape import VoxelShape

SVG = "{http://www.w3.org/2000/svg}"
WHITE = np.array([255, 255, 255])


def hero() -> VoxelShape:
    """The test character's head and shoulders: one 6-connected piece in 5 colours (white eyes, dark hair)."""
    c = character()
    top = c.grid.copy()
    top[:, :, :10] = False
    lab, _ = ndimage.label(top)
    piece = lab == np.argmax(np.bincount(lab.ravel())[1:]) + 1
    return VoxelShape(piece, c.pitch, c.colours.fitted(piece))


def voxel_hex(shape: VoxelShape, voxel: list[int]) -> str:
    """The voxel's colour by a lookup of this test's own: palette row of the index grid's entry."""
    r, g, b, _ = shape.colours.palette[shape.colours.index[tuple(voxel)]].tolist()
    return f"#{r:02x}{g:02x}{b:02x}"


def lightness(hex_rgb: str) -> float:
    """CIELAB L* of an sRGB colour (D65), written out here apart from the library's."""
    c = np.array([int(hex_rgb[i:i + 2], 16) for i in (1, 3, 5)]) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    y = float(lin @ np.array([0.2126729, 0.7151522, 0.0721750]))
    return 116 * y ** (1 / 3) - 16 if y > (6 / 29) ** 3 else y * (29 / 3) ** 3


def rings_of(d: str) -> list[np.ndarray]:
    """The closed rings of an SVG path ``d`` of M/L/Z commands, mm (SVG y down)."""
    out = []
    for sub in re.findall(r"M[^M]*", d):
        pts = re.findall(r"(-?[\d.]+),(-?[\d.]+)", sub)
        out.append(np.array(pts, dtype=float))
    return out


def groups(svg: Path) -> dict[str, ET.Element]:
    return {g.get("id"): g for g in ET.parse(svg).getroot().iter(f"{SVG}g")}


def filled_paths(svg: Path) -> list[tuple[str, str, list[np.ndarray]]]:
    """``(id, fill, rings)`` of every path of the FILL layer."""
    fill = groups(svg)["FILL"]
    return [(p.get("id") or "", p.get("fill"), rings_of(p.get("d"))) for p in fill.iter(f"{SVG}path")]


def render(pdf: Path, tmp: Path, dpi: int = 254) -> np.ndarray:
    """The PDF's first page rendered by pdftoppm, RGB, ``dpi / 25.4`` pixels per mm."""
    assert shutil.which("pdftoppm"), "pdftoppm is needed"
    subprocess.run(["pdftoppm", "-r", str(dpi), "-png", "-singlefile", str(pdf), str(tmp / "page")], check=True)
    from PIL import Image

    return np.asarray(Image.open(tmp / "page.png").convert("RGB")).astype(int)


def make(tmp: Path, cutter: str = "none", bleed: float = 1.0, formats=("svg", "pdf", "png")) -> Path:
    fabricate_net(hero(), NetOptions(formats=formats), DrawingOptions(pitch=8.0, sheet="A4", cutter=cutter,
                                                                      bleed=bleed), tmp, name="hero", seed=1)
    return tmp


@pytest.fixture(scope="module")
def plain(tmp_path_factory) -> Path:
    return make(tmp_path_factory.mktemp("plain"))


@pytest.fixture(scope="module")
def silhouette(tmp_path_factory) -> Path:
    return make(tmp_path_factory.mktemp("silhouette"), cutter="silhouette")


def faces_of(folder: Path) -> dict[int, tuple[str, np.ndarray]]:
    """Face index (in net.json) -> (fill, square in SVG mm)."""
    out = {}
    for name, fill, rings in filled_paths(folder / "net.svg"):
        if name.startswith("face-"):
            assert len(rings) == 1 and len(rings[0]) == 4
            out[int(name[5:])] = (fill, rings[0])
    return out


def test_every_face_is_filled_with_its_voxels_colour(plain) -> None:
    shape = hero()
    net = json.loads((plain / "net.json").read_text())
    faces = faces_of(plain)
    assert sorted(faces) == list(range(net["face_count"])) == list(range(shape.exposed_faces))
    seen = set()
    for i, record in enumerate(net["faces"]):
        want = voxel_hex(shape, record["voxel"])
        assert record["colour"] == want
        assert faces[i][0] == want
        seen.add(want)
    # Every colour of the shape's surface, from the white eyes to the dark hair, is printed.
    assert {CHARACTER_COLOURS[k][:3] for k in ("eyes", "hair", "skin", "mouth", "shirt")} == \
        {tuple(int(c[j:j + 2], 16) for j in (1, 3, 5)) for c in seen}


def test_uncoloured_nets_say_no_colour_and_fill_no_face(tmp_path) -> None:
    shape = hero()
    fabricate_net(VoxelShape(shape.grid, shape.pitch), NetOptions(formats=("svg",)),
                  DrawingOptions(pitch=8.0, sheet="A4", svg_lines="preview"), tmp_path, name="hero", seed=1)
    net = json.loads((tmp_path / "net.json").read_text())
    assert all("colour" not in f for f in net["faces"])
    assert not any(name.startswith("face-") for name, _, _ in filled_paths(tmp_path / "net.svg"))


def test_the_rendered_pdf_shows_each_faces_colour_and_no_white_past_the_cut(plain, tmp_path) -> None:
    px = 254 / 25.4
    image = render(plain / "net.pdf", tmp_path)
    faces = faces_of(plain)
    squares = [sq for _, sq in faces.values()]
    centres = np.array([sq.mean(axis=0) for sq in squares])
    outside = []
    for fill, sq in faces.values():
        want = np.array([int(fill[j:j + 2], 16) for j in (1, 3, 5)])
        c = sq.mean(axis=0)
        # The middle of a face shows its colour (labels keep to the edges).
        r, col = int(round(c[1] * px)), int(round(c[0] * px))
        assert np.abs(image[r, col] - want).max() <= 3
        for k in range(4):
            a, b = sq[k], sq[(k + 1) % 4]
            mid = (a + b) / 2
            out = mid + (mid - c) / np.linalg.norm(mid - c) * 0.6  # 0.6 mm past the edge
            # An edge with another face beyond it is a fold or a slit, not the outline.
            if np.any(np.abs(centres - (2 * mid - c)).max(axis=1) < 0.01):
                continue
            outside.append(image[int(round(out[1] * px)), int(round(out[0] * px))])
    outside = np.array(outside)
    assert len(outside) > 50
    white = (outside >= 250).all(axis=1)
    assert not white.any(), f"{int(white.sum())} of {len(outside)} points just past the cut line are white"


def test_without_bleed_the_same_check_finds_white(tmp_path) -> None:
    folder = make(tmp_path / "nobleed", bleed=0.0, formats=("svg", "pdf"))
    px = 254 / 25.4
    image = render(folder / "net.pdf", tmp_path)
    faces = faces_of(folder)
    centres = np.array([sq.mean(axis=0) for _, sq in faces.values()])
    white = 0
    for _, sq in faces.values():
        c = sq.mean(axis=0)
        for k in range(4):
            mid = (sq[k] + sq[(k + 1) % 4]) / 2
            if np.any(np.abs(centres - (2 * mid - c)).max(axis=1) < 0.01):
                continue
            out = mid + (mid - c) / np.linalg.norm(mid - c) * 0.6
            white += bool((image[int(round(out[1] * px)), int(round(out[0] * px))] >= 250).all())
    assert white > 20


def test_labels_and_folds_contrast_with_their_faces(plain) -> None:
    faces = faces_of(plain)
    squares = [(fill, sq.min(axis=0), sq.max(axis=0)) for fill, sq in faces.values()]

    def face_at(p: np.ndarray) -> str | None:
        for fill, lo, hi in squares:
            if (p > lo).all() and (p < hi).all():
                return fill
        return None

    g = groups(plain / "net.svg")
    checked = 0
    for gid in [k for k in g if k.startswith("LABEL-ink")]:
        ink = g[gid].get("stroke")
        for path in g[gid].iter(f"{SVG}path"):
            start = np.array(re.findall(r"(-?[\d.]+),(-?[\d.]+)", path.get("d"))[0], dtype=float)
            fill = face_at(start)
            if fill is None:
                continue  # the title, on the paper's white
            assert abs(lightness(ink) - lightness(fill)) >= 50, (ink, fill)
            checked += 1
    assert checked > 300
    # A fold between two faces: its ink contrasts with their mean lightness, its halo is the other ink.
    folds = 0
    for gid in [k for k in g if re.fullmatch(r"(MOUNTAIN|VALLEY)-ink\d", k)]:
        ink = g[gid].get("stroke")
        halo = g[gid.replace("ink", "halo")].get("stroke")
        assert {ink, halo} == {"#000000", "#ffffff"}
        for path in g[gid].iter(f"{SVG}path"):
            a, b = np.array(re.findall(r"(-?[\d.]+),(-?[\d.]+)", path.get("d")), dtype=float)[:2]
            d = (b - a) / np.linalg.norm(b - a)
            for t in np.arange(4.0, np.linalg.norm(b - a), 8.0):  # the middle of each 8 mm face edge
                side = [face_at(a + t * d + s * 0.3 * np.array([-d[1], d[0]])) for s in (1, -1)]
                sides = [lightness(f) for f in side if f]
                if len(sides) == 2:
                    assert abs(lightness(ink) - sum(sides) / 2) >= 50
                    folds += 1
    assert folds > 100  # the mountain and valley folds (coplanar ones are not drawn)


def test_tabs_take_a_light_tint_of_the_face_they_glue_under(plain) -> None:
    net = json.loads((plain / "net.json").read_text())
    faces = faces_of(plain)
    c3 = [np.array(f["corners3d"]) for f in net["faces"]]
    tabs = [(fill, ring) for name, fill, rings in filled_paths(plain / "net.svg") if name.startswith("tabs-")
            for ring in rings]
    assert len(tabs) > 50
    ids = list(faces)
    p = np.array([faces[i][1] for i in ids])
    q = np.roll(p, -1, axis=1)
    d = (q - p) / np.linalg.norm(q - p, axis=2, keepdims=True)
    for fill, ring in tabs:
        a, b = ring[0], ring[1]  # the tab's fold
        on = np.ones((len(ids), 4), dtype=bool)
        for x in (a, b):  # both ends on the edge from corner k to corner k + 1 of a face
            v = x - p
            on &= (np.abs(d[..., 0] * v[..., 1] - d[..., 1] * v[..., 0]) < 0.01)
            on &= ((d * v).sum(axis=2) > -0.01) & ((d * v).sum(axis=2) < 8.01)
        hits = np.argwhere(on)
        assert len(hits) == 1
        found = (ids[hits[0][0]], int(hits[0][1]))
        i, k = found
        edge = {tuple(c3[i][k]), tuple(c3[i][(k + 1) % 4])}
        across = [j for j in range(len(c3)) if j != i and edge <= {tuple(v) for v in c3[j]}]
        assert across
        tab = np.array([int(fill[j:j + 2], 16) for j in (1, 3, 5)])
        options = [np.array([int(net["faces"][j]["colour"][t:t + 2], 16) for t in (1, 3, 5)]) for j in across]
        # A light tint: the face's colour with TINT of white mixed in.
        assert any(np.abs(tab - (o + (255 - o) * TINT)).max() <= 1 for o in options), (fill, options)
        assert lightness(fill) > max(lightness(net["faces"][j]["colour"]) for j in across) - 1e-9


def test_silhouette_print_and_cut_files_register(silhouette, tmp_path) -> None:
    print_svg, cut_svg = silhouette / "net.svg", silhouette / "net.cut.svg"
    gp, gc = groups(print_svg), groups(cut_svg)
    assert "CUT" not in gp and "CUT" in gc
    assert set(gc) == {"CUT", "REGISTRATION"}
    marks_p = rings_of(gp["REGISTRATION"].find(f"{SVG}path").get("d"))
    marks_c = rings_of(gc["REGISTRATION"].find(f"{SVG}path").get("d"))
    assert len(marks_p) == 3 and all(np.array_equal(a, b) for a, b in zip(marks_p, marks_c))
    w, h = 210.0, 297.0
    # Type 1: a 5 mm square at the top left, 10 mm in; L marks of 20 mm arms, 0.5 mm thick, top right and
    # bottom left, their outer corners 10 mm from both edges.
    square, top_right, bottom_left = marks_p
    assert np.allclose(square.min(axis=0), (10, 10)) and np.allclose(square.max(axis=0), (15, 15))
    assert np.allclose(top_right.min(axis=0), (w - 30, 10)) and np.allclose(top_right.max(axis=0), (w - 10, 30))
    assert np.allclose(bottom_left.min(axis=0), (10, h - 30)) and np.allclose(bottom_left.max(axis=0), (30, h - 10))
    assert sorted(np.round(np.diff(np.unique(top_right[:, 0])), 3).tolist()) == [0.5, 19.5]
    # The cut lines run along the printed faces' and tabs' edges: every corner of the cut is a printed corner.
    printed = np.concatenate([r for name, _, rings in filled_paths(print_svg)
                              if name.startswith(("face-", "tabs-")) for r in rings])
    cut = np.concatenate([r for p in gc["CUT"].iter(f"{SVG}path") for r in rings_of(p.get("d"))])
    nearest = np.abs(cut[:, None, :] - printed[None, :, :]).max(axis=2).min(axis=1)
    assert nearest.max() < 0.002
    # Nothing printed or cut comes within 18 mm of the edges (the marks' room).
    assert cut.min() >= 18 - 1e-6 and (w - cut[:, 0]).min() >= 18 - 1e-6 and (h - cut[:, 1]).min() >= 18 - 1e-6
    # The PDF prints the marks black where the SVGs have them, and no red cut line.
    image = render(silhouette / "net.pdf", tmp_path)
    px = 254 / 25.4
    for x, y in [(12.5, 12.5), (w - 20, 10.25), (10.25, h - 20)]:
        assert (image[int(round(y * px)), int(round(x * px))] < 40).all()
    red = (image[..., 0] > 240) & (image[..., 1] < 20) & (image[..., 2] < 20)  # the cut colour, #ff0000
    assert red.sum() == 0


def test_a_pdf_print_alone_comes_with_its_cut_file(tmp_path, silhouette) -> None:
    # The print is made to be cut: asked for as a PDF alone, it still gets the cut lines beside it.
    r = _cli(*_hero_vox(tmp_path), "-o", "n.pdf", "--face-size", "8", "--cutter", "silhouette", "--seed", "1",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["written"] == ["n.pdf", "n.cut.svg"]
    gc = groups(tmp_path / "n.cut.svg")
    assert set(gc) == {"CUT", "REGISTRATION"} and len(list(gc["CUT"].iter(f"{SVG}path"))) > 0
    # The same cut as the one beside the SVG print, and the library lists it once for its SVG and PDF prints.
    assert (tmp_path / "n.cut.svg").read_bytes() == (silhouette / "net.cut.svg").read_bytes()
    both = make(tmp_path / "both", cutter="silhouette", formats=("pdf", "svg"))
    assert sorted(p.name for p in both.iterdir()) == ["net.cut.svg", "net.json", "net.pdf", "net.svg"]


def _hero_vox(tmp: Path) -> list[str]:
    from voxfab.io import write

    write(hero(), tmp / "hero.vox")
    return ["hero.vox"]


def test_the_title_keeps_clear_of_the_silhouette_corner_mark(silhouette) -> None:
    # The bottom-left L fills x, y = 10..30 mm from the corner: the title line under the art starts past it,
    # 3 mm clear (SVG y runs down the 297 mm page).
    label = [r for name, g in groups(silhouette / "net.svg").items() if name.startswith("LABEL")
             for p in g.iter(f"{SVG}path") for r in rings_of(p.get("d"))]
    title = np.concatenate([r for r in label if r[:, 1].min() > 297 - 18 - 1 - 3.0 - 1e-6])
    assert title[:, 0].min() >= 30 + 3 - 1e-6
    assert title[:, 1].max() <= 297 - 18 - 1 + 1e-6 and len(title) > 20  # the whole title, on its baseline


def test_the_png_print_says_its_size_in_mm(silhouette) -> None:
    # A cutter's program sizes an imported picture by its resolution: the print must come out A4, so the
    # marks land where the cut file has them.
    from PIL import Image

    with Image.open(silhouette / "net.png") as im:
        dpi, size, pixels = im.info["dpi"], im.size, np.asarray(im.convert("RGB")).astype(int)
    assert np.allclose(np.array(size) / np.array(dpi) * 25.4, (210, 297), atol=0.1)
    px = size[0] / 210
    for x, y in [(12.5, 12.5), (210 - 20, 10.25), (10.25, 297 - 20)]:
        assert (pixels[int(y * px), int(x * px)] < 40).all()  # the marks, black, where the SVG has them


def test_cricut_art_keeps_inside_its_print_then_cut_area(tmp_path) -> None:
    folder = make(tmp_path, cutter="cricut", formats=("svg",))
    gp, gc = groups(folder / "net.svg"), groups(folder / "net.cut.svg")
    cut = np.concatenate([r for p in gc["CUT"].iter(f"{SVG}path") for r in rings_of(p.get("d"))])
    x0, y0 = (210 - 171.45) / 2, (297 - 234.95) / 2
    assert cut[:, 0].min() >= x0 - 1e-6 and cut[:, 0].max() <= 210 - x0 + 1e-6
    assert cut[:, 1].min() >= y0 - 1e-6 and cut[:, 1].max() <= 297 - y0 + 1e-6
    marks = rings_of(gp["REGISTRATION"].find(f"{SVG}path").get("d"))
    again = rings_of(gc["REGISTRATION"].find(f"{SVG}path").get("d"))
    assert len(marks) == 4 and all(np.array_equal(a, b) for a, b in zip(marks, again))
    # Four Ls of one-inch arms frame the area's corners, every point outside it.
    for m in marks:
        assert np.allclose(m.max(axis=0) - m.min(axis=0), 25.4)
        inside = (m[:, 0] > x0) & (m[:, 0] < 210 - x0) & (m[:, 1] > y0) & (m[:, 1] < 297 - y0)
        assert not inside.any()


def _cli(*args, cwd):
    import sys

    return subprocess.run([sys.executable, "-m", "voxfab", "net", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


def test_the_cli_reads_a_coloured_vox_and_writes_print_then_cut_files(tmp_path) -> None:
    from voxfab.io import write

    shape = hero()
    write(shape, tmp_path / "hero.vox")
    r = _cli("hero.vox", "-o", "n.svg", "-o", "n.json", "--face-size", "8", "--cutter", "cricut", "--bleed", "2",
             "--seed", "1", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["written"] == ["n.svg", "n.cut.svg", "n.json"]
    net = json.loads((tmp_path / "n.json").read_text())
    faces = faces_of_svg(tmp_path / "n.svg")
    assert all(faces[i] == voxel_hex(shape, f["voxel"]) == f["colour"] for i, f in enumerate(net["faces"]))
    # The bleed asked for: a face's bleed ring reaches 2 mm past its square.
    bleed = [r for name, _, rings in filled_paths(tmp_path / "n.svg") if name.startswith("bleed-") for r in rings]
    squares = [r for r in bleed if len(np.unique(r[:, 0])) == 2 and len(np.unique(r[:, 1])) == 2]
    sizes = {round(float(s), 3) for r in squares for s in r.max(axis=0) - r.min(axis=0)}
    assert sizes == {8.0, 10.0, 12.0}  # faces grown by 2 mm across none, one or two opposite edges


def faces_of_svg(svg: Path) -> dict[int, str]:
    return {int(name[5:]): fill for name, fill, _ in filled_paths(svg) if name.startswith("face-")}


@pytest.mark.parametrize(("flag", "value"), [("--cutter", "brother"), ("--bleed", "-1"), ("--bleed", "nan"),
                                             ("--bleed", "11")])
def test_bad_cutter_or_bleed_is_one_line(tmp_path, flag, value) -> None:
    np.save(tmp_path / "g.npy", np.ones((2, 2, 2), bool))
    r = _cli("g.npy", "-o", "n.svg", flag, value, cwd=tmp_path)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert flag.lstrip("-") in r.stderr


def test_a_recipe_paints_and_asks_for_print_then_cut_files(tmp_path) -> None:
    from voxfab.recipe import build, load_recipe

    (tmp_path / "ball.toml").write_text('''
name = "ball"
pitch = 3.0
[source]
maker = "implicit"
expression = "x^2 + y^2 + z^2 - 1"
size = 6
[[operations]]
op = "paint"
colour = "#c03020"
where = "3 - z"
[outputs.net]
face_size = 9
formats = ["svg", "pdf"]
cutter = "silhouette"
bleed = 1.5
''')
    folder = build(load_recipe(tmp_path / "ball.toml"), tmp_path / "out")
    assert {"net.json", "net.svg", "net.cut.svg", "net.pdf"} <= {p.name for p in folder.iterdir()}
    colours = {f["colour"] for f in json.loads((folder / "net.json").read_text())["faces"]}
    assert colours == {"#c03020", "#ffffff"}  # painted where z > 3, the rest white
    manifest = (folder / "manifest.json").read_text()
    assert "net.cut.svg" in manifest and "register" in manifest
