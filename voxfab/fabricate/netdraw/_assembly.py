"""Pieces a maker can find: piece numbers, which pieces join which, a gluing order and the assembly page.

Every piece of a several-piece net carries its number ``(N)`` in the middle of
one of its faces, drawn on the LABEL layer of every format, so the sheets, the
SVG and DXF files and the assembly page name each piece the same way.  The
gluing order starts from the largest piece and always takes next the largest
piece that joins what is already built.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from voxfab.drawing import Page, Polylines, text_polylines, text_width

from ._tabs import TabPlan

#: Height of the text lines of the assembly page, mm.
ASSEMBLY_TEXT = 3.5


def piece_name(number: int) -> str:
    """How piece ``number`` (1-based) is named on the assembly page: ``(3)``; brackets are no seam label's
    characters.  On the sheets it is boxed instead (:func:`number_text`)."""
    return f"({number})"


def piece_joins(face_piece: npt.NDArray[np.int64], sides: npt.NDArray[np.int64]) -> list[tuple[int, int]]:
    """Pairs ``(a, b)``, ``a < b``, of 0-based pieces that share a seam, sorted."""
    a = face_piece[sides[:, 0, 0]]
    b = face_piece[np.maximum(sides[:, 1, 0], 0)]
    keep = (sides[:, 1, 0] >= 0) & (a != b)
    pairs = np.unique(np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1)[keep], axis=0)
    return [(int(x), int(y)) for x, y in pairs.tolist()]


def gluing_order(sizes: list[int], joins: list[tuple[int, int]]) -> list[int]:
    """0-based pieces in gluing order: the largest first, then always the largest joining those built."""
    near: dict[int, set[int]] = {i: set() for i in range(len(sizes))}
    for a, b in joins:
        near[a].add(b)
        near[b].add(a)
    left = set(range(len(sizes)))
    order: list[int] = []
    while left:
        touching = [i for i in left if near[i] & set(order)] or list(left)
        nxt = min(touching, key=lambda i: (-sizes[i], i))
        order.append(nxt)
        left.discard(nxt)
    return order


def number_faces(face_piece: npt.NDArray[np.int64], joined: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    """For each piece the face that carries its number: the one with most edges joined (fewest labels)."""
    pieces = int(face_piece.max(initial=-1)) + 1
    score = joined.sum(axis=1)
    out = np.zeros(pieces, dtype=np.int64)
    for p in range(pieces):
        faces = np.flatnonzero(face_piece == p)
        out[p] = faces[np.argmax(score[faces])]  # argmax keeps the first of ties
    return out


#: Piece-number heights tried, over the seam labels' height: the largest that finds room is drawn.
NUMBER_SCALES = (1.6, 1.4, 1.25)
#: Room between a number and its box, over the number's height; the box's clear paper to any label, mm.
BOX_PAD = 0.3
NUMBER_CLEAR = 0.3
#: Where a number may stand on a face, in face sizes from its middle (the nearest first).
_OFFSETS = sorted(((dx, dy) for dx in (-0.5, -0.25, 0.0, 0.25, 0.5) for dy in (-0.5, -0.25, 0.0, 0.25, 0.5)),
                  key=lambda o: (o[0] ** 2 + o[1] ** 2, o))
#: Where a number may stand beside its piece, in face sizes from a face's middle (the nearest first).
_BESIDE = sorted(((dx / 4, dy / 4) for dx in range(-20, 21) for dy in range(-20, 21) if max(abs(dx), abs(dy)) >= 2),
                 key=lambda o: (o[0] ** 2 + o[1] ** 2, o))


def number_box(name: str, centre: npt.ArrayLike, height: float) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Lower and upper corners, mm, of the box drawn round piece number ``name`` of ``height`` mm at ``centre``."""
    half = np.array([text_width(name, height) / 2, height / 2]) + BOX_PAD * height
    c = np.asarray(centre, dtype=np.float64)
    return c - half, c + half


Boxes = tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]


def place_numbers(names: list[str], face_piece: npt.NDArray[np.int64], face_sheet: npt.NDArray[np.int64],
                  pos: npt.NDArray[np.float64], prefer: npt.NDArray[np.int64], pitch: float, label_h: float,
                  blocked: dict[int, Boxes], paper: dict[int, Boxes], area: tuple[float, float, float, float],
                  ) -> list[tuple[int, npt.NDArray[np.float64], float]]:
    """Where each piece's number stands: ``(sheet, centre mm, height mm)``, boxed on its own piece's faces.

    The number is taller than the seam labels (:data:`NUMBER_SCALES` times them, the largest that
    finds room), and its box lies on faces of its piece, clear of every box of ``blocked`` (per sheet:
    the seam labels and tape marks, ``(lo, hi)`` arrays) and of the numbers placed before, so numbers
    never run into labels or into each other, as two one-face pieces side by side would.  Faces are
    tried from ``prefer`` (per piece, the face with most folded edges) outwards by folded edges, each
    from its middle outwards.  A piece whose faces have no such room (a one-face piece: its four
    labels fill it) has its number on the free paper beside it, inside ``area`` and clear of all
    ``paper`` (per sheet: the faces and tabs), nearest first; with no room there either, its
    preferred face's middle at the smallest scale.
    """
    out: list[tuple[int, npt.NDArray[np.float64], float]] = []
    placed: dict[int, list[tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]] = {}
    lows = pos.min(axis=1)  # (F, 2) each face's lower corner
    for i, name in enumerate(names):
        faces = np.flatnonzero(face_piece == i)
        first = int(prefer[i])
        sheet = int(face_sheet[first])
        faces = faces[face_sheet[faces] == sheet]
        faces = np.concatenate([[first], faces[faces != first]])
        origin = lows[first]
        cells = np.rint((lows[faces] - origin) / pitch).astype(np.int64)
        centres = (lows[faces][:, None, :] + pitch / 2 + np.array(_OFFSETS)[None] * pitch).reshape(-1, 2)
        lo_b, hi_b = blocked.get(sheet, (np.zeros((0, 2)), np.zeros((0, 2))))
        mine = placed.setdefault(sheet, [])
        if mine:
            lo_b = np.concatenate([lo_b, np.array([b[0] for b in mine])])
            hi_b = np.concatenate([hi_b, np.array([b[1] for b in mine])])
        spot = None
        for scale in NUMBER_SCALES:
            h = scale * label_h
            lo, hi = number_box(name, np.zeros(2), h)
            at = _first_clear(centres + lo, centres + hi, lo_b, hi_b, on=(origin, pitch, cells))
            if at is not None:
                spot = (centres[at], h)
                break
        if spot is None:  # beside the piece, on free paper
            # the nearest spots to any face of the piece first, so the number reads as its piece's
            near = (lows[faces][None, :, :] + pitch / 2 + np.array(_BESIDE)[:, None, :] * pitch).reshape(-1, 2)
            lo_p, hi_p = paper.get(sheet, (np.zeros((0, 2)), np.zeros((0, 2))))
            lo_all, hi_all = np.concatenate([lo_b, lo_p]), np.concatenate([hi_b, hi_p])
            for scale in NUMBER_SCALES:
                h = scale * label_h
                lo, hi = number_box(name, np.zeros(2), h)
                at = _first_clear(near + lo, near + hi, lo_all, hi_all, area=area)
                if at is not None:
                    spot = (near[at], h)
                    break
        if spot is None:
            spot = (lows[first] + pitch / 2, NUMBER_SCALES[-1] * label_h)
        mine.append(number_box(name, spot[0], spot[1]))
        out.append((sheet, spot[0], spot[1]))
    return out


#: Boxes tried at once for a number's spot: the first few faces' spots mostly hold one, and a piece's
#: every spot against every label of its sheet is a large table (the queen's take a tenth of a second).
_BLOCK = 256


def _first_clear(lo: npt.NDArray[np.float64], hi: npt.NDArray[np.float64], lo_b: npt.NDArray[np.float64],
                 hi_b: npt.NDArray[np.float64], *,
                 on: tuple[npt.NDArray[np.float64], float, npt.NDArray[np.int64]] | None = None,
                 area: tuple[float, float, float, float] | None = None) -> int | None:
    """The first of the boxes ``lo``-``hi`` clear of every box ``lo_b``-``hi_b`` and wholly on the cells of
    ``on`` (origin, pitch, cells: :func:`_on_cells`) or inside ``area``; tried :data:`_BLOCK` at a time."""
    for start in range(0, lo.shape[0], _BLOCK):
        a, b = lo[start:start + _BLOCK], hi[start:start + _BLOCK]
        if on is not None:
            ok = _on_cells(a, b, *on)
        else:
            ok = np.ones(a.shape[0], dtype=bool)
        if area is not None:
            ok &= (a[:, 0] >= area[0]) & (a[:, 1] >= area[1]) & (b[:, 0] <= area[2]) & (b[:, 1] <= area[3])
        ok[ok] = ~_meets(a[ok], b[ok], lo_b, hi_b).any(axis=1)
        if ok.any():
            return start + int(np.argmax(ok))
    return None


def _meets(lo: npt.NDArray[np.float64], hi: npt.NDArray[np.float64], lo_b: npt.NDArray[np.float64],
           hi_b: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
    """``(n, m)``: which of boxes ``lo``-``hi`` come within :data:`NUMBER_CLEAR` of which of ``lo_b``-``hi_b``."""
    return ((lo[:, None, 0] < hi_b[None, :, 0] + NUMBER_CLEAR) & (hi[:, None, 0] > lo_b[None, :, 0] - NUMBER_CLEAR)
            & (lo[:, None, 1] < hi_b[None, :, 1] + NUMBER_CLEAR) & (hi[:, None, 1] > lo_b[None, :, 1] - NUMBER_CLEAR))


def _on_cells(lo: npt.NDArray[np.float64], hi: npt.NDArray[np.float64], origin: npt.NDArray[np.float64],
              pitch: float, cells: npt.NDArray[np.int64]) -> npt.NDArray[np.bool_]:
    """Which boxes (at most two faces across) lie wholly on the cells ``cells`` ``(K, 2)`` counted from ``origin``."""
    # The cells as a raster, looked up all at once: every face of the queen's pieces is tried, at each
    # scale, at nine points of each box.
    base = cells.min(axis=0)
    on = np.zeros(tuple((cells.max(axis=0) - base + 1).tolist()), dtype=bool)
    on[cells[:, 0] - base[0], cells[:, 1] - base[1]] = True
    ok = np.ones(lo.shape[0], dtype=bool)
    eps = 1e-6 * pitch
    for fx in (0.0, 0.5, 1.0):
        for fy in (0.0, 0.5, 1.0):
            pt = lo + (hi - lo) * (fx, fy) + np.where(np.array([fx, fy]) == 0.0, eps, np.where(np.array([fx, fy]) == 1.0, -eps, 0.0))
            cell = np.floor((pt - origin) / pitch).astype(np.int64) - base
            inside = (cell >= 0).all(axis=1) & (cell < on.shape).all(axis=1)
            ok &= inside
            ok[inside] &= on[cell[inside, 0], cell[inside, 1]]
    return ok


def ink_under(centre: npt.NDArray[np.float64], s: int, fs: npt.NDArray[np.int64], pos: npt.NDArray[np.float64],
              ink: npt.NDArray[np.int64], paper: int) -> int:
    """The ink of the face under ``centre`` on sheet ``s`` (a piece number on its piece), else ``paper``'s."""
    lo, hi = pos.min(axis=1), pos.max(axis=1)
    under = np.flatnonzero((fs == s) & (lo <= centre).all(axis=1) & (hi >= centre).all(axis=1))
    return int(ink[under[0]]) if under.size else paper


def paper_boxes(pos: npt.NDArray[np.float64], fs: npt.NDArray[np.int64], sides: npt.NDArray[np.int64],
                 tabs: TabPlan) -> dict[int, tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
    """Per sheet, the boxes ``(lo, hi)`` of every face and glue tab: the paper a number beside its piece must keep off."""
    seam_face = sides[np.arange(sides.shape[0]), np.maximum(tabs.side, 0), 0]
    poly = tabs.polygon[tabs.placed]
    lo = np.concatenate([pos.min(axis=1), poly.min(axis=1)])
    hi = np.concatenate([pos.max(axis=1), poly.max(axis=1)])
    sheets = np.concatenate([fs, fs[seam_face[tabs.placed]]])
    return {int(s): (lo[sheets == s], hi[sheets == s]) for s in np.unique(sheets).tolist()}


def number_text(names: list[str], centres: npt.NDArray[np.float64], heights: npt.NDArray[np.float64]) -> Polylines:
    """Piece numbers in bold (each stroke twice, a hair apart), each in its box (:func:`number_box`)."""
    if not names:
        return Polylines.empty()
    centres = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
    heights = np.asarray(heights, dtype=np.float64).reshape(-1)
    origins = centres - np.stack([np.zeros(len(names)), heights / 2], axis=1)
    right = np.tile([1.0, 0.0], (len(names), 1))
    bold = (0.07 * heights)[:, None] * np.array([1.0, 0.0])
    boxes = []
    for name, c, h in zip(names, centres, heights.tolist()):
        lo, hi = number_box(name, c, h)
        boxes.append(np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]]))
    return Polylines.concat([
        text_polylines(names, origins - bold, right, heights, center=True),
        text_polylines(names, origins + bold, right, heights, center=True),
        Polylines.from_list(boxes, [True] * len(boxes)),
    ])


def assembly_page(sheets: list[tuple[float, float, Polylines, list[tuple[int, npt.NDArray[np.float64]]]]],
                  joins: list[tuple[int, int]], order: list[int], size: tuple[float, float], margin: float,
                  title: str) -> Page:
    """The first page of a printed net: a map of every sheet with its pieces' numbers, the joins and the order.

    Parameters
    ----------
    sheets : list of (width, height, cut outlines, [(piece, centre mm)])
        Each sheet's size, its cut lines and where each piece's number stands.
    joins : list of (int, int)
        0-based pieces that share seams.
    order : list of int
        0-based pieces in gluing order.
    size : (float, float)
        Page size, mm.
    margin : float
        Empty border, mm.
    title : str
        The net's title.
    """
    w, h = size
    th = ASSEMBLY_TEXT
    lines = [f"ASSEMBLY  {title}".strip()]
    lines += _wrapped("GLUE IN THIS ORDER: " + " ".join(piece_name(i + 1) for i in order), w - 2 * margin, th)
    for i in order:
        mates = sorted({b for a, b in joins if a == i} | {a for a, b in joins if b == i})
        lines += _wrapped(f"{piece_name(i + 1)} JOINS " + (" ".join(piece_name(m + 1) for m in mates) or "-"),
                          w - 2 * margin, th)
    step = 1.6 * th
    text_h = step * len(lines)
    ys = h - margin - th - step * np.arange(len(lines))
    label = [text_polylines(lines, np.stack([np.full(len(lines), margin), ys], axis=1),
                            np.tile([1.0, 0.0], (len(lines), 1)), th)]
    # The sheet maps in a grid below the text, each scaled alike and labelled with its number.
    area_w, area_h = w - 2 * margin, h - 2 * margin - text_h - step
    n = len(sheets)
    cols = max(1, int(np.ceil(np.sqrt(n * area_w / max(area_h, 1.0) * sheets[0][1] / sheets[0][0]))))
    cols = min(cols, n)
    rows = int(np.ceil(n / cols))
    cell_w, cell_h = area_w / cols, area_h / rows
    scale = min((cell_w - 2.0) / sheets[0][0], (cell_h - step - 2.0) / sheets[0][1])
    cut: list[Polylines] = []
    names: list[str] = []
    where: list[npt.NDArray[np.float64]] = []
    for s, (sw, sh, outline, numbers) in enumerate(sheets):
        r, c = divmod(s, cols)
        origin = np.array([margin + c * cell_w + 1.0, margin + (rows - 1 - r) * cell_h + 1.0])
        frame = origin + np.array([[0, 0], [sw, 0], [sw, sh], [0, sh]]) * scale
        cut.append(Polylines.from_list([frame], [True]))
        if len(outline):
            cut.append(Polylines(outline.points * scale + origin, outline.offsets, outline.closed))
        label.append(text_polylines([f"SHEET {s + 1}"], [origin + np.array([0.0, sh * scale + 0.5])], [(1.0, 0.0)],
                                    min(th, 0.8 * step)))
        for piece, centre in numbers:
            names.append(piece_name(piece + 1))
            where.append(origin + centre * scale - np.array([0.0, th / 2]))
    if names:
        label.append(text_polylines(names, np.array(where), np.tile([1.0, 0.0], (len(names), 1)), th, center=True))
    layers = {"CUT": Polylines.concat(cut), "LABEL": Polylines.concat(label)}
    return Page(w, h, layers, title="assembly")


def _wrapped(text: str, width: float, height: float) -> list[str]:
    """``text`` broken at spaces into lines no wider than ``width`` at cap height ``height``."""
    out: list[str] = []
    line = ""
    for word in text.split(" "):
        trial = f"{line} {word}" if line else word
        if line and text_width(trial, height) > width:
            out.append(line)
            line = "    " + word
        else:
            line = trial
    if line:
        out.append(line)
    return out
