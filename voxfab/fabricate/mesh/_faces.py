"""Triangle mesh from the exposed voxel faces, with coplanar faces merged.

The vertex ids split exactly like those of :func:`voxfab.shape.surface_graph`
(a table per lattice point, read off it, see :func:`lattice_faces`), so voxels touching
only along an edge or at a corner get separate vertices there.  Two more steps
make the mesh manifold by index and small:

* **Contact segments.**  Where two voxels touch along an edge and both end points
  stay shared (the contact is closed around by other voxels at both ends), the
  four faces on that segment would use the same vertex pair.  Each of the two
  face pairs glued by the surface graph gets its own midpoint vertex there.
* **Coplanar merging.**  Faces of one plane and direction are grouped into
  rectangles (runs along one axis stacked along the other).  A vertex is kept
  when it is a rectangle corner anywhere in the mesh; every rectangle keeps each
  kept vertex on its border.  Two rectangles glued along a border see the same
  kept vertices on it (they share the vertex ids, and where one neighbour ends
  its corner is kept), so no vertex lies inside another triangle's edge: there
  are no T-junctions.  Split vertices (several ids at one point) are always
  kept, so two border chains between the same end vertices never collapse into
  the same edge.
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
from voxfab.shape._surface import CORNER_OFFSETS, DIRECTIONS, EDGE_OF, EDGE_OUT

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


def _runs(keys: npt.NDArray[np.int64], step: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """Run id of each row of sorted data: a new run starts where ``keys`` change or ``step`` != 1."""
    brk = np.ones(keys.shape[0], dtype=bool)
    brk[1:] = (keys[1:] != keys[:-1]) | (step[1:] != 1)
    return np.cumsum(brk) - 1


def _first_of_side(
    ent_rect: npt.NDArray[np.int64],
    side_n: npt.NDArray[np.int64],
    side: npt.NDArray[np.int64],
) -> npt.NDArray[np.int64]:
    """Local index (within its rectangle's polygon) of the first entry of ``side``."""
    before = np.cumsum(side_n, axis=1) - side_n  # entries of the sides before each side
    return before[ent_rect, side]


def _fan_table() -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
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


def lattice_faces(
    grid: npt.NDArray[np.bool_],
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """Exposed faces with vertex ids split like the surface graph's, from a table per lattice point.

    Faces are sorted by ``(x, y, z, d)`` as in :func:`voxfab.shape.surface_graph`,
    and two corners get the same id exactly when ``surface_graph(grid).vertex``
    gives them the same id (see :func:`_fan_table`); the numbering differs.
    The ids at one lattice point are consecutive.

    Returns
    -------
    voxel : (F, 3) int64 ndarray
    direction : (F,) int64 ndarray
    vertex : (F, 4) int64 ndarray
    position : (V, 3) int64 ndarray
    """
    from ._kernels import exposed_cells, lattice_vertices

    global _FAN
    if _FAN is None:
        _FAN = _fan_table()
    fan, fan_count = _FAN
    p = np.pad(grid, 1)
    dims = np.array(p.shape, dtype=np.int64)
    # Filled cells of the padded grid never touch its border, so every neighbour index is valid.
    voxel, direction = exposed_cells(
        p, DIRECTIONS @ np.array([dims[1] * dims[2], dims[2], 1], dtype=np.int64), int(np.count_nonzero(grid))
    )
    vertex, position = lattice_vertices(voxel, direction, p, CORNER_OFFSETS, fan, fan_count)
    return voxel, direction, vertex, position


def _contact_midpoints(
    voxel: npt.NDArray[np.int64],
    direction: npt.NDArray[np.int64],
    padded: npt.NDArray[np.bool_],
    vid: npt.NDArray[np.int64],
    ipos: npt.NDArray[np.int64],
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:
    """Midpoint vertex of each face edge on a contact segment (-1 elsewhere), and their positions.

    Four faces meet on a segment only where two filled voxels sit diagonally
    across it: a convex fold whose cell beyond the corner is filled.  Only those
    face edges need the vertex-pair count.  Faces must be sorted by ``(x, y, z, d)``.
    """
    from ._kernels import diagonal_folds, pair_counts

    nf = direction.size
    n_base = int(vid.max()) + 1
    cand = diagonal_folds(voxel, direction, padded, EDGE_OUT, DIRECTIONS)
    mid_of = np.full(nf * 4, -1, dtype=np.int64)
    mid_pos = np.zeros((0, 3))
    if not cand.size:
        return mid_of, mid_pos
    cf, ck = cand // 4, cand % 4
    a_ids, b_ids = vid[cf, ck], vid[cf, (ck + 1) % 4]
    counts = pair_counts(np.minimum(a_ids, b_ids), np.maximum(a_ids, b_ids), n_base)
    fe = cand[counts == 4]
    if not fe.size:
        return mid_of, mid_pos
    # The face glued to a convex edge k of (v, d) is (v, u), u = EDGE_OUT[d, k], at its edge facing d.
    dims = np.array(padded.shape, dtype=np.int64)
    strides = np.array([dims[1] * dims[2], dims[2], 1], dtype=np.int64)
    keys = ((voxel + 1) @ strides) * 6 + direction
    ff, fk = fe // 4, fe % 4
    u = EDGE_OUT[direction[ff], fk]
    partner = np.searchsorted(keys, ((voxel[ff] + 1) @ strides) * 6 + u) * 4 + EDGE_OF[u, direction[ff]]
    pair = np.minimum(fe, partner)
    upair, pinv = np.unique(pair, return_inverse=True)
    mid_of[fe] = n_base + pinv
    f0, k0 = upair // 4, upair % 4
    pos = ipos.astype(np.float64)
    mid_pos = (pos[vid[f0, k0]] + pos[vid[f0, (k0 + 1) % 4]]) / 2.0
    return mid_of, mid_pos


def voxel_mesh(
    grid: npt.ArrayLike,
    *,
    pitch: float = 1.0,
    merge: bool = True,
    part_labels: npt.NDArray[np.int64] | None = None,
    coords: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]] | None = None,
    contact_free: bool = False,
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
    contact_free : bool
        The caller knows that no voxels touch only along an edge (e.g. a bridged
        grid), so no face edge needs a contact midpoint and the search for them is
        skipped.  A wrong promise gives edges in four triangles, which
        :func:`check_mesh` refuses.

    Returns
    -------
    MeshData
        Manifold by index, counter-clockwise from outside, in mm.
    """
    g = as_grid(grid)
    voxel, d_all, vid, ipos = lattice_faces(g)
    if contact_free:
        mid_of = np.full(d_all.size * 4, -1, dtype=np.int64)
        mid_pos = np.zeros((0, 3))
    else:
        mid_of, mid_pos = _contact_midpoints(voxel, d_all, np.pad(g, 1), vid, ipos)
    nf = d_all.size
    n_base = int(vid.max()) + 1
    pos = ipos.astype(np.float64)

    # --- rectangles per plane and direction ----------------------------------------
    axis = d_all // 2
    ub = (axis + 1) % 3
    vb = (axis + 2) % 3
    rows = np.arange(nf)
    plane = voxel[rows, axis]
    u = voxel[rows, ub]
    v = voxel[rows, vb]
    side = int(voxel.max()) + 2
    # Faces sorted by (d, plane, v, u): rows of each plane, u increasing.
    fkey = ((d_all * side + plane) * side + v) * side + u
    order = np.argsort(fkey)
    fkey_sorted = fkey[order]
    if merge:
        lk = fkey_sorted // side
        du = np.zeros(nf, dtype=np.int64)
        us = u[order]
        du[1:] = us[1:] - us[:-1]
        run_sorted = _runs(lk, du)
        run = np.empty(nf, dtype=np.int64)
        run[order] = run_sorted
        n_runs = int(run_sorted[-1]) + 1
        brk = np.flatnonzero(np.r_[True, run_sorted[1:] != run_sorted[:-1]])
        first = order[brk]
        r_u0 = us[brk]
        r_u1 = np.r_[us[brk[1:] - 1], us[-1]] + 1
        r_d, r_plane, r_v = d_all[first], plane[first], v[first]
        # Runs with the same (d, plane, u0, u1) on consecutive rows stack into one rectangle.
        skey_full = (((r_d * side + r_plane) * side + r_u0) * (side + 1) + r_u1) * side + r_v
        r_order = np.argsort(skey_full)
        sk = skey_full[r_order] // side
        dv = np.zeros(n_runs, dtype=np.int64)
        rv = r_v[r_order]
        dv[1:] = rv[1:] - rv[:-1]
        rect_sorted = _runs(sk, dv)
        rect_of_run = np.empty(n_runs, dtype=np.int64)
        rect_of_run[r_order] = rect_sorted
        n_rect = int(rect_sorted[-1]) + 1
        rect = rect_of_run[run]
        # A rectangle's runs are consecutive in r_order, by increasing v, and share u0 and u1.
        rbrk = np.flatnonzero(np.r_[True, rect_sorted[1:] != rect_sorted[:-1]])
        q_u0 = r_u0[r_order[rbrk]]
        q_u1 = r_u1[r_order[rbrk]]
        q_v0 = rv[rbrk]
        q_v1 = rv[np.r_[rbrk[1:] - 1, n_runs - 1]] + 1
    else:
        n_rect = nf
        rect = rows
        q_u0, q_v0, q_u1, q_v1 = u, v, u + 1, v + 1
    q_first = np.zeros(n_rect, dtype=np.int64)
    q_first[rect] = rows
    q_d, q_plane = d_all[q_first], plane[q_first]

    # --- border vertices and triangles of every rectangle (compiled loops) -----------
    # Rectangle corners are kept everywhere they appear, and so are split vertices
    # (several ids at one point): dropping them could give two border chains the
    # same end points and so the same edge twice.
    from ._kernels import first_appearance, mark_corners, triangulate

    # Faces of each rectangle stored row by row, so the kernels find a border face
    # by arithmetic instead of a search.
    area = (q_u1 - q_u0) * (q_v1 - q_v0)
    rstart = np.cumsum(area) - area
    fidx = np.empty(nf, dtype=np.int64)
    fidx[rstart[rect] + (v - q_v0[rect]) * (q_u1 - q_u0)[rect] + (u - q_u0[rect])] = rows
    keep_vertex = np.zeros(n_base, dtype=bool)
    mark_corners(q_d, q_u0, q_v0, q_u1, q_v1, rstart, fidx, vid, keep_vertex,
                  _ALONG_U, _ASCENDING, _AT_MAX)
    # The ids of one lattice point are consecutive (see lattice_faces): no sort needed.
    same = (ipos[1:, 0] == ipos[:-1, 0]) & (ipos[1:, 1] == ipos[:-1, 1]) & (ipos[1:, 2] == ipos[:-1, 2])
    keep_vertex[1:][same] = True
    keep_vertex[:-1][same] = True
    base_pos = np.concatenate([pos, mid_pos])
    n_mid = mid_pos.shape[0]
    triangles, tri_rect, star = triangulate(
        q_d, q_u0, q_v0, q_u1, q_v1, rstart, fidx, vid, mid_of, keep_vertex,
        base_pos, n_base + n_mid, _ALONG_U, _ASCENDING, _AT_MAX,
    )

    # Centre positions in voxel-corner coordinates.
    sd = q_d[star]
    ax = sd // 2
    cpos = np.zeros((star.size, 3))
    rows_s = np.arange(star.size)
    cpos[rows_s, ax] = q_plane[star] + (sd % 2 == 0)
    cpos[rows_s, (ax + 1) % 3] = (q_u0[star] + q_u1[star]) / 2.0
    cpos[rows_s, (ax + 2) % 3] = (q_v0[star] + q_v1[star]) / 2.0

    all_pos = np.concatenate([pos, mid_pos, cpos])
    used = np.zeros(all_pos.shape[0], dtype=bool)
    used[triangles.ravel()] = True
    remap = np.cumsum(used) - 1
    vertices = all_pos[used]
    triangles = remap[triangles]
    if coords is not None:
        # Piecewise-linear and strictly increasing: midpoints and centres stay
        # strictly inside their segments and rectangles.
        for a in range(3):
            vertices[:, a] = np.interp(vertices[:, a], np.arange(len(coords[a])), coords[a])
    vertices *= float(pitch)

    # Deterministic order: by rectangle (the kernel emits them so), which follows the sorted faces.
    if part_labels is None:
        from voxfab.shape import label_components

        part_labels, _ = label_components(grid)
    vox = voxel[q_first]
    rect_lab = np.asarray(part_labels)[vox[:, 0], vox[:, 1], vox[:, 2]].astype(np.int64)
    part = first_appearance(rect_lab[tri_rect])
    return MeshData(vertices=vertices, triangles=triangles.astype(np.int64), part=part.astype(np.int64))
