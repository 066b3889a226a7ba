"""A net in pieces laid out again after an edit: the pieces the edit left as they were keep their place.

A cut or a join in the studio's editor changes one or two pieces of many.
Packing them all again moves every piece on the sheets the artist was looking
at, and costs a quarter second on the queen's 35 pieces (six packings).  Here,
in turn, until the pieces take no more sheets than before:

1. each piece the edit did not change (the same faces on the same cells, up to
   a move of the whole piece) keeps the sheet, turns and spot the placement
   gave it; a changed piece keeps the place of the old piece it shares most
   faces with (on the same cells) where it has room there; the others are
   packed, by the packer's own rule, into the room left, on new sheets when
   none has room;
2. the sheets the changed pieces were on are packed again, with them, and the
   other sheets are left as they were;
3. the whole net is packed again (:func:`._sheets.pack_pieces`).

The layout on the fewest sheets is kept, the first of them on a tie.  It is a
:class:`~._placement.Placement`, drawn (and checked) by
:func:`~._placement.plan_placement` like any placement from the page, so the
files made from it are the layout the editor shows.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

from voxfab.unfold import Net

from ._options import DrawingOptions
from ._placement import PiecePlace, Placement, PlacementError, plan_placement, turned
from ._sheets import (
    _dilated,
    _orders,
    _pack_once,
    _quarter_turns,
    _Sheet,
    _spot_mm,
    _turns,
    auto_face_size,
    extent_of,
    fits,
    paper,
)

__all__ = ["kept_places", "relayout"]


def _codes(net: Net) -> npt.NDArray[np.int64]:
    """One number per face of a piece, from its voxel and normal (the same face, the same number)."""
    v = np.asarray(net.voxel, dtype=np.int64) + 512
    n = np.asarray(net.normal, dtype=np.int64) + 1
    return ((v[:, 0] * 1024 + v[:, 1]) * 1024 + v[:, 2]) * 27 + n @ np.array([9, 3, 1])


def _moved(place: PiecePlace, p: int, by: npt.NDArray[np.int64], face: float) -> PiecePlace:
    """``place`` of a piece whose frame moved by ``by`` cells, for piece ``p``: corner c lands at
    (x, y) + turned(c) * face, so (x, y) goes back by the turned move."""
    dx, dy = turned(by, place.turns) * face
    return PiecePlace(p, place.sheet, place.x - float(dx), place.y - float(dy), place.turns, place.mirror)


def kept_places(pieces: Sequence[Net], before: Sequence[Net], placement: Placement) -> list[PiecePlace | None]:
    """Per piece of the edited net, the place ``placement`` gave it before the edit when the edit left it
    as it was (the same faces on the same cells up to a move of the whole piece, which the place follows),
    None for a piece the edit made or changed."""
    return _places(pieces, before, placement)[0]


def _places(pieces: Sequence[Net], before: Sequence[Net], placement: Placement
            ) -> tuple[list[PiecePlace | None], list[PiecePlace | None], set[int]]:
    """:func:`kept_places`; per changed piece the place of the old piece it shares most faces with on the
    same cells (ties: the lower old piece, then the smaller move), None when it shares none; and the sheets
    of the old pieces that are not kept."""
    if len(before) != len(placement.pieces):
        return [None] * len(pieces), [None] * len(pieces), set()
    codes = [_codes(net) for net in before]
    owner = np.repeat(np.arange(len(before)), [c.size for c in codes])
    flat = np.concatenate(codes)
    order = np.argsort(flat, kind="stable")
    flat, owner = flat[order], owner[order]
    cells = np.concatenate([np.asarray(n.corners2d, dtype=np.int64).reshape(-1, 8) for n in before])[order]
    kept: list[PiecePlace | None] = []
    near: list[PiecePlace | None] = []
    whole = set()
    for p, net in enumerate(pieces):
        mine = _codes(net)
        at = np.minimum(np.searchsorted(flat, mine), flat.size - 1)
        found = flat[at] == mine
        move = np.asarray(net.corners2d, dtype=np.int64).reshape(-1, 8)[found] - cells[at[found]]
        rigid = (move == np.tile(move[:, :2], 4)).all(axis=1)  # its four corners moved alike: not turned
        q, by = owner[at[found]][rigid], move[rigid][:, :2]
        if q.size == 0:
            kept.append(None)
            near.append(None)
            continue
        groups, count = np.unique(np.column_stack([q, by]), axis=0, return_counts=True)
        best = groups[np.lexsort((np.abs(groups[:, 1:]).sum(axis=1), groups[:, 0], -count))[0]]
        q0, by0 = int(best[0]), best[1:]
        same = count.size == 1 and int(count[0]) == net.face_count == before[q0].face_count
        place = _moved(placement.pieces[q0], p, by0, placement.face_size)
        kept.append(place if same else None)
        near.append(None if same else place)
        if same:
            whole.add(q0)
    touched = {placement.pieces[q].sheet for q in range(len(before)) if q not in whole}
    return kept, near, touched


def relayout(pieces: Sequence[Net], tab_edges: list[npt.NDArray[np.int64]] | None, options: DrawingOptions,
             before: tuple[Sequence[Net], Placement]) -> Placement | None:
    """The placement of ``pieces`` after an edit of the net ``before[0]`` placed as ``before[1]``.

    ``tab_edges`` are the pieces' tab edges as the drawing chose them (the packer keeps room for them).
    None when no piece can keep its place (another sheet, margin or face size, or every piece changed)
    or a piece fits no sheet (a join made it too big): the caller packs them all, and refuses such a
    piece as the packer does.  Every layout returned passes :func:`._placement.plan_placement`.
    """
    corners = [np.asarray(p.corners2d, dtype=np.int64) for p in pieces]
    old_net, old = before
    pitch = auto_face_size(max((extent_of(c) for c in corners), key=lambda e: e[0] * e[1]), options)
    if not old.suits(dataclasses.replace(options, pitch=pitch)):
        return None
    if any(fits(extent_of(c), options, pitch) is None for c in corners):
        return None  # centred alone on a sheet it would cross the margin: the packer's refusal instead
    if tab_edges is None:
        tab_edges = [np.zeros((0, 2), dtype=np.int64) for _ in pieces]
    kept, near, touched = _places(pieces, old_net, old)
    if not any(kept):
        return None
    sheet = paper(options, pitch)
    turns = [_turns(c, tab_edges[i], sheet.per_cell, sheet.tab_steps, sheet.raster, sheet.tab_trim)
             for i, c in enumerate(corners)]
    x0, y0 = sheet.area[:2]
    by = _orders([c.shape[0] for c in corners], turns)

    def spot(i: int, place: PiecePlace) -> tuple[int, int] | None:
        """The raster step of piece ``i``'s mask at ``place``, None off the raster or across the margin."""
        shape = turns[i][place.turns].shape
        lo = turned(corners[i], place.turns).reshape(-1, 2).min(axis=0)
        at = (np.array([place.x, place.y]) + lo * pitch - (x0, y0)) / sheet.step + shape.start
        if place.mirror or np.abs(at - np.rint(at)).max() > 1e-3:
            return None
        ax, ay = (int(v) for v in np.rint(at))
        w, h = shape.mask.shape
        inside = ax >= 0 and ay >= 0 and ax + w <= sheet.raster[0] and ay + h <= sheet.raster[1]
        return (ax, ay) if inside else None

    def laid(stay: list[PiecePlace | None], order: Callable[[int], tuple[int, int]], touch: bool
             ) -> tuple[int, list[PiecePlace]]:
        """The pieces with a place in ``stay`` there where they have room (in that order), the others
        packed in ``order`` into the room left: the sheets and every piece's place."""
        on: dict[int, _Sheet] = {}
        where: dict[int, PiecePlace] = {}
        for i in sorted((i for i, p in enumerate(stay) if p is not None), key=lambda i: (kept[i] is None, i)):
            place = stay[i]
            assert place is not None
            at = spot(i, place)
            mask = turns[i][place.turns].shape.mask
            board = on.get(place.sheet) or _Sheet(sheet.raster)
            if at is None or (board.blocked[at[0]:at[0] + mask.shape[0], at[1]:at[1] + mask.shape[1]] & mask).any():
                continue  # off the raster, or a tab grown into another piece: packed again
            on[place.sheet] = board
            board.block(_dilated(mask, sheet.clear), at[0] - sheet.clear, at[1] - sheet.clear)
            where[i] = place
        used = sorted(on)
        renumber = {s: k for k, s in enumerate(used)}
        rest = sorted((i for i in range(len(pieces)) if i not in where), key=order)
        count, packed = _pack_once(turns, rest, sheet.raster, sheet.clear, touch, [on[s] for s in used])
        places = []
        for i in range(len(pieces)):
            if i in where:
                places.append(dataclasses.replace(where[i], sheet=renumber[where[i].sheet]))
                continue
            s, shape, at = packed[i]
            cells, mm = _spot_mm(corners[i], shape, at, options, sheet)
            t = next(k for k in range(4) if np.array_equal(_quarter_turns(corners[i], k), cells))
            x, y = np.array([x0, y0]) + mm - turned(corners[i], t).reshape(-1, 2).min(axis=0) * pitch
            places.append(PiecePlace(i, s, round(float(x), 6), round(float(y), 6), t))
        return count, places

    # The tries of the module's list, each until one takes no more sheets than before: 1, the pieces kept
    # and the changed ones near their old place, or packed; 2, the sheets of the changed ones packed
    # again; 3, all packed again, as :func:`._sheets.pack_pieces` does (stopping at the sheets of before).
    both = (True, False)
    tries = [(lambda: [k if k is not None else n for k, n in zip(kept, near)], by[:1], both),
             (lambda: kept, by[:1], both),
             (lambda: [k if k is not None and k.sheet not in touched else None for k in kept], by, (True,)),
             (lambda: [None] * len(pieces), by, both)]
    least = math.ceil(sum(t[0].size for t in turns) / (sheet.raster[0] * sheet.raster[1]))  # no packing beats it
    size = (float(options.sheet_size[0]), float(options.sheet_size[1]))
    checked = dataclasses.replace(options, pitch=pitch)
    best: Placement | None = None
    for stay, order, touch in ((stay, o, t) for stay, orders, rules in tries for t in rules for o in orders):
        count, places = laid(stay(), order, touch)
        if best is not None and count >= best.sheets:
            continue
        got = Placement(size, float(options.margin), pitch, count, tuple(places))
        try:  # a layout the drawing would refuse is never offered: the next try, else the caller's packing
            plan_placement(got, corners, checked, tab_edges)
        except PlacementError:
            continue
        best = got
        if best.sheets <= max(old.sheets, least):
            break
    return best
