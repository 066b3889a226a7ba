"""The construction as assembled: one solid per plate, in the print mesh's frame, written as 3MF.

Every plate is its outline (slots, voxel and dowel holes cut) extruded by its
thickness with manifold3d and moved to where it sits in the assembly: origin
at the shape's minimum corner, z up, millimetres, as ``mesh.3mf``.  Objects
are named by the plates' labels.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike

from ._outline import _TRANSPOSE, axis_value
from ._slotted import SlottedPlate
from ._stack import Plate

__all__ = ["assembly_3mf", "plate_frame", "plate_solid_mesh", "write_assembly_3mf"]


def plate_frame(plate: Plate, axis: str = "z") -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64],
                                                        npt.NDArray[np.float64], float]:
    """``origin``, ``U``, ``V`` and the start of the thickness along ``U × V`` of a plate in the assembly.

    A stacked plate's ``(u, v)`` frame is the stack's (see :mod:`._outline`),
    its bottom face at ``plate.z`` along the stack ``axis``; a slotted plate is
    centred on its plane.
    """
    if isinstance(plate, SlottedPlate):
        return (np.asarray(plate.origin, dtype=np.float64), np.asarray(plate.u_dir, dtype=np.float64),
                np.asarray(plate.v_dir, dtype=np.float64), -plate.thickness / 2)
    w, u, v = _TRANSPOSE[axis_value(axis)]
    eye = np.eye(3)
    return eye[w] * plate.z, eye[u], eye[v], 0.0


def plate_solid_mesh(plate: Plate, axis: str = "z") -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """Vertices (mm, assembly frame) and outward triangles of one plate's solid."""
    import manifold3d

    polygon = plate.polygon()
    rings = [np.asarray(polygon.exterior.coords)[:-1]] + [np.asarray(r.coords)[:-1] for r in polygon.interiors]
    section = manifold3d.CrossSection([r.astype(np.float64) for r in rings], manifold3d.FillRule.EvenOdd)
    mesh = section.extrude(plate.thickness).to_mesh64()
    local = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(mesh.tri_verts, dtype=np.int64)
    origin, u_dir, v_dir, start = plate_frame(plate, axis)
    normal = np.cross(u_dir, v_dir)
    # U, V, U × V is right-handed, so outward triangles stay outward
    world = origin + local[:, :1] * u_dir + local[:, 1:2] * v_dir + (local[:, 2:3] + start) * normal
    return world, tris


def assembly_3mf(plates: tuple[Plate, ...], *, axis: str = "z", name: str = "") -> bytes:
    """The 3MF package of the assembled plates: one object per plate, named by its label."""
    from voxfab.fabricate.mesh.formats.threemf import objects_xml, package_bytes

    def objects():  # noqa: ANN202 - a generator of (name, vertices, triangles)
        for plate in plates:
            v, t = plate_solid_mesh(plate, axis)
            # -0.0 and 0.0 print differently: add 0.0 so equal plates give equal bytes
            yield plate.label.text, np.round(v, 6) + 0.0, t

    return package_bytes(objects_xml(objects(), title=name or "plates"))


def write_assembly_3mf(plates: tuple[Plate, ...], path: PathLike, *, axis: str = "z", name: str = "") -> None:
    """Write :func:`assembly_3mf` to ``path`` (atomically)."""
    write_bytes(path, assembly_3mf(plates, axis=axis, name=name))
