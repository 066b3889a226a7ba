"""What a print weighs, how long it prints, where its mass lies, and whether a top spins.

The mass properties come from the closed triangle mesh itself (signed tetrahedra
from a reference point), so an engraved label, a base plate or a magnet pocket
count as printed.  The filament and time figures model a slicer's default
profile: perimeters and solid top and bottom layers around a sparse infill.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from ._data import MeshData

#: Density of PLA, g/cm³.
PLA_DENSITY = 1.24
#: Default sparse infill, percent (PrusaSlicer's default profile).
DEFAULT_INFILL = 20.0
#: Furthest the centre of mass may lie from the axis through a top's tip, mm.
SPIN_AXIS_TOLERANCE = 0.5
#: Standard gravity, mm/s² (for the slowest upright spin of a top).
GRAVITY = 9806.65


@dataclasses.dataclass(frozen=True)
class PrintProfile:
    """The slicer settings the filament and time estimates assume (PrusaSlicer 2.5's defaults).

    Attributes
    ----------
    layer_height : float
        mm.
    perimeters : int
        Loops around each layer's outline.
    extrusion_width : float
        mm (1.125 x a 0.4 mm nozzle).
    solid_layers : int
        Solid layers under every bottom face and over every top face.
    perimeter_speed, external_perimeter_speed, infill_speed, solid_infill_speed : float
        mm/s.
    layer_overhead : float
        Seconds per layer for travel, retraction and the turn-arounds the plain speeds miss.
    speed_efficiency : float
        Fraction of the nominal speeds a move reaches on average (acceleration and
        short segments), measured on the bundled recipes against PrusaSlicer's estimate.
    """

    layer_height: float = 0.3
    perimeters: int = 3
    extrusion_width: float = 0.45
    solid_layers: int = 3
    perimeter_speed: float = 60.0
    external_perimeter_speed: float = 30.0
    infill_speed: float = 80.0
    solid_infill_speed: float = 20.0
    layer_overhead: float = 1.5
    speed_efficiency: float = 0.85

    @property
    def bead_area(self) -> float:
        """Cross-section of one extruded bead, mm² (a rectangle with round ends, as slicers model it)."""
        h, w = self.layer_height, self.extrusion_width
        return (w - h) * h + np.pi * h * h / 4.0


DEFAULT_PROFILE = PrintProfile()


@dataclasses.dataclass(frozen=True)
class MassProperties:
    """The volume, centre of mass and inertia of a closed mesh of unit density.

    Attributes
    ----------
    volume : float
        mm³.
    center : (3,) float ndarray
        Centre of mass (of volume), mm, in the mesh's frame.
    inertia : (3, 3) float ndarray
        Inertia tensor about ``center`` per unit density, mm⁵ (multiply by a
        density in g/mm³ for g·mm²).
    """

    volume: float
    center: npt.NDArray[np.float64]
    inertia: npt.NDArray[np.float64]


def mass_properties(mesh: MeshData) -> MassProperties:
    """Volume, centre and inertia tensor of the solid a closed, outward-facing mesh bounds.

    Each triangle spans a signed tetrahedron with a reference point (the box
    centre, for well-conditioned sums); the tetrahedra's volumes, first and
    second moments add up to the solid's.
    """
    v = np.asarray(mesh.vertices, dtype=np.float64)
    t = np.asarray(mesh.triangles, dtype=np.int64)
    lo, hi = v.min(axis=0), v.max(axis=0)
    ref = (lo + hi) / 2.0
    a, b, c = (v[t[:, k]] - ref for k in range(3))
    det = np.einsum("ij,ij->i", a, np.cross(b, c))  # six times the signed volume
    volume = float(det.sum() / 6.0)
    s = a + b + c
    first = (det[:, None] * s).sum(axis=0) / 24.0
    # ∫ x xᵀ dV over a tetrahedron (0, a, b, c) = det/120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ).
    second = np.einsum("i,ij,ik->jk", det, a, a) + np.einsum("i,ij,ik->jk", det, b, b)
    second += np.einsum("i,ij,ik->jk", det, c, c) + np.einsum("i,ij,ik->jk", det, s, s)
    second /= 120.0
    d = first / volume
    about_center = second - volume * np.outer(d, d)
    inertia = np.trace(about_center) * np.eye(3) - about_center
    return MassProperties(volume, ref + d, (inertia + inertia.T) / 2.0)


def surface_areas(mesh: MeshData) -> tuple[float, float]:
    """Mesh area facing up or down (within 45° of vertical normals) and the rest, mm²."""
    v = np.asarray(mesh.vertices, dtype=np.float64)
    t = np.asarray(mesh.triangles, dtype=np.int64)
    n = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    area = np.linalg.norm(n, axis=1) / 2.0
    flat = np.abs(n[:, 2]) * np.sqrt(2.0) > np.linalg.norm(n, axis=1)
    return float(area[flat].sum()), float(area[~flat].sum())


def overhang_area(mesh: MeshData) -> tuple[float, float | None]:
    """Downward faces above the bed that a slicer supports, mm², and the height of the lowest, mm (None: none).

    A face overhangs when it leans more than 45° from vertical towards the bed and
    is not on the bed itself.  A voxel print's only such faces are the horizontal
    ledges under each voxel step, so a shape needs no support exactly when every
    layer stands within the layer below it.
    """
    v = np.asarray(mesh.vertices, dtype=np.float64)
    t = np.asarray(mesh.triangles, dtype=np.int64)
    if not len(t):
        return 0.0, None
    n = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    length = np.linalg.norm(n, axis=1)
    low = v[t][:, :, 2].min(axis=1)
    bed = float(v[:, 2].min())
    down = (-n[:, 2] * np.sqrt(2.0) > length) & (low > bed + 1e-6)
    if not down.any():
        return 0.0, None
    return float(length[down].sum() / 2.0), float(low[down].min() - bed)


@dataclasses.dataclass(frozen=True)
class PrintEstimate:
    """Filament and time a print takes under a :class:`PrintProfile`.

    Attributes
    ----------
    infill : float
        Sparse infill assumed, percent.
    filament_mm3 : float
        Extruded plastic, mm³.
    mass_g : float
        Its mass in PLA.
    time_s : float
        Print time, seconds.
    """

    infill: float
    filament_mm3: float
    mass_g: float
    time_s: float


def estimate_print(mesh: MeshData, volume: float, *, infill: float = DEFAULT_INFILL,
                   profile: PrintProfile = DEFAULT_PROFILE) -> PrintEstimate:
    """Estimate the filament and the time of a print: walls and solid skins at full density, infill inside.

    The walls are the side area times the perimeters' thickness, the skins the
    up- and down-facing area times the solid layers' thickness; what is left of
    the volume is infill.  Each part prints at its own speed, and every layer
    adds a fixed overhead.
    """
    flat, side = surface_areas(mesh)
    wall = min(side * profile.perimeters * profile.extrusion_width, volume)
    skin = min(flat * profile.solid_layers * profile.layer_height, volume - wall)
    sparse = (volume - wall - skin) * infill / 100.0
    filament = wall + skin + sparse
    bead = profile.bead_area * profile.speed_efficiency
    outer = wall / profile.perimeters  # the outermost loop prints at the external perimeter speed
    seconds = (outer / (bead * profile.external_perimeter_speed)
               + (wall - outer) / (bead * profile.perimeter_speed)
               + skin / (bead * profile.solid_infill_speed)
               + sparse / (bead * profile.infill_speed))
    bounds = mesh.bounds()
    layers = int(np.ceil((bounds[1, 2] - bounds[0, 2]) / profile.layer_height))
    seconds += layers * profile.layer_overhead
    return PrintEstimate(float(infill), float(filament), float(filament * PLA_DENSITY / 1000.0), float(seconds))


def format_duration(seconds: float) -> str:
    """``"1 h 05 min"`` or ``"42 min"``, as slicers show a print time."""
    minutes = int(round(seconds / 60.0))
    return f"{minutes // 60} h {minutes % 60:02d} min" if minutes >= 60 else f"{minutes} min"


@dataclasses.dataclass(frozen=True)
class SpinReport:
    """How a print spins as a top standing on its lowest point, spin axis vertical.

    Attributes
    ----------
    tip : (3,) float ndarray
        Centre of the lowest contact patch, mm.
    tip_width : float
        Largest horizontal extent of the lowest patch, mm.
    tip_patches : int
        Separate lowest patches (one for a top).
    axis_offset : float
        Distance from the centre of mass to the vertical axis through the tip, mm.
    height : float
        Height of the centre of mass over the tip, mm.
    moment_ratio : float
        Moment about the spin axis over the smaller transverse moment, both about the tip.
    center_ratio : float
        The same ratio about the centre of mass: under 1 the top is taller than wide
        in its mass, and spinning about its axis of least moment it turns over.
    sleep_rpm : float
        Slowest spin at which the top stands upright (the "sleeping" top):
        ω² = 4 m g h I_transverse / I_spin², with the moments about the tip.
    warnings : tuple of str
        Why the top would wobble or fall, one line each.
    """

    tip: npt.NDArray[np.float64]
    tip_width: float
    tip_patches: int
    axis_offset: float
    height: float
    moment_ratio: float
    center_ratio: float
    sleep_rpm: float
    warnings: tuple[str, ...]


def spin_report(mesh: MeshData, props: MassProperties, *, pitch: float) -> SpinReport:
    """Check a print as a spinning top: a single lowest tip, the centre of mass over it, wide in its mass.

    A voxel tip is one voxel face, so a tip is single when the faces at the
    lowest height form one patch no wider than one voxel (``pitch``).
    """
    from ._data import shell_labels

    v = np.asarray(mesh.vertices, dtype=np.float64)
    t = np.asarray(mesh.triangles, dtype=np.int64)
    z0 = float(v[:, 2].min())
    eps = 1e-6 * max(float(np.ptp(v, axis=0).max()), 1.0)
    low = t[(np.abs(v[t, 2] - z0) <= eps).all(axis=1)]
    if low.size:
        # Patches: the lowest triangles joined where they share a corner position (split
        # vertices at an edge contact have one position and two indices).
        keys, inverse = np.unique(np.round(v[low.ravel(), :2] / eps).astype(np.int64), axis=0, return_inverse=True)
        _, patches = shell_labels(inverse.reshape(-1, 3).astype(np.int64), len(keys))
        pts = v[low.ravel()]
    else:  # the mesh ends in a point or an edge
        pts = v[np.abs(v[:, 2] - z0) <= eps]
        patches = 1
    tip = np.array([*(pts[:, :2].min(axis=0) + pts[:, :2].max(axis=0)) / 2.0, z0])
    width = float(np.ptp(pts[:, :2], axis=0).max())
    r = props.center - tip
    offset = float(np.hypot(r[0], r[1]))
    about_tip = props.inertia + props.volume * (np.dot(r, r) * np.eye(3) - np.outer(r, r))
    transverse = float(np.linalg.eigvalsh(about_tip[:2, :2]).min())
    ratio = float(about_tip[2, 2] / transverse)
    center_ratio = float(props.inertia[2, 2] / np.linalg.eigvalsh(props.inertia[:2, :2]).min())
    # Per unit density: the density cancels in m h I_t / I_s².
    omega2 = 4.0 * props.volume * GRAVITY * max(float(r[2]), 0.0) * transverse / about_tip[2, 2] ** 2
    sleep_rpm = float(np.sqrt(omega2) * 60.0 / (2.0 * np.pi))
    warnings = []
    if patches != 1 or width > pitch * (1 + 1e-6):
        warnings.append(f"spin: the lowest point is not a single tip ({patches} patch(es) {width:.3g} mm wide "
                        f"at the bottom); the top stands on it instead of spinning on a point")
    if offset > SPIN_AXIS_TOLERANCE:
        warnings.append(f"spin: the centre of mass is {offset:.3g} mm off the axis through the tip "
                        f"(more than {SPIN_AXIS_TOLERANCE:g} mm); the top wobbles")
    if center_ratio < 1.0:
        warnings.append(f"spin: the spin-axis moment is {center_ratio:.3g} x the transverse moment about the "
                        "centre of mass (under 1: taller than wide in its mass); the top turns over")
    return SpinReport(tip, width, int(patches), offset, float(r[2]), ratio, center_ratio, sleep_rpm,
                      tuple(warnings))
