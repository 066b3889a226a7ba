"""From a voxel shape to a checked, print-ready mesh."""

from __future__ import annotations

import dataclasses
from enum import Enum
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid, check_choice, check_positive
from voxfab.errors import FabricationError, InvalidShapeError
from voxfab.shape import VoxelShape, bounding_box, crop, exposed_faces, fill_cavities

from ._check import MeshReport, check_mesh
from ._colours import MAX_FILAMENTS, Filaments, assign_filaments
from ._contacts import NO_CONTACTS, Contacts, bridge_boxes, bridged_colours, bridged_grid, find_contacts
from ._data import MeshData
from ._faces import voxel_mesh

#: Most exposed voxel faces a mesh may have.  Meshing and checking a 256³
#: one-voxel sphere shell (0.54 M faces) peaks at about 0.5 GB (measured, 0.2 GB
#: of it the interpreter and libraries), under 1 kB per face, so this keeps a mesh
#: well under 2 GB.  Random noise at 256³ has about 25 M faces and is refused
#: after a count that costs a fraction of a second.
MAX_FACES = 1_500_000
#: Thinnest wall a 0.4 mm nozzle prints reliably (two perimeters), mm.
MIN_WALL = 0.8
#: Default width of a contact bridge, mm (at most :data:`BRIDGE_MAX_FRACTION` of the pitch).
BRIDGE_WIDTH = 1.0
BRIDGE_DEFAULT_FRACTION = 0.6
BRIDGE_MAX_FRACTION = 0.9
#: Default engraving depth of a label, mm.
ENGRAVE_DEPTH = 0.6
#: Smallest letter height that prints legibly when engraved, mm.
MIN_LETTER = 3.0


class ContactMode(Enum):
    """What to do with voxels that touch only along an edge or at a corner."""

    BRIDGE = "bridge"
    SPLIT = "split"
    ERROR = "error"


@dataclasses.dataclass(frozen=True)
class MeshResult:
    """A checked mesh and what was done to make it.

    Attributes
    ----------
    mesh : MeshData
        The mesh in mm, minimum corner at the origin.
    report : MeshReport
        The checker's measures of ``mesh``.
    pitch : float
        Millimetres per voxel used.
    contacts : int
        Edge-only and corner-only contacts found in the shape.
    bridges : int
        Bridge boxes added.
    warnings : tuple of str
        Printability warnings, one line each.
    filaments : Filaments or None
        For a coloured shape, the filament of each colour (``mesh.colour`` holds
        each triangle's filament, ``mesh.palette`` their colours).
    """

    mesh: MeshData
    report: MeshReport
    pitch: float
    contacts: int
    bridges: int
    warnings: tuple[str, ...]
    filaments: Filaments | None = None


def parse_magnet(spec: str) -> tuple[float, float]:
    """Parse ``"DxH"`` (diameter × depth in mm), e.g. ``"6x3"``."""
    parts = str(spec).lower().replace("×", "x").split("x")
    try:
        d, h = (float(p) for p in parts)
    except ValueError:
        raise InvalidShapeError(f"magnet: expected DIAMETERxDEPTH in mm such as 6x3, got {spec!r}") from None
    return check_positive(d, name="magnet diameter"), check_positive(h, name="magnet depth")


def resolve_pitch(grid: npt.NDArray[np.bool_], *, pitch: float | None, size: float | None, default: float) -> float:
    """Millimetres per voxel from a pitch, or from a target size of the longest side."""
    if pitch is not None and size is not None:
        raise InvalidShapeError("pitch and size: give one of them, not both")
    if size is not None:
        return check_positive(size, name="size") / max(grid.shape)
    return check_positive(pitch if pitch is not None else default, name="pitch")


def hollow_out(grid: npt.NDArray[np.bool_], wall: int) -> npt.NDArray[np.bool_]:
    """Keep a wall of ``wall`` voxels and open each inner cavity with a drain hole.

    The wall is every voxel within Chebyshev distance ``wall`` of the outside,
    so it is at least ``wall`` voxels thick along every axis and a cavity never
    touches the outside, not even at a corner.  Each cavity gets one drain: a
    one-voxel column from one of its voxels straight down to the outside, from
    the lowest voxel nearest the cavity's centre when that keeps the print's
    footprint.  A drain never takes the last voxels of the bottom layer (a
    spinning top's one-voxel tip): the print keeps the footprint it stands on,
    and the drain opens on the underside beside it instead.
    """
    from scipy import ndimage

    g = fill_cavities(grid)
    inner = ndimage.binary_erosion(g, structure=np.ones((3, 3, 3), bool), iterations=wall, border_value=0)
    shell = g & ~inner
    labels, n = ndimage.label(inner, structure=ndimage.generate_binary_structure(3, 1))
    if n == 0:
        return shell
    everywhere = np.argwhere(labels > 0)
    lab_all = labels[everywhere[:, 0], everywhere[:, 1], everywhere[:, 2]]
    centre = np.stack([np.bincount(lab_all, weights=everywhere[:, a], minlength=n + 1) for a in range(2)], axis=1)
    centre /= np.maximum(np.bincount(lab_all, minlength=n + 1), 1)[:, None]
    # A drain starts at a cavity voxel with wall right under it (the bottom of its column in the cavity).
    idx = everywhere[~inner[everywhere[:, 0], everywhere[:, 1], everywhere[:, 2] - 1]]
    lab = labels[idx[:, 0], idx[:, 1], idx[:, 2]]
    dist = np.hypot(idx[:, 0] - centre[lab, 0], idx[:, 1] - centre[lab, 1])
    # Each cavity's voxels, lowest first, then nearest its centre (then x, y: a fixed order).
    order = np.lexsort((idx[:, 1], idx[:, 0], dist, idx[:, 2], lab))
    starts = np.flatnonzero(np.r_[True, lab[order][1:] != lab[order][:-1]])
    ends = np.r_[starts[1:], len(order)]
    for first, stop in zip(starts, ends):
        candidates = idx[order[first:stop]]
        _drill_drain(shell, candidates)
    return shell


def _drill_drain(shell: npt.NDArray[np.bool_], candidates: npt.NDArray[np.int64]) -> None:
    """Drill one drain below the first candidate voxel whose column keeps a voxel in the bottom layer.

    When every column would empty the bottom layer (a cavity standing straight on a
    one-voxel foot), the first one is drilled: the print then stands one voxel higher,
    and the mesh check measures the box of the voxels it meshes.
    """
    bottom = int(shell[:, :, 0].sum())
    chosen = None
    for x, y, z in candidates:
        col = shell[x, y, :z]
        gaps = np.flatnonzero(~col)
        start = int(gaps.max()) + 1 if gaps.size else 0
        if start > 0 or bottom > 1 or not col[0]:
            chosen = (x, y, start, z)
            break
        if chosen is None:
            chosen = (x, y, start, z)
    assert chosen is not None
    x, y, start, z = chosen
    shell[x, y, start:z] = False


def thin_wall_warning(grid: npt.NDArray[np.bool_], pitch: float) -> str | None:
    """A warning when some part is one voxel thick and one voxel is under :data:`MIN_WALL`."""
    if pitch >= MIN_WALL:
        return None
    p = np.pad(grid, 1)
    core = p[1:-1, 1:-1, 1:-1]
    thin = np.zeros_like(core)
    for a in range(3):
        lo = [slice(1, -1)] * 3
        hi = [slice(1, -1)] * 3
        lo[a] = slice(0, -2)
        hi[a] = slice(2, None)
        thin |= core & ~p[tuple(lo)] & ~p[tuple(hi)]
    if not thin.any():
        return None
    return (
        f"{int(thin.sum())} voxels are in one-voxel walls, which at {pitch:g} mm per voxel are thinner "
        f"than the {MIN_WALL:g} mm a 0.4 mm nozzle prints reliably; use --pitch {MIN_WALL:g} or more"
    )


def largest_rectangle(mask: npt.NDArray[np.bool_]) -> tuple[int, int, int, int]:
    """Largest axis-aligned rectangle of True cells, as ``(x0, y0, x1, y1)`` (exclusive ends)."""
    nx, ny = mask.shape
    heights = np.zeros(ny + 1, dtype=np.int64)
    best = (0, 0, 0, 0, 0)
    for x in range(nx):  # one row of the footprint at a time (a 2D histogram sweep)
        heights[:ny] = np.where(mask[x], heights[:ny] + 1, 0)
        stack: list[int] = []
        for y in range(ny + 1):
            while stack and heights[stack[-1]] >= heights[y]:
                h = int(heights[stack.pop()])
                y0 = stack[-1] + 1 if stack else 0
                area = h * (y - y0)
                if area > best[0]:
                    best = (area, x - h + 1, y0, x + 1, y)
            stack.append(y)
    return best[1], best[2], best[3], best[4]


def _bottom_regions(
    rect: tuple[float, float, float, float], *, magnet: tuple[float, float] | None, label: str | None
) -> tuple[tuple[float, float, float, float] | None, tuple[float, float, float, float] | None]:
    """Split the bottom rectangle (mm) between the magnet pocket and the label."""
    x0, y0, x1, y1 = rect
    if magnet is None:
        return None, rect if label else None
    if not label:
        return rect, None
    w, h = x1 - x0, y1 - y0
    # The pocket takes a square at one end with a rim of 2 mm; the label the rest.
    side = min(min(w, h), magnet[0] + 4.0)
    if w >= h:
        return (x0, y0, x0 + side, y1), (x0 + side, y0, x1, y1)
    return (x0, y0, x1, y0 + side), (x0, y0 + side, x1, y1)


def build_mesh(
    shape: VoxelShape | npt.ArrayLike,
    *,
    pitch: float | None = None,
    size: float | None = None,
    contacts: str | ContactMode = ContactMode.BRIDGE,
    bridge_width: float | None = None,
    fill: bool = True,
    hollow: int = 0,
    label: str | None = None,
    engrave_depth: float = ENGRAVE_DEPTH,
    base: float = 0.0,
    magnet: tuple[float, float] | str | None = None,
    merge: bool = True,
    name: str = "shape",
    colours: int | None = None,
) -> MeshResult:
    """Turn a voxel shape into a checked, print-ready mesh.

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
        The voxels, ``[x, y, z]`` with z up.  It is cropped to its bounding box.
    pitch : float, optional
        Millimetres per voxel (default: the shape's pitch, or 1.0 for arrays).
    size : float, optional
        Target length of the longest side in mm, instead of ``pitch``.
    contacts : {"bridge", "split", "error"}
        Voxels touching only along an edge or at a corner: join them with a small
        square bridge, keep them as separate shells, or refuse.
    bridge_width : float, optional
        Bridge width in mm (default 1.0, at most 0.6 × pitch; at most 0.9 × pitch).
    fill : bool
        Fill enclosed cavities (solid print).
    hollow : int
        When > 0, hollow the shape with walls this many voxels thick and a drain
        hole per cavity.
    label : str, optional
        Text engraved, mirrored, on the bottom.
    engrave_depth : float
        Depth of the label in mm.
    base : float
        Thickness in mm of a flat plate under the shape's footprint (0: none).
    magnet : (float, float) or str, optional
        Diameter and depth in mm (or ``"DxH"``) of a round pocket in the bottom.
    merge : bool
        Merge coplanar faces.
    name : str
        Name used in messages.
    colours : int, optional
        For a coloured shape, the most filaments: more colours are merged
        perceptually (:func:`assign_filaments`).  Default: one filament per
        visible colour.  Each triangle takes the colour of the voxel whose face it
        lies on; bridges, a base plate and pocket or label walls that of a
        neighbouring voxel.

    Returns
    -------
    MeshResult

    Raises
    ------
    InvalidShapeError
        On an empty grid or bad parameters.
    FabricationError
        When the mesh would be too large, contacts are refused, or a check fails.
    """
    if colours is not None and not 1 <= int(colours) <= MAX_FILAMENTS:
        raise InvalidShapeError(f"colours: expected a number of filaments from 1 to {MAX_FILAMENTS}, got {colours}")
    inputs = _check_inputs(
        shape, pitch=pitch, size=size, contacts=contacts, hollow=hollow, base=base, magnet=magnet,
        label=label, engrave_depth=engrave_depth, name=name,
    )
    warnings: list[str] = []
    g, index = _solid_grid(inputs.grid, inputs, fill=fill, warnings=warnings)
    found = _checked_contacts(g, inputs)
    surface = _voxel_surface(g, index, found, inputs, bridge_width=bridge_width, merge=merge, warnings=warnings)
    if not (surface.boxes_left or inputs.base or inputs.label or inputs.magnet):
        out, checked = surface.mesh, surface.report
    else:
        out, checked = _cad_features(g, index, surface, inputs, warnings=warnings)
    filaments = None
    if index is not None:
        assert inputs.palette is not None
        out, filaments = assign_filaments(out, index, inputs.palette, colours)
    return MeshResult(out, checked, inputs.pitch, found.count, len(surface.boxes),
                      tuple(warnings + _parts_warning(checked)), filaments)


@dataclasses.dataclass(frozen=True, eq=False)
class _Inputs:
    """The checked parameters of :func:`build_mesh` (lengths in mm)."""

    grid: npt.NDArray[np.bool_]
    index: npt.NDArray[np.uint8] | None  # the colour index of each voxel of ``grid`` (None: uncoloured)
    palette: npt.NDArray[np.uint8] | None
    pitch: float
    mode: ContactMode
    hollow: int
    base: float
    magnet: tuple[float, float] | None
    label: str | None
    depth: float
    name: str


@dataclasses.dataclass(frozen=True, eq=False)
class _Surface:
    """The checked voxel surface, and the contact bridges still to add as CAD boxes."""

    mesh: MeshData
    report: MeshReport
    boxes: npt.NDArray[np.float64]
    boxes_left: bool
    volume: float


def _check_inputs(
    shape: VoxelShape | npt.ArrayLike, *, pitch: float | None, size: float | None, contacts: str | ContactMode,
    hollow: int, base: float, magnet: tuple[float, float] | str | None, label: str | None,
    engrave_depth: float, name: str,
) -> _Inputs:
    """Check every parameter before any work; crop the grid and resolve the pitch."""
    default_pitch = shape.pitch if isinstance(shape, VoxelShape) else 1.0
    g0 = as_grid(shape.grid if isinstance(shape, VoxelShape) else shape, name=name)
    mode = check_choice(contacts, ContactMode, name="contacts")
    g = crop(g0)
    coloured = isinstance(shape, VoxelShape) and shape.colours is not None
    index = crop(shape.colours.index) if coloured else None  # type: ignore[union-attr]
    palette = shape.colours.palette if coloured else None  # type: ignore[union-attr]
    pitch_mm = resolve_pitch(g, pitch=pitch, size=size, default=default_pitch)
    hollow = int(hollow)
    if hollow < 0:
        raise InvalidShapeError(f"hollow: expected a wall thickness in voxels >= 0, got {hollow}")
    base = float(base)
    if base < 0 or not np.isfinite(base):
        raise InvalidShapeError(f"base: expected a thickness in mm >= 0, got {base}")
    magnet_dh = parse_magnet(magnet) if isinstance(magnet, str) else magnet
    if magnet_dh is not None:
        magnet_dh = (check_positive(magnet_dh[0], name="magnet diameter"), check_positive(magnet_dh[1], name="magnet depth"))
    if label is not None and not label.strip():
        raise InvalidShapeError("label: expected some text, got an empty string")
    depth = check_positive(engrave_depth, name="engrave_depth")
    faces = exposed_faces(g)
    if faces > MAX_FACES:
        raise FabricationError(
            f"{name}: {faces} exposed voxel faces, over the limit of {MAX_FACES} for a mesh "
            f"(a noisy grid?); smooth or crop the shape first"
        )
    return _Inputs(g, index, palette, pitch_mm, mode, hollow, base, magnet_dh, label, depth, name)


def _solid_grid(
    g: npt.NDArray[np.bool_], inputs: _Inputs, *, fill: bool, warnings: list[str]
) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.uint8] | None]:
    """The voxels to print, hollowed or with enclosed cavities filled, and their colour indices; warn
    about thin walls.  A filled cavity takes the colour of its nearest voxel."""
    index = inputs.index
    if inputs.hollow:
        _check_wall(g, inputs)
        hollowed = hollow_out(g, inputs.hollow)
        lo, hi = bounding_box(hollowed)
        box = tuple(slice(a, b) for a, b in zip(lo, hi))
        g = hollowed[box].copy()
        if g.shape != hollowed.shape:
            # Only a drain through a one-voxel foot empties the bottom layer (see hollow_out).
            warnings.append("a drain hole goes through the voxel the print stood on; it stands one voxel higher")
        if index is not None:
            index = np.where(g, index[box], 0).astype(np.uint8)
    elif fill:
        filled_g = _fill_cavities(g)
        if index is not None and filled_g.sum() != g.sum():
            from voxfab.shape import VoxelColours

            index = VoxelColours(index, inputs.palette).fitted(filled_g).index
        g = filled_g
    w = thin_wall_warning(g, inputs.pitch)
    if w:
        warnings.append(w)
    return g, index


def _check_wall(g: npt.NDArray[np.bool_], inputs: _Inputs) -> None:
    """Refuse a hollowing that would leave no cavity: the print would be solid, the option without effect.

    :func:`hollow_out` keeps every voxel within ``hollow`` (Chebyshev distance) of
    the outside, so a cavity is left only when some voxel lies deeper than that.
    """
    from scipy import ndimage

    depth = int(ndimage.distance_transform_cdt(np.pad(fill_cavities(g), 1), metric="chessboard").max())
    if inputs.hollow < depth:
        return
    if depth <= 1:
        raise InvalidShapeError(f"hollow: {inputs.name} is nowhere thicker than 2 voxels; a wall of "
                                f"{inputs.hollow} leaves no cavity (the print would be solid; use 0)")
    raise InvalidShapeError(f"hollow: walls of {inputs.hollow} voxels leave no cavity in {inputs.name} (the print "
                            f"would be solid); at most {depth - 1} leaves one")


def _checked_contacts(g: npt.NDArray[np.bool_], inputs: _Inputs) -> Contacts:
    """Edge and corner contacts; with ``contacts="error"`` refuse them, and a print in several parts."""
    found = find_contacts(g)
    if inputs.mode is not ContactMode.ERROR:
        return found
    if found.count:
        raise FabricationError(f"{inputs.name}: refused with --contacts error: {found.describe()}")
    from scipy import ndimage

    # A print in several pieces needs an explicit choice (bridge or split), not a silent success.
    n_pieces = ndimage.label(g, structure=np.ones((3, 3, 3), bool))[1]
    if n_pieces > 1:
        raise FabricationError(
            f"{inputs.name}: refused with --contacts error: the print would be {n_pieces} separate parts "
            "(use split to print them apart)"
        )
    return found


def _voxel_surface(
    g: npt.NDArray[np.bool_], index: npt.NDArray[np.uint8] | None, found: Contacts, inputs: _Inputs, *,
    bridge_width: float | None, merge: bool, warnings: list[str],
) -> _Surface:
    """Mesh and check the voxels' surface, with contact bridges as grid cells where they fit.

    With colour indices, each triangle takes its voxel's (a bridge, its box's neighbour's).
    """
    from scipy import ndimage

    pitch_mm, name = inputs.pitch, inputs.name
    do_bridge = inputs.mode is ContactMode.BRIDGE and found.count > 0
    bounds = np.stack([np.zeros(3), np.array(g.shape) * pitch_mm])
    boxes = np.zeros((0, 2, 3))
    colour = {} if index is None else {"colour": index, "palette": inputs.palette}
    if do_bridge:
        width = _bridge_width(bridge_width, pitch_mm, warnings)
        boxes = bridge_boxes(found, pitch=pitch_mm, width=width)
        # The bridges join every edge and corner contact, so each 26-connected
        # component of the voxels is one piece of the bridged grid: its part.  (The
        # checker counts the bodies and refuses a shell split between parts.)
        labels26, n_bodies = ndimage.label(g, structure=np.ones((3, 3, 3), bool))
        refined = bridged_grid(g, boxes, pitch=pitch_mm, labels=labels26)
        if refined is not None:
            # Bridges as cells of a rectilinear grid: meshed and checked exactly, no CAD kernel.
            cells, coords, labels_r = refined
            if index is not None:
                colour["colour"] = bridged_colours(index, boxes, coords, pitch=pitch_mm, palette=inputs.palette)
            sizes = [np.diff(c) for c in coords]
            exact_volume = float(sizes[0] @ (cells.astype(np.float64) @ sizes[2]) @ sizes[1]) * pitch_mm**3
            expect = dict(
                what=name, expected_volume=exact_volume, expected_bounds=bounds, expected_bodies=n_bodies,
            )
            try:
                # Bridges close every edge contact: no contact midpoints to look for.
                mesh = voxel_mesh(cells, pitch=pitch_mm, merge=merge, part_labels=labels_r, coords=coords,
                                  contacts=NO_CONTACTS, **colour)
                report = check_mesh(mesh, **expect)
            except FabricationError:
                # An edge contact left between bridges: mesh again with its midpoints.
                mesh = voxel_mesh(cells, pitch=pitch_mm, merge=merge, part_labels=labels_r, coords=coords, **colour)
                report = check_mesh(mesh, **expect)
            return _Surface(mesh, report, boxes, False, exact_volume)
    elif bridge_width is not None:
        check_positive(bridge_width, name="bridge_width")
    labels6 = ndimage.label(g, structure=ndimage.generate_binary_structure(3, 1))[0]
    mesh = voxel_mesh(g, pitch=pitch_mm, merge=merge, part_labels=labels6, contacts=found, **colour)
    exact_volume = float(g.sum()) * pitch_mm**3
    report = check_mesh(mesh, what=name, expected_volume=exact_volume, expected_bounds=bounds)
    return _Surface(mesh, report, boxes, do_bridge, exact_volume)


def _cad_features(
    g: npt.NDArray[np.bool_], index: npt.NDArray[np.uint8] | None, surface: _Surface, inputs: _Inputs, *,
    warnings: list[str],
) -> tuple[MeshData, MeshReport]:
    """Add bridges and the base, cut the magnet pocket and the label with the CAD kernel; check again.

    The voxel surface's colours go through the kernel as face ids; what the kernel
    adds (bridges, the base, pocket and label walls) takes its nearest voxel's colour.
    """
    from . import _cad

    pitch_mm, base = inputs.pitch, inputs.base
    if index is None:
        solid = _cad.to_manifold(surface.mesh)
    else:
        solid, source = _cad.to_manifold_traced(surface.mesh, surface.mesh.colour)
    added: list[Any] = []
    added_volume = 0.0
    boxes = surface.boxes
    if surface.boxes_left:
        added += _cad.box_solids(boxes)
        added_volume += float(np.prod(boxes[:, 1] - boxes[:, 0], axis=1).sum())
    if base:
        plate = np.array([[0.0, 0.0, -base], [g.shape[0] * pitch_mm, g.shape[1] * pitch_mm, 0.0]])
        added += _cad.box_solids(plate[None])
        added_volume += float(np.prod(plate[1] - plate[0]))
    if added:
        solid = _cad.union([solid, *added])
    removed_volume = 0.0
    if inputs.label or inputs.magnet:
        cutters, removed_volume = _bottom_cutters(g, inputs, warnings=warnings)
        pieces = len(solid.decompose())
        solid = _cad.subtract(solid, cutters)
        if inputs.magnet and len(solid.decompose()) > pieces:
            # The pocket took all the material joining the print to its base (a one-voxel foot over it).
            d, h = inputs.magnet
            raise FabricationError(
                f"{inputs.name}: a magnet pocket {d:g} mm wide and {h:g} mm deep cuts the print off its "
                f"{base:g} mm base; make the pocket shallower than the base, narrower, or the base thicker"
                if base else
                f"{inputs.name}: a magnet pocket {d:g} mm wide and {h:g} mm deep cuts the print in pieces; "
                "make it shallower or narrower, or add --base")
    if index is None:
        out = _cad.from_manifold(solid)
    else:
        out, faces = _cad.from_manifold_traced(solid, source)
        out = dataclasses.replace(out, colour=_traced_colours(out, faces, index, pitch_mm),
                                  palette=surface.mesh.palette)
    shift = -out.vertices.min(axis=0)
    out = dataclasses.replace(out, vertices=out.vertices + shift)
    return out, _final_check(out, solid, g, inputs, surface.volume, added_volume, removed_volume)


def _bottom_cutters(g: npt.NDArray[np.bool_], inputs: _Inputs, *, warnings: list[str]) -> tuple[list[Any], float]:
    """The magnet pocket and the engraved label under the print, and the volume they may remove."""
    from . import _cad

    pitch_mm, base, name, magnet_dh, label = inputs.pitch, inputs.base, inputs.name, inputs.magnet, inputs.label
    z_bottom = -base if base else 0.0
    cutters: list[Any] = []
    removed_volume = 0.0
    if base:
        rect_mm = (0.0, 0.0, g.shape[0] * pitch_mm, g.shape[1] * pitch_mm)
    else:
        x0, y0, x1, y1 = largest_rectangle(g[:, :, 0])
        rect_mm = (x0 * pitch_mm, y0 * pitch_mm, x1 * pitch_mm, y1 * pitch_mm)
    floor = base if base else _floor_thickness(g) * pitch_mm
    magnet_rect, label_rect = _bottom_regions(rect_mm, magnet=magnet_dh, label=label)
    if magnet_dh is not None and magnet_rect is not None:
        d, h = magnet_dh
        mx0, my0, mx1, my1 = magnet_rect
        side = min(mx1 - mx0, my1 - my0)
        if d > side:
            raise FabricationError(
                f"{name}: a magnet pocket of {d:g} mm does not fit the flat bottom "
                f"({side:g} mm across); add --base or use a smaller magnet"
            )
        if d + 2 * MIN_WALL > side:
            warnings.append(f"the magnet pocket leaves side walls under {MIN_WALL:g} mm")
        total_height = g.shape[2] * pitch_mm + base
        if h >= total_height:
            raise FabricationError(f"{name}: a magnet pocket {h:g} mm deep is as tall as the print ({total_height:g} mm)")
        cutters.append(_cad.cylinder(((mx0 + mx1) / 2, (my0 + my1) / 2), z_bottom - 1.0, z_bottom + h, d))
        removed_volume += np.pi * d * d / 4 * (h + 1.0)
    if label and label_rect is not None:
        lx0, ly0, lx1, ly1 = label_rect
        margin = max(1.0, 0.1 * min(lx1 - lx0, ly1 - ly0))
        box = (lx1 - lx0 - 2 * margin, ly1 - ly0 - 2 * margin)
        if min(box) <= 0:
            raise FabricationError(f"{name}: no room for the label on the bottom; add --base")
        cutter, letter = _cad.label_cutter(
            label, centre=((lx0 + lx1) / 2, (ly0 + ly1) / 2), box=box, z_bottom=z_bottom, depth=inputs.depth
        )
        cutters.append(cutter)
        removed_volume += box[0] * box[1] * (inputs.depth + 1.0)
        if letter < MIN_LETTER:
            warnings.append(f"the label is {letter:.1f} mm tall, under {MIN_LETTER:g} mm it may not be legible")
        if inputs.depth >= floor:
            warnings.append(f"the label ({inputs.depth:g} mm deep) cuts through the {floor:g} mm thick bottom")
    return cutters, removed_volume


def _final_check(
    out: MeshData, solid: Any, g: npt.NDArray[np.bool_], inputs: _Inputs, exact_volume: float,
    added_volume: float, removed_volume: float,
) -> MeshReport:
    """Check the CAD kernel's mesh: edges, volume bounds, bodies and the bounding box."""
    from scipy import ndimage

    pitch_mm, base, name = inputs.pitch, inputs.base, inputs.name
    expected_bodies = None
    if inputs.mode is ContactMode.BRIDGE:
        gb = np.concatenate([np.ones(g.shape[:2] + (1,), bool), g], axis=2) if base else g
        expected_bodies = ndimage.label(gb, structure=np.ones((3, 3, 3), bool))[1]
    ext = np.array(g.shape, dtype=np.float64) * pitch_mm + np.array([0.0, 0.0, base])
    checked = check_mesh(
        out,
        what=name,
        expected_volume=(exact_volume - removed_volume, exact_volume + added_volume),
        expected_bodies=expected_bodies,
    )
    if np.abs(np.array(checked.bounds[1]) - ext).max() > 1e-6 * ext.max():
        raise FabricationError(f"{name}: mesh check failed: bounding box {checked.bounds[1]} mm, expected {ext.tolist()}")
    if abs(checked.volume - solid.volume()) > 1e-6 * max(checked.volume, 1.0):
        raise FabricationError(
            f"{name}: mesh check failed: volume {checked.volume:.6g} mm³ differs from the CAD kernel's {solid.volume():.6g}"
        )
    return checked


def _traced_colours(
    mesh: MeshData, faces: npt.NDArray[np.int64], index: npt.NDArray[np.uint8], pitch: float
) -> npt.NDArray[np.int64]:
    """The colour of each triangle the CAD kernel gave back (in the voxels' frame).

    A triangle of the voxel surface kept its colour as its face id; any other
    takes the colour of the voxel just inside it, or of the filled voxel nearest to
    that (a bridge over an empty voxel, the base plate under the footprint).
    """
    from scipy import ndimage

    missing = faces < 0
    colour = faces.copy()
    if missing.any():
        tri = mesh.vertices[mesh.triangles[missing]]
        normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
        inside = tri.mean(axis=1) - normal * (1e-3 * pitch)
        v = np.clip(np.floor(inside / pitch).astype(np.int64), 0, np.array(index.shape) - 1)
        _, nearest = ndimage.distance_transform_edt(index == 0, return_indices=True)
        colour[missing] = index[tuple(nearest[a][v[:, 0], v[:, 1], v[:, 2]] for a in range(3))]
    return colour


def _parts_warning(report: MeshReport) -> list[str]:
    """A maker must know that the print comes off the bed in several pieces."""
    if report.bodies <= 1:
        return []
    return [f"the print is {report.bodies} separate parts"]


def _fill_cavities(g: npt.NDArray[np.bool_]) -> npt.NDArray[np.bool_]:
    """:func:`voxfab.shape.fill_cavities` with scipy's labelling (scipy is loaded here anyway).

    Every empty voxel not 6-connected to the outside of the grid is filled.
    """
    from scipy import ndimage

    padded = np.pad(~g, 1, constant_values=True)
    labels, _ = ndimage.label(padded, structure=ndimage.generate_binary_structure(3, 1))
    return (labels != labels[0, 0, 0])[1:-1, 1:-1, 1:-1]


def _bridge_width(width: float | None, pitch: float, warnings: list[str]) -> float:
    if width is None:
        return min(BRIDGE_WIDTH, BRIDGE_DEFAULT_FRACTION * pitch)
    w = check_positive(width, name="bridge_width")
    if w > BRIDGE_MAX_FRACTION * pitch:
        warnings.append(
            f"bridge width {w:g} mm clamped to {BRIDGE_MAX_FRACTION * pitch:g} mm ({BRIDGE_MAX_FRACTION:g} × pitch)"
        )
        w = BRIDGE_MAX_FRACTION * pitch
    return w


def _floor_thickness(g: npt.NDArray[np.bool_]) -> int:
    """Voxels of solid above the bottom layer's cells, at the thinnest column."""
    bottom = g[:, :, 0]
    runs = np.cumprod(g, axis=2).sum(axis=2)
    return int(runs[bottom].min()) if bottom.any() else 0
