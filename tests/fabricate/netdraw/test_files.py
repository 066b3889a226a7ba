"""Net drawing files: SVG, DXF and PDF read back by independent parsers, CLI hooks and recipes."""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from voxfab.cli._options import add_option_arguments, options_from_args
from voxfab.errors import UnknownFormatError
from voxfab.fabricate.netdraw import DrawingOptions, draw_net, write_net_drawing
from voxfab.shape import VoxelShape, examples, surface_graph
from voxfab.unfold import Net


def drawing_args(*argv: str, pitch: float | None = None) -> DrawingOptions:
    """The drawing options of ``voxfab net`` parsed from ``argv``."""
    parser = argparse.ArgumentParser()
    add_option_arguments(parser, DrawingOptions)
    return options_from_args(DrawingOptions, parser.parse_args(list(argv)), pitch=pitch)


BALL = examples.ball(3)


@pytest.fixture(scope="module")
def ball_net() -> Net:
    """A net of the r = 3 ball from the net engine."""
    from voxfab.unfold import unfold

    return unfold(BALL, rng=2, timeout=30.0)


def test_drawing_arguments_leave_command_options_alone() -> None:
    parser = argparse.ArgumentParser()
    add_option_arguments(parser, DrawingOptions)
    options = {s for a in parser._actions for s in a.option_strings}
    assert {"--sheet", "--margin", "--tab-width", "--tab-angle", "--dxf-version", "--grid-lines",
            "--perforate", "--colors", "--no-numbers", "--no-tabs", "--min-label-height", "--min-tab-depth",
            "--svg-lines"} <= options
    assert not options & {"--pitch", "-o", "--seed", "--count", "--strategy", "--timeout", "--fit",
                          "--pieces", "--fill", "--repo", "--debug"}


def test_svg_reads_back_in_mm(tmp_path: Path, ball_net: Net) -> None:
    from lxml import etree

    out = tmp_path / "ball.svg"
    result = write_net_drawing(BALL, ball_net, out, drawing_args("--sheet", "A2", "--grid-lines"), title="ball")
    assert result.files == [str(out)]
    root = etree.parse(str(out)).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    assert root.get("width") == "420mm" and root.get("height") == "594mm"
    assert root.get("viewBox") == "0 0 420 594"
    groups = root.findall("s:g", ns)
    assert [g.get("id") for g in groups] == ["LABEL", "GRID", "VALLEY", "MOUNTAIN", "CUT"]
    style = {g.get("id"): (g.get("stroke"), g.get("stroke-dasharray"), g.get("stroke-width")) for g in groups}
    assert style["CUT"] == ("#ff0000", None, "0.01")
    assert style["MOUNTAIN"][0] == "#ff00ff" and style["MOUNTAIN"][1]
    assert style["VALLEY"][0] == "#00ff00" and len(style["VALLEY"][1].split()) == 4
    # The cut outline path lies inside the sheet.
    import svgpathtools

    cut = groups[-1].find("s:path", ns).get("d")
    path = svgpathtools.parse_path(cut)
    xmin, xmax, ymin, ymax = path.bbox()
    assert 10 <= xmin < xmax <= 410 and 10 <= ymin < ymax <= 584
    assert path.isclosed()


def _dxf_lengths(doc) -> dict[str, float]:
    lengths: Counter[str] = Counter()
    for e in doc.modelspace():
        if e.dxftype() == "LINE":
            lengths[e.dxf.layer] += float(np.hypot(*(np.array(e.dxf.end)[:2] - np.array(e.dxf.start)[:2])))
        else:
            if e.dxftype() == "LWPOLYLINE":
                pts = np.array([p[:2] for p in e.get_points("xy")], dtype=float)
            else:
                pts = np.array([(v.dxf.location.x, v.dxf.location.y) for v in e.vertices], dtype=float)
            if e.is_closed:
                pts = np.vstack([pts, pts[:1]])
            lengths[e.dxf.layer] += float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    return lengths


@pytest.mark.parametrize("version", ["R12", "R2000"])
def test_dxf_passes_audit_and_reads_back(tmp_path: Path, version: str, ball_net: Net) -> None:
    import ezdxf

    net = ball_net
    out = tmp_path / "ball.dxf"
    args = drawing_args("--dxf-version", version, "--grid-lines", "--sheet", "600x600", pitch=20.0)
    write_net_drawing(BALL, net, out, args, title="ball")
    doc = ezdxf.readfile(out)
    auditor = doc.audit()
    assert not auditor.has_errors, [e.message for e in auditor.errors]
    assert not auditor.has_fixes, [f.message for f in auditor.fixes]
    assert doc.dxfversion == {"R12": "AC1009", "R2000": "AC1015"}[version]
    assert {"CUT", "MOUNTAIN", "VALLEY", "GRID", "LABEL"} <= {layer.dxf.name for layer in doc.layers}
    assert doc.layers.get("CUT").color == 1 and doc.layers.get("MOUNTAIN").color == 6
    assert doc.layers.get("MOUNTAIN").dxf.linetype == "DASHED"
    kinds = {e.dxftype() for e in doc.modelspace()}
    assert kinds <= ({"LINE", "POLYLINE"} if version == "R12" else {"LINE", "LWPOLYLINE"})
    if version == "R2000":
        assert doc.header["$INSUNITS"] == 4
    # Lengths per layer equal the drawing's, and the folds equal the net's.
    d = draw_net(BALL, net, options=DrawingOptions(pitch=20.0, grid_lines=True, sheet="600x600"), name="ball")
    assert len(d.sheets) == 1
    got = _dxf_lengths(doc)
    for layer in ("CUT", "MOUNTAIN", "VALLEY", "GRID"):
        assert got[layer] == pytest.approx(d.sheets[0].layers[layer].length(), abs=1e-3)
    counts = surface_graph(BALL).fold
    assert d.fold_counts["mountain"] + d.fold_counts["valley"] + d.fold_counts["flat"] == len(net.folds)
    assert got["VALLEY"] == pytest.approx(
        d.fold_counts["valley"] * 20.0 + d.tab_fold_length[d.seam_type < 0].sum(), abs=1e-3)
    assert (counts == -1).any()


def test_pdf_renders_non_blank(tmp_path: Path, ball_net: Net) -> None:
    out = tmp_path / "ball.pdf"
    # A4 takes this net at 9.4 mm faces only: too small for numbers, so they are left out explicitly.
    write_net_drawing(BALL, ball_net, out, drawing_args("--no-numbers"), title="ball")
    data = out.read_bytes()
    assert data.startswith(b"%PDF-1.4") and b"CreationDate" not in data
    if shutil.which("pdftoppm") is None:
        pytest.skip("pdftoppm (poppler-utils) is not installed; cannot render the PDF")
    subprocess.run(["pdftoppm", "-r", "60", "-png", str(out), str(tmp_path / "page")], check=True)
    from PIL import Image

    img = np.asarray(Image.open(tmp_path / "page-1.png").convert("RGB"))
    assert abs(img.shape[0] - 297 / 25.4 * 60) < 2 and abs(img.shape[1] - 210 / 25.4 * 60) < 2
    rgb = img.astype(int)
    red = rgb[..., 0] - np.maximum(rgb[..., 1], rgb[..., 2]) > 60
    magenta = np.minimum(rgb[..., 0], rgb[..., 2]) - rgb[..., 1] > 60
    assert red.sum() > 100 and magenta.sum() > 20


def test_pieces_packed_on_sheets_write_numbered_files(tmp_path: Path) -> None:
    from voxfab.fabricate.netdraw import DrawingOptions, draw_pieces, write_net_drawing
    from voxfab.unfold import unfold

    g = np.ones((3, 3, 3), dtype=bool)
    pieces = unfold(g, rng=1, fit=(3, 4), pieces="auto", timeout=20.0)
    assert len(pieces) > 1
    options = DrawingOptions(pitch=40.0)
    d = draw_pieces(g, pieces, options=options)
    n = len(d.sheets)
    assert n > 1 and d.pieces == len(pieces)
    for ext in ("svg", "dxf"):
        result = write_net_drawing(g, pieces, tmp_path / f"box.{ext}", options, title="box")
        assert result.files == [str(tmp_path / f"box.sheet-{i}.{ext}") for i in range(1, n + 1)]
        assert any(w.startswith(f"net split into {len(pieces)} pieces") for w in result.warnings)
    write_net_drawing(g, pieces, tmp_path / "box.pdf", options, title="box")
    # The sheets, after the assembly page.
    assert (tmp_path / "box.pdf").read_bytes().count(b"/Type /Page ") == n + 1
    assert not (tmp_path / "box.svg").exists()


def test_same_input_same_bytes(tmp_path: Path, ball_net: Net) -> None:
    net = ball_net
    for argv in (("--sheet", "A2"), ("--sheet", "A2", "--dxf-version", "R2000")):
        for ext in ("svg", "dxf", "pdf"):
            a, b = tmp_path / f"a.{ext}", tmp_path / f"b.{ext}"
            write_net_drawing(BALL, net, a, drawing_args(*argv), title="ball")
            write_net_drawing(BALL, net, b, drawing_args(*argv), title="ball")
            assert a.read_bytes() == b.read_bytes(), ext


def test_colors_reach_the_files(tmp_path: Path, ball_net: Net) -> None:
    import ezdxf
    from lxml import etree

    args = drawing_args("--colors", "cut=blue,mountain=#ff0000:dotted", "--dxf-version", "R2000", "--sheet", "A2")
    write_net_drawing(BALL, ball_net, tmp_path / "c.svg", args)
    write_net_drawing(BALL, ball_net, tmp_path / "c.dxf", args)
    root = etree.parse(str(tmp_path / "c.svg")).getroot()
    strokes = {g.get("id"): g.get("stroke") for g in root}
    assert strokes["CUT"] == "#0000ff" and strokes["MOUNTAIN"] == "#ff0000"
    doc = ezdxf.readfile(tmp_path / "c.dxf")
    assert doc.layers.get("CUT").color == 5 and doc.layers.get("MOUNTAIN").dxf.linetype == "DOT"


def test_unknown_extension(tmp_path: Path, ball_net: Net) -> None:
    with pytest.raises(UnknownFormatError, match="unknown drawing format"):
        write_net_drawing(BALL, ball_net, tmp_path / "x.eps", drawing_args())


def _recipe(tmp_path: Path, outputs: str) -> Path:
    np.save(tmp_path / "ball.npy", examples.ball(2))
    path = tmp_path / "ball.toml"
    path.write_text(f'name = "ball"\nseed = 4\n[source]\nfile = "ball.npy"\n[outputs.net]\n{outputs}\n')
    return path


@pytest.mark.parametrize("line, key", [
    ('tab_width = "wide"', "tab_width"),
    ('perforate = "both"', "perforate"),
    ("formats = 3", "formats"),
    ("paper = 1", "paper"),
])
def test_recipe_rejects_bad_net_options(tmp_path: Path, line: str, key: str) -> None:
    from voxfab.errors import RecipeError
    from voxfab.recipe import load_recipe

    with pytest.raises(RecipeError, match=key):
        load_recipe(_recipe(tmp_path, line))


def test_recipe_builds_net_json_and_drawings(tmp_path: Path) -> None:
    import json

    import voxfab.unfold as unfold

    if not hasattr(unfold, "unfold"):
        pytest.skip("the net engine (voxfab.unfold.unfold) is not available yet")
    from voxfab.recipe import build, load_recipe

    recipe = load_recipe(_recipe(tmp_path, 'formats = ["svg", "dxf", "pdf"]\nsheet = "A3"\nperforate = "valley"\nface_size = 12.0'))
    folder = build(recipe, tmp_path / "out")
    manifest = (folder / "manifest.json").read_text()
    for name in ("net.json", "net.svg", "net.dxf", "net.pdf"):
        assert (folder / name).is_file() and name in manifest
    net = Net.from_json((folder / "net.json").read_text())
    assert net.seed == 4 and net.face_count == surface_graph(examples.ball(2)).face_count
    assert "<title>ball  FACES" in (folder / "net.svg").read_text()
    outputs = json.dumps(json.loads(manifest))
    assert "laser" in outputs and "print at 100 %" in outputs


def test_voxfab_net_writes_all_drawings_of_one_net(tmp_path: Path) -> None:
    import ezdxf
    from lxml import etree

    from voxfab.cli import main

    np.save(tmp_path / "ball.npy", examples.ball(2))
    outs = [tmp_path / f"n.{ext}" for ext in ("json", "svg", "dxf", "pdf")]
    argv = ["net", str(tmp_path / "ball.npy"), "--seed", "5", "--pitch", "12", "--sheet", "A3",
            "--tab-width", "4", "--grid-lines"]
    for p in outs:
        argv += ["-o", str(p)]
    assert main(argv) == 0
    net = Net.from_json(outs[0].read_text())
    assert net.seed == 5
    root = etree.parse(str(outs[1])).getroot()
    assert root.get("width") == "297mm"
    assert not ezdxf.readfile(outs[2]).audit().has_errors
    assert outs[3].read_bytes().startswith(b"%PDF")
    # The drawings show the JSON's net: drawn again from it, the SVG is the same.
    again = tmp_path / "again.svg"
    args = drawing_args("--sheet", "A3", "--tab-width", "4", "--grid-lines", pitch=12.0)
    title = root.find("{http://www.w3.org/2000/svg}title").text.split("  FACES")[0]
    write_net_drawing(examples.ball(2), net, again, args, title=title)
    assert again.read_bytes() == outs[1].read_bytes()


def test_net_pipeline_asks_the_engine_for_a_net_that_fits(tmp_path: Path) -> None:
    from voxfab.fabricate.netdraw import NetOptions, fabricate_net

    shape = VoxelShape(examples.ball(2))
    made = fabricate_net(shape, NetOptions(formats=("svg", "png"), timeout=30.0),
                         DrawingOptions(sheet="300x260", margin=5.0, pitch=11.0), tmp_path, name="ball", seed=1)
    assert [f.path for f in made.files] == ["net.json", "net.svg", "net.png"]
    assert made.report["face_size_mm"] == 11.0 and made.report["sheets"] == 1
    net = Net.from_json((tmp_path / "net.json").read_text())
    x0, y0, x1, y1 = net.bounds()
    # 300 x 260 mm less margins, title band and tab room, in 11 mm cells, either way round.
    cells = sorted([(300 - 10 - 10) // 11, (260 - 10 - 5 - 10) // 11])
    extent = sorted([x1 - x0, y1 - y0])
    assert extent[0] <= cells[0] and extent[1] <= cells[1]


def _dxf_segments(path: Path) -> dict[str, np.ndarray]:
    """Every straight piece per layer of a DXF file as ``(n, 2, 2)`` arrays, read with ezdxf."""
    import ezdxf

    out: dict[str, list] = {}
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "LINE":
            pts = np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
            closed = False
        elif e.dxftype() == "LWPOLYLINE":
            pts, closed = np.array([p[:2] for p in e.get_points("xy")]), e.closed
        else:
            pts, closed = np.array([tuple(v.dxf.location)[:2] for v in e.vertices]), e.is_closed
        if closed:
            pts = np.vstack([pts, pts[:1]])
        out.setdefault(e.dxf.layer, []).append(np.stack([pts[:-1], pts[1:]], axis=1))
    return {k: np.concatenate(v) for k, v in out.items()}


def _paper(cut: np.ndarray):
    """The paper the CUT segments outline: inside an odd number of their closed rings (holes stay empty)."""
    import functools

    import shapely

    faces = shapely.polygonize(shapely.linestrings(cut)).geoms
    return functools.reduce(shapely.symmetric_difference, [shapely.Polygon(f.exterior) for f in faces])


@pytest.fixture(scope="module")
def engine_dxf(tmp_path_factory, ball_net: Net):
    """The ball's net at the smallest legible face size on A2, as R12 DXF."""
    folder = tmp_path_factory.mktemp("dxf")
    # Two-character labels reach 2 mm at 6.8 mm; 3 mm tabs at 45 degrees need 7.5 mm.
    options = DrawingOptions(pitch=7.5, sheet="A2", grid_lines=True)
    from voxfab.fabricate.netdraw import write_net_drawing

    result = write_net_drawing(BALL, ball_net, folder / "ball.dxf", options, title="ball")
    return Path(result.files[0]), options, result


def test_dxf_cut_layer_polygonizes_inside_the_sheet_with_the_paper_area(engine_dxf, ball_net: Net) -> None:
    import ezdxf
    import shapely

    path, options, _ = engine_dxf
    paper = _paper(_dxf_segments(path)["CUT"])
    w, h = options.sheet_size
    margin = shapely.box(options.margin, options.margin, w - options.margin, h - options.margin)
    assert paper.within(margin)
    # Faces and tabs: the face area plus at least one 3 mm deep tab per seam with a tab.
    faces_area = ball_net.face_count * options.pitch**2
    assert faces_area < paper.area < faces_area + ball_net.face_count * options.pitch * 3.0
    doc = ezdxf.readfile(path)
    lo, hi = tuple(doc.header["$EXTMIN"])[:2], tuple(doc.header["$EXTMAX"])[:2]
    x0, y0, x1, y1 = paper.bounds
    assert lo[0] <= x0 and lo[1] <= y0 and hi[0] >= x1 and hi[1] >= y1


def test_tab_depth_and_text_height_measured_in_the_dxf(engine_dxf) -> None:
    import shapely

    path, options, result = engine_dxf
    seg = _dxf_segments(path)
    boundary = _paper(seg["CUT"]).boundary
    folds = np.concatenate([seg["MOUNTAIN"], seg["VALLEY"]])
    length = np.linalg.norm(folds[:, 1] - folds[:, 0], axis=1)
    # Folds between faces run whole face edges; tab folds are inset from the corners, so not a
    # whole number of face edges long.  A tab's depth is the distance from its fold's middle to
    # the outline on its short side.
    units = length / options.pitch
    tab_folds = folds[np.abs(units - np.round(units)) > 1e-3]
    assert len(tab_folds)
    depths = []
    for a, b in tab_folds:
        mid, d = (a + b) / 2, (b - a) / np.linalg.norm(b - a)
        n = np.array([-d[1], d[0]])
        hits = [shapely.intersection(boundary, shapely.LineString([mid, mid + s * n * 2 * options.pitch]))
                for s in (1, -1)]
        depths.append(min(shapely.distance(shapely.Point(mid), x) for x in hits if not x.is_empty))
    assert min(depths) >= options.min_tab_depth - 1e-3
    # Labels read along the face edges: a character's extent across its baseline is the cap height.
    label = shapely.union_all([x.buffer(0.01) for x in shapely.linestrings(seg["LABEL"])])
    heights = []
    for blob in label.geoms:
        x0, y0, x1, y1 = blob.bounds
        heights.append(max(x1 - x0, y1 - y0) - 0.02)
    assert np.median(heights) >= options.min_label_height - 1e-3
    told = re.search(r"(\d)-character labels (\d+\.\d) mm high", result.report[1])
    assert told and told[1] == "2" and float(told[2]) == pytest.approx(np.median(heights), abs=0.05)


def test_the_drawing_refolds_onto_the_shape(engine_dxf, ball_net: Net) -> None:
    """Faces and folds read back from the DXF alone make a net that refolds onto the ball."""
    import dataclasses

    from voxfab.unfold import validate

    path, options, _ = engine_dxf
    seg = _dxf_segments(path)
    p = options.pitch
    # Face squares: the cells the full-length folds and cut edges bound; every face edge of the
    # drawing is a full-length segment of CUT, MOUNTAIN, VALLEY or GRID, split at the lattice.
    def unit_edges(s: np.ndarray) -> set:
        out = set()
        for a, b in s:
            n = int(round(np.linalg.norm(b - a) / p))
            if n == 0 or abs(np.linalg.norm(b - a) - n * p) > 1e-3:
                continue
            for i in range(n):
                q0, q1 = a + (b - a) * i / n, a + (b - a) * (i + 1) / n
                out.add(tuple(sorted([tuple(np.round(q0, 3)), tuple(np.round(q1, 3))])))
        return out

    folds = unit_edges(np.concatenate([seg["MOUNTAIN"], seg["VALLEY"], seg["GRID"]]))
    # Map the JSON net's layout onto the drawing: the drawing is the layout moved (and maybe turned).
    c = ball_net.corners2d.astype(float)
    fold_pts = np.array([pt for e in folds for pt in e])
    for turned in (False, True):
        cc = np.stack([-c[..., 1], c[..., 0]], axis=-1) if turned else c
        mm = (cc - cc.reshape(-1, 2).min(axis=0)) * p
        # the shift that puts the layout's shared edges onto the drawing's folds
        for shift in fold_pts[0] - mm.reshape(-1, 2):
            pos = np.round(mm + shift, 3)
            edges = {tuple(sorted([tuple(pos[f, k]), tuple(pos[f, (k + 1) % 4])])): f
                     for f in range(len(pos)) for k in range(4)}
            if all(e in edges for e in folds):
                break
        else:
            continue
        break
    else:
        raise AssertionError("the drawing's folds do not match the net's layout")
    # Folds read from the drawing: pairs of faces whose edges coincide on a drawn fold line.
    owners: dict = {}
    for f in range(len(pos)):
        for k in range(4):
            owners.setdefault(tuple(sorted([tuple(pos[f, k]), tuple(pos[f, (k + 1) % 4])])), []).append(f)
    drawn = np.array(sorted(tuple(sorted(owners[e])) for e in folds if len(owners.get(e, [])) == 2))
    assert len(drawn) == len(folds)
    rebuilt = dataclasses.replace(ball_net, folds=drawn)
    assert validate(BALL, rebuilt).ok


def test_a_preview_svg_shows_its_lines_in_a_browser_and_a_laser_svg_keeps_hairlines(tmp_path: Path) -> None:
    """Chromium draws both files: the laser file's 0.01 mm strokes vanish, the preview's do not."""
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        pytest.skip("chromium is not installed")
    from PIL import Image

    from voxfab.fabricate.netdraw import write_net_drawing
    from voxfab.unfold import unfold

    g = np.ones((2, 2, 2), dtype=bool)
    net = unfold(g, rng=0)
    dark = {}
    for lines in ("laser", "preview"):
        svg = tmp_path / f"{lines}.svg"
        write_net_drawing(g, net, svg, DrawingOptions(pitch=20.0, svg_lines=lines))
        shot = tmp_path / f"{lines}.png"
        # A4 at 96 px per inch, as a browser shows a page of the file.
        subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                        "--window-size=794,1123", f"--screenshot={shot}", svg.as_uri()],
                       capture_output=True, timeout=120, check=False)
        img = np.asarray(Image.open(shot).convert("RGB")).astype(int)
        dark[lines] = int((img.sum(axis=-1) < 600).sum())
    assert dark["laser"] < 50 < 2000 < dark["preview"]
