"""The construction as assembled: one solid per plate, in the print mesh's frame, written as 3MF.

Every plate is its outline (slots, voxel and dowel holes cut) extruded by its
thickness with manifold3d and moved to where it sits in the assembly: origin
at the shape's minimum corner, z up, millimetres, as ``mesh.3mf``.  Objects
are named by the plates' labels.
"""

from __future__ import annotations

import io
import zipfile
from xml.sax.saxutils import escape, quoteattr

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
    from voxfab.fabricate.mesh.formats._text import format_rows
    from voxfab.fabricate.mesh.formats.threemf import _CONTENT_TYPES, _DATE, _NS, _RELS

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="millimeter" xml:lang="en-US" xmlns="{_NS}">\n',
        f'<metadata name="Title">{escape(name or "plates")}</metadata>\n',
        '<metadata name="Application">voxfab</metadata>\n',
        "<resources>\n",
    ]
    for i, plate in enumerate(plates, start=1):
        v, t = plate_solid_mesh(plate, axis)
        # -0.0 and 0.0 print differently: add 0.0 so equal plates give equal bytes
        v = np.round(v, 6) + 0.0
        out.append(f'<object id="{i}" type="model" name={quoteattr(plate.label.text)}>\n<mesh>\n<vertices>\n')
        out.append(format_rows(v, '<vertex x="%.9g" y="%.9g" z="%.9g"/>\n'))
        out.append("</vertices>\n<triangles>\n")
        out.append(format_rows(t, '<triangle v1="%d" v2="%d" v3="%d"/>\n'))
        out.append("</triangles>\n</mesh>\n</object>\n")
    out.append("</resources>\n<build>\n")
    out.extend(f'<item objectid="{i}"/>\n' for i in range(1, len(plates) + 1))
    out.append("</build>\n</model>\n")
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for arcname, text in (("[Content_Types].xml", _CONTENT_TYPES), ("_rels/.rels", _RELS),
                              ("3D/3dmodel.model", "".join(out))):
            info = zipfile.ZipInfo(arcname, date_time=_DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, text.encode("utf-8"), compresslevel=6)
    return buf.getvalue()


def write_assembly_3mf(plates: tuple[Plate, ...], path: PathLike, *, axis: str = "z", name: str = "") -> None:
    """Write :func:`assembly_3mf` to ``path`` (atomically)."""
    write_bytes(path, assembly_3mf(plates, axis=axis, name=name))
