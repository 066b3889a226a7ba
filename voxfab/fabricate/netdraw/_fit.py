"""Nets for a sheet: one piece on one sheet at the face size asked for, or a clear error, or pieces.

The default order of a paper net (issue: buildable objects):

1. one piece on one sheet at the requested face size, found by steering the
   net search into the sheet (``unfold(fit=...)``);
2. when none is found, an error naming the largest face size at which a net
   fits this sheet and the smallest sheet that takes it at this face size,
   both measured from the most compact net found; never a silent split;
3. with ``pieces="auto"``, pieces from flat patches or the fewest large
   pieces, whichever packs on fewer sheets by :func:`draw_pieces`.

Faces too small for legible marks are refused before any search.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.unfold import Net

from ._labels import label_length
from ._legible import legibility_problem, smallest_face_size
from ._options import DrawingOptions
from ._sheets import extent_of, fit_error, largest_face_size, sheet_cells, smallest_sheet

#: Budget of the search that measures a net when the sheet search gave no extent, seconds.
MEASURE_TIMEOUT = 20.0


@dataclasses.dataclass(frozen=True, eq=False)
class SheetNets:
    """Nets found for a sheet.

    Attributes
    ----------
    nets : list of list of Net
        Each result as its pieces (one Net for a one-piece net).
    options : DrawingOptions
        The drawing options with the face size settled.
    notes : list of str
        Report lines (how many distinct nets were found, the face size chosen).
    """

    nets: list[list[Net]]
    options: DrawingOptions
    notes: list[str]


def _surface_faces(grid: Any, fill: bool) -> int:
    from voxfab.shape import fill_cavities, surface_graph

    g = np.asarray(grid, dtype=bool)
    return surface_graph(fill_cavities(g) if fill else g).face_count


def _measured_extent(err: UnfoldError, grid: Any, rng: Any, search: dict[str, Any]) -> tuple[int, int]:
    """Extent of the most compact net: from the error when it says, else from an unconstrained search."""
    from voxfab.unfold import unfold

    best = getattr(err, "best_extent", None)
    if best is not None:
        return int(best[0]), int(best[1])
    kept = {k: v for k, v in search.items() if k not in ("fit", "timeout", "compact")}
    net = unfold(grid, rng=rng, compact=True, timeout=min(float(search.get("timeout", 60.0)), MEASURE_TIMEOUT),
                 **kept)
    return extent_of(net.corners2d)


def find_sheet_nets(grid: Any, options: DrawingOptions, *, rng: int, pieces: str = "one", count: int = 1,
                    budget: float = 60.0, **search: Any) -> SheetNets:
    """Search nets of ``grid`` that fit the sheet of ``options``.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
    options : DrawingOptions
        Sheet, face size (``pitch``; ``None`` for the largest at which a one-piece
        net fits), tabs and marks.
    rng : int
        Seed of the search.
    pieces : {"one", "auto"}
        ``"auto"``: when one piece does not fit, split into pieces that do, cut
        the way that packs on the fewest sheets (:func:`_fewest_sheets`).
    count : int
        Distinct one-piece nets wanted.
    budget : float
        Seconds for all ``count`` nets together (each also has its ``timeout``).
    **search
        ``strategy``, ``timeout``, ``fill``, ``compact``, ``tab_aware`` for
        :func:`voxfab.unfold.unfold`.

    Returns
    -------
    SheetNets

    Raises
    ------
    InvalidShapeError
        When the faces are too small for legible numbers and tabs (before any search).
    SheetFitError
        When no one-piece net fits and pieces were not allowed.
    """
    from voxfab.unfold import unfold, unfold_many

    search = {k: v for k, v in search.items() if k != "fit"}
    faces = _surface_faces(grid, bool(search.get("fill", False)))
    # A one-piece net has at most F + 1 seams; pieces label seams by their surface edge, of which there are 2F.
    chars = label_length(2 * faces if pieces == "auto" else faces + 1)
    notes: list[str] = []
    if options.pitch is None:
        options, auto_notes = _auto_face_size(grid, options, rng=rng, pieces=pieces, chars=chars, search=search)
        notes += auto_notes
    problem = legibility_problem(options, float(options.pitch), chars)
    if problem:
        raise InvalidShapeError(problem)
    fit = sheet_cells(options, float(options.pitch))
    if min(fit) < 1:
        raise InvalidShapeError(f"sheet: {options.sheet} has no room for one {options.pitch:g} mm face with its tabs")
    if count > 1:
        found = unfold_many(grid, count=count, rng=rng, fit=fit, budget=budget, **search)
        if len(found) < count:
            notes.append(f"{len(found)} distinct nets found of the {count} asked for")
        return SheetNets([[n] for n in found], options, notes)
    # With pieces allowed, a surface larger than the sheet goes straight to the split.
    if pieces != "auto" or faces <= fit[0] * fit[1]:
        try:
            return SheetNets([[unfold(grid, rng=rng, fit=fit, **search)]], options, notes)
        except UnfoldError as err:
            if pieces != "auto":
                extent = _measured_extent(err, grid, rng, search)
                raise fit_error(extent, options, float(options.pitch), what="the most compact net found") from None
    return SheetNets([_fewest_sheets(grid, options, fit, rng, search)], options, notes)


def _fewest_sheets(grid: Any, options: DrawingOptions, fit: tuple[int, int], rng: int,
                   search: dict[str, Any]) -> list[Net]:
    """Pieces from flat patches when they pack within the goal of sheets, else the better of both ways.

    Pieces from flat patches are compact and pack densely, but there are more
    of them; the few large pieces of ``"auto"`` are tried when the flat ones
    miss ``ceil(1.25 A / U)`` sheets (:func:`sheets_needed`), and the fewer
    sheets win, then the fewer seams without room for a tab, then the fewer
    pieces.
    """
    from voxfab.fabricate.netdraw._drawing import sheets_needed
    from voxfab.shape import fill_cavities
    from voxfab.unfold import unfold

    g = np.asarray(grid, dtype=bool)
    shape = fill_cavities(g) if search.get("fill", False) else g
    best: tuple[tuple[int, int, int], list[Net]] | None = None
    for mode in ("flat", "auto"):
        try:
            nets = list(unfold(grid, rng=rng, fit=fit, pieces=mode, **search))
        except UnfoldError:
            if mode == "auto" and best is None:
                raise
            continue
        sheets, goal, untabbed = sheets_needed(shape, nets, options)
        key = (sheets, untabbed, len(nets))
        if best is None or key < best[0]:
            best = (key, nets)
        if sheets <= goal and untabbed == 0:
            break
    assert best is not None
    return best[1]


def _auto_face_size(grid: Any, options: DrawingOptions, *, rng: int, pieces: str, chars: int,
                    search: dict[str, Any]) -> tuple[DrawingOptions, list[str]]:
    """The largest face size at which a compact one-piece net fits the sheet, if its marks are legible."""
    from voxfab.unfold import unfold

    net = unfold(grid, rng=rng, **{**search, "compact": True})
    extent = extent_of(net.corners2d)
    p = largest_face_size(extent, options)
    need = smallest_face_size(options, chars)
    if p >= need:
        return dataclasses.replace(options, pitch=p), [f"face size {p:g} mm: the largest at which the net fits"]
    if pieces == "auto":
        return dataclasses.replace(options, pitch=need), [
            f"face size {need:g} mm: the smallest with legible marks (one piece fits only at {p:g} mm)"]
    sheet = smallest_sheet(extent, options, need)
    where = f"at {need:g} mm it needs {sheet}" if sheet else f"at {need:g} mm it is larger than every standard sheet"
    raise InvalidShapeError(
        f"the most compact net found ({extent[0]} x {extent[1]} faces) fits {options.sheet} only at faces up "
        f"to {p:g} mm, too small for legible numbers and tabs (at least {need:g} mm); {where} (--sheet), "
        "or give a face size and split it (--pieces auto)"
    )
