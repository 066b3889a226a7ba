"""The marks of the bundled queen's paper net, read back from the files written: every line kind in a colour of
its own in every format, and seam labels that never run together."""

from __future__ import annotations

import re
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests._net_sheets import queen
from voxfab.drawing import LAYERS
from voxfab.fabricate.netdraw import DrawingOptions, draw_net, save_drawing

#: The queen recipe's paper net: 8.6 mm faces on a 900 x 600 mm laser bed with 2 mm seam labels; every fold drawn.
QUEEN_NET = {"pitch": 8.6, "sheet": "900x600", "label_height": 2.0, "grid_lines": True}
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def queen_files(tmp_path_factory) -> tuple[Path, Any]:
    """The queen's one-piece net drawn once and written as SVG, R12 and R2000 DXF, and PDF."""
    from voxfab.unfold import unfold

    grid = queen()
    folder = tmp_path_factory.mktemp("queen-marks")
    drawing = draw_net(grid, unfold(grid, rng=1), options=DrawingOptions(**QUEEN_NET, heading=False), name="queen")
    assert len(drawing.sheets) == 1
    save_drawing(drawing, folder / "queen.svg", DrawingOptions(**QUEEN_NET))
    save_drawing(drawing, folder / "queen.dxf", DrawingOptions(**QUEEN_NET))
    save_drawing(drawing, folder / "queen-2000.dxf", DrawingOptions(**QUEEN_NET, dxf_version="R2000"))
    save_drawing(drawing, folder / "queen.pdf", DrawingOptions(**QUEEN_NET))
    return folder, drawing


def test_every_layer_has_a_colour_of_its_own_in_every_format(queen_files) -> None:
    import ezdxf
    from lxml import etree

    folder, _ = queen_files
    # DXF: the layer table names every layer (the plates' SCORE too); a colour (ACI) maps one layer.
    for name in ("queen.dxf", "queen-2000.dxf"):
        doc = ezdxf.readfile(folder / name)
        assert not doc.audit().has_errors
        colours = {layer.dxf.name: layer.dxf.color for layer in doc.layers if layer.dxf.name in LAYERS}
        assert colours.keys() == set(LAYERS) >= {"CUT", "MOUNTAIN", "VALLEY", "SCORE", "GRID", "LABEL"}
        assert len(set(colours.values())) == len(colours), (name, colours)
        # The lines take their layer's colour.
        assert {e.dxf.color for e in doc.modelspace()} <= {256}  # BYLAYER
    # SVG: one group per line kind used, each with its own stroke.
    groups = etree.parse(str(folder / "queen.svg")).getroot().findall(f"{SVG}g")
    strokes = {g.get("id"): g.get("stroke") for g in groups}
    assert {"CUT", "MOUNTAIN", "VALLEY", "GRID", "LABEL"} <= strokes.keys()
    assert len(set(strokes.values())) == len(strokes), strokes
    # PDF: each layer's lines are stroked after setting its colour (RG) once.
    data = (folder / "queen.pdf").read_bytes()
    content = b"".join(zlib.decompress(m.group(1)) for m in
                       re.finditer(rb"/FlateDecode >>\nstream\n(.*?)\nendstream", data, re.S))
    set_colours = re.findall(rb"([\d.]+ [\d.]+ [\d.]+) RG", content)
    assert len(set_colours) >= 5  # cut, mountain, valley, grid, labels
    assert len(set(set_colours)) == len(set_colours), set_colours


def _svg_strokes(path: Path, layer: str) -> list[np.ndarray]:
    """The polylines of one layer of a voxfab SVG, in mm."""
    from lxml import etree

    group = next(g for g in etree.parse(str(path)).getroot().findall(f"{SVG}g") if g.get("id") == layer)
    out = []
    for p in group.findall(f"{SVG}path"):
        for sub in re.split(r"(?=M)", p.get("d")):
            pts = [tuple(map(float, xy.split(","))) for xy in re.findall(r"-?[\d.]+,-?[\d.]+", sub)]
            if pts:
                out.append(np.array(pts))
    return out


def _across_a_cut(a: Any, b: Any, cuts: Any) -> bool:
    """Whether the shortest way from ``a`` to ``b`` crosses a cut line: then they end on separate pieces of paper."""
    import shapely
    from shapely.ops import nearest_points

    return bool(shapely.LineString(nearest_points(a, b)).intersects(cuts))


def _groups(geoms: list[Any], reach: float, cuts: Any) -> list[list[int]]:
    """Geometries joined when closer than ``reach`` on the same side of every cut line (single linkage)."""
    import shapely

    tree = shapely.STRtree(geoms)
    parent = list(range(len(geoms)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in zip(*(x.tolist() for x in tree.query(geoms, predicate="dwithin", distance=reach))):
        if i < j and root(i) != root(j) and not _across_a_cut(geoms[i], geoms[j], cuts):
            parent[root(i)] = root(j)
    out: dict[int, list[int]] = {}
    for i in range(len(geoms)):
        out.setdefault(root(i), []).append(i)
    return list(out.values())


def test_seam_labels_stand_a_letter_apart(queen_files) -> None:
    import shapely

    folder, drawing = queen_files
    h = drawing.label_height
    assert h == pytest.approx(2.0)
    letter = 4 / 6 * h  # the width of a letter of the single-stroke font: 4 wide, 6 tall
    cuts = shapely.MultiLineString([p for p in _svg_strokes(folder / "queen.svg", "CUT") if len(p) > 1])
    strokes = [shapely.LineString(p) for p in _svg_strokes(folder / "queen.svg", "LABEL") if len(p) > 1]
    # Letters of one label are at most three font units apart ("1" is 2 wide in its box of 4): strokes closer
    # than 3.5 units are one label, unless a cut line runs between them.
    labels = [shapely.MultiLineString([strokes[i] for i in g]) for g in _groups(strokes, 3.5 / 6 * h, cuts)]
    # Each group is one label: its two seam ends' labels are all there, none merged with another.
    assert len(labels) == 2 * drawing.seams
    sides = np.sort(np.array([np.subtract(*np.reshape(g.bounds, (2, 2))[::-1]) for g in labels]), axis=1)
    chars = drawing.label_chars
    assert sides[:, 0].max() <= h + 1e-3
    assert sides[:, 1].max() <= ((chars - 1) * 5 + 4) / 6 * h + 1e-3
    # No two labels on the same paper (no cut between them) come closer than a letter's width; the file
    # rounds coordinates to 0.001 mm.
    tree = shapely.STRtree(labels)
    close = [(i, j) for i, j in zip(*(x.tolist() for x in tree.query(labels, predicate="dwithin", distance=letter)))
             if i < j and not _across_a_cut(labels[i], labels[j], cuts)]
    gaps = sorted(labels[i].distance(labels[j]) for i, j in close)
    assert not gaps or gaps[0] >= letter - 2e-3, gaps[:10]
