"""The net gallery: distinct nets ordered by fit, their LAYOUT and PLACEMENT, and the ways out of a small sheet."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from voxfab._shared.options import OptionError
from voxfab.fabricate.netdraw import (
    DrawingOptions,
    NetOptions,
    draw_net,
    draw_pieces,
    find_sheet_nets,
    gallery_json,
    gallery_options,
    net_gallery,
    net_layout,
)
from voxfab.fabricate.netdraw._sheets import extent_of
from voxfab.shape import examples, surface_graph
from voxfab.unfold import outline_key, unfold, validate


def _queen() -> np.ndarray:
    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape

    return make_shape(load_recipe(Path(__file__).parents[3] / "recipes/chess/queen.toml")).grid


def _turn(c: np.ndarray, turns: int) -> np.ndarray:
    for _ in range(turns):
        c = np.stack([-c[..., 1], c[..., 0]], axis=-1)
    return c


def _placed_mm(layout: dict, placement: dict) -> list[tuple[int, np.ndarray]]:
    """Each face's corners in mm on its sheet, computed from the LAYOUT and PLACEMENT alone."""
    corners = np.array(layout["corners"]).reshape(-1, 4, 2)
    piece = np.array(layout["piece"])
    f = placement["face_size"]
    out = []
    for p in placement["pieces"]:
        c = corners[piece == p["piece"]].astype(float)
        if p["mirror"]:
            c[..., 0] *= -1
        out.append((p["sheet"], _turn(c, p["turns"]) * f + (p["x"], p["y"])))
    return out


def _check_on_sheets(layout: dict, placement: dict) -> None:
    w, h = placement["sheet"]
    m = placement["margin"]
    cells: set[tuple[int, int, int]] = set()
    f = placement["face_size"]
    for sheet, mm in _placed_mm(layout, placement):
        assert mm[..., 0].min() >= m - 1e-6 and mm[..., 0].max() <= w - m + 1e-6
        assert mm[..., 1].min() >= m - 1e-6 and mm[..., 1].max() <= h - m + 1e-6
        for face in mm:
            lo = face.min(axis=0)
            key = (sheet, int(round(lo[0] / f * 4)), int(round(lo[1] / f * 4)))
            assert key not in cells, "two faces on one spot"
            cells.add(key)


def test_a_gallery_that_fits_is_ordered_by_fit_and_placed_on_the_sheet() -> None:
    grid = examples.ball(2)
    net, drawing = gallery_options({"sheet": "A3", "face_size": 10, "timeout": 10})
    gallery = net_gallery(grid, net, drawing, count=4, seed=2)
    assert gallery.options.pitch == 10.0 and 1 <= len(gallery.nets) <= 4
    keys = {outline_key(item.pieces[0]) for item in gallery.nets}
    assert len(keys) == len(gallery.nets)
    fills = [item.fit["fill"][0] for item in gallery.nets]
    assert fills == sorted(fills, reverse=True)
    body = gallery_json(gallery, grid)
    for item, js in zip(gallery.nets, body["nets"]):
        n = item.pieces[0]
        assert validate(grid, n).ok
        ex, ey = js["fit"]["extent"]
        assert js["fit"]["fits"] and js["fit"]["sheets"] == 1
        # The net fits A3 (297 x 420 mm) inside the 10 mm margin, in some orientation.
        assert min(ex, ey) * 10 <= 277 and max(ex, ey) * 10 <= 400
        assert js["fit"]["fill"][0] == pytest.approx(n.face_count * 100 / (297 * 420), abs=1e-4)
        _check_on_sheets(js["layout"], js["placement"])


def test_layout_matches_the_net_and_its_drawing() -> None:
    grid = examples.ball(2)
    n = unfold(grid, rng=4, timeout=20)
    lay = net_layout(grid, n)
    f = n.face_count
    assert np.array_equal(np.array(lay["corners3d"]).reshape(-1, 4, 3), n.corners3d)
    assert np.array_equal(np.array(lay["corners"]).reshape(-1, 4, 2), n.corners2d)
    nb = np.array(lay["neighbor"]).reshape(-1, 4)
    c3 = n.corners3d
    for i in range(f):
        for k in range(4):
            j = nb[i, k]
            # Edge k of face i (corner k to k + 1) is an edge of face j as well.
            edge = {tuple(c3[i, k]), tuple(c3[i, (k + 1) % 4])}
            assert edge <= {tuple(c) for c in c3[j]} and i in nb[j]
    folds = {tuple(sorted(p)) for p in np.array(lay["folds"]).reshape(-1, 2).tolist()}
    parent = lay["parent"]
    assert parent.count(-1) == 1 and all(p == -1 or tuple(sorted((i, p))) in folds for i, p in enumerate(parent))
    # Every cut edge pair has the label the drawing prints.
    drawing = draw_net(grid, n, options=DrawingOptions(pitch=12.0, sheet="A3"))
    cut = {tuple(sorted((i, int(j)))) for i in range(f) for j in nb[i]} - folds
    assert {tuple(map(int, k.split("-"))) for k in lay["labels"]} == cut
    printed = [x for v in lay["labels"].values() for x in v.split()]
    assert sorted(printed) == sorted(drawing.seam_labels)


def test_pieces_share_one_layout_and_sit_apart_on_their_sheets() -> None:
    grid = np.ones((3, 3, 3), dtype=bool)
    net, drawing = gallery_options({"sheet": "A5", "face_size": 40, "pieces": "auto", "timeout": 10})
    gallery = net_gallery(grid, net, drawing, count=1, seed=0)
    (item,) = gallery.nets
    assert len(item.pieces) > 1 and validate(grid, item.pieces).ok
    js = gallery_json(gallery, grid)["nets"][0]
    lay = js["layout"]
    assert len(lay["faces"]) == 54 and sorted(set(lay["piece"])) == list(range(len(item.pieces)))
    # Face ids are the surface graph's, as for a one-piece net.
    sg = surface_graph(grid)
    dirs = ["+x", "-x", "+y", "-y", "+z", "-z"]
    assert lay["faces"] == [[*v, dirs[d]] for v, d in zip(sg.voxel.tolist(), sg.direction.tolist())]
    folds = {tuple(sorted(p)) for p in np.array(lay["folds"]).reshape(-1, 2).tolist()}
    assert all(p == -1 or tuple(sorted((i, p))) in folds for i, p in enumerate(lay["parent"]))
    assert lay["parent"].count(-1) == len(item.pieces)
    assert js["placement"]["sheets"] == js["fit"]["sheets"] > 1
    _check_on_sheets(lay, js["placement"])
    # The seam labels are the ones the drawing of the pieces prints.
    drawn = draw_pieces(grid, item.pieces, options=gallery.options)
    assert sorted(x for v in lay["labels"].values() for x in v.split()) == sorted(drawn.seam_labels)
    assert len(drawn.sheets) == js["placement"]["sheets"]


def test_the_queen_on_a4_says_what_would_work() -> None:
    grid = _queen()
    net, drawing = gallery_options({"sheet": "A4", "timeout": 30, "face_size": 8.6})
    gallery = net_gallery(grid, net, drawing, count=3, seed=0)
    assert gallery.options.pitch == 8.6  # the smallest face size with legible marks, as asked
    assert len({outline_key(i.pieces[0]) for i in gallery.nets}) == len(gallery.nets) >= 2
    for item in gallery.nets:
        fit = item.fit
        assert not fit["fits"] and "does not fit sheet A4 at 8.6 mm faces" in fit["message"]
        ways = {tuple(sorted(w["options"])): w["options"] for w in fit["ways_out"]}
        assert ways[("pieces",)] == {"pieces": "auto"}
        # The larger sheet offered holds the net at 8.6 mm faces inside its margins.
        sheet = ways[("sheet",)]["sheet"]
        sw, sh = DrawingOptions(sheet=sheet).sheet_size
        ex, ey = fit["extent"]
        assert (ex * 8.6 <= sw - 20 and ey * 8.6 <= sh - 20) or (ey * 8.6 <= sw - 20 and ex * 8.6 <= sh - 20)
        # The face size offered is too small for the marks: it comes without them.
        small = ways[("face_size", "numbers", "tabs")]
        assert small["numbers"] is False and small["tabs"] is False
        # ... the face size measured for the shape (a one-piece net was found to fit A4 at it), named by the words
        assert small["face_size"] == fit["largest_face_size"] and f"up to {small['face_size']:g} mm" in fit["message"]
    bare = drawing.replace(pitch=gallery.nets[0].fit["largest_face_size"], numbers=False, tabs=False)
    (found,) = find_sheet_nets(grid, bare, rng=0).nets[0]
    ex, ey = extent_of(found.corners2d)
    # A4 less its 10 mm margins and the title band: 190 x 272 mm
    assert min(ex, ey) * bare.pitch <= 190 and max(ex, ey) * bare.pitch <= 272
    order = [(i.fit["extent"][0] * i.fit["extent"][1]) for i in gallery.nets]
    assert order == sorted(order)


def test_faces_too_small_fail_with_ways_out() -> None:
    from voxfab.fabricate.netdraw import FaceSizeError

    net, drawing = gallery_options({"face_size": 3})
    with pytest.raises(FaceSizeError, match=r"what works: make the faces [0-9.]+ mm \(--face-size") as err:
        net_gallery(examples.ball(2), net, drawing, count=2, seed=0)
    options = [w["options"] for w in err.value.ways_out]
    assert {"numbers": False, "tabs": False} in options and any("face_size" in o for o in options)


def test_the_search_reports_progress_and_stops_when_cancelled() -> None:
    import threading

    from voxfab._shared.progress import cancel_scope
    from voxfab.errors import CancelledError

    net, drawing = gallery_options({"sheet": "A3", "face_size": 10, "timeout": 10})
    seen: list[tuple[int, int]] = []
    gallery = net_gallery(examples.ball(2), net, drawing, count=3, seed=1, progress=lambda d, t: seen.append((d, t)))
    assert seen == [(i + 1, 3) for i in range(len(gallery.nets))] and len(gallery.nets) == 3
    stop = threading.Event()
    seen.clear()

    def step(done: int, total: int) -> None:
        seen.append((done, total))
        stop.set()  # the stop button, pressed once the first net is in

    with cancel_scope(stop), pytest.raises(CancelledError):
        net_gallery(examples.ball(2), net, drawing, count=6, seed=1, progress=step)
    assert seen == [(1, 6)]


def test_options_are_checked_by_the_dataclasses() -> None:
    net, drawing = gallery_options({"face_size": 7.5, "sheet": "A3", "tabs": False}, defaults={"timeout": 5.0})
    assert (net.timeout, drawing.pitch, drawing.sheet, drawing.tabs) == (5.0, 7.5, "A3", False)
    with pytest.raises(OptionError, match="unknown option"):
        gallery_options({"colour": "red"})
    with pytest.raises(OptionError) as ours:
        gallery_options({"face_size": -1})
    with pytest.raises(OptionError) as cli:
        NetOptions(face_size=-1)
    assert str(ours.value) == str(cli.value)


def test_without_marks_the_face_size_is_the_largest_that_fits() -> None:
    net, drawing = gallery_options({"sheet": "A4", "numbers": False, "tabs": False, "timeout": 10})
    gallery = net_gallery(examples.ball(2), net, drawing, count=1, seed=0)
    (item,) = gallery.nets
    ex, ey = item.fit["extent"]
    p = gallery.options.pitch
    # A4 inside its 10 mm margin and above the title line: it fits, and 0.1 mm more would not.
    assert item.fit["fits"] and p == item.fit["largest_face_size"]
    def room(q: float) -> bool:  # 190 x 272 mm: A4 less the margins and the 5 mm title band
        return min(ex, ey) * q <= 190 and max(ex, ey) * q <= 272

    assert room(p) and not room(p + 0.2)


def test_an_empty_face_size_is_the_largest_at_which_one_piece_fits() -> None:
    """One piece, no face size: the largest at which a net fits the sheet, as ``voxfab net`` takes it."""
    from voxfab.fabricate.netdraw import FaceSizeError

    grid = _queen()
    net, drawing = gallery_options({"sheet": "900x600", "timeout": 30})
    gallery = net_gallery(grid, net, drawing, count=3, seed=0)
    face = float(gallery.options.pitch)
    assert face > 8.6  # not the smallest with legible marks
    assert all(item.fit["fits"] and item.fit["face_size"] == face for item in gallery.nets)
    assert face in {item.fit["largest_face_size"] for item in gallery.nets}  # and no larger for one of them
    # On A4 no legible face size fits one piece: refused at once, with every way out
    net, drawing = gallery_options({"sheet": "A4", "timeout": 30})
    with pytest.raises(FaceSizeError) as err:
        net_gallery(grid, net, drawing, count=3, seed=0)
    ways = [w["options"] for w in err.value.ways_out]
    assert {"numbers": False, "tabs": False} in ways and any(w.get("pieces") == "auto" for w in ways)


@pytest.mark.parametrize(("sheet", "words"), [("30x30", "no room for one 8.6 mm face with its tabs"),
                                              ("50x50", "too small for a net in pieces")])
def test_a_gallery_in_pieces_refuses_a_sheet_in_the_clis_words(tmp_path, sheet, words):
    """No room for one face with its tabs, or a sheet hopeless for pieces: the gallery in pieces (which cuts
    its own nets, seed by seed) refuses it before any search, in the words of `voxfab net --pieces auto`."""
    import subprocess
    import sys

    from voxfab.errors import VoxfabError

    queen = _queen()
    net, drawing = gallery_options({"sheet": sheet, "face_size": 8.6, "pieces": "auto"})
    with pytest.raises(VoxfabError) as refused:
        net_gallery(queen, net, drawing, count=3, seed=0)
    assert words in str(refused.value) and str(refused.value).startswith("sheet")
    np.save(tmp_path / "queen.npy", queen)
    cli = subprocess.run([sys.executable, "-m", "voxfab", "net", "queen.npy", "--sheet", sheet, "--face-size", "8.6",
                          "--pieces", "auto", "-o", "q.svg"], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert cli.returncode != 0 and str(refused.value) in cli.stderr and "Traceback" not in cli.stderr
    assert not (tmp_path / "q.svg").exists()
