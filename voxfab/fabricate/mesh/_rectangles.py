"""Compiled mesher: exposed faces as merged rectangles, and their triangles with split vertices.

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
def stack_runs(faces, nu, nv, d, merge, colour):  # pragma: no cover - compiled
    """Rectangles of the exposed faces of one direction ``d``.

    ``faces`` are sorted flat indices into a ``(planes, nv, nu)`` array (u
    fastest).  Each row is cut into runs along u, and a run with the same ends as
    a rectangle's last row, just below it, extends that rectangle.  Returns
    ``(R, 6)`` rows ``(d, plane, u0, v0, u1, v1)``, exclusive ends, ordered by
    ``(plane, v0, u0)``; without ``merge`` every face is a rectangle.  ``colour``
    is empty, or the colour of each face: then a run and a rectangle hold faces
    of one colour only.
    """
    coloured = colour.size > 0
    nf = faces.size
    out = np.empty((nf, 6), dtype=np.int64)
    last = np.empty(nu, dtype=np.int64)  # rectangle whose last run starts at u
    rect_colour = np.empty(nf if coloured else 0, dtype=colour.dtype)
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
        c = colour[i] if coloured else 0
        j = i + 1
        if merge:
            while j < nf and faces[j] == faces[j - 1] + 1 and faces[j] < row_end:
                if coloured and colour[j] != c:
                    break
                j += 1
        u1 = u0 + (j - i)
        i = j
        r = last[u0]
        if merge and r >= 0 and out[r, 5] == v and out[r, 4] == u1 and (not coloured or rect_colour[r] == c):
            out[r, 5] = v + 1
            continue
        out[n, 0] = d
        out[n, 1] = plane
        out[n, 2] = u0
        out[n, 3] = v
        out[n, 4] = u1
        out[n, 5] = v + 1
        if coloured:
            rect_colour[n] = c
        last[u0] = n
        n += 1
    return out[:n]


@njit(cache=True)
def rectangle_mesh(lattice, rects, contact_keys, tables):  # pragma: no cover - compiled
    """Triangles of merged rectangles, with vertices split like the surface graph.

    ``lattice`` is ``(p, config, fan, fan_count, half_steps)``: ``p`` the grid with
    one empty cell around it, ``config`` the filling of the 8 cells around each
    lattice point (flat, see ``_faces.point_configs``), ``fan``/``fan_count`` the
    vertex table of each configuration and ``half_steps[a, i]`` the position in mm
    of lattice coordinate ``i / 2`` along axis ``a`` (vertices sit on half steps).
    ``rects`` are the rows of :func:`stack_runs`.  ``contact_keys`` are the sorted
    keys ``3 * point + axis`` of the lattice edges where two voxels touch along an
    edge, keyed by their lower end point.  ``tables`` is ``(corner_offsets,
    edge_out, dirs, along_u, ascending, at_max)`` from ``_faces``.

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
    slot, pos, n_lattice, steps, longest = number_points(lattice, rects, contact_keys.size, tables)
    n = contact_midpoints(pos, n_lattice, contact_keys, lattice)
    bound = 2 * steps
    tris = np.empty((bound, 3), dtype=np.int64)
    tri_rect = np.empty(bound, dtype=np.int64)
    ent = np.empty(4 * longest + 8, dtype=np.int64)
    ent_uv = np.empty((4 * longest + 8, 2), dtype=np.int64)  # lattice coordinates (u, v), in half steps
    side_n = np.zeros(4, dtype=np.int64)
    nt = 0
    for r in range(rects.shape[0]):
        e = border_vertices(r, rects, slot, n_lattice, contact_keys, lattice, tables, ent, ent_uv, side_n)
        k1 = -1
        if side_n[1] == 1 and side_n[3] == 1:
            k1 = 0
        elif side_n[0] == 1 and side_n[2] == 1:
            k1 = 1
        if k1 < 0:
            nt = star(r, rects, n, pos, lattice[4], tables[0], ent, e, tris, tri_rect, nt)
            n += 1
        else:
            nt = zipper(r, k1, rects[r, 0], ent, ent_uv, e, side_n, tables[3], tris, tri_rect, nt)
    if contact_keys.size == 0:
        return tris[:nt], tri_rect[:nt], pos[:n]
    n = drop_unused_midpoints(tris, nt, pos, n, n_lattice, contact_keys.size)
    return tris[:nt], tri_rect[:nt], pos[:n]


@njit(cache=True)
def number_points(lattice, rects, n_keys, tables):  # pragma: no cover - compiled
    """Mark the rectangle corners, then give every kept lattice point its vertex ids.

    Returns ``(slot, pos, n_lattice, steps, longest)``: the first id of each kept
    point (-1 elsewhere), the position array with room for the midpoints and
    centres to come, the number of lattice vertices, the border steps of all
    rectangles and the longest half border.
    """
    p, config, _, fan_count, half_steps = lattice
    corner_offsets, _, _, along_u_t, asc_t, at_max_t = tables
    nr = rects.shape[0]
    sx, sy, sz = p.shape[0] - 1, p.shape[1] - 1, p.shape[2] - 1
    n_points = sx * sy * sz
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
    return slot, pos, n, steps, longest


@njit(cache=True)
def contact_midpoints(pos, n_lattice, contact_keys, lattice):  # pragma: no cover - compiled
    """Two midpoints per contact edge, one for each voxel's pair of faces; returns the next free id."""
    p, half_steps = lattice[0], lattice[4]
    sy, sz = p.shape[1] - 1, p.shape[2] - 1
    n = n_lattice
    for i in range(contact_keys.size):
        q0, axis = contact_keys[i] // 3, contact_keys[i] % 3
        x, y, z = q0 // (sy * sz), (q0 // sz) % sy, q0 % sz
        for _side in range(2):  # the same point for both voxels
            pos[n, 0] = half_steps[0, 2 * x + (1 if axis == 0 else 0)]
            pos[n, 1] = half_steps[1, 2 * y + (1 if axis == 1 else 0)]
            pos[n, 2] = half_steps[2, 2 * z + (1 if axis == 2 else 0)]
            n += 1
    return n


@njit(cache=True)
def border_vertices(r, rects, slot, n_lattice, contact_keys, lattice, tables, ent, ent_uv,
                    side_n):  # pragma: no cover - compiled
    """Walk rectangle ``r``'s border, collecting its kept vertices into ``ent``; return their count.

    ``ent_uv`` gets each vertex's lattice coordinates in half steps and
    ``side_n[k]`` the vertices of side ``k``.  Along a side the point moves by the
    face edge's direction, so its flat index moves by a fixed stride and the
    face's cell around it stays the same.
    """
    p, config, fan, _, _ = lattice
    corner_offsets, edge_out, dirs, along_u_t, asc_t, at_max_t = tables
    sy, sz = p.shape[1] - 1, p.shape[2] - 1
    n_keys = contact_keys.size
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
    return e


@njit(cache=True)
def star(r, rects, centre, pos, half_steps, corner_offsets, ent, e, tris, tri_rect, nt):  # pragma: no cover
    """Fan rectangle ``r``'s border vertices around a new vertex at its centre; return the triangle count."""
    d, plane, u0, v0, u1, v1 = rects[r, 0], rects[r, 1], rects[r, 2], rects[r, 3], rects[r, 4], rects[r, 5]
    a = d // 2
    ub, vb = (a + 1) % 3, (a + 2) % 3
    pos[centre, a] = half_steps[a, 2 * (plane + corner_offsets[d, 0, a])]
    pos[centre, ub] = half_steps[ub, u0 + u1]
    pos[centre, vb] = half_steps[vb, v0 + v1]
    for i in range(e):
        tris[nt, 0] = centre
        tris[nt, 1] = ent[i]
        tris[nt, 2] = ent[i + 1 if i + 1 < e else 0]
        tri_rect[nt] = r
        nt += 1
    return nt


@njit(cache=True)
def zipper(r, k1, d, ent, ent_uv, e, side_n, along_u_t, tris, tri_rect, nt):  # pragma: no cover - compiled
    """Zip side ``k1`` (forward) with side ``k1 + 2`` (backward), both by distance from side k1's first corner.

    Returns the triangle count.
    """
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
    return nt


@njit(cache=True)
def drop_unused_midpoints(tris, nt, pos, n, n_lattice, n_keys):  # pragma: no cover - compiled
    """Renumber the vertices after the lattice ones, leaving out the midpoints no triangle uses.

    Every kept lattice id and centre is used.  Returns the vertex count.
    """
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
    return n


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
