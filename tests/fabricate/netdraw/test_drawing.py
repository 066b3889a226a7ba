"""Net drawings: geometry, tabs, seam labels and sheets, checked against the net and with shapely."""

from __future__ import annotations

import functools

import numpy as np
import pytest
import shapely
from _handnets import tree_net

from voxfab.drawing import Polylines
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.fabricate.netdraw import DrawingOptions, draw_net, parse_colors, parse_sheet
from voxfab.fabricate.netdraw._geometry import merge_unit_segments
from voxfab.fabricate.netdraw._legible import LABEL_ADVANCE
from voxfab.fabricate.netdraw._tabs import place_tabs
from voxfab.shape import examples, surface_graph
from voxfab.unfold import Net


def cross_net() -> tuple[np.ndarray, Net]:
    """The classic cross net of the unit cube: bottom in the middle, four sides, top on one side."""
    g = np.ones((1, 1, 1), dtype=bool)
    sg = surface_graph(g)
    bottom = int(np.flatnonzero(sg.direction == 5)[0])
    top = int(np.flatnonzero(sg.direction == 4)[0])
    sides = [int(x) for x in sg.neighbor[bottom]]
    tree = [(bottom, s) for s in sides] + [(sides[0], top)]
    return g, lay_out_rooted(g, tree, bottom)


def lay_out_rooted(grid: np.ndarray, tree: list[tuple[int, int]], root: int) -> Net:
    """Like :func:`lay_out` with a given tree, starting from ``root``."""
    sg = surface_graph(grid)
    nf = sg.face_count
    c2 = np.zeros((nf, 4, 2), dtype=np.int64)
    c2[root] = [(0, 0), (1, 0), (1, 1), (0, 1)]
    cells = {(0, 0)}
    for f, g in tree:
        k = int(np.flatnonzero(sg.neighbor[f] == g)[0])
        kk = int(sg.neighbor_edge[f, k])
        p0, p1 = c2[f, k], c2[f, (k + 1) % 4]
        d = p1 - p0
        n = np.array([d[1], -d[0]])
        c2[g, kk], c2[g, (kk + 1) % 4], c2[g, (kk + 2) % 4], c2[g, (kk + 3) % 4] = p1, p0, p0 + n, p1 + n
        cell = tuple(c2[g].min(axis=0).tolist())
        assert cell not in cells
        cells.add(cell)
    assert len(cells) == nf
    return Net(voxel=sg.voxel, normal=sg.normal, corners3d=sg.corners, corners2d=c2, folds=np.array(tree),
               seed=3, strategy="layout", mountain=len(tree))


L_SHAPE = np.array([[[1, 1], [1, 0]]], dtype=bool)
SHAPES = {
    "cube": np.ones((1, 1, 1), dtype=bool),
    "box112": np.ones((1, 1, 2), dtype=bool),
    "L": L_SHAPE,
    "ball1": examples.ball(1),
    "box333": np.ones((3, 3, 3), dtype=bool),
    "engine-ball2": examples.ball(2),
    "engine-ball4": examples.ball(4),
    "engine-tunnel5": examples.tunnel_cube(5),
    "engine-random": examples.random_shape(4, side=8),
}


@functools.cache
def net_of(name: str) -> Net:
    """Breadth-first layouts for the small shapes, the net engine's tab-aware nets for the others."""
    g = SHAPES[name]
    if name.startswith("engine-"):
        from voxfab.unfold import unfold

        return unfold(g, rng=11, timeout=60.0)
    return tree_net(g)


def expected_fold_lengths(grid: np.ndarray, net: Net, drawing) -> dict[str, float]:
    """Mountain and valley lengths from the net and the surface graph alone."""
    sg = surface_graph(grid)
    c = net.corners2d
    kinds = {1: 0, -1: 0}
    for f, g in net.folds.tolist():
        k = int(np.flatnonzero(sg.neighbor[f] == g)[0])
        if sg.fold[f, k] != 0:
            kinds[int(sg.fold[f, k])] += 1
    # Seams whose two sides already meet in the plane are left uncut: they fold too.
    fold_pairs = {tuple(sorted(p)) for p in net.folds.tolist()}
    for f in range(sg.face_count):
        for k in range(4):
            g, kk = int(sg.neighbor[f, k]), int(sg.neighbor_edge[f, k])
            if f < g and (f, g) not in fold_pairs:
                if (c[g, kk] == c[f, (k + 1) % 4]).all() and (c[g, (kk + 1) % 4] == c[f, k]).all():
                    if sg.fold[f, k] != 0:
                        kinds[int(sg.fold[f, k])] += 1
    p = drawing.pitch
    tab_m = drawing.tab_fold_length[drawing.seam_type >= 0].sum()
    tab_v = drawing.tab_fold_length[drawing.seam_type < 0].sum()
    return {"MOUNTAIN": kinds[1] * p + tab_m, "VALLEY": kinds[-1] * p + tab_v}


def all_layer(drawing, name: str) -> float:
    return sum(s.layers[name].length() for s in drawing.sheets)


def test_cross_net_of_the_cube() -> None:
    g, net = cross_net()
    d = draw_net(g, net, options=DrawingOptions(pitch=40.0), name="cube")
    (sheet,) = d.sheets
    assert sheet.pieces == 1
    cut = sheet.layers["CUT"]
    # One closed outline; the cross has no slit.
    assert len(cut) == 1 and cut.closed.all()
    assert d.seams == 7 and d.tab_seams.all()
    assert d.fold_counts == {"mountain": 5, "valley": 0, "flat": 0}
    assert all_layer(d, "MOUNTAIN") == pytest.approx(5 * 40.0 + 7 * d.tab_fold_length[0])
    assert d.title == "cube  FACES 40 MM  SEED 3"


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_fold_lengths_match_the_net(name: str) -> None:
    g = SHAPES[name]
    net = net_of(name)
    d = draw_net(g, net, options=DrawingOptions(pitch=15.0, sheet="2000x2000"), name=name)
    exp = expected_fold_lengths(g, net, d)
    assert all_layer(d, "MOUNTAIN") == pytest.approx(exp["MOUNTAIN"])
    assert all_layer(d, "VALLEY") == pytest.approx(exp["VALLEY"])
    assert all_layer(d, "GRID") == 0.0


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_tabs_never_overlap(name: str) -> None:
    g = SHAPES[name]
    net = net_of(name)
    d = draw_net(g, net, options=DrawingOptions(pitch=16.0, tab_width=6.0, sheet="2000x2000"), name=name)
    for sheet in d.sheets:
        faces = shapely.polygons(sheet.faces)
        tabs = shapely.polygons(sheet.tabs)
        # Faces tile without overlap; each tab meets its own face along its fold only.
        assert shapely.union_all(faces).area == pytest.approx(len(faces) * d.pitch**2)
        for i, t in enumerate(tabs):
            touching = shapely.intersects(faces, t)
            assert touching.sum() == 1
            assert shapely.intersection(faces[touching][0], t).area == pytest.approx(0, abs=1e-9)
            others = np.delete(tabs, i)
            assert not shapely.intersects(others, t).any()
        assert shapely.union_all(tabs).area == pytest.approx(shapely.area(tabs).sum())
        x0, y0 = 10.0, 10.0
        assert sheet.tabs[..., 0].min() >= x0 and sheet.tabs[..., 1].min() >= y0
        assert sheet.tabs[..., 0].max() <= sheet.width - x0 and sheet.tabs[..., 1].max() <= sheet.height - y0
    # Exactly one tab per glued seam that has room, none for the others.
    assert sum(len(s.tabs) for s in d.sheets) == int(d.tab_seams.sum())
    if name.startswith("engine-"):
        # Every seam the engine left tab room on gets a tab.
        assert len(d.marked_seams) <= net.seams_without_tab_room


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_cut_outline_is_closed_and_never_doubled(name: str) -> None:
    g = SHAPES[name]
    net = net_of(name)
    d = draw_net(g, net, options=DrawingOptions(pitch=15.0, sheet="2000x2000"), name=name)
    (sheet,) = d.sheets
    cut = sheet.layers["CUT"]
    a, b = cut.segments()
    lines = shapely.linestrings(np.stack([a, b], axis=1))
    # A line drawn twice would make the union shorter than the sum.
    assert shapely.union_all(lines).length == pytest.approx(cut.length())
    exteriors = int(cut.closed.sum())
    assert sheet.pieces == 1 and exteriors >= 1
    # The cut lines separate the paper from the sheet: the largest closed ring
    # encloses every face and tab.
    rings = [shapely.Polygon(x) for x, c in zip(cut.lines(), cut.closed) if c]
    outer = max(rings, key=lambda r: r.area)
    paper = shapely.union_all(np.concatenate([shapely.polygons(sheet.faces), shapely.polygons(sheet.tabs)]))
    assert outer.buffer(1e-6).contains(paper)


def test_every_seam_labelled_on_both_edges_inside_its_faces() -> None:
    g = examples.ball(1)
    net = tree_net(g)
    d = draw_net(g, net, options=DrawingOptions(pitch=20.0), name="")
    (sheet,) = d.sheets
    labels = sheet.layers["LABEL"]
    faces = shapely.polygons(sheet.faces)
    title_band = 10.0 + 3.0 + 2.0
    numbers = labels.points[labels.points[:, 1] > title_band]
    inside = shapely.STRtree(faces).query(shapely.points(numbers), predicate="within")
    # Every stroke point of the numbers lies strictly inside a face.
    assert np.unique(inside[0]).size == numbers.shape[0]
    title_strokes = int((labels.points[labels.offsets[:-1], 1] < title_band).sum())
    assert title_strokes > 10
    from voxfab.drawing._font import _local

    # 25 < seams <= 25²: two characters, one label per seam.
    assert 25 < d.seams <= 625 and d.label_chars == 2
    assert len(set(d.seam_labels)) == d.seams and {len(x) for x in d.seam_labels} == {2}
    strokes = sum(2 * len(_local(label)[1]) for label in d.seam_labels)
    marks = 2 * int((~d.tab_seams).sum())
    assert len(labels) == strokes + marks + title_strokes


def glyph_heights(lines: Polylines) -> list[float]:
    """Height of each single-stroke glyph of ``lines`` (strokes that touch form one glyph), mm."""
    geoms = [shapely.LineString(x) for x in lines.lines() if len(x) > 1]
    blobs = shapely.union_all([g.buffer(0.01) for g in geoms])
    out = []
    for blob in getattr(blobs, "geoms", [blobs]):
        x0, y0, x1, y1 = blob.bounds
        out.append(max(x1 - x0, y1 - y0) - 0.02)
    return out


def test_numbers_are_legible_or_refused_with_the_face_size_that_works() -> None:
    g, net = cross_net()
    # The cross has 7 seams: one-character labels.  They shrink with the face, down to 2 mm.
    d = draw_net(g, net, options=DrawingOptions(pitch=60.0, heading=False))
    assert d.label_height == 5.0 and d.warnings() == []
    small = draw_net(g, net, options=DrawingOptions(pitch=10.0, heading=False))
    assert 2.0 <= small.label_height < 5.0
    # Shrinking between the largest and the smallest height is by design: said in the report, not a warning.
    assert small.warnings() == []
    assert any(f"labels {small.label_height:.1f} mm high (fitted to the faces; at most 5 mm)" in line
               for line in small.report())
    # Measured from the LABEL geometry: the characters are that tall.
    heights = sorted(glyph_heights(small.sheets[0].layers["LABEL"]))
    assert np.median(heights) == pytest.approx(small.label_height, abs=0.02)
    with pytest.raises(InvalidShapeError, match=r"too small for 2 mm edge labels.*works is 6.7 mm.*--no-numbers"):
        draw_net(g, net, options=DrawingOptions(pitch=6.6, tabs=False))
    assert draw_net(g, net, options=DrawingOptions(pitch=6.7, tabs=False)).label_height >= 2.0
    with pytest.raises(InvalidShapeError, match=r"labels .* and 3 mm glue tabs .*works is 7.5 mm"):
        draw_net(g, net, options=DrawingOptions(pitch=6.0))
    # An explicit opt-out draws no numbers at all; tabs still need 3 mm.
    bare = draw_net(g, net, options=DrawingOptions(pitch=7.5, numbers=False, heading=False))
    assert len(bare.sheets[0].layers["LABEL"]) == 0 and bare.tab_height >= 3.0
    with pytest.raises(InvalidShapeError, match=r"3 mm glue tabs.*smallest face size that works is 7.5 mm"):
        draw_net(g, net, options=DrawingOptions(pitch=6.0, numbers=False))


def test_long_labels_on_small_faces_stay_inside_and_apart() -> None:
    from voxfab.drawing import text_polylines

    g = SHAPES["engine-ball4"]
    net = net_of("engine-ball4")
    # Two-character labels on the smallest faces with 3 mm tabs: pushed along their edges.
    d = draw_net(g, net, options=DrawingOptions(pitch=7.5, sheet="1000x1000", heading=False))
    assert d.label_chars == 2 and d.label_height >= 2.0
    (sheet,) = d.sheets
    labels = sheet.layers["LABEL"]
    numbers = labels
    faces = shapely.polygons(sheet.faces)
    inside = shapely.STRtree(faces).query(shapely.points(numbers.points), predicate="within")
    assert np.unique(inside[0]).size == numbers.points.shape[0]

    def blobs(lines: Polylines) -> int:
        geoms = [shapely.LineString(x) for x in lines.lines()]
        u = shapely.union_all([x.buffer(0.05) for x in geoms])
        return len(getattr(u, "geoms", [u]))

    # Glyphs of different labels never touch: the blobs are those of each label drawn alone.
    alone = sum(2 * blobs(text_polylines([label], [(0.0, 0.0)], [(1.0, 0.0)], d.label_height,
                                         advance=LABEL_ADVANCE)) for label in d.seam_labels)
    marks = 2 * int((~d.tab_seams).sum())
    assert blobs(labels) == alone + marks


def test_tabs_are_at_least_3_mm_deep() -> None:
    g = examples.ball(2)
    net = net_of("engine-ball2")
    d = draw_net(g, net, options=DrawingOptions(pitch=11.0, sheet="A2"))
    tabs = np.concatenate([s.tabs for s in d.sheets])
    # Depth of each trapezoid: distance from its top edge to its fold line.
    fold, top = tabs[:, 1] - tabs[:, 0], tabs[:, 3]
    unit = fold / np.linalg.norm(fold, axis=1, keepdims=True)
    rel = top - tabs[:, 0]
    depth = np.abs(rel[:, 0] * unit[:, 1] - rel[:, 1] * unit[:, 0])
    assert depth.min() >= 3.0 - 1e-9


def test_seams_meeting_in_the_plane_are_left_uncut() -> None:
    g = np.ones((1, 1, 2), dtype=bool)
    net = tree_net(g)
    d = draw_net(g, net, options=DrawingOptions(pitch=20.0))
    assert d.closed_in_plane == 2
    # 9 folds + 2 closed seams = 11 joins for 10 faces: 21 edges - 11 = 10... each face edge counted once.
    assert d.fold_counts["mountain"] + d.fold_counts["flat"] == len(net.folds) + 2
    assert d.seams == 20 - len(net.folds) - 2


def test_tab_placement_other_side_shrink_and_mark() -> None:
    # Faces A, B, C in a row and D above A; cells (0,0) (1,0) (2,0) (0,1), pitch 10.
    sq = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], dtype=float)
    pos = np.stack([sq + (0, 0), sq + (1, 0), sq + (2, 0), sq + (0, 1), sq + (4, 0)]) * 10.0 + 50.0
    sheet = np.zeros(5, dtype=np.int64)
    # Edges: 0 bottom, 1 right, 2 top, 3 left (counter-clockwise corners).
    sides = np.array([
        [[0, 1], [2, 3]],  # A right / C left: both face B -> no room, a mark
        [[0, 2], [2, 2]],  # A top is covered by D -> the tab goes on C top
        [[4, 3], [3, 2]],  # E left and D top: free cells, first side wins
        [[4, 1], [1, 0]],
    ])
    kw = dict(pitch=10.0, area=(0.0, 0.0, 200.0, 200.0), sheet_width=200.0, tab_width=4.0, tab_angle=45.0)
    plan = place_tabs(pos, sheet, sides, **kw)
    assert plan.side.tolist() == [-1, 1, 0, 0]
    assert plan.height[1] == pytest.approx(4.0)
    # Two steep tabs facing each other across E's free left cell (x 30..40): one shrinks.
    steep = dict(kw, tab_width=6.0, tab_angle=60.0)
    sides2 = np.array([[[2, 1], [0, 1]], [[4, 3], [2, 3]]])
    plan2 = place_tabs(pos, sheet, sides2, **steep)
    assert plan2.side.tolist() == [0, 0]
    assert sorted(plan2.height.tolist()) == pytest.approx([3.0, 6.0])
    # Near the sheet edge a tab must stay inside the area.
    plan3 = place_tabs(pos, sheet, sides[2:3], **dict(kw, area=(0.0, 61.0, 200.0, 200.0)))
    assert plan3.side.tolist() == [1]


def test_auto_pitch_fits_one_sheet_and_turns_the_net() -> None:
    g = np.ones((1, 1, 6), dtype=bool)
    net = tree_net(g)
    d = draw_net(g, net, options=DrawingOptions(sheet="300x150", margin=5.0))
    (sheet,) = d.sheets
    ext = np.ptp(net.corners2d.reshape(-1, 2), axis=0)
    assert d.pitch >= 5.0 and round(d.pitch * 10) == d.pitch * 10
    assert sheet.width == 300.0 and sheet.height == 150.0
    allx = np.concatenate([sheet.faces.reshape(-1, 2), sheet.tabs.reshape(-1, 2)])
    assert allx.min() >= 5.0 and allx[:, 0].max() <= 295.0 and allx[:, 1].max() <= 145.0
    # The tall net goes across the landscape sheet.
    assert d.rotated == (ext[1] > ext[0])


def test_a_net_that_does_not_fit_names_the_largest_face_size_and_the_smallest_sheet() -> None:
    from voxfab.fabricate.netdraw import SheetFitError

    g = np.ones((3, 3, 3), dtype=bool)
    net = tree_net(g)
    with pytest.raises(SheetFitError, match="does not fit sheet A4 at 40 mm") as info:
        draw_net(g, net, options=DrawingOptions(pitch=40.0), name="box")
    err = info.value
    # Both figures hold: the net fits at the largest face size and not 0.1 mm above it,
    best = err.largest_face_size
    draw_net(g, net, options=DrawingOptions(pitch=best))
    with pytest.raises(SheetFitError):
        draw_net(g, net, options=DrawingOptions(pitch=round(best + 0.1, 1)))
    # and the smallest sheet takes it at 40 mm while the next smaller one does not.
    from voxfab.fabricate.netdraw import SHEETS

    names = sorted(SHEETS, key=lambda n: SHEETS[n][0] * SHEETS[n][1])
    assert err.smallest_sheet in names
    draw_net(g, net, options=DrawingOptions(pitch=40.0, sheet=err.smallest_sheet))
    for smaller in names[: names.index(err.smallest_sheet)]:
        with pytest.raises(SheetFitError):
            draw_net(g, net, options=DrawingOptions(pitch=40.0, sheet=smaller))


def test_pieces_are_packed_on_few_sheets_with_numbered_seams_between_them() -> None:
    from voxfab.fabricate.netdraw import draw_pieces
    from voxfab.unfold import unfold

    g = np.ones((3, 3, 3), dtype=bool)
    pieces = unfold(g, rng=3, fit=(3, 4), pieces="auto", timeout=20.0)
    d = draw_pieces(g, pieces, options=DrawingOptions(pitch=40.0, sheet="A3"), name="box")
    faces = shapely.polygons(np.concatenate([s.faces for s in d.sheets]))
    assert len(faces) == surface_graph(g).face_count
    area = sum(len(p.corners2d) * 40.0**2 for p in pieces)
    # Every sheet is filled by its faces and tabs; pieces never overlap on a sheet.
    for s in d.sheets:
        polys = shapely.polygons(np.concatenate([s.faces, s.tabs]))
        assert shapely.union_all(polys).area == pytest.approx(shapely.area(polys).sum())
        assert s.fill == pytest.approx(shapely.area(polys).sum() / (s.width * s.height))
    assert sum(s.fill * s.width * s.height for s in d.sheets) > area
    # A lower bound on sheets: the paper area over one sheet's drawable area.
    assert len(d.sheets) <= len(pieces)
    assert d.pieces == len(pieces) and d.warnings()[0].startswith(f"net split into {len(pieces)} pieces")
    # Labels pair up: each stands for one seam, drawn on its two edges.
    assert d.seams == len(d.seam_labels) and len(set(d.seam_labels)) == d.seams


def test_grid_lines_and_perforation() -> None:
    g = np.ones((3, 3, 3), dtype=bool)
    net = tree_net(g)
    d = draw_net(g, net, options=DrawingOptions(pitch=12.0, grid_lines=True))
    assert all_layer(d, "GRID") == pytest.approx(d.fold_counts["flat"] * 12.0)
    plain = draw_net(g, net, options=DrawingOptions(pitch=12.0))
    perf = draw_net(g, net, options=DrawingOptions(pitch=12.0, perforate="mountain", perf_cut=1.5, perf_bridge=1.0))
    (ps,), (qs,) = perf.sheets, plain.sheets
    assert ps.layers["MOUNTAIN"].length() == 0.0
    extra = ps.layers["CUT"].length() - qs.layers["CUT"].length()
    mountain = qs.layers["MOUNTAIN"].length()
    assert 0.4 * mountain < extra < 0.7 * mountain
    a, b = ps.layers["CUT"].segments()
    dashes = np.linalg.norm(b - a, axis=1)
    assert (dashes[-10:] <= 1.5 + 1e-9).all()


def test_net_of_another_shape_is_rejected() -> None:
    net = tree_net(np.ones((1, 1, 2), dtype=bool))
    with pytest.raises(FormatError, match="do not match"):
        draw_net(np.ones((1, 1, 1), dtype=bool), net)


def test_broken_fold_is_rejected() -> None:
    g = np.ones((1, 1, 2), dtype=bool)
    net = tree_net(g)
    c2 = net.corners2d.copy()
    c2[5] += 10
    bad = Net(voxel=net.voxel, normal=net.normal, corners3d=net.corners3d, corners2d=c2, folds=net.folds,
              seed=0, strategy="x")
    with pytest.raises(FormatError, match="not a shared edge"):
        draw_net(g, bad)


@pytest.mark.parametrize("kwargs, match", [
    (dict(sheet="B5"), "sheet"),
    (dict(sheet="100x"), "sheet"),
    (dict(tab_angle=89.0), "tab_angle"),
    (dict(perforate="both"), "perforate"),
    (dict(dxf_version="R14"), "dxf_version"),
    (dict(colors="cut=#ff00"), "colors"),
    (dict(colors="paint=red"), "colors"),
    (dict(pitch=-1.0), "pitch"),
    (dict(sheet="30x30", margin=12.0), "sheet"),
    (dict(tab_width=2.5), "tab_width.*min_tab_depth"),
    (dict(label_height=1.5), "label_height.*min_label_height"),
    (dict(svg_lines="thick"), "svg_lines"),
])
def test_bad_options(kwargs: dict, match: str) -> None:
    with pytest.raises(InvalidShapeError, match=match):
        DrawingOptions(**kwargs)


def test_colors_and_sheets_parse() -> None:
    styles = parse_colors("cut=#00FF00, mountain=red:dotted")
    assert styles["CUT"].color == "#00ff00" and styles["CUT"].style.value == "solid"
    assert styles["MOUNTAIN"].rgb == (255, 0, 0) and styles["MOUNTAIN"].style.value == "dotted"
    assert styles["VALLEY"].color == "#00ff00" and styles["VALLEY"].style.value == "dashdot"
    assert parse_sheet("a3") == (297.0, 420.0) and parse_sheet("600 x 400") == (600.0, 400.0)


def test_merge_unit_segments_and_polylines() -> None:
    a = np.array([[0, 0], [1, 0], [2, 0], [4, 0], [1, 0], [3, 3]])
    b = np.array([[1, 0], [2, 0], [3, 0], [5, 0], [2, 0], [3, 4]])
    st, en = merge_unit_segments(a, b)
    assert sorted(zip(map(tuple, st.tolist()), map(tuple, en.tolist()))) == [
        ((0, 0), (3, 0)), ((3, 3), (3, 4)), ((4, 0), (5, 0))]
    sq = Polylines.from_list([np.array([[0.0, 0], [2, 0], [2, 2], [0, 2]])], [True])
    assert sq.length() == 8.0
    both = Polylines.concat([sq, Polylines.from_segments([[0, 0]], [[3, 4]])])
    assert len(both) == 2 and both.length() == 13.0


def split_pieces(grid: np.ndarray, net: Net, cut: int) -> list[Net]:
    """Two pieces of ``net``: drop fold ``cut``; each piece lists its faces in reverse order."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    folds = np.delete(net.folds, cut, axis=0)
    n = net.face_count
    adj = coo_matrix((np.ones(len(folds)), (folds[:, 0], folds[:, 1])), shape=(n, n))
    _, label = connected_components(adj, directed=False)
    pieces = []
    for lab in range(2):
        faces = np.flatnonzero(label == lab)[::-1]
        local = np.full(n, -1)
        local[faces] = np.arange(faces.size)
        keep = (label[folds[:, 0]] == lab)
        pieces.append(Net(voxel=net.voxel[faces], normal=net.normal[faces], corners3d=net.corners3d[faces],
                          corners2d=net.corners2d[faces], folds=local[folds[keep]], seed=net.seed,
                          strategy="piece"))
    return pieces


def test_pieces_drawn_apart_agree_on_numbers_and_tabs() -> None:
    g = examples.ball(1)
    net = tree_net(g)
    whole = draw_net(g, net, options=DrawingOptions(pitch=15.0))
    pieces = split_pieces(g, net, cut=len(net.folds) // 2)
    drawings = [draw_net(g, p, options=DrawingOptions(pitch=15.0)) for p in pieces]
    seams = [dict(zip(d.seam_numbers.tolist(), zip(d.tab_seams.tolist(), d.tab_elsewhere.tolist())))
             for d in drawings]
    shared = set(seams[0]) & set(seams[1])
    # Labels as long as the surface has edges, so a seam's label is one string in both pieces.
    assert drawings[0].label_chars == drawings[1].label_chars
    labels = [dict(zip(d.seam_numbers.tolist(), d.seam_labels)) for d in drawings]
    assert all(labels[0][n] == labels[1][n] for n in shared)
    # The cut fold became one seam numbered alike in both pieces, plus the seams between them.
    assert len(shared) >= 1
    assert sum(len(s) for s in seams) - len(shared) == whole.seams + 1
    for number in shared:
        (tab0, else0), (tab1, else1) = seams[0][number], seams[1][number]
        # Exactly one of the two pieces draws the tab (or, without room, a mark on it).
        assert else0 != else1
        assert not (tab0 and tab1)
    for d in drawings:
        assert d.sheets[0].pieces == 1
        own = ~d.tab_elsewhere
        assert len(d.sheets[0].tabs) == int(d.tab_seams[own].sum())


def test_face_of_another_shape_in_a_piece_is_rejected() -> None:
    g = examples.ball(1)
    piece = split_pieces(g, tree_net(g), cut=0)[0]
    moved = Net(voxel=piece.voxel + 5, normal=piece.normal, corners3d=piece.corners3d + 5,
                corners2d=piece.corners2d, folds=piece.folds, seed=0, strategy="x")
    with pytest.raises(FormatError, match="do not match"):
        draw_net(g, moved)
