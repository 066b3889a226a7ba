"""Net drawing files: SVG, DXF and PDF read back by independent parsers, CLI hooks and recipes."""

from __future__ import annotations

import argparse
import shutil
import subprocess
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from _handnets import tree_net

from voxfab.errors import UnknownFormatError
from voxfab.fabricate.netdraw import DrawingOptions, add_drawing_arguments, draw_net, write_drawing
from voxfab.shape import VoxelShape, examples, surface_graph
from voxfab.unfold import Net


def drawing_args(*argv: str, pitch: float | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_drawing_arguments(parser)
    args = parser.parse_args(list(argv))
    args.pitch = pitch
    return args


BALL = examples.ball(3)


@pytest.fixture(scope="module")
def ball_net() -> Net:
    """A net of the r = 3 ball from the net engine."""
    from voxfab.unfold import unfold

    return unfold(BALL, rng=2, timeout=30.0)


def test_drawing_arguments_leave_command_options_alone() -> None:
    parser = argparse.ArgumentParser()
    add_drawing_arguments(parser)
    options = {s for a in parser._actions for s in a.option_strings}
    assert {"--sheet", "--margin", "--tab-width", "--tab-angle", "--dxf-version", "--grid-lines",
            "--perforate", "--colors"} <= options
    assert not options & {"--pitch", "-o", "--seed", "--count", "--strategy", "--timeout", "--fit",
                          "--pieces", "--fill", "--repo", "--debug"}


def test_svg_reads_back_in_mm(tmp_path: Path, ball_net: Net) -> None:
    from lxml import etree

    out = tmp_path / "ball.svg"
    lines = write_drawing(VoxelShape(BALL), ball_net, out, drawing_args("--sheet", "A3", "--grid-lines"),
                          title="ball")
    assert lines[-1] == f"wrote {out}"
    root = etree.parse(str(out)).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    assert root.get("width") == "297mm" and root.get("height") == "420mm"
    assert root.get("viewBox") == "0 0 297 420"
    groups = root.findall("s:g", ns)
    assert [g.get("id") for g in groups] == ["LABEL", "GRID", "VALLEY", "MOUNTAIN", "CUT"]
    style = {g.get("id"): (g.get("stroke"), g.get("stroke-dasharray"), g.get("stroke-width")) for g in groups}
    assert style["CUT"] == ("#ff0000", None, "0.01")
    assert style["MOUNTAIN"][0] == "#0000ff" and style["MOUNTAIN"][1]
    assert style["VALLEY"][0] == "#00ff00" and len(style["VALLEY"][1].split()) == 4
    # The cut outline path lies inside the sheet.
    import svgpathtools

    cut = groups[-1].find("s:path", ns).get("d")
    path = svgpathtools.parse_path(cut)
    xmin, xmax, ymin, ymax = path.bbox()
    assert 10 <= xmin < xmax <= 287 and 10 <= ymin < ymax <= 410
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
    write_drawing(VoxelShape(BALL), net, out, args, title="ball")
    doc = ezdxf.readfile(out)
    auditor = doc.audit()
    assert not auditor.has_errors, [e.message for e in auditor.errors]
    assert not auditor.has_fixes, [f.message for f in auditor.fixes]
    assert doc.dxfversion == {"R12": "AC1009", "R2000": "AC1015"}[version]
    assert {"CUT", "MOUNTAIN", "VALLEY", "GRID", "LABEL"} <= {layer.dxf.name for layer in doc.layers}
    assert doc.layers.get("CUT").color == 1 and doc.layers.get("MOUNTAIN").color == 5
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
    write_drawing(VoxelShape(BALL), ball_net, out, drawing_args(), title="ball")
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
    blue = rgb[..., 2] - np.maximum(rgb[..., 0], rgb[..., 1]) > 60
    assert red.sum() > 100 and blue.sum() > 20


def test_split_sheets_write_numbered_files(tmp_path: Path) -> None:
    g = np.ones((3, 3, 3), dtype=bool)
    net = tree_net(g)
    args = drawing_args(pitch=40.0)
    d = draw_net(g, net, options=DrawingOptions(pitch=40.0))
    n = len(d.sheets)
    assert n > 1
    for ext in ("svg", "dxf"):
        lines = write_drawing(VoxelShape(g), net, tmp_path / f"box.{ext}", args, title="box")
        assert [ln for ln in lines if ln.startswith("wrote")] == [
            f"wrote {tmp_path / f'box.sheet-{i}.{ext}'}" for i in range(1, n + 1)]
    write_drawing(VoxelShape(g), net, tmp_path / "box.pdf", args, title="box")
    assert (tmp_path / "box.pdf").read_bytes().count(b"/Type /Page ") == n
    assert not (tmp_path / "box.svg").exists()


def test_same_input_same_bytes(tmp_path: Path, ball_net: Net) -> None:
    net = ball_net
    for argv in ((), ("--dxf-version", "R2000")):
        for ext in ("svg", "dxf", "pdf"):
            a, b = tmp_path / f"a.{ext}", tmp_path / f"b.{ext}"
            write_drawing(VoxelShape(BALL), net, a, drawing_args(*argv), title="ball")
            write_drawing(VoxelShape(BALL), net, b, drawing_args(*argv), title="ball")
            assert a.read_bytes() == b.read_bytes(), ext


def test_colors_reach_the_files(tmp_path: Path, ball_net: Net) -> None:
    import ezdxf
    from lxml import etree

    args = drawing_args("--colors", "cut=blue,mountain=#ff0000:dotted", "--dxf-version", "R2000")
    write_drawing(VoxelShape(BALL), ball_net, tmp_path / "c.svg", args)
    write_drawing(VoxelShape(BALL), ball_net, tmp_path / "c.dxf", args)
    root = etree.parse(str(tmp_path / "c.svg")).getroot()
    strokes = {g.get("id"): g.get("stroke") for g in root}
    assert strokes["CUT"] == "#0000ff" and strokes["MOUNTAIN"] == "#ff0000"
    doc = ezdxf.readfile(tmp_path / "c.dxf")
    assert doc.layers.get("CUT").color == 5 and doc.layers.get("MOUNTAIN").dxf.linetype == "DOT"


def test_unknown_extension(tmp_path: Path, ball_net: Net) -> None:
    with pytest.raises(UnknownFormatError, match="unknown drawing format"):
        write_drawing(VoxelShape(BALL), ball_net, tmp_path / "x.eps", drawing_args())


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

    recipe = load_recipe(_recipe(tmp_path, 'formats = ["svg", "dxf", "pdf"]\nsheet = "A3"\nperforate = "valley"'))
    folder = build(recipe, tmp_path / "out")
    manifest = (folder / "manifest.json").read_text()
    for name in ("net.json", "net.svg", "net.dxf", "net.pdf"):
        assert (folder / name).is_file() and name in manifest
    net = Net.from_json((folder / "net.json").read_text())
    assert net.seed == 4 and net.face_count == surface_graph(examples.ball(2)).face_count
    assert "<title>ball  PITCH" in (folder / "net.svg").read_text()
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
    title = root.find("{http://www.w3.org/2000/svg}title").text.split("  PITCH")[0]
    write_drawing(VoxelShape(examples.ball(2)), net, again, args, title=title)
    assert again.read_bytes() == outs[1].read_bytes()


def test_recipe_output_asks_the_engine_for_a_net_that_fits(tmp_path: Path) -> None:
    from voxfab.errors import RecipeError
    from voxfab.fabricate.netdraw import recipe_output

    shape = VoxelShape(examples.ball(3))
    files = recipe_output(shape, tmp_path, name="ball", seed=1, formats=["svg"], sheet="200x150",
                          margin=5.0, pitch=6.0, fit=True, timeout=30.0)
    assert [f.path for f in files] == ["net.json", "net.svg"]
    net = Net.from_json((tmp_path / "net.json").read_text())
    x0, y0, x1, y1 = net.bounds()
    # 200 x 150 mm less margins, title band and tab room, in 6 mm cells.
    assert (x1 - x0) <= (200 - 10 - 10) // 6 and (y1 - y0) <= (150 - 10 - 5 - 10) // 6
    with pytest.raises(RecipeError, match="fit"):
        recipe_output(shape, tmp_path, name="ball", seed=1, fit=True)
    with pytest.raises(RecipeError, match="formats"):
        recipe_output(shape, tmp_path, name="ball", seed=1, formats=["png"])
