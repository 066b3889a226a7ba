"""From a net to sheets of layered polylines: cut outlines, folds, tabs, seam labels and a title."""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab._shared.arrays import unique
from voxfab.drawing import (
    LAYERS,
    Cutter,
    Fill,
    Ink,
    Page,
    Polylines,
    clear_of_marks,
    registration_marks,
    text_polylines,
    text_width,
)
from voxfab.drawing import Drawing as Document
from voxfab.errors import InvalidShapeError
from voxfab.shape import SurfaceGraph, VoxelColours, surface_graph
from voxfab.unfold import Net

from ._assembly import (
    assembly_page,
    gluing_order,
    ink_under,
    number_faces,
    number_text,
    paper_boxes,
    piece_joins,
    piece_name,
    place_numbers,
)
from ._geometry import NetEdges, check_net, classify_edges, merge_unit_segments, trace_outlines
from ._labels import label_length, seam_labels
from ._legible import LABEL_ADVANCE, NUMBER_INSET, legibility_problem, number_height, number_start
from ._options import DrawingOptions, Perforate
from ._paint import INKS, Paint, net_paint, sheet_fills, tint
from ._placement import Placement, placement_of, plan_placement
from ._sheets import SheetPlan, pack_pieces, plan_sheets
from ._tabs import TabPlan, place_tabs, tab_heights, tab_sides

_NEXT = np.array([1, 2, 3, 0])
#: Shade of glue tabs in previews and prints (Blender's paper-model convention).
TAB_FILL = "#e4e4e4"


@dataclasses.dataclass(frozen=True, eq=False)
class Sheet:
    """One sheet of a drawing.

    Attributes
    ----------
    number : int
        1-based sheet number.
    width, height : float
        Sheet size, mm.
    layers : dict of str to Polylines
        Polylines per layer (CUT, MOUNTAIN, VALLEY, GRID, LABEL), mm, y up,
        origin at the sheet's lower-left corner.
    faces : (n, 4, 2) float ndarray
        The faces on this sheet, mm.
    face_index : (n,) int ndarray
        Their indices in the net.
    tabs : (t, 4, 2) float ndarray
        The glue tabs on this sheet, mm.
    pieces : int
        Number of separate paper pieces (closed outlines) on this sheet.
    fill : float
        Share of the sheet's area covered by paper (faces and tabs), 0 to 1.
    colour_fills : tuple of Fill
        A coloured net's bleed, tab tints and faces (:mod:`._paint`); empty otherwise.
    inks : tuple of Ink
        A coloured net's folds and labels in black or white over the fills.
    marks : Polylines
        The cutter's registration marks (empty without a cutter).
    """

    number: int
    width: float
    height: float
    layers: dict[str, Polylines]
    faces: npt.NDArray[np.float64]
    face_index: npt.NDArray[np.int64]
    tabs: npt.NDArray[np.float64]
    pieces: int
    fill: float
    colour_fills: tuple[Fill, ...] = ()
    inks: tuple[Ink, ...] = ()
    marks: Polylines = dataclasses.field(default_factory=Polylines.empty)

    def page(self, title: str = "", part: str = "all") -> Page:
        """This sheet as a drawing page; glue tabs are shaded in previews and prints.

        ``part`` is ``all`` (the sheet), ``print`` (without the cut lines: a cutter cuts them) or ``cut``
        (the cut lines alone); the registration marks are on all three, at the same place.
        """
        if part == "cut":
            return Page(self.width, self.height, {"CUT": self.layers["CUT"]}, marks=self.marks, title=title)
        layers = self.layers if part == "all" else {k: v for k, v in self.layers.items() if k != "CUT"}
        if self.colour_fills:
            return Page(self.width, self.height, layers, fills=self.colour_fills, title=title, inks=self.inks,
                        marks=self.marks, artwork=True)
        tabs = self.tabs[np.isfinite(self.tabs).all(axis=(1, 2))]
        fills = (Fill(Polylines.from_list(list(tabs), [True] * len(tabs)), TAB_FILL),) if len(tabs) else ()
        return Page(self.width, self.height, layers, fills=fills, title=title, marks=self.marks)


@dataclasses.dataclass(frozen=True, eq=False)
class NetDrawing:
    """A net drawn on one or more sheets, ready for the file writers.

    Attributes
    ----------
    sheets : tuple of Sheet
    pitch : float
        Face edge length, mm.
    rotated : bool
        The net was turned a quarter turn to fit.
    seams : int
        Glued seam pairs (each labelled on both edges).
    tab_seams : (S,) bool ndarray
        Which seams got a tab here.
    tab_elsewhere : (S,) bool ndarray
        Seams to another piece whose tab is drawn with that piece.
    seam_numbers : (S,) int ndarray
        The number of each seam: 1..S for a whole net, the surface edge's global
        index + 1 for a piece (so pieces drawn apart agree).
    label_chars : int
        Characters of every seam label (:mod:`._labels`), from the largest number.
    seam_type : (S,) int ndarray
        +1 convex, -1 concave, 0 coplanar seam.
    tab_fold_length : (S,) float ndarray
        Length of each tab's fold line, mm (0 without a tab).
    fold_counts : dict of str to int
        Folds drawn per type (``mountain``, ``valley``, ``flat``), tabs excluded.
    closed_in_plane : int
        Seams of the net left uncut because their two sides meet in the plane.
    pieces : int
        Separate pieces of paper the net was split into (1 for a one-piece net).
    label_height, tab_height : float
        Cap height of the seam labels and full tab height, mm.
    label_wanted : float
        The largest label height asked for, mm (``label_height`` is smaller when
        the faces could not carry it).
    title : str
        The title printed on the sheets (without sheet numbers).
    face_piece : (F,) int ndarray
        0-based piece of each face (all 0 for a one-piece net); piece ``i`` is
        printed ``(i + 1)``.
    joins : tuple of (int, int)
        0-based pieces that share seams.
    order : tuple of int
        0-based pieces in gluing order (largest first, each next joining those built).
    number_at : tuple of (int, (2,) ndarray)
        Per piece, its sheet (0-based) and the centre in mm of the face carrying its number.
    """

    sheets: tuple[Sheet, ...]
    pitch: float
    rotated: bool
    seams: int
    tab_seams: npt.NDArray[np.bool_]
    tab_elsewhere: npt.NDArray[np.bool_]
    seam_numbers: npt.NDArray[np.int64]
    label_chars: int
    seam_type: npt.NDArray[np.int64]
    tab_fold_length: npt.NDArray[np.float64]
    fold_counts: dict[str, int]
    closed_in_plane: int
    pieces: int
    label_height: float
    tab_height: float
    label_wanted: float
    numbers: bool
    title: str
    face_piece: npt.NDArray[np.int64]
    joins: tuple[tuple[int, int], ...]
    order: tuple[int, ...]
    number_at: tuple[tuple[int, npt.NDArray[np.float64]], ...]

    def document(self, *, assembly: bool = False, part: str = "all") -> Document:
        """The sheets as a :class:`voxfab.drawing.Drawing` for the backends.

        With ``assembly`` (printed nets of several pieces), an assembly page
        (:meth:`assembly_page`) comes first.  ``part``: see :meth:`Sheet.page`.
        """
        pages = tuple(s.page(self.title, part) for s in self.sheets)
        if assembly and self.pieces > 1:
            pages = (self.assembly_page(),) + pages
        return Document(pages, self.title)

    def assembly_page(self, margin: float = 10.0) -> Page:
        """A map of every sheet with its pieces' numbers, which pieces join which, and the gluing order."""
        maps = []
        for s, sheet in enumerate(self.sheets):
            cut = sheet.layers["CUT"]
            outline = Polylines(cut.points, cut.offsets, cut.closed)
            maps.append((sheet.width, sheet.height, outline,
                         [(p, c) for p, (ps, c) in enumerate(self.number_at) if ps == s]))
        size = (self.sheets[0].width, self.sheets[0].height)
        return assembly_page(maps, list(self.joins), list(self.order), size, margin, self.title)

    @property
    def coloured(self) -> bool:
        """The faces are printed in their voxels' colours."""
        return any(s.colour_fills for s in self.sheets)

    @property
    def seam_labels(self) -> list[str]:
        """The label printed on both edges of each seam."""
        return seam_labels(self.seam_numbers.tolist(), self.label_chars)

    @property
    def marked_seams(self) -> list[str]:
        """Labels of the seams without room for a tab (marked for tape instead)."""
        return seam_labels(self.seam_numbers[~self.tab_seams & ~self.tab_elsewhere].tolist(), self.label_chars)

    def warnings(self) -> list[str]:
        """The lines a maker must not miss: a net split into pieces, seams without tabs.

        Labels that shrink to fit the faces are no warning: ``label_height`` is their largest
        height, and a face too small for ``min_label_height`` is refused; :meth:`report` gives
        the height drawn.
        """
        out = []
        if self.pieces > 1:
            n = len(self.sheets)
            out.append(f"net split into {self.pieces} pieces on {n} sheet{'s' if n > 1 else ''}: "
                       "glue the seams between pieces by their labels")
        marked = self.marked_seams
        if marked:
            shown = ", ".join(marked[:20]) + (" ..." if len(marked) > 20 else "")
            out.append(f"{len(marked)} seam{'s' if len(marked) > 1 else ''} without room for a tab, marked for "
                       f"tape: {shown}")
        return out

    def report(self) -> list[str]:
        """Human-readable lines about fitting, fill, tabs and folds (the warnings included)."""
        n = len(self.sheets)
        w, h = self.sheets[0].width, self.sheets[0].height
        fills = ", ".join(f"{100 * s.fill:.0f} %" for s in self.sheets)
        lines = [
            f"faces {self.pitch:g} mm, {n} sheet{'s' if n > 1 else ''} of {w:g} x {h:g} mm, "
            f"filled {fills}" + (", net turned a quarter turn" if self.rotated else "")
        ]
        fitted = f" (fitted to the faces; at most {self.label_wanted:g} mm)" \
            if self.label_height < self.label_wanted - 1e-9 else ""
        numbers = (f", {self.label_chars}-character labels {self.label_height:.1f} mm high{fitted}" if self.numbers
                   else ", no labels")
        lines.append(
            f"{self.seams} glued seams; {int(self.tab_seams.sum())} tabs ({self.tab_height:.1f} mm deep){numbers}"
        )
        if self.pieces > 1:
            lines.append("gluing order: " + " ".join(piece_name(i + 1) for i in self.order))
        if self.tab_elsewhere.any():
            lines.append(f"{int(self.tab_elsewhere.sum())} seams to other pieces take their tabs there")
        fc = self.fold_counts
        lines.append(f"folds: {fc['mountain']} mountain, {fc['valley']} valley, {fc['flat']} coplanar")
        if self.closed_in_plane:
            lines.append(f"{self.closed_in_plane} seams meet in the plane and are left uncut")
        return lines + self.warnings()


def _seam_sides(edges: NetEdges, joined: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    f, k = np.nonzero(~joined & edges.canonical())
    g, kk = edges.partner_face[f, k], edges.partner_edge[f, k]
    return np.stack([np.stack([f, k], 1), np.stack([g, kk], 1)], axis=1)


def _perforate(a: npt.NDArray[np.float64], b: npt.NDArray[np.float64], cut: float, bridge: float) -> Polylines:
    """Short through-cuts along segments ``a → b``, with a bridge at both ends."""
    if a.shape[0] == 0:
        return Polylines.empty()
    vec = b - a
    length = np.linalg.norm(vec, axis=1)
    d = vec / length[:, None]
    n = np.maximum(np.floor((length - bridge) / (cut + bridge)), 0).astype(np.int64)
    short = n == 0
    # Segments too short for one full cut get one cut of a third of their length.
    dash = np.where(short, length / 3, cut)
    n = np.where(short, 1, n)
    start = (length - (n * dash + (n - 1) * bridge)) / 2
    seg = np.repeat(np.arange(a.shape[0]), n)
    idx = np.arange(seg.size) - np.repeat(np.cumsum(n) - n, n)
    t0 = start[seg] + idx * (dash[seg] + bridge)
    p = a[seg] + t0[:, None] * d[seg]
    return Polylines.from_segments(p, p + dash[seg][:, None] * d[seg])


def _shared_in_plane(plan: SheetPlan) -> npt.NDArray[np.bool_]:
    """``(F, 4)`` edges lying on the same sheet segment as an edge of another face."""
    a, b = plan.corners2d, plan.corners2d[:, _NEXT]
    lo = np.minimum(a, b)
    horizontal = a[..., 1] == b[..., 1]
    m = int(plan.corners2d.max()) + 2
    key = ((plan.face_sheet[:, None] * m + lo[..., 0]) * m + lo[..., 1]) * 2 + horizontal
    _, inverse, counts = np.unique(key.ravel(), return_inverse=True, return_counts=True)
    return (counts[inverse] == 2).reshape(key.shape)


def _edge_points(pos: npt.NDArray[np.float64], fe: npt.NDArray[np.int64]) -> tuple[np.ndarray, np.ndarray]:
    return pos[fe[:, 0], fe[:, 1]], pos[fe[:, 0], _NEXT[fe[:, 1]]]


def draw_net(grid: npt.ArrayLike, net: Net, *, options: DrawingOptions | None = None, name: str = "",
             colours: VoxelColours | None = None) -> NetDrawing:
    """Lay a net out on sheets with cut outlines, folds, glue tabs, seam labels and a title.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape the net unfolds.
    net : Net
        A net of that shape (face ``i`` is face ``i`` of its surface graph).
    options : DrawingOptions, optional
        Sheet, pitch, tab and style options.
    name : str
        The shape's name, printed in the title of every sheet with the pitch,
        the net's seed and, when there are several, the sheet number.
    colours : VoxelColours, optional
        The voxels' colours: each face is printed in its voxel's colour
        (:mod:`._paint`).  None draws lines only.

    Returns
    -------
    NetDrawing

    Raises
    ------
    FormatError
        When ``net`` is not a net of ``grid``.
    SheetFitError
        When the net does not fit the sheet at the face size asked for.
    InvalidShapeError
        When the faces are too small for the seam labels or glue tabs; the
        message gives the smallest face size that works.
    """
    opts = options or DrawingOptions()
    graph = surface_graph(grid)
    check_net(graph, net)
    return _draw(graph, net, plan_sheets(net.corners2d, opts), opts, name=name,
                 face_piece=np.zeros(net.face_count, dtype=np.int64), colours=colours)


def draw_pieces(grid: npt.ArrayLike, pieces: list[Net], *, options: DrawingOptions | None = None,
                name: str = "", placement: Placement | None = None,
                colours: VoxelColours | None = None) -> NetDrawing:
    """Pack the pieces of a several-piece unfolding on as few sheets as possible and draw them.

    Seams between pieces are labelled on both edges and get a tab on one side,
    like every other seam; the report gives the fill of each sheet.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape the pieces unfold.
    pieces : list of Net
        Pieces covering its surface (faces identified by voxel and normal).
    options : DrawingOptions, optional
    name : str
        The shape's name for the title.
    placement : Placement, optional
        Where each piece goes (the studio's layout), instead of packing them.
    colours : VoxelColours, optional
        The voxels' colours, as for :func:`draw_net`.

    Returns
    -------
    NetDrawing

    Raises
    ------
    FormatError
        When a piece is not part of a net of ``grid``, or two pieces share a face.
    SheetFitError
        When a piece alone does not fit the sheet.
    PlacementError
        When ``placement`` puts pieces over each other or across the margin.
    """
    opts = options or DrawingOptions()
    graph = surface_graph(grid)
    net, plan, swap, face_piece, _, _ = _packed(graph, pieces, opts, placement)
    return _draw(graph, net, plan, opts, name=name, face_piece=face_piece, swap=swap, colours=colours)


def sheet_plan(graph: SurfaceGraph, pieces: list[Net], options: DrawingOptions) -> SheetPlan:
    """The sheets the drawing puts ``pieces`` on: a one-piece net on its own sheets, pieces packed with
    room for their tabs, as :func:`draw_net` and :func:`draw_pieces` place them."""
    if len(pieces) == 1:
        return plan_sheets(pieces[0].corners2d, options)
    return _packed(graph, pieces, options)[1]


def placement_for(grid: npt.ArrayLike, pieces: list[Net], options: DrawingOptions) -> Placement:
    """The placement the drawing code gives a net of ``grid`` (one :class:`~voxfab.unfold.Net` per piece) by itself."""
    from voxfab.shape import fill_cavities

    g = np.asarray(grid, dtype=bool)
    graph = surface_graph(fill_cavities(g) if pieces[0].filled else g)
    return placement_of(sheet_plan(graph, pieces, options), [p.corners2d for p in pieces], float(options.margin))


def sheets_needed(grid: npt.ArrayLike, pieces: list[Net], options: DrawingOptions) -> tuple[int, int, int]:
    """How :func:`draw_pieces` packs ``pieces``, without drawing them: ``(sheets, goal, untabbed)``.

    ``goal`` is ``ceil(1.25 A / U)``, ``A`` the paper of the faces and of a
    full tab per seam that has room for one, ``U`` a sheet's drawable area;
    ``untabbed`` counts the seams with no free cell beyond either side.
    """
    import math

    net, plan, _, _, tabs, seams = _packed(surface_graph(grid), pieces, options)
    p = plan.pitch
    inset, h = tab_heights(p, options.tab_width, options.tab_angle)
    base = p - 2 * inset
    top = max(base - 2 * h / math.tan(math.radians(options.tab_angle)), 0.0)
    paper = net.face_count * p * p + tabs * (base + top) / 2 * h
    x0, y0, x1, y1 = plan.area
    return plan.count, math.ceil(1.25 * paper / ((x1 - x0) * (y1 - y0)) - 1e-9), seams - tabs


def _packed(graph: SurfaceGraph, pieces: list[Net], opts: DrawingOptions, placement: Placement | None = None,
            before: tuple[list[Net], Placement] | None = None
            ) -> tuple[Net, SheetPlan, npt.NDArray[np.bool_], npt.NDArray[np.int64], int, int]:
    """The pieces as one net packed on sheets: the net, its plan, each seam's tab side, each face's piece,
    the number of tabs the packer kept room for and the number of seams.

    A ``placement`` (the studio's layout) puts the pieces where it says, checked, instead of packing them.
    ``before`` (the net before an edit and its placement) lays them out again keeping the pieces the edit
    left as they were in place (:func:`._relayout.relayout`).
    """
    for piece in pieces:
        check_net(graph, piece)
    swap, sides, tab_edges = piece_tabs(graph, pieces, opts)
    if placement is None and before is not None:
        from ._relayout import relayout

        placement = relayout(pieces, tab_edges, opts, before)
    if placement is None:
        plan, placed = pack_pieces([p.corners2d for p in pieces], opts, tab_edges)
    else:
        plan, placed = plan_placement(placement, [p.corners2d for p in pieces], opts, tab_edges)
    tabs = 0 if tab_edges is None else sum(int(t.shape[0]) for t in tab_edges)
    face_piece = np.repeat(np.arange(len(pieces)), [p.face_count for p in pieces])
    return _joined(pieces, placed), plan, swap, face_piece, tabs, int(sides.shape[0]) if opts.tabs else 0


def _joined(pieces: list[Net], corners: list[npt.NDArray[np.int64]]) -> Net:
    """The pieces as one net, laid at ``corners``."""
    counts = np.cumsum([0] + [p.face_count for p in pieces])
    return Net(voxel=np.concatenate([p.voxel for p in pieces]), normal=np.concatenate([p.normal for p in pieces]),
               corners3d=np.concatenate([p.corners3d for p in pieces]), corners2d=np.concatenate(corners),
               folds=np.concatenate([p.folds.reshape(-1, 2) + c for p, c in zip(pieces, counts[:-1])]),
               seed=pieces[0].seed, strategy=pieces[0].strategy, filled=pieces[0].filled)


def piece_tabs(graph: SurfaceGraph, pieces: list[Net], opts: DrawingOptions
               ) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.int64], list[npt.NDArray[np.int64]] | None]:
    """Each seam's tab side ``swap``, the seams' ``sides`` and each piece's ``(t_i, 2)`` face and edge pairs that
    take a tab (None without tabs), as the drawing chooses them."""
    # Tab sides are chosen on the pieces laid apart (a quarter turn changes none), so the packer can
    # keep room for exactly those tabs.
    apart = _apart([p.corners2d for p in pieces])
    corners = np.concatenate(apart)
    edges = classify_edges(graph, _joined(pieces, apart), corners)
    sides = _seam_sides(edges, edges.joined)
    swap, reserved = tab_sides(corners, sides, edges.global_low[sides[:, 1, 0], sides[:, 1, 1]])
    if not opts.tabs:
        return swap, sides, None
    counts = np.cumsum([0] + [p.face_count for p in pieces])
    face_piece = np.repeat(np.arange(len(pieces)), [p.face_count for p in pieces])
    chosen = np.where(swap[:, None], sides[:, 1], sides[:, 0])[reserved]
    of = face_piece[chosen[:, 0]]
    return swap, sides, [np.stack([chosen[of == i, 0] - counts[i], chosen[of == i, 1]], axis=1)
                         for i in range(len(pieces))]


def _apart(corners: list[npt.NDArray[np.int64]]) -> list[npt.NDArray[np.int64]]:
    """Pieces' corners moved to start at cell (0, 0) and laid side by side two cells apart."""
    out, x = [], 0
    for c in corners:
        c = c - c.reshape(-1, 2).min(axis=0)
        out.append(c + (x, 0))
        x += int(c[..., 0].max()) + 2
    return out


def _draw(graph: SurfaceGraph, net: Net, plan: SheetPlan, opts: DrawingOptions, *, name: str,
          face_piece: npt.NDArray[np.int64], swap: npt.NDArray[np.bool_] | None = None,
          colours: VoxelColours | None = None) -> NetDrawing:
    """Draw ``net`` (a whole net, a piece, or pieces side by side, ``face_piece`` saying which) on ``plan``.

    ``swap`` (one per seam) puts a seam's second side first, so its tab goes there when it has room;
    ``colours`` paints the faces.
    """
    pieces = int(face_piece.max(initial=0)) + 1
    edges = classify_edges(graph, net, plan.corners2d)
    fs = plan.face_sheet
    joined = edges.joined
    sides = _seam_sides(edges, joined)
    if swap is not None:
        sides = np.where(swap[:, None, None], sides[:, ::-1], sides)
    seam_type = edges.fold_type[sides[:, 0, 0], sides[:, 0, 1]].astype(np.int64)
    external = sides[:, 1, 0] < 0
    # A seam to another piece takes its tab on the copy seen from the lower surface face.
    elsewhere = external & ~edges.global_low[sides[:, 0, 0], sides[:, 0, 1]]
    allowed = np.stack([~elsewhere, ~external], axis=1)
    if external.any():
        numbers = edges.seam_id[sides[:, 0, 0], sides[:, 0, 1]] + 1
        # Label length from all 2F surface edges, so pieces drawn apart print one label per seam.
        chars = label_length(2 * graph.face_count)
    else:
        numbers = np.arange(1, sides.shape[0] + 1)
        chars = label_length(int(numbers.max(initial=1)))
    p = plan.pitch
    problem = legibility_problem(opts, p, chars)
    if problem:
        raise InvalidShapeError(problem)
    pos = plan.face_positions()
    shared = _shared_in_plane(plan)
    w, h = plan.size
    if not opts.tabs:
        allowed = np.zeros_like(allowed)
    tabs = place_tabs(pos, fs, sides, pitch=p, area=plan.area, sheet_width=w, tab_width=opts.tab_width,
                      tab_angle=opts.tab_angle, allowed=allowed, min_height=opts.min_tab_depth)
    inset, tab_h = tab_heights(p, opts.tab_width, opts.tab_angle)
    label_h = number_height(opts, p, chars)
    fold_mask = joined & edges.canonical()
    fold_counts = {
        kind: int(np.count_nonzero(fold_mask & (edges.fold_type == t)))
        for kind, t in (("mountain", 1), ("valley", -1), ("flat", 0))
    }
    title = f"{name}  FACES {p:g} MM  SEED {net.seed}".strip()
    joins = piece_joins(face_piece, sides)
    order = gluing_order(np.bincount(face_piece, minlength=pieces).tolist(), joins)
    labels = seam_labels(numbers.tolist(), chars)
    paint = net_paint(graph, net, colours, opts.bleed) if colours is not None else None
    ink = paint.ink if paint is not None else np.zeros(net.face_count, dtype=np.int64)
    firsts = np.searchsorted(face_piece, face_piece)  # each face's piece starts here in the joined net
    local = np.arange(net.face_count) - firsts
    names = [f"face-{i}" if pieces == 1 else f"piece-{p + 1}-face-{i}"
             for p, i in zip(face_piece.tolist(), local.tolist())]
    piece_names = [str(i + 1) for i in range(pieces)] if pieces > 1 else []
    # Each piece's number, boxed, clear of every seam label and tape mark and of the other numbers.
    spots = place_numbers(piece_names, face_piece, fs, pos, number_faces(face_piece, joined), p, label_h,
                          _mark_boxes(pos, fs, sides, labels, tabs, elsewhere, p, label_h, opts.numbers),
                          paper_boxes(pos, fs, sides, tabs), plan.area) if piece_names else []
    number_at = tuple((s, c) for s, c, _ in spots)
    paper_ink = 0 if paint is None else min(INKS)  # the ink of the bare paper, as the heading's
    number_ink = [ink_under(c, s, fs, pos, ink, paper_ink) for s, c, _ in spots]
    sheets = tuple(
        _draw_sheet(s, plan, edges, joined, sides, seam_type, tabs, opts, label_h, title, pos, shared,
                    labels, elsewhere, [(piece_names[i], c, h, number_ink[i]) for i, (ps, c, h) in enumerate(spots)
                                        if ps == s], paint, names)
        for s in range(plan.count)
    )
    return NetDrawing(
        sheets=sheets, pitch=p, rotated=plan.rotated, seams=int(sides.shape[0]),
        tab_seams=tabs.placed, tab_elsewhere=elsewhere, seam_numbers=numbers, label_chars=chars,
        seam_type=seam_type,
        tab_fold_length=np.where(tabs.placed, p - 2 * inset, 0.0), fold_counts=fold_counts,
        closed_in_plane=int(np.count_nonzero(edges.closed_in_plane & edges.canonical())),
        pieces=pieces, label_height=float(label_h), tab_height=float(tab_h) if opts.tabs else 0.0,
        label_wanted=float(opts.label_height), numbers=bool(opts.numbers), title=title,
        face_piece=face_piece, joins=tuple(joins), order=tuple(order), number_at=number_at,
    )


def _draw_sheet(
    s: int, plan: SheetPlan, edges: NetEdges, joined: npt.NDArray[np.bool_], sides: npt.NDArray[np.int64],
    seam_type: npt.NDArray[np.int64], tabs: TabPlan, opts: DrawingOptions, label_h: float, title: str,
    pos: npt.NDArray[np.float64], shared: npt.NDArray[np.bool_], labels: list[str],
    elsewhere: npt.NDArray[np.bool_], piece_numbers: list[tuple[str, npt.NDArray[np.float64], float, int]],
    paint: Paint | None = None, names: list[str] | None = None,
) -> Sheet:
    p = plan.pitch
    fs = plan.face_sheet
    on = fs == s
    cells = plan.corners2d
    canon = edges.canonical()
    on_e = np.broadcast_to(on[:, None], joined.shape)
    a_cell, b_cell = cells, cells[:, _NEXT]
    # Faces of one piece share a cell (0, 0) on the sheet; pieces packed apart each have their own.
    face_origin = plan.face_origin()
    origins, group = np.unique(face_origin[on], axis=0, return_inverse=True)
    in_group = np.full(fs.shape[0], -1, dtype=np.int64)
    in_group[on] = group.ravel()

    def runs(mask: npt.NDArray[np.bool_]) -> tuple[np.ndarray, np.ndarray]:
        starts, ends = [np.zeros((0, 2))], [np.zeros((0, 2))]
        for g, origin in enumerate(origins):
            m = mask & (in_group == g)[:, None]
            st, en = merge_unit_segments(a_cell[m], b_cell[m])
            starts.append(origin + st * p)
            ends.append(origin + en * p)
        return np.concatenate(starts), np.concatenate(ends)

    layers: dict[str, list[Polylines]] = {name: [] for name in LAYERS}
    # Lines are drawn per ink (:mod:`._paint`): one group in the layers' own colours without colours.
    face_ink = paint.ink if paint is not None else np.zeros(fs.shape[0], dtype=np.int64)
    edge_ink = paint.edge_ink(edges.partner_face) if paint is not None else np.zeros(joined.shape, np.int64)
    inks: dict[tuple[str, int], list[Polylines]] = {}

    def by_ink(layer: str, ink: npt.NDArray[np.int64], make) -> None:  # noqa: ANN001 - mask -> Polylines
        for i in unique(ink).tolist():
            lines = make(ink == i)
            layers[layer].append(lines)
            inks.setdefault((layer, i), []).append(lines)

    folds = joined & canon & on_e
    ink_values = unique(edge_ink[folds]).tolist() or [0]
    lines_by_type = {(t, i): runs(folds & (edges.fold_type == t) & (edge_ink == i))
                     for t in ((1, -1, 0) if opts.grid_lines else (1, -1)) for i in ink_values}
    # Tab folds on this sheet, typed like the seam they close (coplanar: a full fold, mountain).
    seam_face = sides[np.arange(sides.shape[0]), np.maximum(tabs.side, 0), 0]
    tab_here = tabs.placed & (fs[seam_face] == s)
    tab_poly = tabs.polygon[tab_here]
    tab_kind = np.where(seam_type[tab_here] == -1, -1, 1)
    tab_edge = sides[np.arange(sides.shape[0]), np.maximum(tabs.side, 0)]
    tab_ink = edge_ink[tab_edge[tab_here, 0], tab_edge[tab_here, 1]]
    perf = Perforate(opts.perforate)
    perf_type = {Perforate.MOUNTAIN: 1, Perforate.VALLEY: -1}.get(perf)
    for t, layer in ((1, "MOUNTAIN"), (-1, "VALLEY")):
        groups = []
        for i in ink_values + sorted(set(tab_ink[tab_kind == t].tolist()) - set(ink_values)):
            a, b = lines_by_type.get((t, i), (np.zeros((0, 2)), np.zeros((0, 2))))
            tab = (tab_kind == t) & (tab_ink == i)
            groups.append((i, np.concatenate([a, tab_poly[tab, 0]]), np.concatenate([b, tab_poly[tab, 1]])))
        if t == perf_type:
            a, b = np.concatenate([g[1] for g in groups]), np.concatenate([g[2] for g in groups])
            layers["CUT"].append(_perforate(a, b, opts.perf_cut, opts.perf_bridge))
            continue
        for i, a, b in groups:
            lines = Polylines.from_segments(a, b)
            layers[layer].append(lines)
            inks.setdefault((layer, i), []).append(lines)
    if opts.grid_lines:
        flat = [lines_by_type[(0, i)] for i in ink_values]
        layers["GRID"].append(Polylines.from_segments(np.concatenate([f[0] for f in flat]),
                                                      np.concatenate([f[1] for f in flat])))
    # Slits: cut edges between faces that sit side by side in the plane.
    cut_e = ~joined & on_e
    slit_a, slit_b = runs(cut_e & shared)
    # Closed outlines round the faces and their tabs, one outer ring per piece.
    boundary = cut_e & ~shared
    detour = np.full(joined.shape + (4, 2), np.nan)
    fe = tab_edge[tab_here]
    # Going along the edge with the face on the left, the tab is on the right: a, top a, top b, b.
    detour[fe[:, 0], fe[:, 1]] = tab_poly[:, [0, 3, 2, 1]]
    outer: list[npt.NDArray[np.float64]] = []
    holes: list[npt.NDArray[np.float64]] = []
    pieces = 0
    for g, origin in enumerate(origins):
        m = boundary & (in_group == g)[:, None]
        rings, n = trace_outlines(a_cell[m], b_cell[m], detour[m], origin=origin, pitch=p)
        outer += rings[:n]
        holes += rings[n:]
        pieces += n
    rings = outer + holes
    layers["CUT"].insert(0, Polylines.from_list(rings, [True] * len(rings)))
    layers["CUT"].insert(1, Polylines.from_segments(slit_a, slit_b))
    # The label on both edges of every seam, inside the face, standing on the edge and reading along it.
    texts: list[str] = []
    org: list[np.ndarray] = []
    dirs: list[np.ndarray] = []
    marks: list[tuple[np.ndarray, np.ndarray]] = []
    text_ink: list[np.ndarray] = []
    mark_ink: list[np.ndarray] = []
    for side in (0, 1):
        fe = sides[:, side]
        here = (fe[:, 0] >= 0) & (fs[np.maximum(fe[:, 0], 0)] == s)
        text_ink.append(face_ink[fe[here, 0]])
        p0, p1 = _edge_points(pos, fe[here])
        d = (p1 - p0) / p
        inward = np.stack([-d[:, 1], d[:, 0]], axis=1)
        here_texts = [labels[i] for i in np.flatnonzero(here).tolist()]
        texts += here_texts
        start, _ = _label_span(p0, d, inward, here_texts, p, label_h)
        org.append(start)
        dirs.append(d)
        marks.append(_tape_bar(p0, p1, d, inward, ~tabs.placed[here] & ~elsewhere[here], p))
        mark_ink.append(text_ink[-1][~tabs.placed[here] & ~elsewhere[here]])
    if texts and opts.numbers:
        all_org, all_dirs = np.concatenate(org), np.concatenate(dirs)
        by_ink("LABEL", np.concatenate(text_ink), lambda m: text_polylines(
            [t for t, k in zip(texts, m.tolist()) if k], all_org[m], all_dirs[m], label_h, advance=LABEL_ADVANCE))
    mark_a, mark_b = np.concatenate([m[0] for m in marks]), np.concatenate([m[1] for m in marks])
    by_ink("LABEL", np.concatenate(mark_ink) if len(mark_a) else np.zeros(1, np.int64),
           lambda m: Polylines.from_segments(mark_a[m[:len(mark_a)]], mark_b[m[:len(mark_a)]]))
    if piece_numbers:
        by_ink("LABEL", np.array([k for *_, k in piece_numbers]), lambda m: number_text(
            [t for (t, *_), k in zip(piece_numbers, m.tolist()) if k],
            np.array([c for _, c, _, _ in piece_numbers])[m], np.array([h for _, _, h, _ in piece_numbers])[m]))
    heading = title + (f"  SHEET {s + 1}/{plan.count}" if plan.count > 1 else "")
    if heading and opts.heading:
        x0, _, x1, _ = plan.area
        # Clear of a cutter's mark in the corner, whose sensor would read the text as part of it.
        x0 = clear_of_marks(opts.cutter, plan.size, float(opts.margin), x0,
                            (opts.edge + 1.0, opts.edge + 1.0 + opts.title_height))
        # The left 60 % of the band: printed PDFs put a legend on the right.
        th = min(opts.title_height, 0.6 * (x1 - x0) / max(text_width(heading, 1.0), 1e-9))
        by_ink("LABEL", np.array([0 if paint is None else min(INKS)]),
               lambda m: text_polylines([heading], [(x0, opts.edge + 1.0)], [(1.0, 0.0)], th))
    colour_fills: tuple[Fill, ...] = ()
    ink_list: tuple[Ink, ...] = ()
    if paint is not None:
        here = np.flatnonzero(on)
        tab_rgb = tint(paint.across[tab_edge[tab_here, 0], tab_edge[tab_here, 1]])
        face_names = [names[f] if names else f"face-{f}" for f in here.tolist()]
        colour_fills = sheet_fills(pos[here], paint.face[here], face_names, boundary[here], tab_poly, tab_rgb,
                                   paint.bleed)
        halo = ("MOUNTAIN", "VALLEY")  # lines between two faces: clear of both
        ink_list = tuple(Ink(layer, Polylines.concat(v), INKS[i][0], INKS[i][1] if layer in halo else "")
                         for (layer, i), v in sorted(inks.items()) if i in INKS)
    return Sheet(
        number=s + 1, width=plan.size[0], height=plan.size[1],
        layers={k: Polylines.concat(v) for k, v in layers.items()},
        faces=pos[on], face_index=np.flatnonzero(on), tabs=tab_poly, pieces=pieces,
        fill=(int(on.sum()) * p * p + _polygon_area(tab_poly)) / (plan.size[0] * plan.size[1]),
        colour_fills=colour_fills, inks=ink_list,
        marks=registration_marks(Cutter(opts.cutter), plan.size, float(opts.margin)),
    )


def _label_span(p0: npt.NDArray[np.float64], d: npt.NDArray[np.float64], inward: npt.NDArray[np.float64],
                texts: list[str], p: float, label_h: float) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Where seam labels on edges from ``p0`` along ``d`` start (their baseline's start), and their widths, mm:
    centred on the edge, or pushed along it just clear of the label on the previous edge."""
    width = np.array([text_width(t, label_h, LABEL_ADVANCE) for t in texts]).reshape(-1)
    along = np.maximum((p - width) / 2, number_start(p, label_h))
    return p0 + d * along[:, None] + inward * (NUMBER_INSET * p), width


def _tape_bar(p0: npt.NDArray[np.float64], p1: npt.NDArray[np.float64], d: npt.NDArray[np.float64],
              inward: npt.NDArray[np.float64], no_tab: npt.NDArray[np.bool_], p: float
              ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """A seam without a tab gets a bar along both its edges: tape or glue it edge to edge (its two ends)."""
    off = inward[no_tab] * (0.015 * p)
    return p0[no_tab] + d[no_tab] * 0.2 * p + off, p1[no_tab] - d[no_tab] * 0.2 * p + off


def _mark_boxes(pos: npt.NDArray[np.float64], fs: npt.NDArray[np.int64], sides: npt.NDArray[np.int64],
                labels: list[str], tabs: TabPlan, elsewhere: npt.NDArray[np.bool_], p: float, label_h: float,
                numbers: bool) -> dict[int, tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
    """Per sheet, the boxes ``(lo, hi)`` of every seam label and tape mark drawn: where no piece number may go."""
    lo: list[npt.NDArray[np.float64]] = []
    hi: list[npt.NDArray[np.float64]] = []
    sheet: list[npt.NDArray[np.int64]] = []
    for side in (0, 1):
        fe = sides[:, side]
        here = fe[:, 0] >= 0
        p0, p1 = _edge_points(pos, fe[here])
        d = (p1 - p0) / p
        inward = np.stack([-d[:, 1], d[:, 0]], axis=1)
        on = fs[fe[here, 0]]
        if numbers:
            start, width = _label_span(p0, d, inward, [labels[i] for i in np.flatnonzero(here).tolist()], p, label_h)
            end = start + d * width[:, None] + inward * label_h
            lo.append(np.minimum(start, end))
            hi.append(np.maximum(start, end))
            sheet.append(on)
        no_tab = ~tabs.placed[here] & ~elsewhere[here]
        a, b = _tape_bar(p0, p1, d, inward, no_tab, p)
        lo.append(np.minimum(a, b))
        hi.append(np.maximum(a, b))
        sheet.append(on[no_tab])
    los, his, sheets = np.concatenate(lo), np.concatenate(hi), np.concatenate(sheet)
    return {int(s): (los[sheets == s], his[sheets == s]) for s in unique(sheets).tolist()}


def _polygon_area(polys: npt.NDArray[np.float64]) -> float:
    """Total area of ``(n, k, 2)`` simple polygons, mm²."""
    x, y = polys[..., 0], polys[..., 1]
    return float(np.abs((x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y).sum(axis=1)).sum() / 2)
