"""Cameras: the isometric view, the six axis views, the profile view and turntable positions.

A camera is an orthonormal frame ``(right, up, toward)`` in world coordinates
(voxel units, z up): ``right`` and ``up`` span the picture, ``toward`` points from
the shape to the viewer, and ``right × up = toward`` so pictures are never
mirrored.  Axis views are named after the side the viewer stands on: ``"z"``
looks down from +z, ``"-y"`` is the front view.  The profile view
(:func:`profile_camera`) is the one chosen from the shape itself.
"""

from __future__ import annotations

import dataclasses
import math
from enum import StrEnum

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import check_choice
from voxfab.errors import InvalidShapeError

__all__ = ["View", "Camera", "camera_for", "orbit_camera", "profile_camera", "ISO_AZIMUTH", "ISO_ELEVATION"]


class View(StrEnum):
    """Named views accepted by :func:`voxfab.render.render`."""

    ISO = "iso"
    X = "x"
    NEG_X = "-x"
    Y = "y"
    NEG_Y = "-y"
    Z = "z"
    NEG_Z = "-z"
    PROFILE = "profile"  # chosen from the shape: see profile_camera


#: Azimuth (degrees from +x, counter-clockwise seen from above) of the isometric viewer.
ISO_AZIMUTH = -45.0
#: Elevation (degrees) of the isometric viewer: the cube diagonal points at it.
ISO_ELEVATION = math.degrees(math.atan(1.0 / math.sqrt(2.0)))


@dataclasses.dataclass(frozen=True, eq=False)
class Camera:
    """An orthographic camera frame.

    Attributes
    ----------
    right, up, toward : (3,) float64 ndarray
        Orthonormal, with ``right × up = toward``; ``toward`` points at the viewer.
    axis_aligned : bool
        True for the six axis views, where voxel faces map to whole pixels.
    """

    right: npt.NDArray[np.float64]
    up: npt.NDArray[np.float64]
    toward: npt.NDArray[np.float64]
    axis_aligned: bool = False

    @property
    def matrix(self) -> npt.NDArray[np.float64]:
        """``(3, 3)`` rows ``right, up, toward``: world → camera coordinates."""
        return np.stack([self.right, self.up, self.toward])


def _axis_camera(right: tuple[int, int, int], up: tuple[int, int, int]) -> Camera:
    r = np.array(right, dtype=np.float64)
    u = np.array(up, dtype=np.float64)
    return Camera(right=r, up=u, toward=np.cross(r, u), axis_aligned=True)


_AXIS_CAMERAS: dict[View, Camera] = {
    View.X: _axis_camera((0, 1, 0), (0, 0, 1)),
    View.NEG_X: _axis_camera((0, -1, 0), (0, 0, 1)),
    View.Y: _axis_camera((-1, 0, 0), (0, 0, 1)),
    View.NEG_Y: _axis_camera((1, 0, 0), (0, 0, 1)),
    View.Z: _axis_camera((1, 0, 0), (0, 1, 0)),
    View.NEG_Z: _axis_camera((1, 0, 0), (0, -1, 0)),
}


def orbit_camera(azimuth: float, elevation: float) -> Camera:
    """Return the camera of a viewer at ``azimuth``/``elevation`` degrees, z up.

    Parameters
    ----------
    azimuth : float
        Degrees from +x, counter-clockwise seen from above.
    elevation : float
        Degrees above the xy plane, strictly between -90 and 90.
    """
    a, e = math.radians(azimuth), math.radians(elevation)
    toward = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    z = np.array([0.0, 0.0, 1.0])
    up = z - toward * float(z @ toward)
    up /= np.linalg.norm(up)
    right = np.cross(up, toward)
    return Camera(right=right, up=up, toward=toward, axis_aligned=False)


def camera_for(view: str | View, grid: npt.ArrayLike | None = None) -> Camera:
    """Return the camera of a named view (``"iso"``, ``"x"``, ``"-x"``, ..., ``"-z"``, ``"profile"``).

    ``"profile"`` is chosen from the shape: it needs ``grid``, the ``[x, y, z]`` voxels.
    """
    v = check_choice(view, View, name="view")
    if v is View.PROFILE:
        if grid is None:
            raise InvalidShapeError("view: 'profile' is chosen from a shape's voxels; this picture has none")
        return profile_camera(grid)
    if v is View.ISO:
        return orbit_camera(ISO_AZIMUTH, ISO_ELEVATION)
    return _AXIS_CAMERAS[v]


#: How much longer one side silhouette's outline must be than the other's for the profile view to turn
#: towards it; below, the sides say the same (a piece turned on a lathe) and the view stays isometric.
PROFILE_MARGIN = 1.15
#: The profile view: degrees off the side it faces (towards the isometric view, so the picture keeps its
#: depth), and its elevation, lower than the isometric view's so the outline stands against the paper.
PROFILE_TURN = 25.0
PROFILE_ELEVATION = 20.0


def outline_length(silhouette: npt.ArrayLike) -> int:
    """Edges between filled and empty cells of a 2D silhouette, its border included: how much its outline says."""
    m = np.pad(np.asarray(silhouette, dtype=bool), 1)
    return int((m[1:] != m[:-1]).sum() + (m[:, 1:] != m[:, :-1]).sum())


def profile_camera(grid: npt.ArrayLike) -> Camera:
    """The camera that shows a shape's profile: turned towards the side whose silhouette says the most.

    A piece is pictured standing (z up), seen from the side its outline has the most to say from: of
    the silhouettes seen along x and along y, the one with the longer outline (a knight's head, ears
    and mane seen along x; its narrow block seen along y).  The camera faces that side
    :data:`PROFILE_TURN` degrees off it, from the side the isometric view sees (+x or -y).  When
    neither outline is :data:`PROFILE_MARGIN` times the other's, the view is isometric.
    """
    g = np.asarray(grid, dtype=bool)
    along_x, along_y = outline_length(g.any(axis=0)), outline_length(g.any(axis=1))
    if max(along_x, along_y) < PROFILE_MARGIN * min(along_x, along_y):
        return orbit_camera(ISO_AZIMUTH, ISO_ELEVATION)
    # Azimuth 0 faces +x, -90 faces -y; the isometric viewer stands between them at -45.
    azimuth = -PROFILE_TURN if along_x > along_y else -90.0 + PROFILE_TURN
    return orbit_camera(azimuth, PROFILE_ELEVATION)
