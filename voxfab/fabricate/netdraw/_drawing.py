"""From a net to sheets of layered polylines: cut outlines, folds, tabs, numbers and a title."""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab.drawing import LAYERS, Fill, Page, Polylines, text_polylines, text_width
from voxfab.drawing import Drawing as Document
from voxfab.shape import surface_graph
from voxfab.unfold import Net

from ._geometry import NetEdges, check_net, classify_edges, merge_unit_segments, trace_outlines
from ._options import DrawingOptions, Perforate
from ._sheets import SheetPlan, plan_sheets
from ._tabs import TabPlan, place_tabs, tab_heights

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
    """

    number: int
    width: float
    height: float
    layers: dict[str, Polylines]
    faces: npt.NDArray[np.float64]
    face_index: npt.NDArray[np.int64]
    tabs: npt.NDArray[np.float64]
    pieces: int

    def page(self, title: str = "") -> Page:
        """This sheet as a drawing page; glue tabs are shaded in previews and prints."""
        tabs = self.tabs[np.isfinite(self.tabs).all(axis=(1, 2))]
        fills = (Fill(Polylines.from_list(list(tabs), [True] * len(tabs)), TAB_FILL),) if len(tabs) else ()
        return Page(self.width, self.height, self.layers, fills=fills, title=title)


@dataclasses.dataclass(frozen=True, eq=False)
class Drawing:
    """A net drawn on one or more sheets, ready for the file writers.

    Attributes
    ----------
    sheets : tuple of Sheet
    pitch : float
        Face edge length, mm.
    rotated : bool
        The net was turned a quarter turn to fit.
    seams : int
        Glued seam pairs (each numbered on both edges).
    tab_seams : (S,) bool ndarray
        Which seams got a tab here.
    tab_elsewhere : (S,) bool ndarray
        Seams to another piece whose tab is drawn with that piece.
    seam_numbers : (S,) int ndarray
        The number printed on both edges of each seam: 1..S for a whole net, the
        surface edge's global index + 1 for a piece (so pieces drawn apart agree).
    seam_type : (S,) int ndarray
        +1 convex, -1 concave, 0 coplanar seam.
    tab_fold_length : (S,) float ndarray
        Length of each tab's fold line, mm (0 without a tab).
    fold_counts : dict of str to int
        Folds drawn per type (``mountain``, ``valley``, ``flat``), tabs excluded.
    closed_in_plane : int
        Seams of the net left uncut because their two sides meet in the plane.
    split_seams : int
        Folds of the net cut because their faces went to different sheets.
    label_height, tab_height : float
        Cap height of the edge numbers and full tab height, mm.
    title : str
        The title printed on the sheets (without sheet numbers).
    """

    sheets: tuple[Sheet, ...]
    pitch: float
    rotated: bool
    seams: int
    tab_seams: npt.NDArray[np.bool_]
    tab_elsewhere: npt.NDArray[np.bool_]
    seam_numbers: npt.NDArray[np.int64]
    seam_type: npt.NDArray[np.int64]
    tab_fold_length: npt.NDArray[np.float64]
    fold_counts: dict[str, int]
    closed_in_plane: int
    split_seams: int
    label_height: float
    tab_height: float
    title: str

    def document(self) -> Document:
        """The sheets as a :class:`voxfab.drawing.Drawing` for the backends."""
        return Document(tuple(s.page(self.title) for s in self.sheets), self.title)

    @property
    def marked_seams(self) -> list[int]:
        """Numbers of the seams without room for a tab (marked for tape instead)."""
        return self.seam_numbers[~self.tab_seams & ~self.tab_elsewhere].tolist()

    def report(self) -> list[str]:
        """Human-readable lines about fitting, tabs and folds."""
        n = len(self.sheets)
        w, h = self.sheets[0].width, self.sheets[0].height
        lines = [
            f"pitch {self.pitch:g} mm, {n} sheet{'s' if n > 1 else ''} of {w:g} x {h:g} mm"
            + (", net turned a quarter turn" if self.rotated else "")
        ]
        if self.split_seams:
            lines.append(f"split over {n} sheets: {self.split_seams} folds became numbered seams")
        marked = self.marked_seams
        lines.append(
            f"{self.seams} glued seams numbered on both edges; {int(self.tab_seams.sum())} tabs "
            f"({self.tab_height:.1f} mm), numbers {self.label_height:.1f} mm high"
        )
        if self.tab_elsewhere.any():
            lines.append(f"{int(self.tab_elsewhere.sum())} seams to other pieces take their tabs there")
        if marked:
            shown = ", ".join(map(str, marked[:20])) + (" ..." if len(marked) > 20 else "")
            lines.append(f"{len(marked)} seams without room for a tab, marked for tape: {shown}")
        fc = self.fold_counts
        lines.append(f"folds: {fc['mountain']} mountain, {fc['valley']} valley, {fc['flat']} coplanar")
        if self.closed_in_plane:
            lines.append(f"{self.closed_in_plane} seams meet in the plane and are left uncut")
        return lines


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


def draw_net(grid: npt.ArrayLike, net: Net, *, options: DrawingOptions | None = None, name: str = "") -> Drawing:
    """Lay a net out on sheets with cut outlines, folds, glue tabs, numbers and a title.

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

    Returns
    -------
    Drawing

    Raises
    ------
    FormatError
        When ``net`` is not a net of ``grid``.
    InvalidShapeError
        When the pitch is too large for the sheet.
    """
    opts = options or DrawingOptions()
    graph = surface_graph(grid)
    check_net(graph, net)
    plan = plan_sheets(net.corners2d, opts)
    edges = classify_edges(graph, net, plan.corners2d)
    fs = plan.face_sheet
    partner = edges.partner_face
    same_sheet = (partner >= 0) & (fs[:, None] == fs[np.maximum(partner, 0)])
    joined = edges.joined & same_sheet
    split = int(np.count_nonzero(edges.joined & ~same_sheet & edges.canonical()))
    sides = _seam_sides(edges, joined)
    seam_type = edges.fold_type[sides[:, 0, 0], sides[:, 0, 1]].astype(np.int64)
    external = sides[:, 1, 0] < 0
    # A seam to another piece takes its tab on the copy seen from the lower surface face.
    elsewhere = external & ~edges.global_low[sides[:, 0, 0], sides[:, 0, 1]]
    allowed = np.stack([~elsewhere, ~external], axis=1)
    if external.any():
        numbers = edges.seam_id[sides[:, 0, 0], sides[:, 0, 1]] + 1
    else:
        numbers = np.arange(1, sides.shape[0] + 1)
    pos = plan.face_positions()
    shared = _shared_in_plane(plan)
    w, h = plan.size
    if not opts.tabs:
        allowed = np.zeros_like(allowed)
    tabs = place_tabs(pos, fs, sides, pitch=plan.pitch, area=plan.area, sheet_width=w,
                      tab_width=opts.tab_width, tab_angle=opts.tab_angle, allowed=allowed)
    inset, tab_h = tab_heights(plan.pitch, opts.tab_width, opts.tab_angle)
    n_digits = len(str(int(numbers.max(initial=1))))
    p = plan.pitch
    label_h = min(opts.label_height, 0.15 * p, 0.6 * p * 6.0 / ((n_digits - 1) * 6.0 + 4.0))
    fold_mask = joined & edges.canonical()
    fold_counts = {
        name: int(np.count_nonzero(fold_mask & (edges.fold_type == t)))
        for name, t in (("mountain", 1), ("valley", -1), ("flat", 0))
    }
    title = f"{name}  PITCH {p:g} MM  SEED {net.seed}".strip()
    sheets = tuple(
        _draw_sheet(s, plan, edges, joined, sides, seam_type, tabs, opts, label_h, title, pos, shared,
                    numbers, elsewhere)
        for s in range(plan.count)
    )
    tab_fold = np.where(tabs.placed, p - 2 * inset, 0.0)
    return Drawing(
        sheets=sheets, pitch=p, rotated=plan.rotated, seams=int(sides.shape[0]),
        tab_seams=tabs.placed, tab_elsewhere=elsewhere, seam_numbers=numbers, seam_type=seam_type, tab_fold_length=tab_fold, fold_counts=fold_counts,
        closed_in_plane=int(np.count_nonzero(edges.closed_in_plane & edges.canonical())),
        split_seams=split, label_height=float(label_h), tab_height=float(tab_h), title=title,
    )


def _draw_sheet(
    s: int, plan: SheetPlan, edges: NetEdges, joined: npt.NDArray[np.bool_], sides: npt.NDArray[np.int64],
    seam_type: npt.NDArray[np.int64], tabs: TabPlan, opts: DrawingOptions, label_h: float, title: str,
    pos: npt.NDArray[np.float64], shared: npt.NDArray[np.bool_], numbers: npt.NDArray[np.int64],
    elsewhere: npt.NDArray[np.bool_],
) -> Sheet:
    p = plan.pitch
    fs = plan.face_sheet
    on = fs == s
    cells = plan.corners2d
    origin = plan.origin[s]
    canon = edges.canonical()
    on_e = np.broadcast_to(on[:, None], joined.shape)
    a_cell, b_cell = cells, cells[:, _NEXT]

    def runs(mask: npt.NDArray[np.bool_]) -> tuple[np.ndarray, np.ndarray]:
        st, en = merge_unit_segments(a_cell[mask], b_cell[mask])
        return origin + st * p, origin + en * p

    layers: dict[str, list[Polylines]] = {name: [] for name in LAYERS}
    lines_by_type: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for t in (1, -1, 0):
        lines_by_type[t] = runs(joined & canon & on_e & (edges.fold_type == t))
    # Tab folds on this sheet, typed like the seam they close (coplanar: a full fold, mountain).
    seam_face = sides[np.arange(sides.shape[0]), np.maximum(tabs.side, 0), 0]
    tab_here = tabs.placed & (fs[seam_face] == s)
    tab_poly = tabs.polygon[tab_here]
    tab_kind = np.where(seam_type[tab_here] == -1, -1, 1)
    perf = Perforate(opts.perforate)
    perf_type = {Perforate.MOUNTAIN: 1, Perforate.VALLEY: -1}.get(perf)
    for t, layer in ((1, "MOUNTAIN"), (-1, "VALLEY")):
        a, b = lines_by_type[t]
        ta, tb = tab_poly[tab_kind == t, 0], tab_poly[tab_kind == t, 1]
        a, b = np.concatenate([a, ta]), np.concatenate([b, tb])
        if t == perf_type:
            layers["CUT"].append(_perforate(a, b, opts.perf_cut, opts.perf_bridge))
        else:
            layers[layer].append(Polylines.from_segments(a, b))
    if opts.grid_lines:
        layers["GRID"].append(Polylines.from_segments(*lines_by_type[0]))
    # Slits: cut edges between faces that sit side by side in the plane.
    cut_e = ~joined & on_e
    slit_a, slit_b = runs(cut_e & shared)
    # Closed outlines round the faces and their tabs, one outer ring per piece.
    boundary = cut_e & ~shared
    detour = np.full(joined.shape + (4, 2), np.nan)
    tab_edge = sides[np.arange(sides.shape[0]), np.maximum(tabs.side, 0)]
    fe = tab_edge[tab_here]
    # Going along the edge with the face on the left, the tab is on the right: a, top a, top b, b.
    detour[fe[:, 0], fe[:, 1]] = tab_poly[:, [0, 3, 2, 1]]
    rings, pieces = trace_outlines(a_cell[boundary], b_cell[boundary], detour[boundary], origin=origin, pitch=p)
    layers["CUT"].insert(0, Polylines.from_list(rings, [True] * len(rings)))
    layers["CUT"].insert(1, Polylines.from_segments(slit_a, slit_b))
    # Numbers on both edges of every seam, inside the face, reading along the edge.
    texts: list[str] = []
    org: list[np.ndarray] = []
    dirs: list[np.ndarray] = []
    marks: list[tuple[np.ndarray, np.ndarray]] = []
    for side in (0, 1):
        fe = sides[:, side]
        here = (fe[:, 0] >= 0) & (fs[np.maximum(fe[:, 0], 0)] == s)
        p0, p1 = _edge_points(pos, fe[here])
        d = (p1 - p0) / p
        inward = np.stack([-d[:, 1], d[:, 0]], axis=1)
        mid = (p0 + p1) / 2
        texts += [str(i) for i in numbers[here].tolist()]
        org.append(mid + inward * (0.06 * p))
        dirs.append(d)
        no_tab = ~tabs.placed[here] & ~elsewhere[here]
        # A seam without a tab gets a bar along both its edges: tape or glue it edge to edge.
        off = inward[no_tab] * (0.015 * p)
        marks.append((p0[no_tab] + d[no_tab] * 0.2 * p + off, p1[no_tab] - d[no_tab] * 0.2 * p + off))
    if texts and opts.numbers:
        layers["LABEL"].append(text_polylines(texts, np.concatenate(org), np.concatenate(dirs), label_h,
                                                  center=True, mark_ambiguous=True))
    layers["LABEL"].append(Polylines.from_segments(np.concatenate([m[0] for m in marks]),
                                                   np.concatenate([m[1] for m in marks])))
    heading = title + (f"  SHEET {s + 1}/{plan.count}" if plan.count > 1 else "")
    if heading and opts.heading:
        x0, _, x1, _ = plan.area
        # The left 60 % of the band: printed PDFs put a legend on the right.
        th = min(opts.title_height, 0.6 * (x1 - x0) / max(text_width(heading, 1.0), 1e-9))
        layers["LABEL"].append(
            text_polylines([heading], [(x0, float(opts.margin) + 1.0)], [(1.0, 0.0)], th)
        )
    return Sheet(
        number=s + 1, width=plan.size[0], height=plan.size[1],
        layers={k: Polylines.concat(v) for k, v in layers.items()},
        faces=pos[on], face_index=np.flatnonzero(on), tabs=tab_poly, pieces=pieces,
    )
