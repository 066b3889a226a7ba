"""The queen's net in pieces laid out again after a cut or a join: the pieces the edit left alone keep their
sheet and spot on the plan and in the drawn files, the others go into the room left, and no piece overlaps."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _dxf_read import closed_rings
from _net_sheets import pieces_of, queen

from voxfab.errors import UnfoldError
from voxfab.fabricate.netdraw import NetOptions, fabricate_net, fit_and_placement, gallery_options
from voxfab.fabricate.netdraw._geometry import face_map
from voxfab.fabricate.netdraw._placement import Placement, turned
from voxfab.shape import VoxelShape, surface_graph
from voxfab.unfold import cut_edge, join_edge, unfold

NAMES = {(1, 0, 0): "+x", (-1, 0, 0): "-x", (0, 1, 0): "+y", (0, -1, 0): "-y", (0, 0, 1): "+z", (0, 0, -1): "-z"}


def name(net, i: int) -> tuple:
    return (*net.voxel[i].tolist(), NAMES[tuple(net.normal[i].tolist())])


@pytest.fixture(scope="module")
def laid():
    """The queen in 34 flat pieces on A5 at 8.6 mm faces (the studio's re-layout bench), packed."""
    grid = queen()
    pieces = list(unfold(grid, rng=1, fit=(9, 9), pieces="flat", timeout=120))
    _, drawing = gallery_options({"sheet": "A5", "pieces": "auto", "face_size": 8.6})
    graph = surface_graph(grid)
    fit, shown = fit_and_placement(pieces, drawing, graph)
    assert fit["fits"] and len(pieces) > 30
    return grid, pieces, drawing, graph, shown


def faces_of(net) -> frozenset:
    return frozenset(zip(map(tuple, net.voxel.tolist()), map(tuple, net.normal.tolist())))


def face_spots(pieces, placement: dict) -> dict:
    """Every face's sheet and corners in mm, from the placement alone: corner c of a piece lands at
    (x, y) + c turned * face size."""
    out = {}
    for net, place in zip(pieces, placement["pieces"]):
        mm = np.array([place["x"], place["y"]]) + turned(net.corners2d, place["turns"]) * placement["face_size"]
        for k, face in enumerate(zip(map(tuple, net.voxel.tolist()), map(tuple, net.normal.tolist()))):
            out[face] = (place["sheet"], mm[k])
    return out


def untouched(before, after) -> list[int]:
    """The pieces of ``after`` with the faces of a piece of ``before`` (the edit did not change which)."""
    old = {faces_of(n) for n in before}
    return [i for i, n in enumerate(after) if faces_of(n) in old]


def drawn(grid, pieces, drawing, placement: dict, folder: Path) -> list[list]:
    """The pieces' outlines on each sheet, read back from the DXF files the net pipeline writes."""
    import ezdxf

    made = fabricate_net(VoxelShape(grid), NetOptions(face_size=8.6, pieces="auto", formats=("dxf",)), drawing,
                         folder, name="queen", seed=1, chosen=pieces, placement=placement)
    dxfs = sorted(folder.glob("net.sheet-*.dxf"), key=lambda p: int(p.stem.rsplit("-", 1)[1]))
    assert len(dxfs) == made.report["sheets"] == placement["sheets"]
    return [pieces_of(closed_rings(ezdxf.readfile(p))) for p in dxfs]


def apart(sheets: list[list], drawing, pieces: int) -> None:
    """One outline per piece, none over another, all inside the margin."""
    w, h = drawing.sheet_size
    m = drawing.margin
    assert sum(len(polygons) for polygons in sheets) == pieces
    for polygons in sheets:
        for i, a in enumerate(polygons):
            x0, y0, x1, y1 = a.bounds
            assert x0 >= m - 1e-6 and y0 >= m - 1e-6 and x1 <= w - m + 1e-6 and y1 <= h - m + 1e-6
            for b in polygons[i + 1:]:
                assert a.intersection(b).area < 1e-6, "two pieces overlap"


def inside(sheets: list[list], sheet: int, point: np.ndarray) -> bool:
    import shapely

    return any(p.covers(shapely.Point(*point)) for p in sheets[sheet])


def test_a_cut_keeps_every_other_piece_on_its_sheet_and_spot_in_the_plan_and_the_files(laid, tmp_path: Path) -> None:
    grid, pieces, drawing, graph, shown = laid
    big = max(pieces, key=lambda n: n.face_count)
    i, j = big.folds[5].tolist()
    cut = list(cut_edge(grid, pieces, name(big, i), name(big, j), split=True).pieces)
    fit, placement = fit_and_placement(cut, drawing, graph, before=(pieces, Placement.from_dict(shown)))
    assert fit["fits"] and placement is not None and len(cut) == len(pieces) + 1
    alone = untouched(pieces, cut)
    assert len(alone) == len(pieces) - 1  # all but the piece cut in two
    was, now = face_spots(pieces, shown), face_spots(cut, placement)
    for p in alone:
        for face in faces_of(cut[p]):
            assert was[face][0] == now[face][0]
            assert np.allclose(was[face][1], now[face][1], atol=1e-6)
    # The files: the same pieces at the same places, and no piece over another.
    before = drawn(grid, pieces, drawing, shown, tmp_path / "before")
    after = drawn(grid, cut, drawing, placement, tmp_path / "after")
    apart(after, drawing, len(cut))
    for p in alone:
        for face in faces_of(cut[p]):
            sheet, corners = now[face]
            assert inside(before, sheet, corners.mean(axis=0)) and inside(after, sheet, corners.mean(axis=0))
    # The two halves of the cut piece are drawn too: every face of the net lies in an outline of its sheet.
    assert all(inside(after, s, c.mean(axis=0)) for s, c in now.values())


def test_the_same_edit_gives_the_same_layout(laid) -> None:
    from voxfab.fabricate.netdraw import _sheets

    grid, pieces, drawing, graph, shown = laid
    big = max(pieces, key=lambda n: n.face_count)
    i, j = big.folds[len(big.folds) // 2].tolist()
    cut = list(cut_edge(grid, pieces, name(big, i), name(big, j), split=True).pieces)
    first = fit_and_placement(cut, drawing, graph, before=(pieces, Placement.from_dict(shown)))
    _sheets._TURNS.clear()
    _sheets._PACKED.clear()
    again = list(cut_edge(grid, pieces, name(big, i), name(big, j), split=True).pieces)
    assert fit_and_placement(again, drawing, graph, before=(pieces, Placement.from_dict(shown))) == first


def test_joins_keep_what_room_allows_and_never_take_more_sheets_than_before_or_a_full_packing(
        laid, tmp_path: Path) -> None:
    grid, pieces, drawing, graph, shown = laid
    owner = {int(f): (p, k) for p, n in enumerate(pieces) for k, f in enumerate(face_map(graph, n))}
    pairs = sorted({tuple(sorted((owner[f][0], owner[int(g)][0]))): (f, int(g)) for f in range(graph.face_count)
                    for g in graph.neighbor[f] if owner[f][0] != owner[int(g)][0]}.items())
    kept_somewhere = done = 0
    for _, (f, g) in pairs[::5]:
        (pa, ka), (pb, kb) = owner[f], owner[g]
        try:
            joined = list(join_edge(grid, pieces, name(pieces[pa], ka), name(pieces[pb], kb)).pieces)
        except UnfoldError:
            continue
        fit, placement = fit_and_placement(joined, drawing, graph, before=(pieces, Placement.from_dict(shown)))
        full, _ = fit_and_placement(joined, drawing, graph)
        assert fit["sheets"] <= max(shown["sheets"], full["sheets"])
        was, now = face_spots(pieces, shown), face_spots(joined, placement)
        stayed = [p for p in untouched(pieces, joined)
                  if all(was[x][0] == now[x][0] and np.allclose(was[x][1], now[x][1]) for x in faces_of(joined[p]))]
        kept_somewhere += len(stayed) > 0
        done += 1
        last = (joined, placement)
    assert done >= 4 and kept_somewhere >= 2
    apart(drawn(grid, last[0], drawing, last[1], tmp_path), drawing, len(last[0]))


def test_the_tabs_a_piece_keeps_room_for_do_not_hang_on_the_order_of_the_pieces(laid, monkeypatch) -> None:
    from voxfab.fabricate.netdraw import _drawing

    grid, pieces, drawing, graph, shown = laid
    seen = []
    real = _drawing.pack_pieces
    monkeypatch.setattr(_drawing, "pack_pieces", lambda c, o, t: seen.append(t) or real(c, o, t))
    # An edit numbers the pieces again: a piece it left alone must keep the same tabs, or its spot.
    _drawing._packed(graph, pieces, drawing)
    _drawing._packed(graph, pieces[::-1], drawing)

    def tabs(order, edges):
        return {faces_of(p): sorted((name(p, f), k) for f, k in e.tolist()) for p, e in zip(order, edges)}

    assert tabs(pieces, seen[0]) == tabs(pieces[::-1], seen[1])


@pytest.fixture(scope="module")
def a4_cut():
    """The queen in pieces on A4 as the studio's gallery of one net makes it, its largest piece cut at a fold
    and laid out again around the cut (the browser's net editor, step one)."""
    from voxfab.fabricate.netdraw import net_gallery

    grid = queen()
    search, drawing = gallery_options({"sheet": "A4", "pieces": "auto"})
    gallery = net_gallery(grid, search, drawing, count=1, seed=0)
    options, item = gallery.options, gallery.nets[0]
    graph = surface_graph(grid)
    pieces = list(item.pieces)
    big = max(pieces, key=lambda n: n.face_count)
    i, j = big.folds[0].tolist()
    cut = list(cut_edge(grid, pieces, name(big, i), name(big, j), split=True).pieces)
    fit, placement = fit_and_placement(cut, options, graph, before=(pieces, Placement.from_dict(item.placement)))
    assert fit["fits"] and len(cut) == len(pieces) + 1
    return grid, options, graph, cut, placement


def on_sheets(pieces, placement: dict, drawing) -> None:
    """Every face inside the margin of its sheet, and no face of one piece over a face of another (faces
    squared from the placement alone, not from the packer's masks)."""
    import shapely

    w, h = drawing.sheet_size
    m = drawing.margin
    sheets: dict[int, list] = {}
    for p, (net, place) in enumerate(zip(pieces, placement["pieces"])):
        mm = np.array([place["x"], place["y"]]) + turned(net.corners2d, place["turns"]) * placement["face_size"]
        assert mm[..., 0].min() >= m - 1e-6 and mm[..., 1].min() >= m - 1e-6, f"piece {p + 1} below the margin"
        assert mm[..., 0].max() <= w - m + 1e-6 and mm[..., 1].max() <= h - m + 1e-6, f"piece {p + 1} past it"
        sheets.setdefault(place["sheet"], []).extend(shapely.Polygon(c) for c in mm)
    for faces in sheets.values():
        assert abs(shapely.unary_union(faces).area - sum(f.area for f in faces)) < 1e-3, "faces overlap"


def test_every_join_after_a_cut_is_laid_out_as_the_drawing_checks_it_or_refused_as_a_full_packing_is(a4_cut) -> None:
    grid, options, graph, cut, placement = a4_cut
    owner = {int(f): (p, k) for p, n in enumerate(cut) for k, f in enumerate(face_map(graph, n))}
    folded = {tuple(sorted((int(m[a]), int(m[b])))) for m, n in ((face_map(graph, n), n) for n in cut)
              for a, b in n.folds.reshape(-1, 2).tolist()}
    # Seams inside one piece: joining one closes a loop, which the editor opens elsewhere (a piece may grow).
    seams = sorted((f, int(g)) for f in range(graph.face_count) for g in graph.neighbor[f]
                   if f < g and owner[f][0] == owner[int(g)][0] and (f, int(g)) not in folded)
    refused = placed = 0
    for f, g in seams[::3]:
        (pa, ka), (pb, kb) = owner[f], owner[g]
        try:
            joined = list(join_edge(grid, cut, name(cut[pa], ka), name(cut[pb], kb)).pieces)
        except UnfoldError:
            continue
        fit, after = fit_and_placement(joined, options, graph, before=(cut, Placement.from_dict(placement)))
        full, _ = fit_and_placement(joined, options, graph)
        if not full["fits"]:  # a piece no sheet takes: refused in the packer's words, not laid across the margin
            assert not fit["fits"] and after is None and fit["message"] == full["message"]
            assert "does not fit sheet A4" in fit["message"]
            refused += 1
            continue
        assert fit["fits"] and fit["sheets"] <= max(placement["sheets"], full["sheets"])
        on_sheets(joined, after, options)
        placed += 1
    assert refused >= 1 and placed >= 5


def test_every_cut_after_a_cut_is_laid_out_as_the_drawing_checks_it(a4_cut) -> None:
    grid, options, graph, cut, placement = a4_cut
    folds = [(p, *ij) for p, n in enumerate(cut) for ij in n.folds.reshape(-1, 2).tolist()]
    done = 0
    for p, i, j in folds[::40]:
        try:
            again = list(cut_edge(grid, cut, name(cut[p], i), name(cut[p], j), split=True).pieces)
        except UnfoldError:
            continue
        fit, after = fit_and_placement(again, options, graph, before=(cut, Placement.from_dict(placement)))
        full, _ = fit_and_placement(again, options, graph)
        assert fit["fits"] and full["fits"] and fit["sheets"] <= max(placement["sheets"], full["sheets"])
        on_sheets(again, after, options)
        done += 1
    assert done >= 5
