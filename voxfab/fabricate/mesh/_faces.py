"""Triangle mesh from the exposed voxel faces, with coplanar faces merged.

Vertex ids split exactly like those of :func:`voxfab.shape.surface_graph`, so
voxels touching only along an edge or at a corner get separate vertices there.
The surface graph joins the corners at a lattice point only through the faces
around it, so the split at a point depends on its 8 cells alone: a table read
off the surface graph (:func:`fan_table`) gives it for each filling.

* **Rectangles.**  Faces of one plane and direction are grouped into rectangles:
  runs along one axis stacked along the other.  The work goes with the number of
  rectangles and the length of their borders, not with the number of faces, so a
  finely refined grid (bridges) costs about as much as the plain one.
* **No T-junctions.**  A vertex is kept when it is a rectangle corner anywhere in
  the mesh; every rectangle keeps each kept vertex on its border.  Two
  rectangles glued along a border see the same kept vertices on it (they share
  the vertex ids, and where one neighbour ends its corner is kept), so no vertex
  lies inside another triangle's edge.  Split vertices (several ids at one
  point) are always kept, so two border chains between the same end vertices
  never collapse into the same edge.
* **Contact segments.**  Where two voxels touch along an edge and both end
  points stay shared (the contact is closed around by other voxels at both ends),
  the four faces on that segment would use the same vertex pair.  Each of the
  two face pairs glued by the surface graph gets its own midpoint vertex there.
* **Triangulation without slivers of zero area.**  When extra border vertices
  lie on two opposite sides only (the common case), the rectangle is zipped
  between those sides: each triangle has two vertices on one side and one on
  the other (n - 2 triangles, a plain rectangle gives two).  Otherwise it is
  split into a star around a new centre vertex (n triangles).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid
from voxfab.shape import surface_graph
from voxfab.shape._surface import CORNER_OFFSETS, DIRECTIONS, EDGE_OUT

from ._contacts import Contacts, find_contacts
from ._data import MeshData

#: Corner offsets of each face direction in its plane coordinates (u, v), u along
#: axis (a+1)%3 and v along (a+2)%3 for a face normal to axis a.
_UV = np.stack([CORNER_OFFSETS[d][:, [((d // 2) + 1) % 3, ((d // 2) + 2) % 3]] for d in range(6)])


def _side_tables() -> tuple[npt.NDArray[np.int64], ...]:
    """For edge k of direction d: along-u flag, ascending flag, fixed side at max."""
    along_u = np.zeros((6, 4), dtype=bool)
    ascending = np.zeros((6, 4), dtype=bool)
    at_max = np.zeros((6, 4), dtype=bool)
    for d in range(6):
        for k in range(4):
            s, e = _UV[d, k], _UV[d, (k + 1) % 4]
            along_u[d, k] = s[1] == e[1]
            if along_u[d, k]:
                ascending[d, k] = e[0] > s[0]
                at_max[d, k] = s[1] == 1
            else:
                ascending[d, k] = e[1] > s[1]
                at_max[d, k] = s[0] == 1
    return along_u, ascending, at_max


_ALONG_U, _ASCENDING, _AT_MAX = _side_tables()


def fan_table() -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """The vertex split at a lattice point for each filling of its 2×2×2 cells.

    The surface graph joins the corners at a point only through faces around it,
    and its neighbour rule only looks at the four cells around an edge: so the
    vertices at a point depend on the 8 cells around it alone.  The table is read
    off :func:`voxfab.shape.surface_graph` of each of the 256 blocks.

    Returns
    -------
    fan : (256, 8, 6) int64 ndarray
        ``fan[config, cell, d]``: which vertex at the centre point (numbered by
        first appearance) the face ``d`` of ``cell`` uses; -1 when that face does
        not touch the point or is not exposed.  ``config`` has bit ``cell``
        set per filled cell, ``cell = 4 dx + 2 dy + dz``.
    count : (256,) int64 ndarray
        Number of vertices at the centre point.
    """
    fan = np.full((256, 8, 6), -1, dtype=np.int64)
    count = np.zeros(256, dtype=np.int64)
    for config in range(1, 255):
        block = np.array([(config >> c) & 1 for c in range(8)], dtype=bool).reshape(2, 2, 2)
        sg = surface_graph(block)
        at = (sg.voxel[:, None, :] + CORNER_OFFSETS[sg.direction] == 1).all(axis=2)  # (F, 4)
        f, k = np.nonzero(at)
        ids = sg.vertex[f, k]
        _, first, inverse = np.unique(ids, return_index=True, return_inverse=True)
        local = np.argsort(np.argsort(first))[inverse]
        cell = sg.voxel[f] @ np.array([4, 2, 1])
        fan[config, cell, sg.direction[f]] = local
        count[config] = first.size
    return fan, count


_FAN: tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]] | None = None

#: Axis order (plane, v, u) of the face masks of each axis a, u along (a+1)%3 and v along (a+2)%3.
_PLANE_VU = [(0, 2, 1), (1, 0, 2), (2, 1, 0)]


def face_rectangles(grid: npt.NDArray[np.bool_], *, merge: bool = True,
                    colour: npt.NDArray[np.integer] | None = None) -> npt.NDArray[np.int64]:
    """Exposed faces grouped into rectangles of one plane and direction (and one colour).

    ``colour``, an integer grid like ``grid`` (a colour index per voxel), keeps
    faces of voxels of different colours in different rectangles.

    Returns
    -------
    (R, 6) int64 ndarray
        Rows ``(d, plane, u0, v0, u1, v1)``: direction, the cell coordinate along
        axis ``a = d // 2``, and the cell ranges (exclusive ends) along
        ``(a + 1) % 3`` and ``(a + 2) % 3``.  Ordered by ``(d, plane, v0, u0)``.
    """
    from ._rectangles import stack_runs

    out = []
    no_colour = np.zeros(0, dtype=np.uint8)
    for a in range(3):
        t = np.ascontiguousarray(grid.transpose(_PLANE_VU[a]))
        ct = None if colour is None else np.ascontiguousarray(colour.transpose(_PLANE_VU[a])).ravel()
        beside = np.zeros((t.shape[0] + 2, *t.shape[1:]), dtype=bool)
        beside[1:-1] = t
        for d, nb in ((2 * a, beside[2:]), (2 * a + 1, beside[:-2])):
            faces = np.flatnonzero(t & ~nb)
            out.append(stack_runs(faces, t.shape[2], t.shape[1], d, merge, no_colour if ct is None else ct[faces]))
    return np.concatenate(out)


def rectangle_voxels(rects: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """``(R, 3)`` the first voxel ``(x, y, z)`` of each rectangle of :func:`face_rectangles`."""
    a = rects[:, 0] // 2
    rows = np.arange(rects.shape[0])
    vox = np.empty((rects.shape[0], 3), dtype=np.int64)
    vox[rows, a] = rects[:, 1]
    vox[rows, (a + 1) % 3] = rects[:, 2]
    vox[rows, (a + 2) % 3] = rects[:, 3]
    return vox


def contact_keys(contacts: Contacts, shape: tuple[int, ...]) -> npt.NDArray[np.int64]:
    """Sorted keys ``3 * point + axis`` of the contact edges, keyed by their lower end point.

    Points are numbered ``(x * (Y + 1) + y) * (Z + 1) + z`` over the lattice of a
    grid of ``shape`` (X, Y, Z).
    """
    e = contacts.edges
    if not e.shape[0]:
        return np.zeros(0, dtype=np.int64)
    lo = e[:, 0]
    axis = np.argmax(e[:, 1] - e[:, 0], axis=1)
    point = (lo[:, 0] * (shape[1] + 1) + lo[:, 1]) * (shape[2] + 1) + lo[:, 2]
    return np.sort(point * 3 + axis)


def point_configs(padded: npt.NDArray[np.bool_]) -> npt.NDArray[np.uint8]:
    """Filling of the 8 cells around every lattice point, flat, bit ``4 dx + 2 dy + dz``.

    ``padded`` is the grid with one empty cell around it; point ``(x, y, z)`` of
    the grid's lattice sits between padded cells ``x`` and ``x + 1`` (etc.).
    Built one axis at a time: 6 whole-array operations instead of 8 reads per point.
    """
    p = padded.view(np.uint8)
    z2 = p[:, :, :-1] | (p[:, :, 1:] << 1)
    yz4 = z2[:, :-1, :] | (z2[:, 1:, :] << 2)
    return np.ascontiguousarray(yz4[:-1] | (yz4[1:] << 4)).ravel()


def _half_steps(
    shape: tuple[int, ...], coords: tuple[npt.NDArray[np.float64], ...] | None, pitch: float
) -> npt.NDArray[np.float64]:
    """``(3, L)`` positions in mm of the lattice coordinates 0, 1/2, 1, ... along each axis.

    Midpoints and rectangle centres of a rectilinear grid sit halfway between
    planes, so they stay strictly inside their segments and rectangles.
    """
    out = np.zeros((3, 2 * max(shape) + 1))
    for a in range(3):
        c = np.arange(shape[a] + 1, dtype=np.float64) if coords is None else np.asarray(coords[a], dtype=np.float64)
        out[a, 0 : 2 * len(c) - 1 : 2] = c
        out[a, 1 : 2 * len(c) - 1 : 2] = (c[:-1] + c[1:]) / 2.0
    return out * float(pitch)


def voxel_mesh(
    grid: npt.ArrayLike,
    *,
    pitch: float = 1.0,
    merge: bool = True,
    part_labels: npt.NDArray[np.int64] | None = None,
    coords: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]] | None = None,
    contacts: Contacts | None = None,
    colour: npt.NDArray[np.integer] | None = None,
    palette: npt.NDArray[np.uint8] | None = None,
) -> MeshData:
    """Mesh of the exposed faces of a voxel grid.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The voxels; voxel ``(x, y, z)`` spans ``[x, x+1]·pitch`` etc.
    pitch : float
        Voxel edge in mm.
    merge : bool
        Merge coplanar faces into rectangles (``False``: two triangles per face).
    part_labels : (X, Y, Z) int ndarray, optional
        Part of each filled voxel (e.g. its 6-connected component, 1-based).
        Default: one part per 6-connected component.
    coords : tuple of three 1D float arrays, optional
        For a rectilinear grid: ``coords[a][i]`` is the position, in voxels, of
        lattice plane ``i`` along axis ``a`` (strictly increasing, one more than
        the grid's side).  Default: the unit lattice.
    contacts : Contacts, optional
        The grid's voxels touching only along an edge or at a corner, when the
        caller knows them (:func:`find_contacts`, or none at all for a bridged
        grid); found here otherwise.  Missing edge contacts give edges in four
        triangles, which :func:`check_mesh` refuses.
    colour : (X, Y, Z) int ndarray, optional
        A colour index per filled voxel: faces of different colours are never
        merged, and each triangle gets the colour of the voxel its face belongs to
        (:attr:`MeshData.colour`, rows of ``palette``).
    palette : (K, 4) uint8 ndarray, optional
        The RGBA of each colour index (with ``colour``).

    Returns
    -------
    MeshData
        Manifold by index, counter-clockwise from outside, in mm.
    """
    from ._rectangles import first_appearance, rectangle_mesh

    global _FAN
    if _FAN is None:
        _FAN = fan_table()
    fan, fan_count = _FAN
    g = as_grid(grid)
    if contacts is None:
        contacts = find_contacts(g)
    rects = face_rectangles(g, merge=merge, colour=colour)
    padded = np.pad(g, 1)
    lattice = (padded, point_configs(padded), fan, fan_count, _half_steps(g.shape, coords, pitch))
    tables = (CORNER_OFFSETS, EDGE_OUT, DIRECTIONS, _ALONG_U, _ASCENDING, _AT_MAX)
    triangles, tri_rect, vertices = rectangle_mesh(lattice, rects, contact_keys(contacts, g.shape), tables)

    if part_labels is None:
        from voxfab.shape import label_components

        part_labels, _ = label_components(g)
    # The part (and colour) of a rectangle is that of its first voxel; triangles come rectangle by rectangle.
    vox = rectangle_voxels(rects)
    rect_lab = np.asarray(part_labels)[vox[:, 0], vox[:, 1], vox[:, 2]].astype(np.int64)
    part = first_appearance(rect_lab[tri_rect])
    if colour is None:
        return MeshData(vertices=vertices, triangles=triangles, part=part)
    rect_colour = colour[vox[:, 0], vox[:, 1], vox[:, 2]].astype(np.int64)
    return MeshData(vertices=vertices, triangles=triangles, part=part, colour=rect_colour[tri_rect], palette=palette)
