"""Nets for a sheet: one piece on one sheet at the face size asked for, or a clear error, or pieces.

The default order of a paper net (issue: buildable objects):

1. one piece on one sheet at the requested face size, found by steering the
   net search into the sheet (``unfold(fit=...)``), else by the search of the
   automatic face size from that face size up (:func:`largest_fitting`); no face
   size asked for: the largest at which that search finds a one-piece net;
2. when none is found, an error naming the largest face size at which that
   search found a net on this sheet and the smallest sheet that takes it at this
   face size; never a silent split; every way out offered was checked on the
   shape first (a net found, or the sheet's bound for pieces);
3. with ``pieces="auto"``, pieces from flat patches or bands round the shape,
   whichever packs on fewer sheets (the few large pieces of the net search when
   neither gives pieces), packed once by the drawing (:func:`_cut_pieces`).

Faces too small for legible marks are refused before any search (with ways out checked the same way).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from voxfab.errors import InvalidShapeError, UnfoldError
from voxfab.shape import component_count, describe_parts
from voxfab.unfold import Net
from voxfab.unfold._search import MAX_FIT_SIDE

from ._labels import label_length
from ._legible import legibility_problem, smallest_face_size
from ._net_options import SheetNets
from ._options import DrawingOptions
from ._sheets import (
    check_pieces_sheet,
    extent_of,
    fit_error,
    largest_face_size,
    pieces_problem,
    pieces_sheet,
    sheet_cells,
    smallest_sheet,
)

#: Budget of the search that measures a net when the sheet search gave no extent, seconds.
MEASURE_TIMEOUT = 20.0

#: What :func:`distinct_cuts` keeps of each distinct net.
Kept = TypeVar("Kept")


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


def legibility_ways_out(options: DrawingOptions, chars: int, *, sheet: str | None = None) -> list[dict[str, Any]]:
    """Ways out of faces too small for the marks: the smallest face size that works (on ``sheet``), or no marks."""
    need = smallest_face_size(options, chars)
    out: list[dict[str, Any]] = []
    if sheet:
        out.append({"label": f"make the faces {need:g} mm on a larger sheet ({sheet})",
                    "options": {"face_size": need, "sheet": sheet}})
    else:
        out.append({"label": f"make the faces {need:g} mm", "options": {"face_size": need}})
    off = {k: False for k in ("numbers", "tabs") if getattr(options, k)}
    if off:
        words = " and ".join({"numbers": "seam labels", "tabs": "glue tabs"}[k] for k in off)
        out.append({"label": f"draw without {words}", "options": off})
    return out


def pieces_ways_out(faces: int, options: DrawingOptions, pitch: float, *, split: bool = True) -> list[dict[str, Any]]:
    """Faces of ``pitch`` mm in pieces, offered only where the sheet's bound for pieces lets them be
    (:func:`._sheets.check_pieces_sheet`, the check every net in pieces meets first): on this sheet,
    else on the smallest standard sheet that passes, else not at all."""
    label = f"make the faces {pitch:g} mm" + (" and split the net into pieces" if split else "")
    chosen: dict[str, Any] = {"face_size": pitch, **({"pieces": "auto"} if split else {})}
    if pieces_problem(faces, options, pitch) is None:
        return [{"label": label, "options": chosen}]
    sheet = pieces_sheet(faces, options, pitch)
    if sheet is None:
        return []
    return [{"label": f"{label} on a larger sheet ({sheet})", "options": {**chosen, "sheet": sheet}}]


def ways_in_words(ways: list[dict[str, Any]]) -> str:
    """Ways out as one clause, each with the options that take it: ``make the faces 8.6 mm and split the net
    into pieces (--face-size 8.6 --pieces auto), or draw without ... (--no-numbers --no-tabs)``."""
    from voxfab._shared.options import option_specs

    from ._net_options import NetOptions

    flags = {spec.name: spec.flag for cls in (DrawingOptions, NetOptions) for spec in option_specs(cls)}

    def flag(name: str, value: Any) -> str:
        if value is False:
            return "--no-" + flags[name].removeprefix("--")
        return flags[name] if value is True else f"{flags[name]} {value:g}" if isinstance(value, float) else \
            f"{flags[name]} {value}"

    return ", or ".join(f"{w['label']} ({' '.join(flag(k, v) for k, v in w['options'].items())})" for w in ways)


def split_checked(faces: int, options: DrawingOptions, pitch: float) -> bool:
    """Whether "split it into pieces" at ``pitch`` passes the checks a net in pieces meets first: legible
    marks (pieces number every edge) and the sheet's bound."""
    return (legibility_problem(options, pitch, label_chars(faces, "auto")) is None
            and pieces_problem(faces, options, pitch) is None)


def _check_legible(options: DrawingOptions, faces: int, pieces: str) -> None:
    """Refuse faces too small for the marks; in pieces, each way out checked by the sheet's bound for pieces
    (one piece: :func:`find_sheet_nets` checks them by a search)."""
    chars = label_chars(faces, pieces)
    problem = legibility_problem(options, float(options.pitch), chars)
    if problem:
        raise FaceSizeError(problem, legibility_ways_out(options, chars) if pieces == "one" else
                            _pieces_legibility_ways(options, faces, chars))


def _pieces_legibility_ways(options: DrawingOptions, faces: int, chars: int) -> list[dict[str, Any]]:
    """Ways out of faces too small for the marks of a net in pieces, each passing the sheet's bound for pieces."""
    pitch = float(options.pitch)
    bare = options.replace(numbers=False, tabs=False)
    marks = legibility_ways_out(options, chars)[1:] if pieces_problem(faces, bare, pitch) is None else []
    return pieces_ways_out(faces, options, smallest_face_size(options, chars), split=False) + marks


def label_chars(faces: int, pieces: str) -> int:
    """Characters of a seam label: a one-piece net has at most F + 1 seams, pieces number all 2F surface edges."""
    return label_length(2 * faces if pieces == "auto" else faces + 1)


def find_sheet_nets(grid: Any, options: DrawingOptions, *, rng: int, pieces: str = "one", count: int = 1,
                    budget: float = 60.0, show_unfit: bool = False, nest: bool = True,
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
    nest : bool
        Empty the last sheet of a net in pieces into the gaps of the others when that saves a sheet
        (:func:`._nesting.nest_last_sheet`); the studio's gallery does not: its editor keeps the pieces an
        edit leaves alone in place only with room left on the sheets for the pieces it changes.
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
        options, auto_notes, auto_net = _auto_face_size(grid, options, rng=rng, pieces=pieces, chars=chars,
                                                        search=search)
        notes += auto_notes
        if auto_net is not None:  # the net the face size was measured with: it fits, no second search
            return SheetNets([[n] for n in _with_more(auto_net, grid, count, rng, budget, progress,
                                                      {**search, "fit": sheet_cells(options, float(options.pitch))},
                                                      notes)], options, notes)
    try:
        fit = sheet_room(options, faces, pieces)
    except FaceSizeError as err:  # each way out checked on this shape before it is offered, and named so
        ways = _checked_legibility_ways(grid, options, faces, chars, pieces, rng=rng, search=search)
        head = str(err).split("; the smallest face size that works", 1)[0]
        raise FaceSizeError(f"{head}; what works: {ways_in_words(ways)}" if ways else str(err), ways) from None
    # A surface larger than the sheet has no one-piece net on it: no search can find one.
    room = faces <= fit[0] * fit[1]
    if pieces == "auto" and not room:
        check_pieces_sheet(faces, options, float(options.pitch), smallest_face_size(options, chars))
        return SheetNets(_piece_nets(grid, options, rng, fit, count, budget, progress, search, notes, nest), options,
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
            return SheetNets(_piece_nets(grid, options, rng, fit, count, budget, progress, search, notes, nest),
                             options, notes)
        if failed is not None and not isinstance(failed, NoFitError):
            raise failed  # out of time, or marks that leave no net: not a question of the sheet
        # The search of the automatic face size, from this face size up: a net it finds fits here too.
        best = largest_fitting(grid, options, rng=rng, search=search, least=float(options.pitch))
        if best is not None:
            return SheetNets([[best[1]]], options, notes)
        best = largest_fitting(grid, options, rng=rng, search=search, tab_room=False)  # what fits, for the words
        split = split_checked(faces, options, float(options.pitch))
        if show_unfit:
            found = _nets(grid, count, rng, budget, progress, search)
            notes.append(f"no one-piece net fits {options.sheet} at {options.pitch:g} mm faces")
            return SheetNets([[n] for n in found], options, notes,
                             extent_of(best[1].corners2d) if best is not None else None)
        extent = _measured_extent(failed, grid, rng, search)
        raise fit_error(extent, options, float(options.pitch), what="the most compact net found",
                        found=extent_of(best[1].corners2d) if best is not None else None, split=split) from None
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
    _check_legible(options, faces, pieces)
    fit = sheet_cells(options, float(options.pitch))
    if min(fit) < 1:
        raise InvalidShapeError(f"sheet: {options.sheet} has no room for one {options.pitch:g} mm face with its tabs")
    # Tiny faces make the sheet millions of faces wide: a box wider than the search takes bounds no net.
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


def _piece_nets(grid: Any, options: DrawingOptions, rng: int, fit: tuple[int, int], count: int, budget: float,
                progress: Callable[[int, int], None] | None, search: dict[str, Any],
                notes: list[str], nest: bool = True) -> list[list[Net]]:
    """Nets in pieces, one per seed: seed ``rng`` for one net, seeds drawn from it for several."""
    if count == 1:
        return [_cut_pieces(grid, options, fit, rng, search, nest)]
    gen = np.random.default_rng(rng)
    timeout = float(search.pop("timeout", 60.0))

    def cut(seconds: float) -> list[Net]:
        seed = int(gen.integers(0, 2**31 - 1))
        return _cut_pieces(grid, options, fit, seed, {**search, "timeout": min(timeout, seconds)}, nest)

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


def _cut_pieces(grid: Any, options: DrawingOptions, fit: tuple[int, int], rng: int, search: dict[str, Any],
                nest: bool = True) -> list[Net]:
    """The pieces, cut once, before any packing: from flat patches and as bands round the shape, the cut
    packed on fewer sheets of ``options`` kept (then the one with fewer seams without room for a tab, then
    fewer seams); the few large pieces of ``"auto"`` when neither gives pieces.

    Measured at 8.6 mm faces on A4 (``bench/bench_density.py``): flat patches pack on fewer pages than
    Blender's Paper Model on every bundled shape (queen 4 against 5, pawn 4 against 6, egg 10 against 18);
    bands win where walls go straight on (the vase: 15 sheets against 18, a round column: 3 against 4) and
    lose a sheet or so on the other chess pieces, so both are cut and packed (the winner's packing is the
    drawing's, cached).  The winner's last sheet is then emptied into the gaps of the others when its pieces,
    cut along folds, fit there (:func:`._nesting.nest_last_sheet`: the vase 14 sheets against 15).
    """
    import time

    from voxfab.unfold import unfold

    end = time.monotonic() + float(search.get("timeout", 60.0))
    cuts = []
    for way in ("flat", "bands"):
        left = end - time.monotonic()
        if cuts and left <= 0:
            break  # the budget is spent: the cut made is the one drawn
        try:
            cuts.append(list(unfold(grid, rng=rng, fit=fit, pieces=way, **({**search, "timeout": left} if cuts else search))))
        except UnfoldError:
            pass
    if not cuts:
        return list(unfold(grid, rng=rng, fit=fit, pieces="auto", **search))
    from ._nesting import nest_last_sheet

    best = min(cuts, key=lambda pieces: _packing_rank(grid, pieces, options))
    return nest_last_sheet(grid, best, options, search.get("constraints")) if nest else best


def _packing_rank(grid: Any, pieces: list[Net], options: DrawingOptions) -> tuple[int, int, int]:
    """Sheets, seams without room for a tab, and seams of ``pieces`` as the drawing packs them."""
    from voxfab.shape import fill_cavities, surface_graph

    from ._drawing import _packed

    g = np.asarray(grid, dtype=bool)
    _, plan, _, _, tabs, seams = _packed(surface_graph(fill_cavities(g) if pieces[0].filled else g), pieces,
                                         options)
    return plan.count, seams - tabs, seams


def largest_fitting(grid: Any, options: DrawingOptions, *, rng: int, search: dict[str, Any],
                    least: float = 0.0, tab_room: bool = True) -> tuple[float, Net] | None:
    """The largest face size (0.1 mm steps, ``least`` at least) at which a one-piece net was found to fit the
    sheet of ``options``, and that net; None when none was found (or the strategy is the exact one).

    The sheet's boxes of cells, from face sizes whose box takes a fair multiple of the faces up to
    the largest whose box still has a cell for every face, are bisected by
    :func:`voxfab.unfold._boxfit.smallest_box`; the face size is the largest at which the net
    found fits (:func:`._sheets.largest_face_size` of its extent), the number every refusal names.
    ``tab_room=False`` skips the tab-room repair of the net found (slow in a crowded box): for a check
    or the words of a refusal, where only its extent counts.
    """
    from voxfab.unfold._boxfit import smallest_box

    if str(search.get("strategy", "default")) == "exact":
        return None
    faces = _surface_faces(grid, bool(search.get("fill", False)))
    sizes: list[float] = []
    boxes: list[tuple[int, int]] = []
    p = max(math.ceil(float(least) * 10.0 - 1e-6), 1)
    while True:
        box = sheet_cells(options, p / 10.0)
        if box[0] * box[1] < faces:
            break
        if box[0] * box[1] <= _ROOMY * faces and max(box) <= MAX_FIT_SIDE:
            if boxes and boxes[-1] == box:
                sizes[-1] = p / 10.0
            else:
                sizes.append(p / 10.0)
                boxes.append(box)
        p += 1
    if not boxes:
        return None
    kept = {k: search[k] for k in ("strategy", "timeout", "tab_aware", "fill", "constraints") if k in search}
    if not tab_room:
        kept["tab_aware"] = False
    found = smallest_box(grid, boxes, rng=rng, **kept)
    if found is None:
        return None
    net = found[1]
    return max(largest_face_size(extent_of(net.corners2d), options), sizes[found[0]]), net


#: The roomiest box the face-size search probes, in cells per face: a net of a compact surface lies in far less.
_ROOMY = 16


def _with_more(net: Net, grid: Any, count: int, rng: int, budget: float,
               progress: Callable[[int, int], None] | None, search: dict[str, Any], notes: list[str]) -> list[Net]:
    """``net`` and, for ``count`` > 1, distinct nets of other seeds in the same box, as many as are found."""
    from voxfab.unfold import NoFitError, outline_key

    nets = [net]
    if progress is not None:
        progress(1, count)
    if count > 1:
        try:
            more = _nets(grid, count - 1, rng + 1, budget, None, search)
        except NoFitError:
            more = []  # a box this tight takes few nets: those found are shown
        seen = {outline_key(net)}
        for m in more:
            if outline_key(m) not in seen and len(nets) < count:
                seen.add(outline_key(m))
                nets.append(m)
        if progress is not None:
            progress(len(nets), count)
        if len(nets) < count:
            notes.append(f"{len(nets)} distinct nets found of the {count} asked for")
    return nets


def _checked_legibility_ways(grid: Any, options: DrawingOptions, faces: int, chars: int, pieces: str, *,
                             rng: int, search: dict[str, Any]) -> list[dict[str, Any]]:
    """The ways out of faces too small for the marks, each checked on this shape: the smallest legible face
    size where a one-piece net was found to fit at it or larger (or pieces pass the sheet's bound), and no marks."""
    if pieces != "one":
        return _pieces_legibility_ways(options, faces, chars)
    need = smallest_face_size(options, chars)
    first = legibility_ways_out(options, chars)[:1]
    if largest_fitting(grid, options, rng=rng, search=search, least=need, tab_room=False) is None:
        # no one piece at legible faces: pieces, where the sheet's bound lets them be
        first = pieces_ways_out(faces, options, smallest_face_size(options, label_chars(faces, "auto")))
    return first + _without_marks(grid, options, faces, float(options.pitch), pieces, rng=rng, search=search)


def _without_marks(grid: Any, options: DrawingOptions, faces: int, pitch: float | None, pieces: str, *, rng: int,
                   search: dict[str, Any], fits_one: bool | None = None) -> list[dict[str, Any]]:
    """"Draw without seam labels and glue tabs", offered when, without them, a one-piece net was found to fit at
    ``pitch`` (``fits_one`` when the caller knows) or the pieces pass the sheet's bound there."""
    way = legibility_ways_out(options, 1)[1:]
    if not way:
        return []
    bare = options.replace(numbers=False, tabs=False)
    if pieces == "one":
        if fits_one is None:
            fits_one = largest_fitting(grid, bare, rng=rng, search=search, least=pitch or 0.0, tab_room=False) is not None
        if fits_one:
            return way
        if pitch is None or pieces_problem(faces, bare, pitch) is not None:
            return []
        return [{"label": f"{way[0]['label']} and split the net into pieces",
                 "options": {**way[0]["options"], "pieces": "auto"}}]
    return way if pitch is None or pieces_problem(faces, bare, pitch) is None else []


def _auto_face_size(grid: Any, options: DrawingOptions, *, rng: int, pieces: str, chars: int,
                    search: dict[str, Any]) -> tuple[DrawingOptions, list[str], Net | None]:
    """The largest face size at which a one-piece net was found to fit the sheet, if its marks are legible,
    with that net (None when the face size is not the one-piece net's)."""
    from voxfab.unfold import unfold

    need = smallest_face_size(options, chars)
    best = largest_fitting(grid, options, rng=rng, search=search)
    if best is not None:
        p, found = best
        extent = extent_of(found.corners2d)
    else:  # the exact strategy, or no box held a net: the most compact net's own extent
        net = unfold(grid, rng=rng, **{**search, "compact": True})
        extent = extent_of(net.corners2d)
        p, found = largest_face_size(extent, options), None
    if p >= need:
        return (dataclasses.replace(options, pitch=p),
                [f"face size {p:g} mm: the largest at which a one-piece net was found to fit"], found)
    if pieces == "auto":
        return dataclasses.replace(options, pitch=need), [
            f"face size {need:g} mm: the smallest with legible marks (one piece fits only at {p:g} mm)"], None
    sheet = smallest_sheet(extent, options, need)
    where = f"at {need:g} mm it needs {sheet}" if sheet else f"at {need:g} mm it is larger than every standard sheet"
    faces = _surface_faces(grid, bool(search.get("fill", False)))
    outs = pieces_ways_out(faces, options, smallest_face_size(options, label_chars(faces, "auto")))
    if sheet:
        outs[1:1] = legibility_ways_out(options, chars, sheet=sheet)[:1]
    outs += _without_marks(grid, options, faces, None, pieces, rng=rng, search=search, fits_one=p > 0)
    raise FaceSizeError(
        f"the most compact net found ({extent[0]} x {extent[1]} faces) fits {options.sheet} only at faces up "
        f"to {p:g} mm, too small for legible numbers and tabs (at least {need:g} mm); {where} (--sheet), "
        "or give a face size and split it (--pieces auto)", outs)
