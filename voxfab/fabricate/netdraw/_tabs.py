"""Glue tabs: one trapezoid per glued seam, on a side with room, never overlapping anything.

A tab hangs off a cut edge of a face, outside the face.  Its fold is inset by a
small margin from both edge ends, so two tabs in one free cell (from two sides
of it) never touch, and its slanted sides lean inwards at ``tab_angle``.
For every seam the candidates are tried in order: full size on either side,
then a lower tab (half size, but not under the smallest tab asked for) on either
side; a seam with none left gets a printed mark.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

_NEXT = np.array([1, 2, 3, 0])

#: Tabs lower than this (mm) are not worth gluing; the seam gets a mark instead.
MIN_TAB_HEIGHT = 0.8


@dataclasses.dataclass(frozen=True, eq=False)
class TabPlan:
    """Where the tabs go.

    Attributes
    ----------
    side : (S,) int ndarray
        0: on the seam's first edge, 1: on its second, -1: no room (mark instead).
    height : (S,) float ndarray
        Tab height in mm (0 without a tab).
    polygon : (S, 4, 2) float ndarray
        Tab corners (fold start, fold end, top end, top start), mm; NaN without a tab.
    """

    side: npt.NDArray[np.int64]
    height: npt.NDArray[np.float64]
    polygon: npt.NDArray[np.float64]

    @property
    def placed(self) -> npt.NDArray[np.bool_]:
        """``(S,)`` seams that got a tab."""
        return self.side >= 0


def tab_heights(pitch: float, tab_width: float, tab_angle: float) -> tuple[float, float]:
    """Inset of the tab fold from the edge ends and the full tab height, mm."""
    inset = min(0.5, 0.05 * pitch)
    base = pitch - 2 * inset
    # Keep a short top edge so the tab stays a trapezoid, not a spike.
    height = min(float(tab_width), 0.45 * base * math.tan(math.radians(tab_angle)))
    return inset, height


def trapezoids(p0: npt.NDArray[np.float64], p1: npt.NDArray[np.float64], height: npt.NDArray[np.float64],
               inset: float, tab_angle: float) -> npt.NDArray[np.float64]:
    """``(N, 4, 2)`` tabs on the right of edges ``p0 → p1`` (N, 2), mm."""
    vec = p1 - p0
    d = vec / np.linalg.norm(vec, axis=1, keepdims=True)
    n = np.stack([d[:, 1], -d[:, 0]], axis=1)
    run = (height / math.tan(math.radians(tab_angle)))[:, None]
    a = p0 + inset * d
    b = p1 - inset * d
    h = height[:, None]
    return np.stack([a, b, b + h * n - run * d, a + h * n + run * d], axis=1)


def place_tabs(
    positions: npt.NDArray[np.float64],
    face_sheet: npt.NDArray[np.int64],
    sides: npt.NDArray[np.int64],
    *,
    pitch: float,
    area: tuple[float, float, float, float],
    sheet_width: float,
    tab_width: float,
    tab_angle: float,
    allowed: npt.NDArray[np.bool_] | None = None,
    min_height: float = MIN_TAB_HEIGHT,
) -> TabPlan:
    """Choose a tab for every seam.

    Parameters
    ----------
    positions : (F, 4, 2) float ndarray
        Face corners in mm on their sheet.
    face_sheet : (F,) int ndarray
        Sheet of each face.
    sides : (S, 2, 2) int ndarray
        For each seam its two edges as (face, edge); face -1 for an edge drawn
        with another piece.
    pitch : float
        Face edge length, mm.
    area : (x0, y0, x1, y1)
        Drawable rectangle of a sheet, mm; tabs stay inside it.
    sheet_width : float
        Sheet width, mm (sheets are laid side by side for the overlap test).
    tab_width, tab_angle : float
        Largest tab height (mm) and side angle (degrees).
    allowed : (S, 2) bool ndarray, optional
        Which sides may take a tab (default: every side with a face).
    min_height : float
        Lowest tab worth gluing, mm: a seam whose full tab finds no room on
        either side tries a lower one, down to this height.

    Returns
    -------
    TabPlan
    """
    import shapely

    s_count = sides.shape[0]
    inset, h0 = tab_heights(pitch, tab_width, tab_angle)
    levels = [h for h in dict.fromkeys((h0, max(h0 / 2, min_height))) if h >= min_height - 1e-9]
    if s_count == 0 or not levels:
        return TabPlan(np.full(s_count, -1), np.zeros(s_count), np.full((s_count, 4, 2), np.nan))
    n_lv = len(levels)
    # Lay sheets side by side so one spatial index covers them all.
    gap = sheet_width + 100.0
    shift = np.stack([face_sheet * gap, np.zeros_like(face_sheet)], axis=1).astype(np.float64)
    glob = positions + shift[:, None, :]
    # Candidate order per seam: level-major, then side: other side before shrinking.
    cand_seam = np.repeat(np.arange(s_count), 2 * n_lv)
    cand_level = np.tile(np.repeat(np.arange(n_lv), 2), s_count)
    cand_side = np.tile(np.arange(2), s_count * n_lv)
    face = sides[cand_seam, cand_side, 0]
    usable = face >= 0
    if allowed is not None:
        usable &= allowed[cand_seam, cand_side]
    face = np.maximum(face, 0)
    edge = sides[cand_seam, cand_side, 1]
    p0 = glob[face, edge]
    p1 = glob[face, _NEXT[edge]]
    heights = np.asarray(levels)[cand_level]
    polys = trapezoids(p0, p1, heights, inset, tab_angle)
    # Inside the drawable area of its own sheet.
    local = polys - shift[face][:, None, :]
    x0, y0, x1, y1 = area
    ok = usable & (
        (local[..., 0].min(axis=1) >= x0 - 1e-9) & (local[..., 0].max(axis=1) <= x1 + 1e-9)
        & (local[..., 1].min(axis=1) >= y0 - 1e-9) & (local[..., 1].max(axis=1) <= y1 + 1e-9)
    )
    cand_geoms = shapely.polygons(polys)
    face_geoms = shapely.polygons(glob)
    hit_c, hit_f = shapely.STRtree(face_geoms).query(cand_geoms, predicate="intersects")
    foreign = hit_f != face[hit_c]
    ok[hit_c[foreign]] = False
    # Tab-tab conflicts between candidates of different seams.
    cc_a, cc_b = shapely.STRtree(cand_geoms).query(cand_geoms, predicate="intersects")
    keep = cand_seam[cc_a] != cand_seam[cc_b]
    cc_a, cc_b = cc_a[keep], cc_b[keep]
    order = np.argsort(cc_a, kind="stable")
    cc_a, cc_b = cc_a[order], cc_b[order]
    conflict_start = np.searchsorted(cc_a, np.arange(cand_seam.size + 1))
    per_seam = ok.reshape(s_count, 2 * n_lv)
    # Most constrained seams first, so a seam with one good side keeps it.
    seam_order = np.lexsort((np.arange(s_count), per_seam.sum(axis=1)))
    blocked = ~ok
    chosen = np.full(s_count, -1, dtype=np.int64)
    cb_list = cc_b.tolist()
    cs_list = conflict_start.tolist()
    blocked_list = blocked.tolist()
    width = 2 * n_lv
    for s in seam_order.tolist():
        base = s * width
        for c in range(base, base + width):
            if not blocked_list[c]:
                chosen[s] = c
                for other in cb_list[cs_list[c]:cs_list[c + 1]]:
                    blocked_list[other] = True
                break
    placed = chosen >= 0
    side = np.where(placed, cand_side[np.maximum(chosen, 0)], -1)
    height = np.where(placed, heights[np.maximum(chosen, 0)], 0.0)
    polygon = np.where(placed[:, None, None], local[np.maximum(chosen, 0)], np.nan)
    return TabPlan(side.astype(np.int64), height, polygon)


def tab_sides(corners: npt.NDArray[np.int64], sides: npt.NDArray[np.int64],
              second_low: npt.NDArray[np.bool_] | None = None
              ) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
    """Which side of every seam takes its tab: ``(swap, reserved)``, each ``(S,)``.

    A side has room when the cell beyond its edge holds no face; of two sides
    with room the one whose cell has more faces round it wins (its tab then
    sits in a notch of its own piece, where it costs the sheet no paper), on a
    tie the side seen from the lower surface face (``second_low``: the second
    side is), else the first.  So a tie does not hang on the order of the
    pieces, which an edit renumbers: the pieces it left alone keep their tabs.
    ``swap`` is True where the second side wins, ``reserved`` where either has room.
    """
    step = np.array([[0, -1], [1, 0], [0, 1], [-1, 0]], dtype=np.int64)
    cells = corners.min(axis=1)
    # The cells looked at lie at most two off the faces' (beyond an edge, then round that): a grid padded by two.
    lo = cells.min(axis=0) - 2
    occupied = np.zeros(tuple(cells.max(axis=0) - lo + 3), dtype=bool)
    occupied[tuple((cells - lo).T)] = True

    def taken(c: npt.NDArray[np.int64]) -> npt.NDArray[np.bool_]:
        return occupied[tuple((c - lo).T)]

    room, score = [], []
    for j in (0, 1):
        f, k = sides[:, j, 0], sides[:, j, 1]
        a, b = corners[f, k], corners[f, _NEXT[k]]
        d = b - a
        beyond = cells[f] + np.stack([d[:, 1], -d[:, 0]], axis=1)  # faces run counter-clockwise
        room.append(~taken(beyond))
        score.append(sum(taken(beyond + st).astype(np.int64) for st in step))
    tie = np.zeros(sides.shape[0], dtype=bool) if second_low is None else second_low & (score[1] == score[0])
    swap = (room[1] & ~room[0]) | (room[0] & room[1] & ((score[1] > score[0]) | tie))
    return swap, room[0] | room[1]
