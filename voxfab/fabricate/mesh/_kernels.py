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
    start = np.zeros(nv + 1, dtype=np.int64)
    for h in range(nh):
        start[t[h // 3, h % 3] + 1] += 1
    for i in range(nv):
        start[i + 1] += start[i]
    fill = start[:-1].copy()
    # Half-edges grouped by their start vertex, with their end vertex beside them
    # so that the scans below read contiguous memory.
    out = np.empty(nh, dtype=np.int64)
    out_end = np.empty(nh, dtype=np.int64)
    for h in range(nh):
        a = t[h // 3, h % 3]
        out[fill[a]] = h
        out_end[fill[a]] = t[h // 3, (h % 3 + 1) % 3]
        fill[a] += 1
    twin = np.empty(nh, dtype=np.int64)
    for a in range(nv):
        for i in range(start[a], start[a + 1]):
            b = out_end[i]
            same = 0
            for j in range(start[a], start[a + 1]):
                if out_end[j] == b:
                    same += 1
            if same != 1:
                return 1, labels, 0
            back = 0
            tw = -1
            for j in range(start[b], start[b + 1]):
                if out_end[j] == a:
                    back += 1
                    tw = out[j]
            if back != 1:
                return 2, labels, 0
            twin[out[i]] = tw
    # The corner after h around its start vertex begins the half-edge after h's twin.
    seen = np.zeros(nh, dtype=np.bool_)
    fans = 0
    for h in range(nh):
        if seen[h]:
            continue
        fans += 1
        g = h
        while not seen[g]:
            seen[g] = True
            tw = twin[g]
            g = (tw // 3) * 3 + (tw % 3 + 1) % 3
    if fans != nv:
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
def permutation_cycles(nxt):  # pragma: no cover - compiled
    """Label the cycles of a permutation by order of their smallest element.

    Returns ``(labels, n)``: ``labels[i]`` is the number of cycles whose smallest
    element is below that of the cycle of ``i``.
    """
    n = nxt.size
    labels = np.full(n, -1, dtype=np.int64)
    count = 0
    for i in range(n):
        if labels[i] >= 0:
            continue
        j = i
        while labels[j] < 0:
            labels[j] = count
            j = nxt[j]
        count += 1
    return labels, count


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
