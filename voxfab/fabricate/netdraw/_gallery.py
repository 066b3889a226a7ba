"""A gallery of nets to choose from: distinct outlines, each with its fit to the sheet, its layout and placement.

The gallery is the net search of :func:`._fit.find_sheet_nets` (the one
``voxfab net --count`` runs) with the sheet's face size settled first, so that
the nets it shows are the nets the CLI writes for the same seed; each is
validated (:func:`voxfab.unfold.validate`) before it is shown.  Nets that
cannot fit the sheet as one piece are shown all the same, with what would
work (``ways_out``); they are ordered by how well they fit: fewest sheets,
then the highest mean fill, then the smallest extent.

A gallery of nets in pieces varies only what is worth varying: the cut.  The
first seed is cut each way (flat patches, bands, few large pieces), later seeds
the way that packed on fewer sheets; each cut is laid out once, and handed to
``on_item`` as soon as it is, so the studio shows it while the next is cut.
Nets in pieces stay in the order they were made (the page has shown them so).

Everything the page draws comes from here, as plain JSON-ready dictionaries
(:func:`net_layout`, :func:`._placement.placement_of`), so the studio stays a thin shell.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError
from voxfab.unfold import EdgeConstraints, Net, fold_tree

from ._net_options import NetOptions
from ._options import DrawingOptions
from ._placement import Placement

_DIRS = ("+x", "-x", "+y", "-y", "+z", "-z")


@dataclasses.dataclass(frozen=True, eq=False)
class GalleryNet:
    """One net of a gallery.

    Attributes
    ----------
    pieces : list of Net
        The net as its pieces (one Net for a one-piece net).
    fit : dict
        How it sits on the sheet (fit to the sheet).
    placement : dict or None
        Where its pieces go on the sheets (the PLACEMENT of :mod:`._placement`); None when it does not fit.
    """

    pieces: list[Net]
    fit: dict[str, Any]
    placement: dict[str, Any] | None


@dataclasses.dataclass(frozen=True, eq=False)
class Gallery:
    """Nets ordered by fit, with the options they were searched and fitted with.

    Attributes
    ----------
    nets : list of GalleryNet
    options : DrawingOptions
        The drawing options with the face size settled.
    search : NetOptions
        The search options.
    asked : int
        Nets asked for.
    seconds : float
        Time the gallery took.
    notes : list of str
        Report lines (face size chosen, fewer nets than asked).
    """

    nets: list[GalleryNet]
    options: DrawingOptions
    search: NetOptions
    asked: int
    seconds: float
    notes: list[str]


def gallery_options(values: Mapping[str, Any], *, defaults: Mapping[str, Any] | None = None,
                    ) -> tuple[NetOptions, DrawingOptions]:
    """The net and drawing options named in ``values`` (field name → value), checked by their dataclasses.

    ``face_size`` (a :class:`NetOptions` field) becomes the drawing's ``pitch``; a name of
    neither dataclass is refused with the accepted ones, a bad value in the CLI's words.
    ``defaults`` are used for names ``values`` does not give.
    """
    from voxfab._shared.options import OptionError, from_mapping, option_specs

    if not isinstance(values, Mapping):
        raise InvalidShapeError("options: expected an object of option names and values")
    merged = {**(defaults or {}), **values}
    net_names = {s.name for s in option_specs(NetOptions)}
    draw_names = {s.name for s in option_specs(DrawingOptions)} - {"pitch"}
    for key in merged:
        if key not in net_names | draw_names:
            raise OptionError(str(key), f"unknown option; accepted: {', '.join(sorted(net_names | draw_names))}")
    net = from_mapping(NetOptions, {k: v for k, v in merged.items() if k in net_names}, front="any")
    drawing = from_mapping(DrawingOptions, {k: v for k, v in merged.items() if k in draw_names}, front="any")
    return net, drawing.replace(pitch=net.face_size)


def gallery_face_size(grid: Any, net: NetOptions, drawing: DrawingOptions) -> tuple[DrawingOptions, list[str]]:
    """The drawing options with a face size: the one asked for, else the smallest with legible marks.

    Without marks (no numbers, no tabs) any face size is legible: the pitch stays None and
    the search takes the largest at which a one-piece net fits the sheet, as ``voxfab net``.
    """
    if drawing.pitch is not None:
        return drawing, []
    from ._fit import _surface_faces, label_chars
    from ._legible import smallest_face_size

    p = smallest_face_size(drawing, label_chars(_surface_faces(grid, net.fill), net.pieces))
    if p <= 0:
        return drawing, []
    return drawing.replace(pitch=p), [f"face size {p:g} mm: the smallest with legible marks"]


#: ``on_item(index, item)``: a net of the gallery, ready to show, at its final place in the gallery.
ItemHook = Callable[[int, GalleryNet], None]


def net_gallery(grid: Any, net: NetOptions, drawing: DrawingOptions, *, count: int, seed: int,
                constraints: EdgeConstraints | None = None,
                progress: Callable[[int, int], None] | None = None,
                on_item: ItemHook | None = None) -> Gallery:
    """Search ``count`` nets of ``grid`` that look different once cut out, ordered by fit to the sheet.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
    net : NetOptions
        Search options (``pieces``, ``fill``, ``compact``, ``strategy``, ``timeout`` per net,
        ``budget`` for all).
    drawing : DrawingOptions
        Sheet and marks; ``pitch`` the face size (None: for one piece the largest at which a net
        fits the sheet, for a net in pieces the smallest with legible marks).
    count : int
        Nets wanted.
    seed : int
        Seed of the search: one net is the net of ``seed``, several are the nets of the
        seeds drawn from it, as ``voxfab net --seed`` and ``--count`` (each item's seed
        gives its net again).
    constraints : EdgeConstraints, optional
        Edges to cut or keep folded.
    progress : callable, optional
        ``progress(found, count)`` after each net.  A cancelled studio job stops the
        search (:func:`voxfab._shared.progress.check_cancelled`).
    on_item : callable, optional
        ``on_item(index, item)`` for each net once it is validated and laid out: a net in
        pieces as soon as it is cut, one-piece nets once all are found and ordered.

    Returns
    -------
    Gallery

    Raises
    ------
    FaceSizeError
        Faces too small for the marks (its ``ways_out`` say what works).
    UnfoldError
        No net found at all.
    """
    from voxfab.shape import fill_cavities, surface_graph

    from ._fit import find_sheet_nets
    from ._pipeline import validate_net

    start = time.monotonic()
    # One piece and no face size: the largest at which a net fits, settled by the search as
    # ``voxfab net`` settles it; in pieces, the smallest with legible marks.
    options, notes = (drawing, []) if net.pieces == "one" else gallery_face_size(grid, net, drawing)
    search: dict[str, Any] = dict(strategy=net.strategy, timeout=net.timeout, fill=net.fill, compact=net.compact)
    if constraints is not None:
        search["constraints"] = constraints
    if count > 1 and net.pieces == "auto" and options.pitch is not None and not _one_piece_room(grid, net, options):
        items = _piece_gallery(grid, net, options, count=count, seed=seed, search=search, notes=notes,
                               progress=progress, on_item=on_item)
        return Gallery(items, options, net, count, round(time.monotonic() - start, 3), notes)
    found = find_sheet_nets(grid, options, rng=seed, pieces=net.pieces, count=count, budget=net.budget,
                            show_unfit=True, nest=False, progress=progress, **search)
    options = found.options
    notes += found.notes
    for pieces in found.nets:  # every net shown is a valid net of the shape (and of the marks)
        validate_net(grid, pieces, constraints=constraints)
    graphs: dict[bool, Any] = {}
    for pieces in found.nets:  # one surface graph for the whole gallery
        if pieces[0].filled not in graphs:
            graphs[pieces[0].filled] = surface_graph(fill_cavities(grid) if pieces[0].filled else grid)
    items = [GalleryNet(pieces, *fit_and_placement(pieces, options, graphs[pieces[0].filled], found.best_extent))
             for pieces in found.nets]
    items.sort(key=lambda g: fit_order(g.fit))
    if on_item is not None:
        for i, item in enumerate(items):
            on_item(i, item)
    return Gallery(items, options, net, count, round(time.monotonic() - start, 3), notes)


def _one_piece_room(grid: Any, net: NetOptions, options: DrawingOptions) -> bool:
    """Whether the sheet has a cell for every face (else no one-piece net fits: the gallery is of pieces).

    The sheet is checked as :func:`._fit.find_sheet_nets` checks it before any search
    (:func:`._fit.sheet_room`), and a sheet hopeless for pieces is refused in the same words
    (:func:`._sheets.check_pieces_sheet`).
    """
    from ._fit import _surface_faces, label_chars, sheet_room
    from ._legible import smallest_face_size
    from ._sheets import check_pieces_sheet

    faces = _surface_faces(grid, net.fill)
    fit = sheet_room(options, faces, net.pieces)
    if faces <= fit[0] * fit[1]:
        return True
    if net.pieces != "auto":  # one piece asked for: the search refuses the sheet in its own words
        return False
    smallest = smallest_face_size(options, label_chars(faces, net.pieces))
    check_pieces_sheet(faces, options, float(options.pitch), smallest)
    return False


#: The ways to cut a net in pieces (:func:`voxfab.unfold.unfold`'s ``pieces``): flat patches, bands round the
#: shape, few large pieces.
CUTS = ("flat", "bands", "auto")


def _piece_gallery(grid: Any, net: NetOptions, options: DrawingOptions, *, count: int, seed: int,
                   search: dict[str, Any], notes: list[str], progress: Callable[[int, int], None] | None,
                   on_item: ItemHook | None) -> list[GalleryNet]:
    """``count`` nets in pieces, each cut once and laid out once, handed to ``on_item`` as each is made.

    Seed ``seed`` is cut each way (the flat patches first: they are the quicker to cut),
    so the artist sees every kind of net; the later seeds, drawn from ``seed`` as
    ``voxfab net --count`` draws them, are cut the way that packed better (fewer
    sheets, then fewer seams without room for a tab, then fewer pieces, as
    ``voxfab net --pieces auto`` chooses).  A cut whose outlines repeat one shown is
    dropped; the whole gallery keeps within ``net.budget`` seconds.
    """
    from voxfab.shape import fill_cavities, surface_graph
    from voxfab.unfold import unfold

    from ._fit import distinct_cuts
    from ._pipeline import validate_net
    from ._sheets import sheet_cells

    g = np.asarray(grid, dtype=bool)
    graph = surface_graph(fill_cavities(g) if net.fill else g)
    fit = sheet_cells(options, float(options.pitch))
    timeout = float(search.pop("timeout"))
    gen = np.random.default_rng(seed)
    plan = [(seed, cut) for cut in CUTS]  # (seed, cut) still to try
    ranked: dict[str, tuple[int, int, int]] = {}  # each cut's packing of the first seed
    tried = plan[0]

    def cut_next(seconds: float) -> list[Net]:
        nonlocal tried
        if not plan:
            best = min(ranked, key=ranked.__getitem__) if ranked else CUTS[0]
            plan.append((int(gen.integers(0, 2**31 - 1)), best))
        tried = plan.pop(0)
        rng, cut = tried
        return list(unfold(g, rng=rng, fit=fit, pieces=cut, timeout=min(timeout, max(seconds, 0.1)), **search))

    def lay_out(pieces: list[Net]) -> GalleryNet:
        validate_net(g, pieces, constraints=search.get("constraints"))
        fit_of, placement, untabbed = _laid_out(pieces, options, graph)
        rng, cut = tried
        if rng == seed and fit_of["fits"]:
            ranked[cut] = (int(fit_of["sheets"]), untabbed, len(pieces))
        return GalleryNet(pieces, fit_of, placement)

    return distinct_cuts(cut_next, lay_out, count=count, budget=float(net.budget), notes=notes, progress=progress,
                         on_item=on_item)


def fit_order(fit: dict[str, Any]) -> tuple[Any, ...]:
    """Sort key of a net's fit: fitting first, fewest sheets, highest mean fill, smallest extent."""
    fill = fit.get("fill") or [0.0]
    ex, ey = fit["extent"]
    return (not fit["fits"], fit.get("sheets") or 1 << 30, -round(sum(fill) / len(fill), 6), ex * ey, max(ex, ey))


def fit_and_placement(pieces: list[Net], options: DrawingOptions, graph: Any,
                      best_extent: tuple[int, int] | None = None, *,
                      before: tuple[list[Net], Placement] | None = None
                      ) -> tuple[dict[str, Any], dict[str, Any] | None]:
    """The net's fit to the sheet and the PLACEMENT of its pieces on the sheets (None when it does not fit).

    ``graph`` is the surface graph of the shape the pieces unfold; the sheets are the drawing's own
    (:func:`._drawing.sheet_plan`), so what the studio shows is what the files hold.

    Returns
    -------
    fit : dict
        ``sheet``, ``face_size``, ``extent`` (faces, of the largest piece), ``fits``, ``sheets``
        (None when it does not fit), ``fill`` (share of each sheet covered by faces),
        ``largest_face_size`` (the largest at which the largest piece fits one sheet) and,
        when it does not fit, ``message`` (the CLI's words) and ``ways_out``.
    placement : dict or None

    ``best_extent`` is the extent of the net measured to fit the sheet at the largest face size
    (:attr:`._net_options.SheetNets.best_extent`): a net that does not fit names that face size.
    ``before`` is the net before an edit and its placement: the pieces the edit left as they were keep
    their sheet and spot, the others go into the room left (:func:`._relayout.relayout`), and the
    placement returned is the one to draw the files with.
    """
    fit, placement, _ = _laid_out(pieces, options, graph, best_extent, before)
    return fit, placement


def _laid_out(pieces: list[Net], options: DrawingOptions, graph: Any, best_extent: tuple[int, int] | None = None,
              before: tuple[list[Net], Placement] | None = None) -> tuple[dict[str, Any], dict[str, Any] | None, int]:
    """:func:`fit_and_placement` from one packing, and the seams it leaves without room for a tab."""
    from ._drawing import _packed
    from ._placement import placement_of
    from ._sheets import (
        SheetFitError,
        extent_of,
        fit_error,
        largest_face_size,
        plan_sheets,
    )

    pitch = float(options.pitch)
    w, h = options.sheet_size
    big = max(pieces, key=lambda n: n.face_count)
    extent = extent_of(big.corners2d)
    fit: dict[str, Any] = {"sheet": options.sheet, "face_size": pitch, "extent": list(extent),
                           "largest_face_size": largest_face_size(extent, options)}
    untabbed = sum(int(n.seams_without_tab_room) for n in pieces)
    try:
        # The drawing's own sheets (:func:`._drawing.sheet_plan`), packed once.
        if len(pieces) == 1:
            plan = plan_sheets(pieces[0].corners2d, options)
        else:
            _, plan, _, _, tabs, seams = _packed(graph, pieces, options, before=before)
            untabbed = seams - tabs
    except SheetFitError:
        from ._fit import split_checked

        one = len(pieces) == 1
        err = fit_error(extent, options, pitch, what="the net" if one else "a piece", found=best_extent if one else None,
                        split=one and split_checked(pieces[0].face_count, options, pitch))
        fit.update(fits=False, sheets=None, fill=[], message=str(err), largest_face_size=err.largest_face_size,
                   ways_out=legible_ways_out(err.ways_out, options, pieces))
        return fit, None, untabbed
    faces = np.bincount(plan.face_sheet, minlength=plan.count)
    fit.update(fits=True, sheets=plan.count, fill=[round(float(n) * pitch * pitch / (w * h), 4) for n in faces])
    return fit, placement_of(plan, [p.corners2d for p in pieces], float(options.margin)).to_dict(), untabbed


def legible_ways_out(ways: list[dict[str, Any]], options: DrawingOptions, pieces: list[Net]) -> list[dict[str, Any]]:
    """``ways`` with a smaller face size that is too small for the marks offered without the marks."""
    from ._fit import label_chars
    from ._legible import legibility_problem

    faces = sum(n.face_count for n in pieces)
    chars = label_chars(faces, "auto" if len(pieces) > 1 else "one")
    out = []
    for way in ways:
        size = way["options"].get("face_size")
        if size is not None and legibility_problem(options, float(size), chars):
            off = {k: False for k in ("numbers", "tabs") if getattr(options, k)}
            way = {"label": f"{way['label']} and draw without seam labels and glue tabs",
                   "options": {**way["options"], **off}}
        out.append(way)
    return out


def net_layout(grid: Any, pieces: Net | list[Net], *, graph: Any = None) -> dict[str, Any]:
    """What the page draws and marks, over all the pieces of a net: the LAYOUT of the studio contract.

    Face ids are the faces' order in the surface graph (for a net in pieces as well).
    ``corners`` are each face's 2D corners in its piece's own frame, ``corners3d`` its 3D
    corners (same corner order); ``neighbor`` and ``fold_type`` give, per edge ``k``
    (corner ``k`` to ``k + 1``), the face across it and the fold there as seen from
    outside; ``piece`` and ``parent`` the piece of each face and the face it is hinged on
    in the fold-up (:func:`voxfab.unfold.fold_tree`; -1 for each piece's root);
    ``labels`` the seam label of every cut edge, by face pair ``"i-j"`` (i < j), as
    printed on the drawings.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape (with its cavities filled when the net was searched so).
    pieces : Net or list of Net
    graph : SurfaceGraph, optional
        ``surface_graph(grid)`` when the caller has it already.
    """
    from voxfab.shape import fill_cavities, surface_graph

    from ._geometry import face_map

    nets = [pieces] if isinstance(pieces, Net) else list(pieces)
    if graph is None:
        graph = surface_graph(fill_cavities(grid) if nets[0].filled else grid)
    fmap = np.concatenate([face_map(graph, n) for n in nets])  # surface face of each face, pieces in turn
    order = np.argsort(fmap, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)  # layout id of each face, pieces in turn
    local = np.full(graph.face_count, -1, dtype=np.int64)
    local[fmap[order]] = np.arange(order.size)
    counts = [n.face_count for n in nets]
    offsets = np.cumsum([0] + counts)[:-1]
    folds = np.concatenate([n.folds.reshape(-1, 2) + o for n, o in zip(nets, offsets)])
    # The pieces side by side, apart, for the seam numbering of the drawings (no seam closes between pieces).
    apart = np.concatenate([n.corners2d - n.corners2d.reshape(-1, 2).min(axis=0) + (int(q) * 100_000, 0)
                            for q, n in enumerate(nets)])
    combined = Net(voxel=np.concatenate([n.voxel for n in nets]), normal=np.concatenate([n.normal for n in nets]),
                   corners3d=np.concatenate([n.corners3d for n in nets]), corners2d=apart, folds=folds,
                   seed=nets[0].seed, strategy=nets[0].strategy, filled=nets[0].filled)
    labels: dict[str, str] = {}
    for key, label in seam_labels_of(graph, combined).items():
        i, j = (int(rank[int(x)]) for x in key.split("-"))
        labels[f"{min(i, j)}-{max(i, j)}"] = label
    parent = np.full(order.size, -1, dtype=np.int64)
    for n, o in zip(nets, offsets):
        if n.face_count > 1:
            _, up, _ = fold_tree(n)
            parent[o:o + n.face_count] = np.where(up >= 0, up + o, -1)
    parent = np.where(parent >= 0, rank[np.maximum(parent, 0)], -1)[order]
    corners = np.concatenate([n.corners2d for n in nets])[order]
    piece = np.repeat(np.arange(len(nets)), counts)[order]
    sg_ids = fmap[order]
    return {
        "faces": [[int(v[0]), int(v[1]), int(v[2]), _DIRS[int(d)]]
                  for v, d in zip(graph.voxel[sg_ids].tolist(), graph.direction[sg_ids].tolist())],
        "corners": corners.reshape(-1).tolist(),
        "corners3d": combined.corners3d[order].reshape(-1).tolist(),
        "folds": rank[folds].reshape(-1).tolist(),
        "neighbor": local[graph.neighbor[sg_ids]].reshape(-1).tolist(),
        "fold_type": graph.fold[sg_ids].reshape(-1).tolist(),
        "piece": piece.tolist(),
        "parent": parent.tolist(),
        "labels": dict(sorted(labels.items(), key=lambda kv: tuple(map(int, kv[0].split("-"))))),
    }


def seam_labels_of(graph: Any, net: Net) -> dict[str, str]:
    """The seam label of each cut edge of ``net`` (pieces combined, laid apart), by face pair ``"i-j"``.

    The numbering is the drawings' (:func:`._drawing.draw_net`): seams in the order of their
    first copy (face, then edge), labels of :func:`._labels.label_length` characters.
    """
    from ._geometry import classify_edges
    from ._labels import label_length, seam_label

    edges = classify_edges(graph, net, net.corners2d)
    f, k = np.nonzero(~edges.joined & edges.canonical())
    g = edges.partner_face[f, k]
    chars = label_length(max(int(f.size), 1))
    out: dict[str, str] = {}
    for t, (a, b) in enumerate(zip(f.tolist(), g.tolist())):
        key = f"{min(a, b)}-{max(a, b)}"
        label = seam_label(t + 1, chars)
        # A face pair may meet along two edges (a one-voxel wide strip): both labels, in order.
        out[key] = f"{out[key]} {label}" if key in out else label
    return out


def _fields(options: Any) -> dict[str, Any]:
    return {f.name: (list(v) if isinstance(v := getattr(options, f.name), tuple) else v)
            for f in dataclasses.fields(options)}


def gallery_item_json(index: int, item: GalleryNet, grid: Any, *, graph: Any = None) -> dict[str, Any]:
    """One net of the gallery as the page draws it: its figures, ``fit``, ``layout`` and ``placement``.

    ``graph`` is the surface graph of the shape its pieces unfold, when the caller has it.
    """
    first = item.pieces[0]
    return {
        "index": index, "seed": int(first.seed), "faces": sum(n.face_count for n in item.pieces),
        "pieces": len(item.pieces), "mountain": sum(int(n.mountain) for n in item.pieces),
        "valley": sum(int(n.valley) for n in item.pieces),
        "seams_without_tab_room": sum(int(n.seams_without_tab_room) for n in item.pieces),
        "fit": item.fit, "layout": net_layout(grid, item.pieces, graph=graph),
        "placement": item.placement,
    }


def gallery_json(gallery: Gallery, grid: Any, *, nets: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    """The gallery as the studio's job result: ``asked``, ``found``, ``seconds``, ``options`` and ``nets``.

    ``nets``: the :func:`gallery_item_json` of each net, when they were made as the nets came.
    """
    from voxfab.shape import fill_cavities, surface_graph

    if nets is None:
        graphs: dict[bool, Any] = {}
        nets = []
        for i, item in enumerate(gallery.nets):
            filled = item.pieces[0].filled
            if filled not in graphs:  # one surface graph for every net of the gallery
                graphs[filled] = surface_graph(fill_cavities(grid) if filled else grid)
            nets.append(gallery_item_json(i, item, grid, graph=graphs[filled]))
    # The options as settled, by their field names (face_size: the face size chosen).
    settled = {**_fields(gallery.search), **_fields(gallery.options), "face_size": float(gallery.options.pitch)}
    settled.pop("pitch")
    return {"asked": gallery.asked, "found": len(nets), "seconds": gallery.seconds, "options": settled,
            "notes": list(gallery.notes), "nets": nets}
