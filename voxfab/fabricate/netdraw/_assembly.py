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

from ._legible import NUMBER_INSET

#: Height of the text lines of the assembly page, mm.
ASSEMBLY_TEXT = 3.5


def piece_name(number: int) -> str:
    """How piece ``number`` (1-based) is printed: ``(3)``; brackets are no seam label's characters."""
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


def number_text(names: list[str], centres: npt.NDArray[np.float64], pitch: float, label_h: float,
                free: npt.NDArray[np.bool_] | None = None) -> Polylines:
    """Piece names centred on their faces, clear of the seam labels along the edges, never smaller than those.

    ``free`` marks the faces with no seam label (all four edges folded): the whole face is
    room for the name.  Elsewhere the seam labels keep to a strip inset + label height
    deep along each edge.  A name is at least ``label_h`` tall, as tall as the seam labels
    a maker reads beside it, even where that takes it over a label strip.
    """
    if not names:
        return Polylines.empty()
    clear = np.zeros(len(names), dtype=bool) if free is None else np.asarray(free, dtype=bool)
    heights = []
    for t, whole in zip(names, clear.tolist()):
        room = pitch * (1 - 2 * NUMBER_INSET) - (0.0 if whole else 2 * label_h) - 0.1 * pitch
        fit = min(2 * label_h, 0.9 * room / max(text_width(t, 1.0), 1e-9), 0.8 * room)
        heights.append(max(label_h, fit))
    heights = np.array(heights)
    origins = centres - np.stack([np.zeros(len(names)), heights / 2], axis=1)
    return text_polylines(names, origins, np.tile([1.0, 0.0], (len(names), 1)), heights, center=True)


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
