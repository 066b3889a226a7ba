"""Triangle mesh from the exposed voxel faces, with coplanar faces merged.

The vertex ids come from :func:`voxfab.shape.surface_graph`, so voxels touching
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
from voxfab.shape._surface import CORNER_OFFSETS, DIRECTIONS, EDGE_OUT, FOLD_MOUNTAIN

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


def voxel_mesh(
    grid: npt.ArrayLike,
    *,
    pitch: float = 1.0,
    merge: bool = True,
    part_labels: npt.NDArray[np.int64] | None = None,
    coords: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]] | None = None,
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

    Returns
    -------
    MeshData
        Manifold by index, counter-clockwise from outside, in mm.
    """
    sg = surface_graph(grid)
    vid = sg.vertex
    nf = sg.face_count
    n_base = int(vid.max()) + 1
    pos = sg.vertex_position.astype(np.float64)
    d_all = sg.direction

    # --- contact segments: a vertex pair used by four face edges -----------------
    # Four faces meet on a segment only where two filled voxels sit diagonally
    # across it: a convex fold whose cell beyond the corner is filled.  Only those
    # few face edges need the (costly) vertex-pair count.
    padded = np.pad(as_grid(grid), 1)
    mountain = np.flatnonzero(sg.fold.ravel() == FOLD_MOUNTAIN)
    mf, mk = mountain // 4, mountain % 4
    md = d_all[mf]
    over = sg.voxel[mf] + 1 + DIRECTIONS[EDGE_OUT[md, mk]] + DIRECTIONS[md]
    cand = mountain[padded[over[:, 0], over[:, 1], over[:, 2]]]
    mid_of = np.full(nf * 4, -1, dtype=np.int64)
    mid_pos = np.zeros((0, 3))
    if cand.size:
        cf, ck = cand // 4, cand % 4
        a_ids, b_ids = vid[cf, ck], vid[cf, (ck + 1) % 4]
        ekey = np.minimum(a_ids, b_ids) * n_base + np.maximum(a_ids, b_ids)
        _, inv, counts = np.unique(ekey, return_inverse=True, return_counts=True)
        fe = cand[counts[inv] == 4]
        if fe.size:
            partner = sg.neighbor.ravel()[fe] * 4 + sg.neighbor_edge.ravel()[fe]
            pair = np.minimum(fe, partner)
            upair, pinv = np.unique(pair, return_inverse=True)
            mid_of[fe] = n_base + pinv
            f0, k0 = upair // 4, upair % 4
            mid_pos = (pos[vid[f0, k0]] + pos[vid[f0, (k0 + 1) % 4]]) / 2.0

    # --- rectangles per plane and direction ----------------------------------------
    axis = d_all // 2
    ub = (axis + 1) % 3
    vb = (axis + 2) % 3
    rows = np.arange(nf)
    plane = sg.voxel[rows, axis]
    u = sg.voxel[rows, ub]
    v = sg.voxel[rows, vb]
    side = int(sg.voxel.max()) + 2
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
    else:
        n_rect = nf
        rect = rows
    q_u0 = np.full(n_rect, np.iinfo(np.int64).max)
    q_v0 = np.full(n_rect, np.iinfo(np.int64).max)
    q_u1 = np.zeros(n_rect, dtype=np.int64)
    q_v1 = np.zeros(n_rect, dtype=np.int64)
    np.minimum.at(q_u0, rect, u)
    np.minimum.at(q_v0, rect, v)
    np.maximum.at(q_u1, rect, u + 1)
    np.maximum.at(q_v1, rect, v + 1)
    q_first = np.zeros(n_rect, dtype=np.int64)
    q_first[rect] = rows
    q_d, q_plane = d_all[q_first], plane[q_first]

    # --- border segments of every rectangle, counter-clockwise from outside ---------
    w = q_u1 - q_u0
    h = q_v1 - q_v0
    seg_len = np.where(_ALONG_U[q_d], w[:, None], h[:, None])  # (R, 4)
    counts_rk = seg_len.ravel()
    rk = np.repeat(np.arange(n_rect * 4), counts_rk)
    starts = np.cumsum(counts_rk) - counts_rk
    step = np.arange(rk.size) - starts[rk]
    r = rk // 4
    k = rk % 4
    dd = q_d[r]
    along_u = _ALONG_U[dd, k]
    asc = _ASCENDING[dd, k]
    at_max = _AT_MAX[dd, k]
    run_lo = np.where(along_u, q_u0[r], q_v0[r])
    run_hi = np.where(along_u, q_u1[r], q_v1[r]) - 1
    moving = np.where(asc, run_lo + step, run_hi - step)
    fixed = np.where(along_u, np.where(at_max, q_v1[r] - 1, q_v0[r]), np.where(at_max, q_u1[r] - 1, q_u0[r]))
    cu = np.where(along_u, moving, fixed)
    cv = np.where(along_u, fixed, moving)
    skey = ((dd * side + q_plane[r]) * side + cv) * side + cu
    face = order[np.searchsorted(fkey_sorted, skey)]
    corner_id = vid[face, k]
    mid_id = mid_of[face * 4 + k]

    # Rectangle corners are kept everywhere they appear, and so are split vertices
    # (several ids at one point): dropping them could give two border chains the
    # same end points and so the same edge twice.
    keep_vertex = np.zeros(n_base, dtype=bool)
    keep_vertex[corner_id[step == 0]] = True
    ipos = sg.vertex_position
    pkey = (ipos[:, 0] * side + ipos[:, 1]) * side + ipos[:, 2]
    _, pinv, pcount = np.unique(pkey, return_inverse=True, return_counts=True)
    keep_vertex |= pcount[pinv] > 1

    entries = np.stack([corner_id, mid_id], axis=1)
    keep = np.stack([keep_vertex[corner_id], mid_id >= 0], axis=1)
    ent = entries[keep]
    ent_rect = np.broadcast_to(r[:, None], keep.shape)[keep]
    ent_side = np.broadcast_to(k[:, None], keep.shape)[keep]
    n_per = np.bincount(ent_rect, minlength=n_rect)
    off = np.cumsum(n_per) - n_per
    side_n = np.bincount(ent_rect * 4 + ent_side, minlength=4 * n_rect).reshape(n_rect, 4)
    base_pos = np.concatenate([pos, mid_pos])

    # --- triangulate ---------------------------------------------------------------
    # A zipper between two opposite sides when the other two sides hold only their
    # corner: every triangle has two points on one side and one on the opposite
    # side, so none is degenerate, and no vertex is added (n - 2 triangles).
    # Otherwise a star around a new centre vertex (n triangles).
    zip0 = (side_n[:, 1] == 1) & (side_n[:, 3] == 1)
    zip1 = ~zip0 & (side_n[:, 0] == 1) & (side_n[:, 2] == 1)
    k1 = np.where(zip0, 0, 1)
    zipped = zip0 | zip1
    e_all = np.arange(ent.size)
    e_k1 = k1[ent_rect]
    rel = (ent_side - e_k1) % 4
    in_zip = zipped[ent_rect]
    e_local = e_all - off[ent_rect]
    first_k1 = off[ent_rect] + _first_of_side(ent_rect, side_n, e_k1)
    # Chain 1: side k1 after its first corner, then the corner of side k1+1.
    chain1 = in_zip & (((rel == 0) & (e_all != first_k1)) | (rel == 1))
    # Chain 2: side k1+2, walked backwards from the corner of side k1+3.
    chain2 = in_zip & (rel == 2)
    # Coordinate along the chain axis, measured from the first corner of side k1.
    dd_e = q_d[ent_rect]
    chain_axis_u = _ALONG_U[dd_e, e_k1]
    ax_e = dd_e // 2
    coord_axis = np.where(chain_axis_u, (ax_e + 1) % 3, (ax_e + 2) % 3)
    t_e = base_pos[ent, coord_axis]
    s_e = np.abs(t_e - base_pos[ent[first_k1], coord_axis])
    ev = np.flatnonzero(chain1 | chain2)
    ev = ev[np.lexsort((chain2[ev], s_e[ev], ent_rect[ev]))]
    is2 = chain2[ev]
    ev_rect = ent_rect[ev]
    n_ev = ev.size
    pos_ev = np.arange(n_ev)
    # Latest event of each chain up to here (within the same rectangle).
    last2 = np.maximum.accumulate(np.where(is2, pos_ev, -1)) if n_ev else pos_ev
    last1 = np.maximum.accumulate(np.where(~is2, pos_ev, -1)) if n_ev else pos_ev
    rect_start = np.searchsorted(ev_rect, ev_rect, side="left")
    # The corner where both chains start: side k1's first (chain 1) and side k1+3's (chain 2).
    ca = ent[first_k1]
    cd_idx = off[ent_rect] + _first_of_side(ent_rect, side_n, (e_k1 + 3) % 4)
    cd = ent[cd_idx]
    prev_poly = off[ent_rect] + (e_local - 1) % n_per[ent_rect]
    next_poly = off[ent_rect] + (e_local + 1) % n_per[ent_rect]
    q_cur = np.where(last2 >= rect_start, ent[ev[np.maximum(last2, 0)]], cd[ev])
    # For chain-2 events, the current chain-1 point is the latest chain-1 event before it.
    prev1 = np.where(pos_ev > 0, last1[np.maximum(pos_ev - 1, 0)], -1)
    p_cur = np.where(prev1 >= rect_start, ent[ev[np.maximum(prev1, 0)]], ca[ev])
    tri_zip = np.where(
        is2[:, None],
        np.stack([ent[ev], ent[next_poly[ev]], p_cur], axis=1),
        np.stack([ent[prev_poly[ev]], ent[ev], q_cur], axis=1),
    )
    # q_cur for a chain-1 event must be the chain-2 point current *before* it.
    prev2 = np.where(pos_ev > 0, last2[np.maximum(pos_ev - 1, 0)], -1)
    q_before = np.where(prev2 >= rect_start, ent[ev[np.maximum(prev2, 0)]], cd[ev])
    tri_zip[~is2, 2] = q_before[~is2]

    star = np.flatnonzero(~zipped)
    n_mid = mid_pos.shape[0]
    centre_id = n_base + n_mid + np.arange(star.size)
    e_idx = np.flatnonzero(~in_zip)
    e_rect = ent_rect[e_idx]
    centre_of_rect = np.full(n_rect, -1, dtype=np.int64)
    centre_of_rect[star] = centre_id
    tri_star = np.stack([centre_of_rect[e_rect], ent[e_idx], ent[next_poly[e_idx]]], axis=1)
    triangles = np.concatenate([tri_zip, tri_star])
    tri_rect = np.concatenate([ev_rect, e_rect])

    # Centre positions in voxel-corner coordinates.
    sd = q_d[star]
    ax = sd // 2
    cpos = np.zeros((star.size, 3))
    rows_s = np.arange(star.size)
    cpos[rows_s, ax] = q_plane[star] + (sd % 2 == 0)
    cpos[rows_s, (ax + 1) % 3] = (q_u0[star] + q_u1[star]) / 2.0
    cpos[rows_s, (ax + 2) % 3] = (q_v0[star] + q_v1[star]) / 2.0

    all_pos = np.concatenate([pos, mid_pos, cpos])
    if coords is not None:
        # Piecewise-linear and strictly increasing: midpoints and centres stay
        # strictly inside their segments and rectangles.
        for a in range(3):
            all_pos[:, a] = np.interp(all_pos[:, a], np.arange(len(coords[a])), coords[a])
    all_pos *= float(pitch)
    used = np.zeros(all_pos.shape[0], dtype=bool)
    used[triangles.ravel()] = True
    remap = np.cumsum(used) - 1
    vertices = all_pos[used]
    triangles = remap[triangles]

    # Deterministic order: by rectangle, which follows the sorted faces.
    tord = np.argsort(tri_rect, kind="stable")
    triangles = triangles[tord]
    tri_face = q_first[tri_rect[tord]]
    if part_labels is None:
        from voxfab.shape import label_components

        part_labels, _ = label_components(grid)
    vox = sg.voxel[tri_face]
    lab = np.asarray(part_labels)[vox[:, 0], vox[:, 1], vox[:, 2]].astype(np.int64)
    _, first_t, inv_t = np.unique(lab, return_index=True, return_inverse=True)
    part = np.argsort(np.argsort(first_t))[inv_t]
    return MeshData(vertices=vertices, triangles=triangles.astype(np.int64), part=part.astype(np.int64))
