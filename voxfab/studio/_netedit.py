"""What ``POST /api/nets/edit`` does: cut or join one edge of a chosen net, or undo the last edit.

The edit itself is :func:`voxfab.unfold.cut_edge` / :func:`voxfab.unfold.join_edge`
(a local repair, validated); this module only finds the net the page names in
its job, and makes the record the route keeps as a new job (its net 0, so
``/api/make`` can use it) with the marks made so far and the nets before it (for
undo), and the net laid out for the page (:mod:`._routes.net` is the route).

Body: ``{"job": ID, "index": N, "cut": [faceA, faceB]}`` or ``"join": [...]`` or
``"undo": true``, faces as ``[x, y, z, "+z"]``; ``"grid"`` (packed) is needed only
when the gallery job did not keep its shape, ``"marks"`` (``{"cut": [...], "keep":
[...]}``) starts the marks of a net that has none yet (one fresh from a gallery), and
``"split": true`` makes a cut leave the cut-off side as a piece of its own (the default
for a net already in pieces).  Answer: ``{"job": NEWID, "net": ITEM}``
with ITEM as a gallery item plus ``"marks"``, ``"moved"``, ``"cut"``, ``"joined"``
and ``"undo"`` (edits that undo can take back).

A net in pieces is laid out again on its sheets after each edit: the pieces the edit
left as they were keep their sheet and spot (as the page shows them: ``"placement"``
sent, else as the net's job placed them), the others go into the room left
(:func:`voxfab.fabricate.netdraw.fit_and_placement` with ``before``).  ``"repack":
true`` packs the net again from scratch instead, without editing it.  The new job
keeps the placement, so ``/api/make`` draws the files as the editor shows them.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError

#: Edits one chain of edits remembers for undo.
MAX_UNDO = 50


def _pieces(net: Any) -> list[Any]:
    return [net] if hasattr(net, "corners2d") else list(net)


def net_item(grid: np.ndarray, net: Any, marks: Any, *, history: int, extra: dict[str, Any],
             drawing: Any = None, before: tuple[list[Any], Any] | None = None) -> dict[str, Any]:
    """A gallery item for an edited net, with its marks and how many edits undo can take back.

    The layout, and with the gallery's drawing options the fit and placement on the sheets,
    are the library gallery's own (:mod:`voxfab.fabricate.netdraw`); ``before`` (the pieces
    before the edit and their placement) keeps the pieces the edit left alone in place.
    """
    from voxfab.fabricate.netdraw import fit_and_placement, net_layout
    from voxfab.shape import fill_cavities, surface_graph

    pieces = _pieces(net)
    first = pieces[0]
    graph = surface_graph(fill_cavities(grid) if first.filled else grid)
    placed: dict[str, Any] = {}
    if drawing is not None:
        fit, placement = fit_and_placement(pieces, drawing, graph, before=before)
        placed = {"fit": fit, "placement": placement}
    return {**placed,
        "index": 0, "seed": int(first.seed), "faces": sum(p.face_count for p in pieces), "pieces": len(pieces),
        "mountain": sum(int(p.mountain) for p in pieces), "valley": sum(int(p.valley) for p in pieces),
        "seams_without_tab_room": sum(int(p.seams_without_tab_room) for p in pieces),
        "layout": net_layout(grid, pieces, graph=graph),
        "marks": marks.to_dict() if marks else {"cut": [], "keep": []},
        "undo": history, **extra,
    }


_NORMALS = {"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0), "+z": (0, 0, 1), "-z": (0, 0, -1)}


def piece_of(pieces: list[Any], face: tuple) -> int | None:
    """The 1-based number of the piece holding ``face`` (``(x, y, z, "+z")``), as the nets print it, or None."""
    x, y, z, d = face
    n = np.asarray(_NORMALS[d])
    for i, net in enumerate(pieces):
        if bool(((net.voxel == (x, y, z)).all(axis=1) & (net.normal == n).all(axis=1)).any()):
            return i + 1
    return None


def refusal_words(message: str, pieces: list[Any], a: tuple, b: tuple) -> str:
    """A refused join in the pieces' own numbers (the edge's faces stay in brackets at the end, for the tooltip).

    The library names an edge by its two faces, ``[14,13,7,+x]-[15,13,6,+z]``; the page shows
    pieces by their printed numbers, so the artist reads which pieces would not join and why.
    """
    pa, pb = piece_of(pieces, a), piece_of(pieces, b)
    if pa is None or pb is None or "no room to join" not in message:
        return message
    if pa != pb:
        said = f"pieces {min(pa, pb)} and {max(pa, pb)} cannot be joined along that edge: the joined piece would overlap itself"
    else:
        said = (f"that edge of piece {pa} cannot be closed: every way to open the loop it closes makes faces "
                "overlap or opens a seam that is cut")
    return f"{said} ({message})"


def _edge(value: Any, name: str) -> tuple[tuple, tuple]:
    from voxfab.unfold._constraints import _edge as parse_edge

    return parse_edge(value, name)


def shown_placement(job: Any, index: int, sent: Any) -> Any:
    """The placement the page shows net ``index`` of ``job`` with: the one ``sent`` (the artist may have
    moved pieces), else the one the job gave it; None when it has none (a net that does not fit)."""
    from voxfab.fabricate.netdraw._placement import Placement

    if sent is None:
        sent = job.data.get("placement") if index == 0 else None
    if sent is None:
        items = job.items or (job.result or {}).get("nets") or []
        item = items[index] if index < len(items) and isinstance(items[index], dict) else {}
        sent = item.get("placement")
    return None if sent is None else Placement.from_dict(sent)


def apply_edit(job: Any, data: dict[str, Any]) -> dict[str, Any]:
    """What one edit makes: the record a new job keeps (``nets``, ``grid``, ``marks``, ``history``) and its answer."""
    from voxfab.unfold import EdgeConstraints, cut_edge, join_edge

    from . import _grid
    from ._bodies import flag, whole

    nets = job.data.get("nets") or []
    if not nets:
        raise InvalidShapeError(f"job: job {job.id} has no nets to edit")
    index = whole(data.get("index", 0), name="index", lo=0, hi=len(nets) - 1)
    # A grid sent is checked like every shape input (at most the editor's 25³), and must be the net's own.
    sent = None if data.get("grid") is None else _grid.unpack(data.get("grid"))
    grid = job.data.get("grid")
    if grid is None:
        if sent is None:
            raise InvalidShapeError("grid: this gallery did not keep its shape; send the shape as \"grid\"")
        grid = sent
    elif sent is not None and (sent.shape != grid.shape or not np.array_equal(sent, grid)):
        raise InvalidShapeError("grid: the shape changed since this net was made; make a new gallery to edit it")
    net = nets[index]
    # Marks sent are checked whole (unknown keys, every face) even when the net has marks of its own.
    sent_marks = None
    if data.get("marks") is not None:
        from voxfab.unfold import EdgeConstraints as Marks

        sent_marks = Marks.from_dict(data["marks"])
    marks = job.data.get("marks")
    if marks is None and job.data.get("constraints") is not None:
        marks = job.data["constraints"]
    if marks is None and sent_marks:
        # a net fresh from a gallery: the marks the page made so far start its record
        marks = sent_marks
    history = list(job.data.get("history", []))
    undo = flag(data.get("undo"), name="undo")
    repack = flag(data.get("repack"), name="repack")
    kinds = ([k for k in ("cut", "join") if data.get(k) is not None] + (["undo"] if undo else [])
             + (["repack"] if repack else []))
    if len(kinds) != 1:
        raise InvalidShapeError("edit: give exactly one of \"cut\": [face, face], \"join\": [face, face], "
                                "\"undo\": true, \"repack\": true")
    kind = kinds[0]
    placed = shown_placement(job, index, data.get("placement"))
    before = None if kind == "repack" or placed is None else (_pieces(net), placed)
    start = time.perf_counter()
    if kind == "repack":
        extra: dict[str, Any] = {"moved": 0, "cut": [], "joined": []}
    elif kind == "undo":
        if not history:
            raise InvalidShapeError("undo: no edit of this net to take back")
        net, marks = history.pop()
        extra = {"moved": 0, "cut": [], "joined": []}
    else:
        a, b = _edge(data[kind], kind)
        split = data.get("split")
        if split is not None:
            split = flag(split, name="split")
        known = marks if isinstance(marks, EdgeConstraints) else None
        if kind == "cut":
            result = cut_edge(grid, _pieces(net), a, b, constraints=known, split=split)
        else:
            from voxfab.errors import UnfoldError

            try:
                result = join_edge(grid, _pieces(net), a, b, constraints=known)
            except UnfoldError as exc:
                raise UnfoldError(refusal_words(str(exc), _pieces(net), a, b)) from None
        history = (history + [(net, marks)])[-MAX_UNDO:]
        net = result.pieces[0] if len(result.pieces) == 1 else result.pieces
        marks = result.marks
        extra = {"moved": result.moved, "cut": [[list(x), list(y)] for x, y in result.cut],
                 "joined": [[list(x), list(y)] for x, y in result.joined]}
    extra["edit"] = kind
    extra["seconds"] = round(time.perf_counter() - start, 3)
    # The gallery's options (search, drawing) travel with every edited net, for its fit and files.
    options = job.data.get("options")
    item = net_item(grid, net, marks, history=len(history), extra=extra,
                    drawing=options[1] if options is not None else None, before=before)
    # The placement shown is the one the files are drawn with (/api/make without one sent).
    record = {"nets": [net], "grid": grid, "marks": marks, "history": history, "options": options,
              "placement": item.get("placement")}
    return {"record": record, "item": item}
