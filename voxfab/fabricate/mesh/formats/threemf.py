"""3MF (3D Manufacturing Format) core: a zip package with one object per part, in mm.

The package holds ``[Content_Types].xml``, ``_rels/.rels`` and
``3D/3dmodel.model``.  Zip entries carry a fixed date, so the same mesh gives
the same bytes.

A coloured mesh says each triangle's colour three ways, one for each kind of reader:

* the core spec's materials: a ``<basematerials>`` resource with one ``<base>``
  per filament (its ``displaycolor``), each object's default ``pid``/``pindex``
  and each triangle's ``pid``/``p1``;
* PrusaSlicer's painting, ``slic3rpe:mmu_segmentation`` on each triangle (it
  reads no base materials): the triangle painted whole with extruder ``e``;
* Bambu Studio's and OrcaSlicer's ``paint_color``, the same code.

Filament ``k`` of the mesh's palette is extruder ``k + 1``.
"""

from __future__ import annotations

import io
import zipfile
from collections.abc import Iterable, Sequence
from xml.etree import ElementTree as ET
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError, VoxfabError

from .._data import MeshData
from ._text import format_rows

EXTENSION = ".3mf"
DESCRIPTION = "print-ready solid for a 3D printer slicer (3MF, mm)"

_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
#: PrusaSlicer's namespace (its painting attribute, ``mmu_segmentation``).
SLIC3RPE_NS = "http://schemas.slic3r.org/3mf/2017/06"
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


def paint_code(extruder: int) -> str:
    """PrusaSlicer's (and Bambu Studio's) code for a triangle painted whole with ``extruder`` (1-based).

    PrusaSlicer writes a painted triangle as a bit string, four bits a hex digit,
    the digits in reverse order: two bits for how the triangle is split (0: not
    at all), then the state in two bits when it is 1 or 2, otherwise ``11``
    followed by the state minus 3 in four bits.  The state is the extruder, so
    extruder 1 is ``4``, 2 is ``8``, 3 is ``0C``, 4 is ``1C`` ... 16 is ``DC``.
    """
    if not 1 <= extruder <= 16:
        raise ValueError(f"extruder {extruder}: expected 1 to 16")
    if extruder < 3:
        return f"{extruder << 2:X}"
    return f"{extruder - 3:X}C"


def objects_xml(
    objects: Iterable[tuple[str, np.ndarray, np.ndarray] | tuple[str, np.ndarray, np.ndarray, np.ndarray]], *,
    title: str, materials: Sequence[tuple[str, str]] = (),
) -> str:
    """A ``3D/3dmodel.model`` document of named objects, each ``(name, vertices mm, triangles)``.

    With ``materials`` (``(name, "#rrggbb")`` per filament), each object is
    ``(name, vertices, triangles, filament of each triangle)`` and the triangles
    carry their colour (see the module's text).
    """
    coloured = bool(materials)
    ns = f' xmlns:slic3rpe="{SLIC3RPE_NS}"' if coloured else ""
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="millimeter" xml:lang="en-US" xmlns="{_NS}"{ns}>\n',
        f'<metadata name="Title">{escape(title)}</metadata>\n',
        '<metadata name="Application">voxfab</metadata>\n',
        "<resources>\n",
    ]
    first = 1
    if coloured:
        out.append('<basematerials id="1">\n')
        out.extend(f'<base name={quoteattr(n)} displaycolor="{c.upper()}"/>\n' for n, c in materials)
        out.append("</basematerials>\n")
        first = 2
        # What follows the vertices of a triangle of filament k: its material, and its painting twice.
        tails = [f' pid="1" p1="{k}" slic3rpe:mmu_segmentation="{code}" paint_color="{code}"/>\n'
                 for k, code in enumerate(paint_code(k + 1) for k in range(len(materials)))]
    count = 0
    for count, (obj_name, v, t, *rest) in enumerate(objects, start=first):
        if coloured:
            colour = np.asarray(rest[0], dtype=np.int64)
            default = int(np.argmax(np.bincount(colour, minlength=len(materials))))
            out.append(f'<object id="{count}" type="model" name={quoteattr(obj_name)} pid="1" pindex="{default}">\n')
        else:
            out.append(f'<object id="{count}" type="model" name={quoteattr(obj_name)}>\n')
        out.append("<mesh>\n<vertices>\n")
        out.append(format_rows(v, '<vertex x="%.9g" y="%.9g" z="%.9g"/>\n'))
        out.append("</vertices>\n<triangles>\n")
        if coloured:
            out.extend([f'<triangle v1="{a}" v2="{b}" v3="{c}"{tails[k]}' for (a, b, c), k in zip(t.tolist(), colour.tolist())])
        else:
            out.append(format_rows(t, '<triangle v1="%d" v2="%d" v3="%d"/>\n'))
        out.append("</triangles>\n</mesh>\n</object>\n")
    out.append("</resources>\n<build>\n")
    out.extend(f'<item objectid="{i}"/>\n' for i in range(first, count + 1))
    out.append("</build>\n</model>\n")
    return "".join(out)


def model_xml(mesh: MeshData, *, name: str) -> str:
    """The ``3D/3dmodel.model`` document: one object per part (in its filaments' colours when coloured)."""
    n = mesh.part_count
    names = [name if n == 1 else f"{name} part {p + 1}" for p in range(n)]
    if not mesh.coloured:
        return objects_xml(((names[p], *mesh.part_mesh(p)) for p in range(n)), title=name)
    from .._colours import colour_hexes, material_labels

    assert mesh.palette is not None and mesh.colour is not None
    materials = list(zip(material_labels(mesh.palette), colour_hexes(mesh.palette)))
    parts = ((names[p], *mesh.part_mesh(p), mesh.colour[mesh.part == p]) for p in range(n))
    return objects_xml(parts, title=name, materials=materials)


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
    # Base materials: (group id, index) -> a row of the palette.
    rows: dict[tuple[str, int], int] = {}
    palette: list[tuple[int, int, int, int]] = []
    from voxfab.shape import parse_colour

    for group in root.findall("m:resources/m:basematerials", ns):
        for i, base in enumerate(group.findall("m:base", ns)):
            rows[(group.get("id", ""), i)] = len(palette)
            try:
                palette.append(parse_colour(base.get("displaycolor", "")))
            except VoxfabError as exc:
                raise FormatError(f"{path}: bad displaycolor ({exc})") from None
    verts, tris, parts, colours = [], [], [], []
    base = 0
    for p, obj in enumerate(root.findall("m:resources/m:object", ns)):
        vs = np.array(
            [[float(e.get("x")), float(e.get("y")), float(e.get("z"))] for e in obj.findall("m:mesh/m:vertices/m:vertex", ns)]
        ).reshape(-1, 3)
        elements = obj.findall("m:mesh/m:triangles/m:triangle", ns)
        ts = np.array([[int(e.get("v1")), int(e.get("v2")), int(e.get("v3"))] for e in elements]).reshape(-1, 3)
        if rows:
            pid, pindex = obj.get("pid"), obj.get("pindex", "0")
            try:
                colours.append(np.array([rows[(e.get("pid", pid), int(e.get("p1", pindex)))] for e in elements],
                                        dtype=np.int64))
            except (KeyError, ValueError) as exc:
                raise FormatError(f"{path}: a triangle names a material that is not defined ({exc})") from None
        verts.append(vs)
        tris.append(ts + base)
        parts.append(np.full(len(ts), p))
        base += len(vs)
    if not tris:
        raise FormatError(f"{path}: the 3MF file holds no object")
    colour = np.concatenate(colours) if rows else None
    return MeshData(vertices=np.concatenate(verts), triangles=np.concatenate(tris), part=np.concatenate(parts),
                    colour=colour, palette=np.array(palette, dtype=np.uint8) if rows else None)
