"""Nets for a sheet: one piece on one sheet at the face size asked for, or a clear error, or pieces.

The default order of a paper net (issue: buildable objects):

1. one piece on one sheet at the requested face size, found by steering the
   net search into the sheet (``unfold(fit=...)``);
2. when none is found, an error naming the largest face size at which a net
   fits this sheet and the smallest sheet that takes it at this face size,
   both measured from the most compact net found; never a silent split;
3. with ``pieces="auto"``, pieces from flat patches (the few large pieces of
   the net search when flat patches give none), packed once by the drawing
   (:func:`_cut_pieces`).

Faces too small for legible marks are refused before any search.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.shape import component_count, describe_parts
from voxfab.unfold import Net

from ._labels import label_length
from ._legible import legibility_problem, smallest_face_size
from ._options import DrawingOptions
from ._sheets import check_pieces_sheet, extent_of, fit_error, largest_face_size, sheet_cells, smallest_sheet

#: Budget of the search that measures a net when the sheet search gave no extent, seconds.
MEASURE_TIMEOUT = 20.0

#: The largest ``ceil(1.25 A / U)`` at which the few large pieces are tried beside the flat patches.
_LARGE_PIECES_GOAL = 2

#: What :func:`distinct_cuts` keeps of each distinct net.
Kept = TypeVar("Kept")


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


def _measured_extent(err: UnfoldError | None, grid: Any, rng: Any, search: dict[str, Any]) -> tuple[int, int]:
    """Extent of the most compact net: from the error when it says, else from an unconstrained search."""
    from voxfab.unfold import unfold

    best = getattr(err, "best_extent", None)
    if best is not None:
        return int(best[0]), int(best[1])
    kept = {k: v for k, v in search.items() if k not in ("fit", "timeout", "compact")}
    net = unfold(grid, rng=rng, compact=True, timeout=min(float(search.get("timeout", 60.0)), MEASURE_TIMEOUT),
                 **kept)
    return extent_of(net.corners2d)


class FaceSizeError(InvalidShapeError):
    """Faces too small for legible seam labels and glue tabs.

    Attributes
    ----------
    ways_out : list of dict
        The choices that would work: ``{"label": plain words, "options": {NAME: VALUE}}``.
    """

    def __init__(self, message: str, ways_out: list[dict[str, Any]]) -> None:
        super().__init__(message)
        self.ways_out = ways_out


def legibility_ways_out(options: DrawingOptions, chars: int, *, sheet: str | None = None,
                        pieces: bool = False) -> list[dict[str, Any]]:
    """Ways out of faces too small for the marks: the smallest face size that works, or no marks."""
    need = smallest_face_size(options, chars)
    out: list[dict[str, Any]] = []
    if pieces:
        out.append({"label": f"make the faces {need:g} mm and split the net into pieces",
                    "options": {"face_size": need, "pieces": "auto"}})
    elif sheet:
        out.append({"label": f"make the faces {need:g} mm on a larger sheet ({sheet})",
                    "options": {"face_size": need, "sheet": sheet}})
    else:
        out.append({"label": f"make the faces {need:g} mm", "options": {"face_size": need}})
    off = {k: False for k in ("numbers", "tabs") if getattr(options, k)}
    if off:
        words = " and ".join({"numbers": "edge labels", "tabs": "glue tabs"}[k] for k in off)
        out.append({"label": f"draw without {words}", "options": off})
    return out


def _check_legible(options: DrawingOptions, chars: int) -> None:
    problem = legibility_problem(options, float(options.pitch), chars)
    if problem:
        raise FaceSizeError(problem, legibility_ways_out(options, chars))


def label_chars(faces: int, pieces: str) -> int:
    """Characters of a seam label: a one-piece net has at most F + 1 seams, pieces number all 2F surface edges."""
    return label_length(2 * faces if pieces == "auto" else faces + 1)


def find_sheet_nets(grid: Any, options: DrawingOptions, *, rng: int, pieces: str = "one", count: int = 1,
                    budget: float = 60.0, show_unfit: bool = False,
                    progress: Callable[[int, int], None] | None = None, **search: Any) -> SheetNets:
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
        ``"auto"``: when one piece does not fit, split into pieces that do
        (:func:`_cut_pieces`).
    count : int
        Distinct nets wanted (:func:`voxfab.unfold.unfold_many`; with
        ``pieces="auto"`` each is the unfolding of one of its seeds).
    budget : float
        Seconds for all ``count`` nets together (each also has its ``timeout``).
    show_unfit : bool
        When no one-piece net fits the sheet, return nets searched without the
        sheet (the gallery shows how each fits) instead of raising.
    progress : callable, optional
        ``progress(found, count)`` after each net.  A cancelled studio job stops
        the search (:func:`voxfab._shared.progress.check_cancelled`).
    **search
        ``strategy``, ``timeout``, ``fill``, ``compact``, ``tab_aware`` for
        :func:`voxfab.unfold.unfold`.

    Returns
    -------
    SheetNets

    Raises
    ------
    FaceSizeError
        When the faces are too small for legible numbers and tabs (before any search).
    SheetFitError
        When no one-piece net fits and pieces were not allowed.
    """
    from voxfab.unfold import NoFitError

    search = {k: v for k, v in search.items() if k != "fit"}
    faces = _surface_faces(grid, bool(search.get("fill", False)))
    chars = label_chars(faces, pieces)
    notes: list[str] = []
    if options.pitch is None and pieces == "auto":
        _check_pieces_sheet_at_smallest(faces, options, chars)
    if options.pitch is None and pieces == "auto" and component_count(grid) > 1:
        # Parts joined only by edges or corners (voxel art) have no one-piece net to size the faces by.
        need = smallest_face_size(options, chars)
        options = dataclasses.replace(options, pitch=need)
        notes.append(f"face size {need:g} mm: the smallest with legible marks; one net per part, as the "
                     f"shape is in {describe_parts(grid)} (--join makes it one piece)")
    elif options.pitch is None:
        options, auto_notes = _auto_face_size(grid, options, rng=rng, pieces=pieces, chars=chars, search=search)
        notes += auto_notes
    fit = sheet_room(options, faces, pieces)
    # A surface larger than the sheet has no one-piece net on it: no search can find one.
    room = faces <= fit[0] * fit[1]
    if pieces == "auto" and not room:
        check_pieces_sheet(faces, options, float(options.pitch), smallest_face_size(options, chars))
        return SheetNets(_piece_nets(grid, rng, fit, count, budget, progress, search, notes, options), options,
                         notes)
    found: list[Net] | None = None
    failed: UnfoldError | None = None
    if room:
        try:
            found = _nets(grid, count, rng, budget, progress, {**search, "fit": fit})
        except UnfoldError as err:
            failed = err
    if found is None:
        if pieces == "auto":
            check_pieces_sheet(faces, options, float(options.pitch), smallest_face_size(options, chars))
            return SheetNets(_piece_nets(grid, rng, fit, count, budget, progress, search, notes, options),
                             options, notes)
        if failed is not None and not isinstance(failed, NoFitError):
            raise failed  # out of time, or marks that leave no net: not a question of the sheet
        if show_unfit:
            found = _nets(grid, count, rng, budget, progress, search)
            notes.append(f"no one-piece net fits {options.sheet} at {options.pitch:g} mm faces")
        else:
            extent = _measured_extent(failed, grid, rng, search)
            raise fit_error(extent, options, float(options.pitch), what="the most compact net found") from None
    if count > 1 and len(found) < count:
        notes.append(f"{len(found)} distinct nets found of the {count} asked for")
    return SheetNets([[n] for n in found], options, notes)


def _check_pieces_sheet_at_smallest(faces: int, options: DrawingOptions, chars: int) -> None:
    """Refuse a hopeless sheet for pieces before the search that chooses the face size.

    The smallest face size with legible marks needs the fewest sheets: a sheet hopeless there is hopeless
    at every face size that search could choose (a one-piece net that fits at a larger one fits one sheet),
    and the face size it ends with, when only pieces fit, is that smallest one; so the refusal is the one
    after the search, in the same words, with no search run and no compiled kernel loaded.
    """
    need = smallest_face_size(options, chars)
    smallest = dataclasses.replace(options, pitch=need)
    fit = sheet_room(smallest, faces, "auto")
    if faces > fit[0] * fit[1]:
        check_pieces_sheet(faces, smallest, need, need)


def sheet_room(options: DrawingOptions, faces: int, pieces: str) -> tuple[int, int]:
    """The sheet's cells at the face size of ``options`` for a surface of ``faces`` faces, once its marks are
    legible and a face fits: the checks before any search, shared by :func:`find_sheet_nets` and the
    studio's gallery in pieces (:func:`._gallery.net_gallery`), so both refuse a sheet in the same words."""
    _check_legible(options, label_chars(faces, pieces))
    fit = sheet_cells(options, float(options.pitch))
    if min(fit) < 1:
        raise InvalidShapeError(f"sheet: {options.sheet} has no room for one {options.pitch:g} mm face with its tabs")
    # Tiny faces make the sheet millions of faces wide: a box wider than the search takes bounds no net.
    from voxfab.unfold._search import MAX_FIT_SIDE

    return min(fit[0], MAX_FIT_SIDE), min(fit[1], MAX_FIT_SIDE)


def _nets(grid: Any, count: int, rng: int, budget: float, progress: Callable[[int, int], None] | None,
          search: dict[str, Any]) -> list[Net]:
    """One-piece nets: the net of seed ``rng`` (``voxfab net``), or ``count`` distinct ones (``--count``)."""
    from voxfab.unfold import unfold

    if count > 1:
        from voxfab.unfold import unfold_many

        return unfold_many(grid, count=count, rng=rng, budget=budget, progress=progress, **search)
    found = [unfold(grid, rng=rng, **search)]
    if progress is not None:
        progress(1, 1)
    return found


def _piece_nets(grid: Any, rng: int, fit: tuple[int, int], count: int, budget: float,
                progress: Callable[[int, int], None] | None, search: dict[str, Any],
                notes: list[str], options: DrawingOptions | None = None) -> list[list[Net]]:
    """Nets in pieces, one per seed: seed ``rng`` for one net, seeds drawn from it for several."""
    if count == 1:
        return [_cut_pieces(grid, fit, rng, search, options)]
    gen = np.random.default_rng(rng)
    timeout = float(search.pop("timeout", 60.0))

    def cut(seconds: float) -> list[Net]:
        seed = int(gen.integers(0, 2**31 - 1))
        return _cut_pieces(grid, fit, seed, {**search, "timeout": min(timeout, seconds)})

    return distinct_cuts(cut, list, count=count, budget=budget, notes=notes, progress=progress)


def distinct_cuts(cut: Callable[[float], list[Net]], keep: Callable[[list[Net]], Kept], *, count: int,
                  budget: float, notes: list[str], progress: Callable[[int, int], None] | None = None,
                  on_item: Callable[[int, Kept], None] | None = None) -> list[Kept]:
    """Up to ``count`` nets in pieces that differ once cut out, within ``budget`` seconds.

    ``cut(seconds)`` cuts one net, given the seconds left (an ``UnfoldError``
    skips the try); a net whose outlines repeat one kept is dropped; ``keep``
    turns each other one into what is returned, handed to ``on_item(index, kept)``
    at once.  At most ``4 * count + 8`` tries: a shape with few distinct nets
    ends early, and the notes say how many were found.
    """
    import time

    from voxfab._shared.progress import check_cancelled
    from voxfab.unfold import outline_key

    end = time.monotonic() + budget
    out: list[Kept] = []
    seen: set[bytes] = set()
    tries = 0
    while len(out) < count and tries < 4 * count + 8 and time.monotonic() < end:
        check_cancelled()
        tries += 1
        try:
            nets = cut(end - time.monotonic())
        except UnfoldError:
            continue
        key = b"|".join(sorted(outline_key(n) for n in nets))
        if key in seen:
            continue
        seen.add(key)
        out.append(keep(nets))
        if on_item is not None:
            on_item(len(out) - 1, out[-1])
        if progress is not None:
            progress(len(out), count)
    if not out:
        raise UnfoldError(f"no net in pieces found within the budget of {budget:g} s")
    if len(out) < count:
        notes.append(f"{len(out)} distinct nets found of the {count} asked for")
    return out


def _cut_pieces(grid: Any, fit: tuple[int, int], rng: int, search: dict[str, Any],
                options: DrawingOptions | None = None) -> list[Net]:
    """The pieces, cut once, before any packing: from flat patches, or the few large pieces of ``"auto"``
    when flat patches give none or, packed on the sheets of ``options``, take fewer sheets.

    Measured at 8.6 mm faces: pieces from flat patches pack on fewer pages than Blender's Paper Model
    on every bundled shape (A4: queen 4 against 5, pawn 4 against 6, egg 10 against 18), in about a
    third of the time the few large pieces take to cut; those win a sheet only on a surface of about
    one sheet and a third (the queen on A4: 3 sheets against 4, at twice the time).  So the large
    pieces are cut only when the flat patches pack on more sheets than ``ceil(1.25 A / U)`` on a surface
    of at most :data:`_LARGE_PIECES_GOAL` sheets by that bound (the ball, torus and blob of
    ``bench/bench_density.py`` gain no sheet from them, at up to ten times the time), and kept
    only on fewer sheets with no more seams left without a tab (the packing is kept for the drawing).
    """
    from voxfab.unfold import unfold

    try:
        flat = list(unfold(grid, rng=rng, fit=fit, pieces="flat", **search))
    except UnfoldError:
        return list(unfold(grid, rng=rng, fit=fit, pieces="auto", **search))
    if options is None or options.pitch is None:
        return flat
    from voxfab.shape import fill_cavities

    from ._drawing import sheets_needed

    g = fill_cavities(grid) if flat[0].filled else grid
    sheets, goal, untabbed = sheets_needed(g, flat, options)
    if sheets <= goal or goal > _LARGE_PIECES_GOAL:
        return flat
    try:
        large = list(unfold(grid, rng=rng, fit=fit, pieces="auto", **search))
    except UnfoldError:
        return flat
    fewer, _, left = sheets_needed(g, large, options)
    return large if fewer < sheets and left <= untabbed else flat


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
    outs = legibility_ways_out(options, chars, pieces=True)
    if sheet:
        outs[1:1] = legibility_ways_out(options, chars, sheet=sheet)[:1]
    raise FaceSizeError(
        f"the most compact net found ({extent[0]} x {extent[1]} faces) fits {options.sheet} only at faces up "
        f"to {p:g} mm, too small for legible numbers and tabs (at least {need:g} mm); {where} (--sheet), "
        "or give a face size and split it (--pieces auto)", outs)
