"""Layers of pieces → plates: thickness, dowel holes, labels, scores, checks.

All plate geometry is in mm in the stack's ``(u, v)`` frame (see
:mod:`._outline`), seen from above: labels and scores are on the top face,
the one the next plate is glued onto.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import progress
from voxfab._shared.validate import check_positive
from voxfab.errors import InvalidShapeError

from ._dowels import Dowel, place_dowels
from ._labels import Label, place_label, relabel
from ._options import PlateOptions
from ._outline import Axis, Piece, axis_value, cells_outline, scaled, slice_stack

#: Segments per quarter circle when a dowel hole is turned into a polygon.
QUAD_SEGS = 16


@dataclasses.dataclass(frozen=True, eq=False)
class Plate:
    """One plate to cut: a piece of one layer, one material thickness thick.

    Attributes
    ----------
    number : int
        1-based position in the stack (bottom plate = 1).
    layer, piece, copy : int
        Voxel layer, piece in that layer and plate within the layer (all 1-based;
        ``copy`` > 1 only when a layer takes several plates).
    outline : shapely.Polygon
        Exact voxel outline in mm, with the voxel holes, without dowel holes.
    holes : (H, 2) float ndarray
        Dowel hole centres in mm.
    hole_diameter : float
        Dowel hole diameter in mm.
    z : float
        Height of the plate's bottom face in the stack, in mm.
    thickness : float
        Plate thickness in mm.
    label : Label
        The engraved plate number.
    score : tuple of (n, 2) float ndarray
        Polylines of the next layer's outline drawn on this plate (gluing guide).
    cells : int
        Voxels of the piece.
    """

    number: int
    layer: int
    piece: int
    copy: int
    outline: object
    holes: npt.NDArray[np.float64]
    hole_diameter: float
    z: float
    thickness: float
    label: Label
    score: tuple[npt.NDArray[np.float64], ...]
    cells: int

    @property
    def id(self) -> str:
        """The piece number ``"layer-piece"``."""
        return f"{self.layer}-{self.piece}"

    @property
    def area(self) -> float:
        """Material area in mm² with exact circular dowel holes."""
        return float(self.outline.area) - len(self.holes) * math.pi * (self.hole_diameter / 2.0) ** 2

    def polygon(self, *, quad_segs: int = QUAD_SEGS) -> object:
        """The plate as a shapely Polygon in mm, dowel holes as regular polygons."""
        return with_holes(self.outline, self.holes, self.hole_diameter, quad_segs=quad_segs)


@dataclasses.dataclass(frozen=True, eq=False)
class PlateStack:
    """All plates of a shape, bottom up, and what was found while making them.

    Attributes
    ----------
    axis : str
        Slicing axis (``'x'``, ``'y'`` or ``'z'``).
    pitch, thickness : float
        Voxel pitch and measured plate thickness in mm.
    counts : tuple of int
        Plates of each stack layer (see :func:`layer_runs`).
    sources : tuple of int
        The voxel layer (1-based) each stack layer takes.
    voxel_layers : int
        Voxel layers of the shape along the axis.
    layers : tuple of tuple of Piece
        Pieces per stack layer (outlines in cell units); ``Piece.layer`` is the stack layer.
    plates : tuple of Plate
        In stack order.
    dowels : tuple of Dowel
    dowel_diameter : float
    unsupported : tuple of str
        Pieces sharing no area with the layer below or above.
    thin : tuple of str
        Pieces with a part narrower than ``min_width``.
    undowelled : tuple of str
        Pieces that share area with a neighbour layer but got no dowel hole.
    min_width : float
        Narrowest feature in mm accepted as cuttable.
    """

    axis: str
    pitch: float
    thickness: float
    counts: tuple[int, ...]
    sources: tuple[int, ...]
    voxel_layers: int
    layers: tuple[tuple[Piece, ...], ...]
    plates: tuple[Plate, ...]
    dowels: tuple[Dowel, ...]
    dowel_diameter: float
    unsupported: tuple[str, ...]
    thin: tuple[str, ...]
    undowelled: tuple[str, ...]
    min_width: float

    @property
    def plates_per_layer(self) -> int:
        """Plates of every stack layer when they all take the same number, else 0."""
        return self.counts[0] if len(set(self.counts)) == 1 else 0

    @property
    def resampled(self) -> bool:
        """Whether some voxel layer is skipped or the layers take unequal numbers of plates."""
        return self.plates_per_layer == 0 or len(self.counts) != self.voxel_layers

    def plate_range(self, k: int) -> tuple[int, int]:
        """First and last plate numbers (1-based) of stack layer ``k`` (0-based)."""
        first = sum(self.counts[:k]) + 1
        return first, first + self.counts[k] - 1

    @property
    def height(self) -> float:
        """Height in mm of the plate stack as built."""
        return sum(self.counts) * self.thickness

    @property
    def nominal_height(self) -> float:
        """Height in mm of the voxel shape along the axis."""
        return self.voxel_layers * self.pitch

    @property
    def drift(self) -> float:
        """Stack height minus shape height in mm (plates × thickness − voxels × pitch), under thickness / 2."""
        return self.height - self.nominal_height


def with_holes(outline: object, centres: npt.NDArray[np.float64], diameter: float, *, quad_segs: int = QUAD_SEGS) -> object:
    """``outline`` minus circular holes (regular polygons) at ``centres``."""
    import shapely

    if len(centres) == 0 or diameter <= 0:
        return outline
    discs = shapely.buffer(shapely.points(np.asarray(centres)), diameter / 2.0, quad_segs=quad_segs)
    return shapely.difference(outline, shapely.union_all(discs))


def _lines(geometry: object) -> tuple[npt.NDArray[np.float64], ...]:
    """Polylines of a (multi)line geometry, merged where they join."""
    import shapely
    from shapely.ops import linemerge

    if geometry.is_empty:
        return ()
    parts = [g for g in getattr(geometry, "geoms", [geometry]) if g.geom_type in ("LineString", "MultiLineString")]
    lines = [g for part in parts for g in getattr(part, "geoms", [part]) if not g.is_empty]
    if not lines:
        return ()
    # set operations on lines return them noded already: merging is enough
    merged = linemerge(shapely.multilinestrings(lines)) if len(lines) > 1 else lines[0]
    return tuple(np.asarray(g.coords, dtype=np.float64) for g in getattr(merged, "geoms", [merged]) if not g.is_empty)


def _score_lines(piece: npt.NDArray[np.bool_], above: npt.NDArray[np.bool_]) -> object:
    """Edges of the next layer lying inside this piece, in cell units (exact).

    A unit edge of the lattice is scored when the cells on both of its sides
    belong to the piece and exactly one of them is filled in the next layer.
    """
    import shapely

    segs = []
    # edges on the line x = u + 1 between cells (u, v) and (u + 1, v)
    sel = piece[:-1, :] & piece[1:, :] & (above[:-1, :] != above[1:, :])
    u, v = np.nonzero(sel)
    segs.append(np.stack([np.column_stack([u + 1, v]), np.column_stack([u + 1, v + 1])], axis=1))
    # edges on the line y = v + 1 between cells (u, v) and (u, v + 1)
    sel = piece[:, :-1] & piece[:, 1:] & (above[:, :-1] != above[:, 1:])
    u, v = np.nonzero(sel)
    segs.append(np.stack([np.column_stack([u, v + 1]), np.column_stack([u + 1, v + 1])], axis=1))
    all_segs = np.concatenate(segs).astype(np.float64)
    if len(all_segs) == 0:
        return shapely.LineString()
    merged = shapely.line_merge(shapely.multilinestrings(shapely.linestrings(all_segs)))
    return shapely.simplify(merged, 0.0)


def _is_thin(outline_mm: object, width: float) -> bool:
    """Whether an opening by a ``width`` square removes any part of the outline."""
    opened = outline_mm.buffer(-width / 2.0, join_style="mitre").buffer(width / 2.0, join_style="mitre")
    return bool(outline_mm.difference(opened).area > 1e-9 * max(1.0, outline_mm.area))


#: Most plates a stack may have (a plate count is also a count of laser jobs and glue-ups).
MAX_PLATES = 2000


def plate_count(layers: int, pitch: float, thickness: float) -> int:
    """Plates in a stack as tall as ``layers`` voxels of ``pitch``: height / thickness, rounded half up."""
    return max(1, int(math.floor(layers * pitch / thickness + 0.5)))


def layer_runs(layers: int, pitch: float, thickness: float) -> tuple[tuple[int, int], ...]:
    """Resample voxel layers to plates of another thickness, as slicers do.

    The stack has :func:`plate_count` plates, so its height is within
    ``thickness / 2`` of the object's; each plate takes the voxel layer at its
    mid-height.  A 25-voxel shape at 2 mm becomes 17 plates of 3 mm (51 mm); at
    ``pitch = k × thickness`` every layer takes ``k`` plates.

    Returns
    -------
    tuple of (int, int)
        ``(voxel layer, plates)`` runs bottom up, the layer 0-based; a voxel
        layer that no plate's mid-height falls in is left out.
    """
    n = plate_count(layers, pitch, thickness)
    if n > MAX_PLATES:
        raise InvalidShapeError(
            f"thickness: {layers} layers of {pitch:g} mm in {thickness:g} mm plates make {n} plates, over the "
            f"limit of {MAX_PLATES}; use thicker plates or a smaller pitch"
        )
    mid = (np.arange(n) + 0.5) * thickness
    # The small tolerance keeps a mid-height that lands on a layer boundary in floating point
    # (pitch = k × thickness) in the layer below, as exact arithmetic does.
    source = np.minimum(np.floor(mid / pitch + 1e-9).astype(np.int64), layers - 1)
    starts = np.flatnonzero(np.r_[True, source[1:] != source[:-1]])
    counts = np.diff(np.r_[starts, n])
    return tuple((int(source[a]), int(c)) for a, c in zip(starts, counts))


#: The defaults of :func:`make_plates`: the plate options' own.
_DEFAULTS = PlateOptions()


def make_plates(
    grid: npt.ArrayLike,
    *,
    pitch: float,
    axis: str | Axis = _DEFAULTS.axis,
    thickness: float = _DEFAULTS.thickness,
    dowel: float = _DEFAULTS.dowel,
    dowel_margin: float = _DEFAULTS.dowel_margin,
    dowels_per_joint: int = _DEFAULTS.dowels_per_joint,
    score: bool = _DEFAULTS.score,
    min_width: float = _DEFAULTS.min_width,
    kerf: float = _DEFAULTS.kerf,
) -> PlateStack:
    """Turn a voxel shape into a stack of plates.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The voxel shape.
    pitch : float
        Voxel edge in mm.
    axis : {'x', 'y', 'z'}
        Slicing axis; plates stack along it.
    thickness : float
        Measured plate thickness in mm.  When it differs from the pitch the layers
        are resampled (:func:`layer_runs`): the stack stays as tall as the object.
    dowel : float
        Dowel hole diameter in mm; 0 for no dowels.
    dowel_margin : float
        Least material in mm between a dowel hole and any edge or other hole.
    dowels_per_joint : int
        Most dowels between two overlapping pieces of consecutive layers.
    score : bool
        Score the next layer's outline on each layer's top plate.
    min_width : float
        Narrowest cuttable feature in mm; ``2 × kerf`` is used when larger.
    kerf : float
        Laser kerf in mm (only used here for the thin-feature check).

    Returns
    -------
    PlateStack
    """
    import shapely

    thickness = check_positive(thickness, name="thickness")
    pitch = check_positive(pitch, name="pitch")
    for value, name in ((dowel, "dowel"), (dowel_margin, "dowel_margin"), (kerf, "kerf"), (min_width, "min_width")):
        if not np.isfinite(value) or value < 0:
            raise InvalidShapeError(f"{name}: expected a number >= 0, got {value!r}")
    if int(dowels_per_joint) != dowels_per_joint or dowels_per_joint < 0:
        raise InvalidShapeError(f"dowels_per_joint: expected an integer >= 0, got {dowels_per_joint!r}")
    ax = axis_value(axis)
    voxel_labels, voxel_layers = slice_stack(grid, axis=ax)
    runs = layer_runs(len(voxel_layers), pitch, thickness)
    sources = [k for k, _ in runs]
    counts = [c for _, c in runs]
    # Consecutive stack layers are what touch in the stack: dowels, scores and labels follow them.
    labels = voxel_labels[sources]
    layers = tuple(
        tuple(dataclasses.replace(p, layer=i + 1) for p in voxel_layers[k]) for i, k in enumerate(sources)
    )
    if dowel > 0 and dowels_per_joint > 0:
        dowels, joints = place_dowels(labels, pitch=pitch, diameter=dowel, margin=dowel_margin, per_joint=int(dowels_per_joint))
    else:
        from ._dowels import find_joints

        dowels, joints = (), find_joints(labels)
    holes_of: dict[str, list[tuple[float, float]]] = {}
    for d in dowels:
        holes_of.setdefault(d.lower, []).append((d.x, d.y))
        holes_of.setdefault(d.upper, []).append((d.x, d.y))

    layer_union = [
        cells_outline(np.concatenate([p.cells for p in pcs])) if pcs else None for pcs in layers
    ]
    width = max(min_width, 2.0 * kerf)
    clearance = max(0.1 * pitch, 0.2)
    plates: list[Plate] = []
    thin: list[str] = []
    for k, pieces in progress(enumerate(layers), total=len(layers), desc="plates"):
        n = counts[k]
        below = sum(counts[:k])
        above = layer_union[k + 1] if k + 1 < len(layers) else None
        above_mm = scaled(above, pitch) if above is not None else None
        # what the plates of one piece share, computed once for all its copies
        shared = []
        for piece in pieces:
            outline = scaled(piece.outline, pitch)
            holes = np.array(holes_of.get(piece.id, []), dtype=np.float64).reshape(-1, 2)
            body = with_holes(outline, holes, dowel)
            lines: tuple[npt.NDArray[np.float64], ...] = ()
            if score and above is not None:
                guide = scaled(_score_lines(labels[k] == piece.index, labels[k + 1] > 0), pitch)
                if len(holes):
                    guide = shapely.intersection(guide, body)
                lines = _lines(guide)
            # every cell holds a pitch-wide square: only wider minimum widths can fail
            if width > pitch and _is_thin(outline, width):
                thin.append(piece.id)
            shared.append((outline, holes, body, lines))
        first_label: dict[int, Label] = {}
        for copy in range(1, n + 1):
            top = copy == n
            for piece, (outline, holes, body, lines) in zip(pieces, shared):
                if top:
                    hidden = shapely.intersection(body, above_mm) if above_mm is not None else shapely.Polygon()
                else:
                    hidden = body
                text = piece.id if n == 1 else f"{piece.id}.{copy}"
                # the plates of a layer below its top one share a region: reuse the spot
                label = relabel(first_label[piece.index], text) if copy > 1 and not top else None
                if label is None:
                    # place_label keeps ``clearance`` from every edge, dowel holes included
                    label = place_label(text, body, hidden, pitch=pitch, clearance=clearance)
                if copy == 1:
                    first_label[piece.index] = label
                plates.append(
                    Plate(
                        number=len(plates) + 1,
                        layer=piece.layer,
                        piece=piece.index,
                        copy=copy,
                        outline=outline,
                        holes=holes,
                        hole_diameter=float(dowel) if len(holes) else 0.0,
                        z=(below + copy - 1) * thickness,
                        thickness=thickness,
                        label=label,
                        score=lines if top else (),
                        cells=len(piece.cells),
                    )
                )
    jointed = {j.lower for j in joints} | {j.upper for j in joints}
    all_ids = [p.id for pcs in layers for p in pcs]
    unsupported = tuple(i for i in all_ids if i not in jointed) if len(all_ids) > 1 else ()
    undowelled = tuple(i for i in all_ids if i in jointed and i not in holes_of) if dowel > 0 else ()
    return PlateStack(
        axis=ax.value,
        pitch=pitch,
        thickness=thickness,
        counts=tuple(counts),
        sources=tuple(k + 1 for k in sources),
        voxel_layers=len(voxel_layers),
        layers=layers,
        plates=tuple(plates),
        dowels=dowels,
        dowel_diameter=float(dowel),
        unsupported=unsupported,
        thin=tuple(thin),
        undowelled=undowelled,
        min_width=width,
    )
