"""3MF (3D Manufacturing Format) core: a zip package with one object per part, in mm.

The package holds ``[Content_Types].xml``, ``_rels/.rels`` and
``3D/3dmodel.model``.  Zip entries carry a fixed date, so the same mesh gives
the same bytes.
"""

from __future__ import annotations

import io
import zipfile
from collections.abc import Iterable
from xml.etree import ElementTree as ET
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError

from .._data import MeshData
from ._text import format_rows

EXTENSION = ".3mf"
DESCRIPTION = "print-ready solid for a 3D printer slicer (3MF, mm)"

_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    "</Types>\n"
)
_RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
    "</Relationships>\n"
)
_DATE = (1980, 1, 1, 0, 0, 0)


def objects_xml(objects: Iterable[tuple[str, np.ndarray, np.ndarray]], *, title: str) -> str:
    """A ``3D/3dmodel.model`` document of named objects, each ``(name, vertices mm, triangles)``."""
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="millimeter" xml:lang="en-US" xmlns="{_NS}">\n',
        f'<metadata name="Title">{escape(title)}</metadata>\n',
        '<metadata name="Application">voxfab</metadata>\n',
        "<resources>\n",
    ]
    count = 0
    for count, (obj_name, v, t) in enumerate(objects, start=1):
        out.append(f'<object id="{count}" type="model" name={quoteattr(obj_name)}>\n<mesh>\n<vertices>\n')
        out.append(format_rows(v, '<vertex x="%.9g" y="%.9g" z="%.9g"/>\n'))
        out.append("</vertices>\n<triangles>\n")
        out.append(format_rows(t, '<triangle v1="%d" v2="%d" v3="%d"/>\n'))
        out.append("</triangles>\n</mesh>\n</object>\n")
    out.append("</resources>\n<build>\n")
    out.extend(f'<item objectid="{i}"/>\n' for i in range(1, count + 1))
    out.append("</build>\n</model>\n")
    return "".join(out)


def model_xml(mesh: MeshData, *, name: str) -> str:
    """The ``3D/3dmodel.model`` document: one object per part."""
    n = mesh.part_count
    parts = ((name if n == 1 else f"{name} part {p + 1}", *mesh.part_mesh(p)) for p in range(n))
    return objects_xml(parts, title=name)


def package_bytes(model: str) -> bytes:
    """The 3MF package around a model document (fixed dates: the same model gives the same bytes)."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for arcname, text in (
            ("[Content_Types].xml", _CONTENT_TYPES),
            ("_rels/.rels", _RELS),
            ("3D/3dmodel.model", model),
        ):
            info = zipfile.ZipInfo(arcname, date_time=_DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, text.encode("utf-8"), compresslevel=6)
    return buf.getvalue()


def to_bytes(mesh: MeshData, *, name: str) -> bytes:
    """The 3MF package as bytes (byte-identical for the same mesh and name)."""
    return package_bytes(model_xml(mesh, name=name))


def read(path: PathLike) -> MeshData:
    """Read the objects of a 3MF file; each object becomes a part."""
    try:
        with zipfile.ZipFile(path) as z:
            names = set(z.namelist())
            for required in ("[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"):
                if required not in names:
                    raise FormatError(f"{path}: not a 3MF package (missing {required})")
            root = ET.fromstring(z.read("3D/3dmodel.model"))
    except (zipfile.BadZipFile, ET.ParseError) as exc:
        raise FormatError(f"{path}: not a readable 3MF file ({exc})") from exc
    unit = root.get("unit", "millimeter")
    if unit != "millimeter":
        raise FormatError(f"{path}: unit {unit!r}, expected millimeter")
    ns = {"m": _NS}
    verts, tris, parts = [], [], []
    base = 0
    for p, obj in enumerate(root.findall("m:resources/m:object", ns)):
        vs = np.array(
            [[float(e.get("x")), float(e.get("y")), float(e.get("z"))] for e in obj.findall("m:mesh/m:vertices/m:vertex", ns)]
        ).reshape(-1, 3)
        ts = np.array(
            [[int(e.get("v1")), int(e.get("v2")), int(e.get("v3"))] for e in obj.findall("m:mesh/m:triangles/m:triangle", ns)]
        ).reshape(-1, 3)
        verts.append(vs)
        tris.append(ts + base)
        parts.append(np.full(len(ts), p))
        base += len(vs)
    if not tris:
        raise FormatError(f"{path}: the 3MF file holds no object")
    return MeshData(vertices=np.concatenate(verts), triangles=np.concatenate(tris), part=np.concatenate(parts))
