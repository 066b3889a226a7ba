"""A net in pieces laid out again after an edit: the pieces the edit left as they were keep their place.

A cut or a join in the studio's editor changes one or two pieces of many.
Packing them all again moves every piece on the sheets the artist was looking
at, and costs a quarter second on the queen's 35 pieces (six packings).  Here
each piece the edit did not change (the same faces on the same cells, up to a
move of the whole piece) keeps the sheet, turns and spot the last placement
gave it, and only the others are packed, by the packer's own rule, into the
room left on those sheets, on new sheets when none has room.  When that takes
more sheets than the net had before, the full packing is made too and kept if
it takes fewer.  The result is a :class:`~._placement.Placement`, drawn (and
checked) by :func:`~._placement.plan_placement` like any placement from the
page, so the files made from it are the layout the editor shows.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from voxfab.unfold import Net

from ._options import DrawingOptions
from ._placement import PiecePlace, Placement, turned
from ._sheets import (
    _dilated,
    _pack_once,
    _quarter_turns,
    _Sheet,
    _spot_mm,
    _turns,
    auto_face_size,
    extent_of,
    paper,
)

__all__ = ["kept_places", "relayout"]


def _faces(net: Net) -> tuple[bytes, npt.NDArray[np.int64]]:
    """A piece's faces as a key (their voxels and normals, sorted) and the order that sorts them."""
    names = np.concatenate([np.asarray(net.voxel), np.asarray(net.normal)], axis=1).astype(np.int64)
    order = np.lexsort(names.T[::-1])
    return names[order].tobytes(), order


def kept_places(pieces: Sequence[Net], before: Sequence[Net], placement: Placement) -> list[PiecePlace | None]:
    """Per piece of the edited net, the place ``placement`` gave it before the edit when the edit left it
    as it was (the same faces on the same cells up to a move of the whole piece, which the place follows),
    None for a piece the edit made or changed."""
    if len(before) != len(placement.pieces):
        return [None] * len(pieces)
    known = {}
    for q, net in enumerate(before):
        key, order = _faces(net)
        known[key] = (np.asarray(net.corners2d, dtype=np.int64)[order], placement.pieces[q])
    out: list[PiecePlace | None] = []
    for p, net in enumerate(pieces):
        key, order = _faces(net)
        old = known.get(key)
        if old is None:
            out.append(None)
            continue
        moved = (np.asarray(net.corners2d, dtype=np.int64)[order] - old[0]).reshape(-1, 2)
        if not (moved == moved[0]).all():
            out.append(None)
            continue
        # Corner c of the piece lands at (x, y) + turned(c) * face: the piece's frame moved by d, (x, y) follows.
        place = old[1]
        dx, dy = turned(moved[0], place.turns) * placement.face_size
        out.append(PiecePlace(p, place.sheet, place.x - float(dx), place.y - float(dy), place.turns, place.mirror))
    return out


def relayout(pieces: Sequence[Net], tab_edges: list[npt.NDArray[np.int64]] | None, options: DrawingOptions,
             before: tuple[Sequence[Net], Placement]) -> Placement | None:
    """The placement of ``pieces`` after an edit of the net ``before[0]`` placed as ``before[1]``.

    ``tab_edges`` are the pieces' tab edges as the drawing chose them (the packer keeps room for them).
    None when no piece keeps its place (another sheet, margin or face size, or every piece changed) or
    when a full packing takes fewer sheets: the caller packs them all.
    """
    from ._sheets import pack_pieces

    corners = [np.asarray(p.corners2d, dtype=np.int64) for p in pieces]
    old_net, old = before
    pitch = auto_face_size(max((extent_of(c) for c in corners), key=lambda e: e[0] * e[1]), options)
    if not old.suits(dataclasses.replace(options, pitch=pitch)):
        return None
    if tab_edges is None:
        tab_edges = [np.zeros((0, 2), dtype=np.int64) for _ in pieces]
    kept = kept_places(pieces, old_net, old)
    if not any(kept):
        return None
    sheet = paper(options, pitch)
    turns = [_turns(c, tab_edges[i], sheet.per_cell, sheet.tab_steps, sheet.raster, sheet.tab_trim)
             for i, c in enumerate(corners)]
    x0, y0 = sheet.area[:2]

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

    def boards() -> tuple[dict[int, _Sheet], list[int]]:
        """The sheets with the kept pieces on them, and the pieces left to pack (a kept piece whose spot
        is off the raster or now meets another's, e.g. grown a tab, is packed again)."""
        on: dict[int, _Sheet] = {}
        rest = []
        for i, place in enumerate(kept):
            at = None if place is None else spot(i, place)
            if place is None or at is None:
                rest.append(i)
                continue
            board = on.setdefault(place.sheet, _Sheet(sheet.raster))
            mask = turns[i][place.turns].shape.mask
            if (board.blocked[at[0]:at[0] + mask.shape[0], at[1]:at[1] + mask.shape[1]] & mask).any():
                rest.append(i)
                continue
            board.block(_dilated(mask, sheet.clear), at[0] - sheet.clear, at[1] - sheet.clear)
        return on, rest

    best: tuple[int, dict, dict[int, int], list[int]] | None = None
    for touch in (True, False):
        on, rest = boards()
        used = sorted(on)
        order = sorted(rest, key=lambda i: (-corners[i].shape[0], i))
        count, where = _pack_once(turns, order, sheet.raster, sheet.clear, touch, [on[s] for s in used])
        if best is None or count < best[0]:
            best = (count, where, {s: k for k, s in enumerate(used)}, rest)
        if count <= len(used):  # no new sheet: the other rule cannot do better
            break
    count, where, renumber, rest = best
    if count > old.sheets and pack_pieces(corners, options, tab_edges)[0].count < count:
        return None
    places = []
    for i, place in enumerate(kept):
        if i not in where:
            assert place is not None
            places.append(PiecePlace(i, renumber[place.sheet], place.x, place.y, place.turns))
            continue
        s, shape, at = where[i]
        laid, mm = _spot_mm(corners[i], shape, at, options, sheet)
        t = next(k for k in range(4) if np.array_equal(_quarter_turns(corners[i], k), laid))
        x, y = np.array([x0, y0]) + mm - turned(corners[i], t).reshape(-1, 2).min(axis=0) * pitch
        places.append(PiecePlace(i, s, round(float(x), 6), round(float(y), 6), t))
    return Placement((float(options.sheet_size[0]), float(options.sheet_size[1])), float(options.margin), pitch,
                     count, tuple(places))
