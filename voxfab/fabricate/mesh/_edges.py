"""Compiled checker passes: edge use, vertex fans, shells, index problems, bounds and measures.

Kept apart so that numba is imported only when a mesh is made.
"""

from __future__ import annotations

import numpy as np
from numba import njit


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
