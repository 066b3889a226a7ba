"""Compiled loops of the voxel mesher: border vertices and triangles of merged rectangles.

Kept apart so that numba is imported only when a mesh is made.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
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
def stack_runs(faces, nu, nv, d, merge):  # pragma: no cover - compiled
    """Rectangles of the exposed faces of one direction ``d``.

    ``faces`` are sorted flat indices into a ``(planes, nv, nu)`` array (u
    fastest).  Each row is cut into runs along u, and a run with the same ends as
    a rectangle's last row, just below it, extends that rectangle.  Returns
    ``(R, 6)`` rows ``(d, plane, u0, v0, u1, v1)``, exclusive ends, ordered by
    ``(plane, v0, u0)``; without ``merge`` every face is a rectangle.
    """
    nf = faces.size
    out = np.empty((nf, 6), dtype=np.int64)
    last = np.empty(nu, dtype=np.int64)  # rectangle whose last run starts at u
    plane_now = -1
    row_start = 0
    row_end = 0
    plane = v = 0
    n = 0
    i = 0
    while i < nf:
        f = faces[i]
        if f >= row_end:  # a new row: the only divisions are here
            row = f // nu
            row_start, row_end = row * nu, row * nu + nu
            plane, v = row // nv, row % nv
            if plane != plane_now:
                last[:] = -1
                plane_now = plane
        u0 = f - row_start
        j = i + 1
        if merge:
            while j < nf and faces[j] == faces[j - 1] + 1 and faces[j] < row_end:
                j += 1
        u1 = u0 + (j - i)
        i = j
        r = last[u0]
        if merge and r >= 0 and out[r, 5] == v and out[r, 4] == u1:
            out[r, 5] = v + 1
            continue
        out[n, 0] = d
        out[n, 1] = plane
        out[n, 2] = u0
        out[n, 3] = v
        out[n, 4] = u1
        out[n, 5] = v + 1
        last[u0] = n
        n += 1
    return out[:n]


@njit(cache=True)
def rectangle_mesh(p, config, rects, contact_keys, half_steps, fan, fan_count, corner_offsets, edge_out, dirs,
                   along_u_t, asc_t, at_max_t):  # pragma: no cover - compiled
    """Triangles of merged rectangles, with vertices split like the surface graph.

    ``p`` is the grid with one empty cell around it, ``config`` the filling of
    the 8 cells around each lattice point (flat, see ``_faces.point_configs``) and
    ``rects`` the rows of :func:`stack_runs`.  ``contact_keys`` are the sorted
    keys ``3 * point + axis`` of the lattice edges where two voxels touch along an
    edge (two diagonal cells filled, two empty), keyed by their lower end point.
    ``half_steps[a, i]`` is the position in mm of lattice coordinate ``i / 2``
    along axis ``a``: vertices (corners, midpoints, centres) sit on half steps.

    A point that is a rectangle corner anywhere, or where several vertices meet
    (a split point), is kept and gets ``fan_count[config]`` ids; a face takes the
    one ``fan`` names.  Ids follow the lattice points in order, so vertices near
    in space are near in memory.  Contact midpoints (two per contact edge) and
    then the centres of star-split rectangles follow; midpoints no triangle uses
    are dropped at the end.

    Returns
    -------
    triangles : (T, 3) int64 ndarray
    rectangle : (T,) int64 ndarray
        Rectangle of each triangle.
    position : (V, 3) float64 ndarray
        Vertex positions in mm.
    """
    nr = rects.shape[0]
    sx, sy, sz = p.shape[0] - 1, p.shape[1] - 1, p.shape[2] - 1
    n_points = sx * sy * sz
    # Pass 1: mark the rectangle corners (slot 0), then number the kept points.
    slot = np.empty(n_points, dtype=np.int32)
    slot[:] = -1
    steps = 0
    longest = 1
    for r in range(nr):
        d, plane, u0, v0, u1, v1 = rects[r, 0], rects[r, 1], rects[r, 2], rects[r, 3], rects[r, 4], rects[r, 5]
        half = (u1 - u0) + (v1 - v0)
        steps += 2 * half
        longest = max(longest, half)
        a = d // 2
        for k in range(4):
            cu, cv = _border_corner(d, k, u0, v0, u1, v1, 0, along_u_t, asc_t, at_max_t)
            x = (plane if a == 0 else (cu if a == 2 else cv)) + corner_offsets[d, k, 0]
            y = (plane if a == 1 else (cu if a == 0 else cv)) + corner_offsets[d, k, 1]
            z = (plane if a == 2 else (cu if a == 1 else cv)) + corner_offsets[d, k, 2]
            slot[(x * sy + y) * sz + z] = 0
    n_keys = contact_keys.size
    cap = 4 * min(n_points, 4 * nr + steps)
    pos = np.empty((cap + 2 * n_keys + nr, 3))
    n = 0
    for x in range(sx):
        for y in range(sy):
            q = (x * sy + y) * sz
            for z in range(sz):
                m = fan_count[config[q]]
                if slot[q] == 0 or m > 1:
                    slot[q] = n
                    for j in range(m):
                        pos[n + j, 0] = half_steps[0, 2 * x]
                        pos[n + j, 1] = half_steps[1, 2 * y]
                        pos[n + j, 2] = half_steps[2, 2 * z]
                    n += m
                else:
                    slot[q] = -1
                q += 1
    n_lattice = n
    # Contact midpoints: two per contact edge, one for each voxel's pair of faces.
    for i in range(n_keys):
        q0, axis = contact_keys[i] // 3, contact_keys[i] % 3
        x, y, z = q0 // (sy * sz), (q0 // sz) % sy, q0 % sz
        for _side in range(2):  # the same point for both voxels
            pos[n, 0] = half_steps[0, 2 * x + (1 if axis == 0 else 0)]
            pos[n, 1] = half_steps[1, 2 * y + (1 if axis == 1 else 0)]
            pos[n, 2] = half_steps[2, 2 * z + (1 if axis == 2 else 0)]
            n += 1
    # The triangles are compacted to the vertices they use at the end.
    n = n_lattice + 2 * n_keys  # rectangle centres follow, as stars need them
    # Pass 2: walk each border collecting kept vertices, then zip or fan the polygon.
    # Along a side the point moves by the face edge's direction, so its flat index
    # moves by a fixed stride and the face's cell around it stays the same.
    bound = 2 * steps
    tris = np.empty((bound, 3), dtype=np.int64)
    tri_rect = np.empty(bound, dtype=np.int64)
    ent = np.empty(4 * longest + 8, dtype=np.int64)
    ent_uv = np.empty((4 * longest + 8, 2), dtype=np.int64)  # lattice coordinates (u, v), in half steps
    side_n = np.zeros(4, dtype=np.int64)
    nt = 0
    for r in range(nr):
        d, plane, u0, v0, u1, v1 = rects[r, 0], rects[r, 1], rects[r, 2], rects[r, 3], rects[r, 4], rects[r, 5]
        a = d // 2
        ub, vb = (a + 1) % 3, (a + 2) % 3
        e = 0
        for k in range(4):
            side_n[k] = 0
            length = (u1 - u0) if along_u_t[d, k] else (v1 - v0)
            cu, cv = _border_corner(d, k, u0, v0, u1, v1, 0, along_u_t, asc_t, at_max_t)
            vx = plane if a == 0 else (cu if a == 2 else cv)
            vy = plane if a == 1 else (cu if a == 0 else cv)
            vz = plane if a == 2 else (cu if a == 1 else cv)
            k1 = (k + 1) % 4
            ex = corner_offsets[d, k1, 0] - corner_offsets[d, k, 0]
            ey = corner_offsets[d, k1, 1] - corner_offsets[d, k, 1]
            ez = corner_offsets[d, k1, 2] - corner_offsets[d, k, 2]
            x = vx + corner_offsets[d, k, 0]
            y = vy + corner_offsets[d, k, 1]
            z = vz + corner_offsets[d, k, 2]
            cell = (1 - corner_offsets[d, k, 0]) * 4 + (1 - corner_offsets[d, k, 1]) * 2 + (1 - corner_offsets[d, k, 2])
            dq = (ex * sy + ey) * sz + ez
            q = (x * sy + y) * sz + z
            pu = x if ub == 0 else (y if ub == 1 else z)
            pv = x if vb == 0 else (y if vb == 1 else z)
            du = ex if ub == 0 else (ey if ub == 1 else ez)
            dv = ex if vb == 0 else (ey if vb == 1 else ez)
            for s in range(length):
                if slot[q] >= 0:
                    ent[e] = slot[q] + fan[config[q], cell, d]
                    ent_uv[e, 0] = 2 * (pu + s * du)
                    ent_uv[e, 1] = 2 * (pv + s * dv)
                    e += 1
                    side_n[k] += 1
                q += dq
                if n_keys == 0:
                    continue
                # Edge k of the face at step s is a contact segment when the cell beside
                # it is empty and the cell beyond the corner (voxel b) is filled.  Where
                # both its ends are shared by the two voxels' faces, each voxel's pair of
                # faces on it gets a midpoint of its own, so no edge is in four triangles.
                fx, fy, fz = vx + s * ex, vy + s * ey, vz + s * ez
                u = edge_out[d, k]
                if p[fx + dirs[u, 0] + 1, fy + dirs[u, 1] + 1, fz + dirs[u, 2] + 1]:
                    continue
                bx = fx + dirs[u, 0] + dirs[d, 0]
                by = fy + dirs[u, 1] + dirs[d, 1]
                bz = fz + dirs[u, 2] + dirs[d, 2]
                if not p[bx + 1, by + 1, bz + 1]:
                    continue
                x0, y0, z0 = x + s * ex, y + s * ey, z + s * ez
                q0, q1 = q - dq, q
                c0, c1 = config[q0], config[q1]
                od = d ^ 1  # the opposite direction: b's face on the segment
                if fan[c0, cell, d] != fan[c0, (bx - x0 + 1) * 4 + (by - y0 + 1) * 2 + (bz - z0 + 1), od]:
                    continue
                x1, y1, z1 = x0 + ex, y0 + ey, z0 + ez
                if fan[c1, (fx - x1 + 1) * 4 + (fy - y1 + 1) * 2 + (fz - z1 + 1), d] != \
                        fan[c1, (bx - x1 + 1) * 4 + (by - y1 + 1) * 2 + (bz - z1 + 1), od]:
                    continue
                axis = 0 if ex != 0 else (1 if ey != 0 else 2)
                key = min(q0, q1) * 3 + axis
                i = np.searchsorted(contact_keys, key)
                if i >= n_keys or contact_keys[i] != key:
                    continue  # not a contact of the given list: the checker will say so
                # The lexicographically smaller voxel of the pair takes the first midpoint.
                first = bx > fx or (bx == fx and (by > fy or (by == fy and bz > fz)))
                ent[e] = n_lattice + 2 * i + (0 if first else 1)
                ent_uv[e, 0] = 2 * (pu + s * du) + du
                ent_uv[e, 1] = 2 * (pv + s * dv) + dv
                e += 1
                side_n[k] += 1
        k1 = -1
        if side_n[1] == 1 and side_n[3] == 1:
            k1 = 0
        elif side_n[0] == 1 and side_n[2] == 1:
            k1 = 1
        if k1 < 0:
            # Star around a new centre vertex.
            centre = n
            n += 1
            pos[centre, a] = half_steps[a, 2 * (plane + corner_offsets[d, 0, a])]
            pos[centre, ub] = half_steps[ub, u0 + u1]
            pos[centre, vb] = half_steps[vb, v0 + v1]
            for i in range(e):
                tris[nt, 0] = centre
                tris[nt, 1] = ent[i]
                tris[nt, 2] = ent[i + 1 if i + 1 < e else 0]
                tri_rect[nt] = r
                nt += 1
            continue
        # Zipper between side k1 (forward) and side k1 + 2 (backward), both by
        # distance from the first corner of side k1.
        ca_i = 0
        for kk in range(k1):
            ca_i += side_n[kk]
        cd_i = ca_i + side_n[k1] + side_n[(k1 + 1) % 4] + side_n[(k1 + 2) % 4]  # first of side k1+3
        w_ax = 0 if along_u_t[d, k1] else 1
        origin = ent_uv[ca_i, w_ax]
        i1 = ca_i + 1
        end1 = ca_i + side_n[k1]  # inclusive: the corner of side k1+1
        i2 = cd_i - 1
        end2 = ca_i + side_n[k1] + 1  # inclusive: side k1+2's first entry
        pa = ent[ca_i]
        pb = ent[cd_i if cd_i < e else 0]  # side k1+3 may be the wrap to entry 0; the rest never wraps
        while i1 <= end1 or i2 >= end2:
            take1 = i1 <= end1
            if take1 and i2 >= end2:
                take1 = abs(ent_uv[i1, w_ax] - origin) <= abs(ent_uv[i2, w_ax] - origin)
            if take1:
                w = ent[i1]
                tris[nt, 0] = pa
                tris[nt, 1] = w
                tris[nt, 2] = pb
                pa = w
                i1 += 1
            else:
                w = ent[i2]
                tris[nt, 0] = w
                tris[nt, 1] = pb
                tris[nt, 2] = pa
                pb = w
                i2 -= 1
            tri_rect[nt] = r
            nt += 1
    if n_keys == 0:
        return tris[:nt], tri_rect[:nt], pos[:n]
    # Drop the midpoints no triangle uses (every kept lattice id and centre is used).
    new_id = np.zeros(n - n_lattice, dtype=np.int64)
    for t in range(nt):
        for j in range(3):
            if tris[t, j] >= n_lattice:
                new_id[tris[t, j] - n_lattice] = 1
    new_id[2 * n_keys:] = 1
    n = n_lattice
    for i in range(new_id.size):
        if new_id[i]:
            pos[n] = pos[n_lattice + i]
            new_id[i] = n
            n += 1
    for t in range(nt):
        for j in range(3):
            if tris[t, j] >= n_lattice:
                tris[t, j] = new_id[tris[t, j] - n_lattice]
    return tris[:nt], tri_rect[:nt], pos[:n]


@njit(cache=True)
def edge_fan_shells(t, nv):  # pragma: no cover - compiled
    """The checker's edge, fan and shell pass over a triangle list.

    Looks only at ``t`` (T, 3).  Every undirected edge must be in exactly two
    triangles, once in each direction, and the corners around every vertex must
    form one cycle.

    Returns
    -------
    status : int
        0 when the mesh passed, otherwise the first failed test (1: an edge in
        more than two triangles or twice in one direction, 2: an edge in one
        triangle only, 3: a pinched vertex); the caller then reruns the detailed
        checks for the message.
    labels : (T,) int32 ndarray
        Shell of each triangle, numbered by first appearance (valid when status is 0).
    n_shells : int
    """
    nt = t.shape[0]
    nh = 3 * nt
    labels = np.empty(nt, dtype=np.int32)
    labels[:] = -1
    tf = t.ravel()  # half-edge h runs tf[h] -> tf[h + 1], or tf[h - 2] at a triangle's last corner
    # Half-edges grouped by the lower of their two end vertices: the two halves of
    # an edge land in the same small group.
    start = np.zeros(nv + 1, dtype=np.int32)
    corners = np.zeros(nv, dtype=np.int32)  # corners at each vertex
    a_corner = np.empty(nv, dtype=np.int32)  # one of them (a half-edge starting there)
    for f in range(nt):
        a, b, c = t[f, 0], t[f, 1], t[f, 2]
        start[min(a, b) + 1] += 1
        start[min(b, c) + 1] += 1
        start[min(c, a) + 1] += 1
        corners[a] += 1
        corners[b] += 1
        corners[c] += 1
        a_corner[a] = 3 * f
        a_corner[b] = 3 * f + 1
        a_corner[c] = 3 * f + 2
    for i in range(nv):
        start[i + 1] += start[i]
    fill = start[:-1].copy()
    group = np.empty(nh, dtype=np.int32)  # int32 halves the memory the random accesses touch
    # The other end, times two, plus 1 when the half-edge starts at the group's
    # vertex: partners and their directions are read beside the group, not from t.
    high = np.empty(nh, dtype=np.int32)
    for h in range(nh):
        a = tf[h]
        b = tf[h + 1] if h % 3 != 2 else tf[h - 2]
        m = min(a, b)
        group[fill[m]] = h
        high[fill[m]] = 2 * (a + b - m) + (1 if a == m else 0)
        fill[m] += 1
    twin = np.empty(nh, dtype=np.int32)
    paired = np.zeros(nh, dtype=np.bool_)  # by group slot
    # Small groups pair up by a scan of their own entries; large ones (a vertex
    # with many neighbours) through owner[b] == m: group m's half-edge to b sits
    # at slot first[b].
    owner = np.empty(nv, dtype=np.int32)
    owner[:] = -1
    first = np.empty(nv, dtype=np.int32)
    for m in range(nv):
        g0, g1 = start[m], start[m + 1]
        if g1 - g0 <= 24:
            for i in range(g0, g1):
                if paired[i]:
                    continue
                o = -1
                for j in range(i + 1, g1):
                    if high[j] >> 1 == high[i] >> 1:
                        if o >= 0:
                            return 1, labels, 0  # a third triangle on this edge
                        o = j
                if o < 0:
                    return 2, labels, 0  # (a partner before i would have paired it)
                if high[o] == high[i]:
                    return 1, labels, 0  # both halves run the same way
                paired[o] = True
                twin[group[i]] = group[o]
                twin[group[o]] = group[i]
            continue
        for i in range(g0, g1):
            b = high[i] >> 1
            if owner[b] != m:
                owner[b] = m
                first[b] = i
                continue
            o = first[b]
            if paired[o] or high[o] == high[i]:
                return 1, labels, 0
            paired[o] = True
            paired[i] = True
            twin[group[i]] = group[o]
            twin[group[o]] = group[i]
        for i in range(g0, g1):
            if not paired[i]:
                return 2, labels, 0
    # The corner after h around its start vertex begins the half-edge after h's
    # twin: a permutation of the corners whose cycles are the fans.  Walking from
    # one corner of a vertex must meet all of its corners: one fan per vertex.
    for v in range(nv):
        if corners[v] == 0:
            return 3, labels, 0  # a vertex without corners has no fan
        h0 = a_corner[v]
        h = h0
        steps = 0
        while True:
            g = twin[h]
            h = g + 1 if g % 3 != 2 else g - 2
            steps += 1
            if h == h0 or steps > corners[v]:
                break
        if steps != corners[v]:
            return 3, labels, 0
    # With one fan per vertex, triangles sharing a vertex are joined through edges.
    n_shells = 0
    stack = np.empty(nt, dtype=np.int32)
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
def index_problems(t, nv):  # pragma: no cover - compiled
    """Counts of indices outside ``0..nv-1``, of vertices no triangle uses, and of
    triangles that repeat a vertex, in one pass over ``t`` (T, 3)."""
    used = np.zeros(nv, dtype=np.bool_)
    outside = 0
    repeats = 0
    for f in range(t.shape[0]):
        a, b, c = t[f, 0], t[f, 1], t[f, 2]
        if a == b or b == c or a == c:
            repeats += 1
        for x in (a, b, c):
            if x < 0 or x >= nv:
                outside += 1
            else:
                used[x] = True
    unused = 0
    for i in range(nv):
        if not used[i]:
            unused += 1
    return outside, unused, repeats


@njit(cache=True)
def vertex_bounds(v):  # pragma: no cover - compiled
    """Minimum and maximum corner of the points ``v`` (N, 3) (numpy's axis-0 min is slow on (N, 3))."""
    lo = v[0].copy()
    hi = v[0].copy()
    for i in range(1, v.shape[0]):
        for a in range(3):
            x = v[i, a]
            if x < lo[a]:
                lo[a] = x
            elif x > hi[a]:
                hi[a] = x
    return lo, hi


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
