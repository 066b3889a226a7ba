"""Compiled loops of the voxel mesher: border vertices and triangles of merged rectangles.

Kept apart so that numba is imported only when a mesh is made.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _face_at(r, cu, cv, q_u0, q_v0, q_u1, rstart, fidx):  # pragma: no cover - compiled
    """The face at plane coordinates (cu, cv) of rectangle ``r`` (its faces are stored row by row)."""
    return fidx[rstart[r] + (cv - q_v0[r]) * (q_u1[r] - q_u0[r]) + (cu - q_u0[r])]


@njit(cache=True)
def _border_corner(d, k, u0, v0, u1, v1, step, along_u_t, asc_t, at_max_t):  # pragma: no cover - compiled
    """Plane coordinates (u, v) of the face on side ``k`` at ``step`` of a rectangle."""
    along_u = along_u_t[d, k]
    if along_u:
        lo, hi = u0, u1 - 1
        fixed = v1 - 1 if at_max_t[d, k] else v0
    else:
        lo, hi = v0, v1 - 1
        fixed = u1 - 1 if at_max_t[d, k] else u0
    moving = lo + step if asc_t[d, k] else hi - step
    if along_u:
        return moving, fixed
    return fixed, moving


@njit(cache=True)
def mark_corners(q_d, q_u0, q_v0, q_u1, q_v1, rstart, fidx, vid, keep,
                  along_u_t, asc_t, at_max_t):  # pragma: no cover - compiled
    """Mark the vertex at the start of each side of every rectangle as kept."""
    for r in range(q_d.size):
        d = q_d[r]
        for k in range(4):
            cu, cv = _border_corner(d, k, q_u0[r], q_v0[r], q_u1[r], q_v1[r], 0, along_u_t, asc_t, at_max_t)
            f = _face_at(r, cu, cv, q_u0, q_v0, q_u1, rstart, fidx)
            keep[vid[f, k]] = True


@njit(cache=True)
def triangulate(q_d, q_u0, q_v0, q_u1, q_v1, rstart, fidx, vid, mid_of, keep,
                 base_pos, first_centre, along_u_t, asc_t, at_max_t):  # pragma: no cover - compiled
    """Triangles of every rectangle with its kept border vertices (see the module notes).

    Returns the triangles, the rectangle of each, and the rectangles that got a centre vertex.
    """
    n_rect = q_d.size
    bound = 0
    for r in range(n_rect):
        bound += 4 * ((q_u1[r] - q_u0[r]) + (q_v1[r] - q_v0[r]))
    tris = np.empty((bound, 3), dtype=np.int64)
    tri_rect = np.empty(bound, dtype=np.int64)
    star = np.empty(n_rect, dtype=np.int64)
    n_star = 0
    nt = 0
    cap = 4 * int(max(np.max(q_u1 - q_u0), np.max(q_v1 - q_v0))) + 8
    ent = np.empty(4 * cap, dtype=np.int64)
    side_n = np.zeros(4, dtype=np.int64)
    for r in range(n_rect):
        d = q_d[r]
        n = 0
        side_n[:] = 0
        for k in range(4):
            length = (q_u1[r] - q_u0[r]) if along_u_t[d, k] else (q_v1[r] - q_v0[r])
            for step in range(length):
                cu, cv = _border_corner(d, k, q_u0[r], q_v0[r], q_u1[r], q_v1[r], step, along_u_t, asc_t, at_max_t)
                f = _face_at(r, cu, cv, q_u0, q_v0, q_u1, rstart, fidx)
                c = vid[f, k]
                if step == 0 or keep[c]:
                    ent[n] = c
                    n += 1
                    side_n[k] += 1
                m = mid_of[f * 4 + k]
                if m >= 0:
                    ent[n] = m
                    n += 1
                    side_n[k] += 1
        k1 = -1
        if side_n[1] == 1 and side_n[3] == 1:
            k1 = 0
        elif side_n[0] == 1 and side_n[2] == 1:
            k1 = 1
        if k1 < 0:
            # Star around a new centre vertex.
            centre = first_centre + n_star
            star[n_star] = r
            n_star += 1
            for i in range(n):
                tris[nt, 0] = centre
                tris[nt, 1] = ent[i]
                tris[nt, 2] = ent[(i + 1) % n]
                tri_rect[nt] = r
                nt += 1
            continue
        # Zipper between side k1 (forward) and side k1 + 2 (backward), both by
        # distance from the first corner of side k1.
        start1 = 0
        for kk in range(k1):
            start1 += side_n[kk]
        ca_i = start1
        cd_i = start1 + side_n[k1] + side_n[(k1 + 1) % 4] + side_n[(k1 + 2) % 4]  # first of side k1+3
        axis = d // 2
        ax = (axis + 1) % 3 if along_u_t[d, k1] else (axis + 2) % 3
        origin = base_pos[ent[ca_i], ax]
        # Chain 1: the entries after ca up to the corner of side k1+1 (polygon order).
        i1 = ca_i + 1
        end1 = ca_i + side_n[k1]  # inclusive: the corner of side k1+1
        # Chain 2: side k1+2's entries walked backwards, from the one before cd.
        i2 = cd_i - 1
        end2 = ca_i + side_n[k1] + 1  # inclusive: side k1+2's first entry
        p = ent[ca_i]
        q = ent[cd_i % n]
        while i1 <= end1 or i2 >= end2:
            take1 = False
            if i1 <= end1 and i2 >= end2:
                s1 = abs(base_pos[ent[i1 % n], ax] - origin)
                s2 = abs(base_pos[ent[i2 % n], ax] - origin)
                take1 = s1 <= s2
            else:
                take1 = i1 <= end1
            if take1:
                e = ent[i1 % n]
                tris[nt, 0] = p
                tris[nt, 1] = e
                tris[nt, 2] = q
                p = e
                i1 += 1
            else:
                e = ent[i2 % n]
                tris[nt, 0] = e
                tris[nt, 1] = q
                tris[nt, 2] = p
                q = e
                i2 -= 1
            tri_rect[nt] = r
            nt += 1
    return tris[:nt], tri_rect[:nt], star[:n_star]


@njit(cache=True)
def out_end_of(tf, h):  # pragma: no cover - compiled
    """End vertex of half-edge ``h`` of the flat triangle list ``tf``."""
    return tf[h + 1 if h % 3 != 2 else h - 2]


@njit(cache=True)
def edge_fan_shells(t, nv):  # pragma: no cover - compiled
    """The checker's edge, fan and shell pass over a triangle list, in one sweep.

    Looks only at ``t`` (T, 3).  Every directed edge must occur once and its
    reverse once (so each undirected edge is in exactly two triangles, oppositely
    oriented), and the corners around every vertex must form one cycle.

    Returns
    -------
    status : int
        0 when the mesh passed, otherwise the first failed test (1: a directed
        edge used twice or more, 2: an edge without its reverse, 3: a pinched
        vertex); the caller then reruns the detailed checks for the message.
    labels : (T,) int64 ndarray
        Shell of each triangle, numbered by first appearance (valid when status is 0).
    n_shells : int
    """
    nt = t.shape[0]
    nh = 3 * nt
    labels = np.full(nt, -1, dtype=np.int64)
    tf = t.ravel()  # half-edge h runs tf[h] -> tf[after(h)]
    start = np.zeros(nv + 1, dtype=np.int64)
    for h in range(nh):
        start[tf[h] + 1] += 1
    for i in range(nv):
        start[i + 1] += start[i]
    fill = start[:-1].copy()
    # Half-edges grouped by their start vertex, with their end vertex beside them
    # so that the scans below read contiguous memory.
    out = np.empty(nh, dtype=np.int64)
    out_end = np.empty(nh, dtype=np.int64)
    for h in range(nh):
        a = tf[h]
        out[fill[a]] = h
        out_end[fill[a]] = tf[h + 1 if h % 3 != 2 else h - 2]
        fill[a] += 1
    # Half-edges grouped by their end vertex too, to find each one's reverse.
    in_start = np.zeros(nv + 1, dtype=np.int64)
    for h in range(nh):
        in_start[out_end_of(tf, h) + 1] += 1
    for i in range(nv):
        in_start[i + 1] += in_start[i]
    in_fill = in_start[:-1].copy()
    inc = np.empty(nh, dtype=np.int64)
    for h in range(nh):
        b = out_end_of(tf, h)
        inc[in_fill[b]] = h
        in_fill[b] += 1
    # stamp[b] == a + 1 while vertex a is scanned: a -> b seen, as half-edge slot[b].
    stamp = np.zeros(nv, dtype=np.int64)
    slot = np.empty(nv, dtype=np.int64)
    twin = np.empty(nh, dtype=np.int64)
    for a in range(nv):
        for i in range(start[a], start[a + 1]):
            b = out_end[i]
            if stamp[b] == a + 1:
                return 1, labels, 0  # a -> b twice
            stamp[b] = a + 1
            slot[b] = out[i]
        # Every half-edge c -> a needs the reverse a -> c (unique: checked just above).
        for i in range(in_start[a], in_start[a + 1]):
            h = inc[i]
            c = tf[h]
            if stamp[c] != a + 1:
                return 2, labels, 0
            twin[h] = slot[c]
    # The corner after h around its start vertex begins the half-edge after h's
    # twin; walk each vertex's corners from its first one: one cycle through all
    # of them means one fan.
    for a in range(nv):
        if start[a + 1] == start[a]:
            return 3, labels, 0  # a vertex without corners has no fan
        first = out[start[a]]
        g = first
        steps = 0
        while True:
            tw = twin[g]
            g = tw + 1 if tw % 3 != 2 else tw - 2
            steps += 1
            if g == first or steps > start[a + 1] - start[a]:
                break
        if steps != start[a + 1] - start[a]:
            return 3, labels, 0
    # With one fan per vertex, triangles sharing a vertex are joined through edges.
    n_shells = 0
    stack = np.empty(nt, dtype=np.int64)
    for s in range(nt):
        if labels[s] >= 0:
            continue
        labels[s] = n_shells
        top = 0
        stack[top] = s
        top += 1
        while top > 0:
            top -= 1
            f = stack[top]
            for j in range(3):
                o = twin[3 * f + j] // 3
                if labels[o] < 0:
                    labels[o] = n_shells
                    stack[top] = o
                    top += 1
        n_shells += 1
    return 0, labels, n_shells


@njit(cache=True)
def pair_counts(a, b, n):  # pragma: no cover - compiled
    """How many times each pair ``(a[i], b[i])`` occurs, for ids in ``0..n-1`` (few per id)."""
    m = a.size
    start = np.zeros(n + 1, dtype=np.int64)
    for i in range(m):
        start[a[i] + 1] += 1
    for i in range(n):
        start[i + 1] += start[i]
    fill = start[:-1].copy()
    grouped = np.empty(m, dtype=np.int64)
    for i in range(m):
        grouped[fill[a[i]]] = b[i]
        fill[a[i]] += 1
    out = np.empty(m, dtype=np.int64)
    for i in range(m):
        c = 0
        for j in range(start[a[i]], start[a[i] + 1]):
            if grouped[j] == b[i]:
                c += 1
        out[i] = c
    return out


@njit(cache=True)
def diagonal_folds(voxel, direction, padded, edge_out, dirs):  # pragma: no cover - compiled
    """Flat indices ``4 f + k`` of convex face edges whose cell beyond the corner is filled.

    ``padded`` is the grid with one empty cell around it; ``edge_out[d, k]`` the
    in-plane direction out of edge ``k`` of a face facing ``d``; ``dirs`` the six
    unit directions.  The edge is convex when the cell beside it is empty.
    """
    nf = voxel.shape[0]
    out = np.empty(4 * nf, dtype=np.int64)
    n = 0
    for f in range(nf):
        d = direction[f]
        for k in range(4):
            u = edge_out[d, k]
            x = voxel[f, 0] + 1 + dirs[u, 0]
            y = voxel[f, 1] + 1 + dirs[u, 1]
            z = voxel[f, 2] + 1 + dirs[u, 2]
            if padded[x, y, z]:
                continue
            if padded[x + dirs[d, 0], y + dirs[d, 1], z + dirs[d, 2]]:
                out[n] = 4 * f + k
                n += 1
    return out[:n]


@njit(cache=True)
def triangle_measures(v, t, ref):  # pragma: no cover - compiled
    """Signed volume of each triangle's cone from ``ref`` and twice its area.

    ``det[a - r, b - r, c - r] = (a - r) . ((b - a) x (c - a))``, one cross product per triangle.
    """
    nt = t.shape[0]
    vol = np.empty(nt)
    area2 = np.empty(nt)
    for i in range(nt):
        a, b, c = t[i, 0], t[i, 1], t[i, 2]
        ax, ay, az = v[a, 0], v[a, 1], v[a, 2]
        ux, uy, uz = v[b, 0] - ax, v[b, 1] - ay, v[b, 2] - az
        wx, wy, wz = v[c, 0] - ax, v[c, 1] - ay, v[c, 2] - az
        cx = uy * wz - uz * wy
        cy = uz * wx - ux * wz
        cz = ux * wy - uy * wx
        vol[i] = ((ax - ref[0]) * cx + (ay - ref[1]) * cy + (az - ref[2]) * cz) / 6.0
        area2[i] = np.sqrt(cx * cx + cy * cy + cz * cz)
    return vol, area2


@njit(cache=True)
def first_appearance(labels):  # pragma: no cover - compiled
    """Renumber non-negative labels 0, 1, ... in order of first appearance."""
    top = 0
    for x in labels:
        top = max(top, x)
    new = np.full(top + 1, -1, dtype=np.int64)
    out = np.empty(labels.size, dtype=np.int64)
    n = 0
    for i in range(labels.size):
        x = labels[i]
        if new[x] < 0:
            new[x] = n
            n += 1
        out[i] = new[x]
    return out


@njit(cache=True)
def lattice_vertices(voxel, direction, padded, corner_offsets, fan, fan_count):  # pragma: no cover - compiled
    """Vertex ids of face corners from the per-point split table (see ``_faces.lattice_faces``).

    Ids are given in order of first use, ``fan_count`` of them per lattice point.
    Returns ``(vertex (F, 4), position (V, 3))``.
    """
    nf = voxel.shape[0]
    sx, sy, sz = padded.shape[0] - 1, padded.shape[1] - 1, padded.shape[2] - 1  # lattice points per axis
    slot = np.full(sx * sy * sz, -1, dtype=np.int32)
    cfg = np.zeros(sx * sy * sz, dtype=np.uint8)
    vertex = np.empty((nf, 4), dtype=np.int64)
    position = np.empty((4 * nf, 3), dtype=np.int64)
    n = 0
    for f in range(nf):
        d = direction[f]
        for k in range(4):
            x = voxel[f, 0] + corner_offsets[d, k, 0]
            y = voxel[f, 1] + corner_offsets[d, k, 1]
            z = voxel[f, 2] + corner_offsets[d, k, 2]
            q = (x * sy + y) * sz + z
            if slot[q] < 0:
                # Padded cell (x + dx, ...) is grid cell (x - 1 + dx, ...): the 8 cells around the point.
                c = 0
                for b in range(8):
                    if padded[x + (b >> 2), y + ((b >> 1) & 1), z + (b & 1)]:
                        c |= 1 << b
                slot[q] = n
                cfg[q] = c
                for j in range(fan_count[c]):
                    position[n + j, 0] = x
                    position[n + j, 1] = y
                    position[n + j, 2] = z
                n += fan_count[c]
            cell = (voxel[f, 0] - x + 1) * 4 + (voxel[f, 1] - y + 1) * 2 + (voxel[f, 2] - z + 1)
            vertex[f, k] = slot[q] + fan[cfg[q], cell, d]
    return vertex, position[:n]


@njit(cache=True)
def contact_scan(p, q, edge_diagonals, body_diagonals):  # pragma: no cover - compiled
    """Edge-only and corner-only contacts starting at the padded surface voxels ``q`` (N, 3).

    ``edge_diagonals`` rows are ``(i, j, s)``: voxel v touches v + e_i + s·e_j;
    ``body_diagonals`` rows are a 2×2×2 block's start and opposite corner.
    Returns ``(edges, edge_voxels, points, point_voxels)`` in unpadded corner and
    voxel coordinates, unsorted.
    """
    n = q.shape[0]
    edges = np.empty((6 * n, 2, 3), dtype=np.int64)
    edge_vox = np.empty((6 * n, 2, 3), dtype=np.int64)
    points = np.empty((4 * n, 3), dtype=np.int64)
    point_vox = np.empty((4 * n, 2, 3), dtype=np.int64)
    ne = 0
    nk = 0
    ei = np.zeros(3, dtype=np.int64)
    ej = np.zeros(3, dtype=np.int64)
    for r in range(n):
        x, y, z = q[r, 0], q[r, 1], q[r, 2]
        for e in range(edge_diagonals.shape[0]):
            i, j, s = edge_diagonals[e, 0], edge_diagonals[e, 1], edge_diagonals[e, 2]
            ei[:] = 0
            ej[:] = 0
            ei[i] = 1
            ej[j] = s
            if not p[x + ei[0] + ej[0], y + ei[1] + ej[1], z + ei[2] + ej[2]]:
                continue
            if p[x + ei[0], y + ei[1], z + ei[2]] or p[x + ej[0], y + ej[1], z + ej[2]]:
                continue
            k = 3 - i - j
            for a in range(3):
                v = q[r, a] - 1
                st = v + ei[a] + (1 if (a == j and s > 0) else 0)
                edges[ne, 0, a] = st
                edges[ne, 1, a] = st + (1 if a == k else 0)
                edge_vox[ne, 0, a] = v
                edge_vox[ne, 1, a] = v + ei[a] + ej[a]
            ne += 1
        for b in range(body_diagonals.shape[0]):
            # Padded block anchor: this voxel sits at the block's start corner.
            ax = x - body_diagonals[b, 0, 0]
            ay = y - body_diagonals[b, 0, 1]
            az = z - body_diagonals[b, 0, 2]
            if not p[ax + body_diagonals[b, 1, 0], ay + body_diagonals[b, 1, 1], az + body_diagonals[b, 1, 2]]:
                continue
            count = 0
            for dx in range(2):
                for dy in range(2):
                    for dz in range(2):
                        if p[ax + dx, ay + dy, az + dz]:
                            count += 1
            if count != 2:
                continue
            points[nk, 0] = ax
            points[nk, 1] = ay
            points[nk, 2] = az
            for a in range(3):
                point_vox[nk, 0, a] = q[r, a] - 1
                point_vox[nk, 1, a] = (ax, ay, az)[a] - 1 + body_diagonals[b, 1, a]
            nk += 1
    return edges[:ne], edge_vox[:ne], points[:nk], point_vox[:nk]


@njit(cache=True)
def exposed_cells(padded, steps, filled):  # pragma: no cover - compiled
    """Exposed faces as ``(voxel (F, 3), direction (F,))``, sorted by ``(x, y, z, d)``.

    ``steps[d]`` is the flat offset of direction ``d`` in ``padded`` (the grid with
    one empty cell around it); ``filled`` the number of filled cells.  Voxels are
    in unpadded coordinates.
    """
    flat = padded.ravel()
    nx, ny, nz = padded.shape
    voxel = np.empty((6 * filled, 3), dtype=np.int64)
    direction = np.empty(6 * filled, dtype=np.int64)
    n = 0
    for x in range(nx):
        for y in range(ny):
            row = (x * ny + y) * nz
            for z in range(nz):
                c = row + z
                if flat[c]:
                    for d in range(6):
                        if not flat[c + steps[d]]:
                            voxel[n, 0] = x - 1
                            voxel[n, 1] = y - 1
                            voxel[n, 2] = z - 1
                            direction[n] = d
                            n += 1
    return voxel[:n], direction[:n]


@njit(cache=True)
def fill_boxes(cells, lab, lo, hi):  # pragma: no cover - compiled
    """Fill the cells of each box ``lo[b] .. hi[b]`` (exclusive) and give them one part label.

    ``lab`` holds the part of the voxel under each cell (0 when empty); each box
    takes the largest label it overlaps (a box is one connected block, so all of
    it belongs to one part).
    """
    for b in range(lo.shape[0]):
        m = 0
        for x in range(lo[b, 0], hi[b, 0]):
            for y in range(lo[b, 1], hi[b, 1]):
                for z in range(lo[b, 2], hi[b, 2]):
                    if lab[x, y, z] > m:
                        m = lab[x, y, z]
        for x in range(lo[b, 0], hi[b, 0]):
            for y in range(lo[b, 1], hi[b, 1]):
                for z in range(lo[b, 2], hi[b, 2]):
                    cells[x, y, z] = True
                    lab[x, y, z] = m
