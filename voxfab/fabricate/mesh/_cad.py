"""CAD booleans through manifold3d: bridges, base plate, magnet pocket, engraved label.

manifold3d accepts some non-manifold meshes without complaint and then corrupts
them, so only meshes that passed :func:`check_mesh` are handed to it, and what
comes back is checked again by the caller.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.errors import FabricationError, MissingDependencyError

from ._data import MeshData, parts_from_shells

#: Chord tolerance of glyph outlines, as a fraction of the text height.
_GLYPH_TOLERANCE = 0.01


def _m3d() -> Any:
    try:
        import manifold3d
    except ImportError as exc:  # pragma: no cover - a declared dependency
        raise MissingDependencyError("manifold3d", "CAD booleans on meshes") from exc
    return manifold3d


def to_manifold(mesh: MeshData) -> Any:
    """A manifold3d solid from a checked mesh (positions kept in float64)."""
    return _manifold(mesh, {})


def to_manifold_traced(mesh: MeshData, faces: npt.NDArray[np.integer]) -> tuple[Any, int]:
    """A manifold3d solid whose triangles keep an id (a colour) through every boolean.

    ``faces`` is a non-negative id per triangle: ``simplify`` never merges
    triangles of different ids, and :func:`from_manifold_traced` gives them back.
    Returns the solid and its own mesh id, which tells its triangles from those
    of the solids combined with it.
    """
    m3d = _m3d()
    source = int(m3d.Manifold.reserve_ids(1))
    extra = {"face_id": np.array(faces, dtype=np.uint64, order="C"),
             "run_index": np.array([0, 3 * len(mesh.triangles)], dtype=np.uint64),
             "run_original_id": np.array([source], dtype=np.uint32)}
    return _manifold(mesh, extra), source


def _manifold(mesh: MeshData, extra: dict[str, Any]) -> Any:
    m3d = _m3d()
    mm = m3d.Mesh64(
        vert_properties=np.array(mesh.vertices, dtype=np.float64, order="C"),
        tri_verts=np.array(mesh.triangles, dtype=np.uint64, order="C"),
        **extra,
    )
    solid = m3d.Manifold(mm)
    if solid.status() != m3d.Error.NoError:
        raise FabricationError(f"manifold3d refused the checked mesh: {solid.status()}")
    return solid


def _mesh_out(solid: Any) -> tuple[Any, MeshData]:
    """manifold3d's mesh of ``solid`` after ``simplify``, and it as a :class:`MeshData`.

    Booleans of touching boxes can leave zero-area slivers; ``simplify`` with a
    1 nm tolerance collapses them (and merges coplanar triangles) without
    moving any surface measurably.
    """
    out = solid.simplify(1e-6).to_mesh64()
    v = np.asarray(out.vert_properties, dtype=np.float64)[:, :3]
    t = np.asarray(out.tri_verts, dtype=np.int64)
    if t.size == 0:
        raise FabricationError("the CAD operations left nothing of the shape")
    # Drop vertices no triangle uses, keeping the order.
    used = np.zeros(v.shape[0], dtype=bool)
    used[t.ravel()] = True
    remap = np.cumsum(used) - 1
    v, t = v[used], remap[t]
    return out, MeshData(vertices=v, triangles=t, part=parts_from_shells(v, t))


def from_manifold(solid: Any) -> MeshData:
    """Back to a :class:`MeshData`, parts found from shells."""
    return _mesh_out(solid)[1]


def from_manifold_traced(solid: Any, source: int) -> tuple[MeshData, npt.NDArray[np.int64]]:
    """Back to a :class:`MeshData`, with the face id of each triangle that came from the solid
    ``source`` (see :func:`to_manifold_traced`) and -1 for the others."""
    out, mesh = _mesh_out(solid)
    faces = np.asarray(out.face_id, dtype=np.int64).copy()
    runs = np.asarray(out.run_index, dtype=np.int64)
    ids = np.asarray(out.run_original_id, dtype=np.int64)
    owner = np.repeat(ids, np.diff(runs) // 3)  # run_index counts triangle vertices
    faces[owner != source] = -1
    return mesh, faces


def box_solids(boxes: npt.NDArray[np.float64]) -> list[Any]:
    """One manifold3d cube per ``(2, 3)`` min/max box."""
    m3d = _m3d()
    return [m3d.Manifold.cube(tuple(map(float, hi - lo))).translate(tuple(map(float, lo))) for lo, hi in boxes]


def union(solids: list[Any]) -> Any:
    """Union of several solids in one batch."""
    m3d = _m3d()
    if len(solids) == 1:
        return solids[0]
    return m3d.Manifold.batch_boolean(solids, m3d.OpType.Add)


def subtract(solid: Any, cutters: list[Any]) -> Any:
    """``solid`` minus the union of ``cutters``."""
    m3d = _m3d()
    if not cutters:
        return solid
    return m3d.Manifold.batch_boolean([solid, *cutters], m3d.OpType.Subtract)


def cylinder(centre: tuple[float, float], z0: float, z1: float, diameter: float) -> Any:
    """A vertical cylinder from ``z0`` to ``z1`` (mm) with 64 sides."""
    m3d = _m3d()
    c = m3d.Manifold.cylinder(z1 - z0, diameter / 2.0, diameter / 2.0, 64)
    return c.translate((centre[0], centre[1], z0))


def text_outlines(text: str, *, height: float) -> list[npt.NDArray[np.float64]]:
    """Closed glyph outlines of ``text``, ``height`` mm tall, centred on the origin.

    Returns
    -------
    list of (N, 2) float64 ndarray
        Outer and inner loops; fill them with the even-odd rule.
    """
    from voxfab._shared.deps import require_extra

    require_extra("cad", "an engraved label (--label)")
    import build123d as bd  # lazy: ~4 s to import
    sketch = bd.Text(text, font_size=height, align=(bd.Align.CENTER, bd.Align.CENTER))
    loops: list[npt.NDArray[np.float64]] = []
    tol = _GLYPH_TOLERANCE * height
    for face in sketch.faces():
        for wire in [face.outer_wire(), *face.inner_wires()]:
            pieces = []
            for edge in wire.order_edges():
                ps = edge.positions(deflection=tol) if edge.geom_type != bd.GeomType.LINE else [
                    edge.position_at(0.0), edge.position_at(1.0)]
                pieces.append(np.array([(float(p.X), float(p.Y)) for p in ps]))
            pts = _chain(pieces)
            loop = pts
            if len(loop) > 1 and np.allclose(loop[0], loop[-1]):
                loop = loop[:-1]
            if len(loop) >= 3:
                loops.append(loop)
    if not loops:
        raise FabricationError(f"label {text!r}: the font has no outlines for this text")
    return loops


def _chain(pieces: list[npt.NDArray[np.float64]]) -> npt.NDArray[np.float64]:
    """Join polyline pieces of a closed loop end to end, flipping those that run backwards."""
    if len(pieces) == 1:
        return pieces[0]
    first, second = pieces[0], pieces[1]
    ends = np.array([second[0], second[-1]])
    # Orient the first piece so that it ends where the second piece has an end.
    if np.linalg.norm(ends - first[0], axis=1).min() < np.linalg.norm(ends - first[-1], axis=1).min():
        first = first[::-1]
    out = [first]
    for piece in pieces[1:]:
        tail = out[-1][-1]
        if np.linalg.norm(piece[-1] - tail) < np.linalg.norm(piece[0] - tail):
            piece = piece[::-1]
        out.append(piece[1:])
    return np.concatenate(out)


def label_cutter(
    text: str, *, centre: tuple[float, float], box: tuple[float, float], z_bottom: float, depth: float
) -> tuple[Any, float]:
    """A solid that engraves ``text`` into the bottom face, mirrored to read from below.

    The text is scaled to fit ``box`` (width, height in mm) and centred on
    ``centre``; the cutter reaches from 1 mm below ``z_bottom`` to ``depth`` above it.

    Returns
    -------
    cutter, letter_height
        The manifold3d solid and the resulting cap height in mm.
    """
    m3d = _m3d()
    probe = text_outlines(text, height=10.0)
    pts = np.concatenate(probe)
    size = pts.max(axis=0) - pts.min(axis=0)
    scale = min(box[0] / max(size[0], 1e-9), box[1] / max(size[1], 1e-9))
    loops = [np.column_stack([-(lp[:, 0] - (pts[:, 0].max() + pts[:, 0].min()) / 2), lp[:, 1] - (pts[:, 1].max() + pts[:, 1].min()) / 2]) * scale
             for lp in probe]
    section = m3d.CrossSection([lp + np.array(centre) for lp in loops], m3d.FillRule.EvenOdd)
    cutter = m3d.Manifold.extrude(section, depth + 1.0).translate((0.0, 0.0, z_bottom - 1.0))
    return cutter, float(size[1] * scale)
