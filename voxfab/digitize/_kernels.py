"""Compiled loops (numba): point-in-polygon, stroke distance, RMF transport.

Imported lazily by the modules that need them; compiled once and cached on disk.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["even_odd", "stroke", "transport"]


@njit(cache=True, nogil=True)
def even_odd(px, py, segs, ylo, bh, start, items):  # pragma: no cover - compiled
    """-1 inside, +1 outside, 0 on an edge of the closed polygons (even-odd rule)."""
    nb = len(start) - 1
    out = np.empty(px.shape[0])
    for i in range(px.shape[0]):
        x, y = px[i], py[i]
        if not (x == x and y == y):
            out[i] = 1.0
            continue
        b = int(math.floor((y - ylo) / bh))
        if b < 0 or b >= nb:
            out[i] = 1.0
            continue
        inside = False
        on_edge = False
        for j in range(start[b], start[b + 1]):
            s = items[j]
            x0, y0, x1, y1 = segs[s, 0], segs[s, 1], segs[s, 2], segs[s, 3]
            cr = (x1 - x0) * (y - y0) - (y1 - y0) * (x - x0)
            if cr == 0.0 and min(x0, x1) <= x <= max(x0, x1) and min(y0, y1) <= y <= max(y0, y1):
                on_edge = True
                break
            if (y0 > y) != (y1 > y):
                xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
                if x < xc:
                    inside = not inside
        out[i] = 0.0 if on_edge else (-1.0 if inside else 1.0)
    return out


@njit(cache=True, nogil=True)
def stroke(px, py, segs, ylo, bh, start, items, half):  # pragma: no cover - compiled
    """Distance to the nearest segment minus ``half`` (2 * half where no segment is near)."""
    nb = len(start) - 1
    out = np.empty(px.shape[0])
    for i in range(px.shape[0]):
        x, y = px[i], py[i]
        best = np.inf
        if x == x and y == y:
            b = int(math.floor((y - ylo) / bh))
            if 0 <= b < nb:
                for j in range(start[b], start[b + 1]):
                    s = items[j]
                    x0, y0 = segs[s, 0], segs[s, 1]
                    dx, dy = segs[s, 2] - x0, segs[s, 3] - y0
                    ll = dx * dx + dy * dy
                    t = ((x - x0) * dx + (y - y0) * dy) / ll if ll > 0 else 0.0
                    t = min(1.0, max(0.0, t))
                    ex, ey = x - x0 - t * dx, y - y0 - t * dy
                    d = ex * ex + ey * ey
                    if d < best:
                        best = d
        out[i] = math.sqrt(best) - half if best < np.inf else 2.0 * half
    return out


@njit(cache=True, nogil=True)
def transport(x, t, r0):  # pragma: no cover - compiled
    """Rotation-minimizing reference vectors by double reflection (Wang et al. 2008)."""
    m = x.shape[0]
    r = np.empty((m, 3))
    r[0] = r0
    for i in range(m - 1):
        v1 = x[i + 1] - x[i]
        c1 = v1[0] * v1[0] + v1[1] * v1[1] + v1[2] * v1[2]
        if c1 == 0.0:
            r[i + 1] = r[i]
            continue
        rl = r[i] - (2.0 / c1) * (v1[0] * r[i, 0] + v1[1] * r[i, 1] + v1[2] * r[i, 2]) * v1
        tl = t[i] - (2.0 / c1) * (v1[0] * t[i, 0] + v1[1] * t[i, 1] + v1[2] * t[i, 2]) * v1
        v2 = t[i + 1] - tl
        c2 = v2[0] * v2[0] + v2[1] * v2[1] + v2[2] * v2[2]
        if c2 == 0.0:
            r[i + 1] = rl
        else:
            r[i + 1] = rl - (2.0 / c2) * (v2[0] * rl[0] + v2[1] * rl[1] + v2[2] * rl[2]) * v2
    return r


@njit(cache=True, nogil=True)
def closest_on_grid(xs, ys, zs, pts, closed, reach):  # pragma: no cover - compiled
    """Closest polyline segment for every point of the grid ``xs × ys × zs`` within ``reach``.

    Returns squared distances (inf when farther than reach), the segment index
    (segment a runs from point a to point a + 1, wrapping when closed) and the
    unclamped projection parameter on it.
    """
    nx, ny, nz = xs.shape[0], ys.shape[0], zs.shape[0]
    m = pts.shape[0]
    nseg = m if closed else m - 1
    best = np.full((nx, ny, nz), np.inf)
    seg = np.full((nx, ny, nz), -1, dtype=np.int64)
    par = np.zeros((nx, ny, nz))
    r2 = reach * reach
    for a in range(nseg):
        b = (a + 1) % m
        x0, y0, z0 = pts[a, 0], pts[a, 1], pts[a, 2]
        dx, dy, dz = pts[b, 0] - x0, pts[b, 1] - y0, pts[b, 2] - z0
        ll = dx * dx + dy * dy + dz * dz
        if ll == 0.0:
            continue
        i0 = np.searchsorted(xs, min(x0, x0 + dx) - reach)
        i1 = np.searchsorted(xs, max(x0, x0 + dx) + reach, side="right")
        j0 = np.searchsorted(ys, min(y0, y0 + dy) - reach)
        j1 = np.searchsorted(ys, max(y0, y0 + dy) + reach, side="right")
        k0 = np.searchsorted(zs, min(z0, z0 + dz) - reach)
        k1 = np.searchsorted(zs, max(z0, z0 + dz) + reach, side="right")
        for i in range(i0, i1):
            px = xs[i] - x0
            for j in range(j0, j1):
                py = ys[j] - y0
                for k in range(k0, k1):
                    pz = zs[k] - z0
                    t = (px * dx + py * dy + pz * dz) / ll
                    tc = min(1.0, max(0.0, t))
                    ex, ey, ez = px - tc * dx, py - tc * dy, pz - tc * dz
                    d = ex * ex + ey * ey + ez * ez
                    if d <= r2 and d < best[i, j, k]:
                        best[i, j, k] = d
                        seg[i, j, k] = a
                        par[i, j, k] = t
    return best, seg, par
