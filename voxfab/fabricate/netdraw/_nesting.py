"""Emptying the last sheet: its pieces cut along folds into branches that fill the gaps of the sheets before.

Pieces packed largest first leave the last sheet mostly empty and notches and
holes on the others.  When the paper of the last sheet's pieces is at most half
the free room of the sheets before (:data:`MOST_OF_FREE`), each of them (largest first) goes whole
into a gap if one takes it, else its fold tree is cut: of the branches that
leave both sides at least the size rule's floor (no piece under
:data:`voxfab.unfold._job.MIN_SHARE` of the largest), the largest that fits a
gap (each gap tried with the four quarter turns, the sheets in order, the spot
the packer itself would choose) is put there and the rest goes on.  A branch's
new seams get their tabs where the drawing puts them (:func:`._tabs.tab_sides`:
both sides have room, the cut opens them).  The cut is kept only when the
drawing's own packing of the new pieces takes a whole sheet fewer, with no
seam more without a tab.  A fixed count of branches is tried per piece: no
clock, the same pieces for the same net.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque

import numpy as np
import numpy.typing as npt

from voxfab.unfold import EdgeConstraints, Net, validate

from ._options import DrawingOptions

#: Branches tried per piece of the last sheet (each: four turns rasterized, a correlation per sheet).
MAX_TRIES = 40
#: The last sheet is tried only when its pieces' paper is at most this share of the free room of the sheets
#: before: the rest of that room is slivers round irregular pieces and the clearance kept round each.  Measured
#: at 8.6 mm on A4 (``bench/bench_density.py``): the vase's last sheet takes a tenth of it and goes; the
#: torus's and blob's take 0.3 and the queen's and ball's 0.55 to 0.65, and no try of those found room.
MOST_OF_FREE = 0.5
#: After a branch finds no gap, only branches at most this share of its size are tried.
SHRINK = 0.9


def nest_last_sheet(grid: npt.ArrayLike, pieces: list[Net], options: DrawingOptions,
                    constraints: EdgeConstraints | None = None) -> list[Net]:
    """``pieces`` with those of the last sheet cut into branches packed in the free room of the sheets
    before, when that saves the drawing a sheet and keeps every edge ``constraints`` keep folded (the
    result refolds: :func:`voxfab.unfold.validate`); else ``pieces`` as they are.

    Tried on the pieces as cut, then, when the gaps were worth trying, with every piece over half the
    largest cut in two at its most even branch first: the size rule's floor halves with the largest (the
    vase's last sheet holds pieces under twice the floor, which no cut could split).
    """
    from voxfab.shape import fill_cavities, surface_graph

    from ._fit import _packing_rank
    from ._sheets import SheetFitError

    if len(pieces) < 2 or options.pitch is None:
        return pieces
    g = np.asarray(grid, dtype=bool)
    g = fill_cavities(g) if pieces[0].filled else g
    graph = surface_graph(g)
    try:
        before = _packing_rank(g, pieces, options)
    except SheetFitError:  # a piece larger than the sheet: the caller says so
        return pieces
    out, roomy = _nested(g, graph, pieces, options)
    if out is None and roomy:  # gaps enough, but a piece under twice the floor found none: lower the floor
        halved = _halved(g, graph, pieces)
        out = None if halved is None else _nested(g, graph, halved, options)[0]
    if out is not None:
        after = _packing_rank(g, out, options)
        if after[0] < before[0] and after[1] <= before[1] and validate(g, out, strict=False,
                                                                      constraints=constraints).ok:
            return out
    return pieces


def _nested(g: npt.NDArray[np.bool_], graph, pieces: list[Net], options: DrawingOptions  # noqa: ANN001
            ) -> tuple[list[Net] | None, bool]:
    """The pieces with those of the last sheet of their packing cut into branches put in the free room of
    the sheets before (None when some branch finds no gap), and whether that room was worth trying
    (:data:`MOST_OF_FREE`)."""
    from voxfab.unfold._job import MIN_SHARE

    from ._drawing import piece_tabs
    from ._sheets import paper

    _, _, tab_edges = piece_tabs(graph, pieces, options)
    if tab_edges is None:
        tab_edges = [np.zeros((0, 2), dtype=np.int64) for _ in pieces]
    sheet = paper(options, float(options.pitch))
    packed = _as_packed(graph, pieces, options, tab_edges)
    if packed is None:
        return None, False
    sheets, on, size = packed
    last = len(sheets) - 1
    moving = sorted((i for i in range(len(pieces)) if on[i] == last), key=lambda i: (-pieces[i].face_count, i))
    if last < 1 or sum(size[i] for i in moving) > MOST_OF_FREE * sum(s.free for s in sheets[:last]):
        return None, False
    floor = math.ceil(MIN_SHARE * max(p.face_count for p in pieces))
    parts: dict[int, list[npt.NDArray[np.int64]]] = {}
    for i in moving:
        found = _fill_gaps(pieces[i], tab_edges[i], sheets[:last], sheet, floor)
        if found is None:
            return None, True
        parts[i] = found
    out: list[Net] = []
    for i, p in enumerate(pieces):
        out += [_sub_net(g, graph, p, faces) for faces in parts[i]] if len(parts.get(i, ())) > 1 else [p]
    return out, True


def _as_packed(graph, pieces: list[Net], options: DrawingOptions, tab_edges: list[npt.NDArray[np.int64]]  # noqa: ANN001
               ) -> tuple[list, list[int], list[int]] | None:
    """The drawing's packing of ``pieces`` as the packer left its sheets (each piece's raster blocked where it
    lies, with the clearance round it), each piece's sheet and its raster's size; None when a piece lies alone,
    centred off the raster."""
    from ._drawing import _packed
    from ._sheets import _dilated, _shape, _Sheet, paper

    net, plan, *_ = _packed(graph, pieces, options)
    sheet = paper(options, plan.pitch)
    sheets = [_Sheet(sheet.raster) for _ in range(plan.count)]
    on, size = [], []
    at = 0
    for i, p in enumerate(pieces):
        placed = net.corners2d[at:at + p.face_count]
        bx = int(placed[..., 0].min())
        steps = (plan.shift[at] + (bx * plan.pitch, 0.0)) / sheet.step
        s = int(plan.face_sheet[at])
        at += p.face_count
        if not np.allclose(steps, np.rint(steps), atol=1e-6):
            return None
        shape = _shape(placed - (bx, 0), tab_edges[i], sheet.per_cell, sheet.tab_steps, sheet.tab_trim)
        ox, oy = (np.rint(steps).astype(np.int64) + shape.start - sheet.clear).tolist()
        sheets[s].block(_dilated(shape.mask, sheet.clear), ox, oy)
        on.append(s)
        size.append(int(shape.mask.sum()))
    return sheets, on, size


def _halved(g: npt.NDArray[np.bool_], graph, pieces: list[Net]) -> list[Net] | None:  # noqa: ANN001
    """Every piece over half the largest cut in two at the branch nearest half of it, or None when that
    leaves a piece under the size rule's floor."""
    from voxfab.unfold._job import MIN_SHARE

    half = max(p.face_count for p in pieces) / 2
    floor = math.ceil(MIN_SHARE * half)
    out: list[Net] = []
    for p in pieces:
        rest = np.arange(p.face_count)
        sides = _branches(rest, _fold_edges(p), np.ones(p.face_count, dtype=bool), floor) if p.face_count > half else []
        if not sides:
            out.append(p)
            continue
        one = min(sides, key=lambda f: abs(2 * f.size - rest.size))  # the first of the most even: largest first
        out += [_sub_net(g, graph, p, one), _sub_net(g, graph, p, np.setdiff1d(rest, one))]
    sizes = [p.face_count for p in out]
    return out if len(out) > len(pieces) and min(sizes) >= MIN_SHARE * max(sizes) else None


def _fill_gaps(net: Net, tabs: npt.NDArray[np.int64], sheets: list, sheet, floor: int  # noqa: ANN001
               ) -> list[npt.NDArray[np.int64]] | None:
    """The faces of ``net`` as branches put in the free room of ``sheets`` (blocked there), or None."""
    from ._sheets import _best_spots, _dilated, _quarter_turns, _shape, _Spectra

    n = net.face_count
    link = _fold_edges(net)
    taken = {(int(f), int(k)) for f, k in tabs.tolist()}  # the edges that take a tab, new seams' added
    rest = np.arange(n)
    parts: list[npt.NDArray[np.int64]] = []
    tries = MAX_TRIES
    while rest.size:
        inside = np.zeros(n, dtype=bool)
        inside[rest] = True
        # The whole piece did not fit when it was packed: only what is left of it is tried whole.
        candidates = ([rest] if rest.size < n else []) + _branches(rest, link, inside, floor)
        placed = False
        cap = rest.size
        for faces in candidates:
            if faces.size > cap:
                continue  # a branch as large as one that found no gap: the tries go to smaller ones
            if tries <= 0:
                return None
            tries -= 1
            cut = _new_seams(net, link, faces, inside)
            mine = np.zeros(n, dtype=bool)
            mine[faces] = True
            edges = [e for e in taken | cut if mine[e[0]]]
            local = np.full(n, -1, dtype=np.int64)
            local[faces] = np.arange(faces.size)
            te = np.array([(local[f], k) for f, k in sorted(edges)], dtype=np.int64).reshape(-1, 2)
            corners = net.corners2d[faces]
            turns = [_Spectra(_shape(_quarter_turns(corners, t), te, sheet.per_cell, sheet.tab_steps,
                                     sheet.tab_trim), sheet.raster) for t in range(4)]
            if turns[0].size > max(s.free for s in sheets):
                continue
            for s in sheets:
                best = None
                for t, spot in enumerate(_best_spots(s, turns)):
                    if spot is not None and (best is None or spot[:2] + (t,) < best[0]):
                        best = (spot[:2] + (t,), t, spot[2:])
                if best is None:
                    continue
                ox, oy = best[2]
                s.block(_dilated(turns[best[1]].shape.mask, sheet.clear), ox - sheet.clear, oy - sheet.clear)
                placed = True
                break
            if not placed:
                cap = min(cap, faces.size - 1, int(faces.size * SHRINK))
                continue
            parts.append(faces)
            taken |= cut
            rest = np.setdiff1d(rest, faces)
            break
        if not placed:
            return None
    return parts


def _fold_edges(net: Net) -> dict[int, list[tuple[int, int, int]]]:
    """Per face, its folds as ``(other face, its edge, the other's edge)``: the edges matched in the plane."""
    c = np.asarray(net.corners2d)
    ends = {}
    for f in range(c.shape[0]):
        for k in range(4):
            ends[(f, k)] = (tuple(c[f, k]), tuple(c[f, (k + 1) % 4]))
    link: dict[int, list[tuple[int, int, int]]] = {f: [] for f in range(c.shape[0])}
    for a, b in np.asarray(net.folds, dtype=np.int64).reshape(-1, 2).tolist():
        for ka in range(4):
            kb = next((kb for kb in range(4) if ends[(b, kb)] == ends[(a, ka)][::-1]), None)
            if kb is not None:
                link[a].append((b, ka, kb))
                link[b].append((a, kb, ka))
                break
    return link


def _branches(rest: npt.NDArray[np.int64], link: dict, inside: npt.NDArray[np.bool_], floor: int
              ) -> list[npt.NDArray[np.int64]]:
    """The two sides of every fold of a spanning tree of ``rest`` (breadth first from its first face) that
    leave both at least ``floor`` faces, largest first (ties by the fold's place in the walk)."""
    root = int(rest[0])
    parent = {root: -1}
    order = [root]
    queue = deque([root])
    while queue:
        a = queue.popleft()
        for b, _, _ in sorted(link[a]):
            if inside[b] and b not in parent:
                parent[b] = a
                order.append(b)
                queue.append(b)
    below: dict[int, list[int]] = {f: [f] for f in order}
    for f in reversed(order[1:]):
        below[parent[f]] += below[f]
    out = []
    for j, f in enumerate(order[1:]):
        side = np.array(sorted(below[f]), dtype=np.int64)
        other = np.setdiff1d(rest, side)
        for k, faces in enumerate((side, other)):
            if floor <= faces.size <= rest.size - floor:
                out.append((-faces.size, j, k, faces))
    return [faces for *_, faces in sorted(out, key=lambda t: t[:3])]


def _new_seams(net: Net, link: dict, faces: npt.NDArray[np.int64], inside: npt.NDArray[np.bool_]
               ) -> set[tuple[int, int]]:
    """The folds between ``faces`` and the rest of ``inside`` that the cut opens, as the edges that take their
    tabs (:func:`._tabs.tab_sides` on the two sides laid apart)."""
    from ._tabs import tab_sides

    mine = np.zeros(inside.size, dtype=bool)
    mine[faces] = True
    pairs = [(a, ka, b, kb) for a in faces.tolist() for b, ka, kb in link[a] if inside[b] and not mine[b]]
    if not pairs:
        return set()
    c = np.asarray(net.corners2d).copy()
    c[~mine] += int(np.ptp(c[..., 0])) + 4  # the rest laid apart: nothing beyond a cut edge
    sides = np.array([[[a, ka], [b, kb]] for a, ka, b, kb in pairs], dtype=np.int64)
    swap, room = tab_sides(c, sides)
    return {(int(s[1 if w else 0, 0]), int(s[1 if w else 0, 1])) for s, w, r in zip(sides, swap, room) if r}


def _sub_net(grid: npt.NDArray[np.bool_], graph, net: Net, faces: npt.NDArray[np.int64]) -> Net:  # noqa: ANN001
    """The piece of ``net`` made of ``faces``, as laid: their folds among them, fold kinds recounted."""
    from voxfab.unfold._layout import _face_ids, count_without_tab_room

    local = np.full(net.face_count, -1, dtype=np.int64)
    local[faces] = np.arange(faces.size)
    folds = np.asarray(net.folds, dtype=np.int64).reshape(-1, 2)
    folds = local[folds[(local[folds] >= 0).all(axis=1)]]
    folds = np.sort(folds, axis=1)
    folds = folds[np.lexsort((folds[:, 1], folds[:, 0]))]
    ids = _face_ids(graph, net)[faces]
    a, b = ids[folds[:, 0]], ids[folds[:, 1]]
    kinds = graph.fold[a, np.argmax(graph.neighbor[a] == b[:, None], axis=1)]
    c2 = net.corners2d[faces]
    sub = dataclasses.replace(net, voxel=net.voxel[faces], normal=net.normal[faces],
                              corners3d=net.corners3d[faces], corners2d=c2 - c2.reshape(-1, 2).min(axis=0),
                              folds=folds if folds.size else np.zeros((0, 2), dtype=np.int64),
                              mountain=int(np.count_nonzero(kinds == 1)), valley=int(np.count_nonzero(kinds == -1)),
                              flat=int(np.count_nonzero(kinds == 0)))
    return dataclasses.replace(sub, seams_without_tab_room=count_without_tab_room(grid, sub))
