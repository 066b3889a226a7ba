"""Compiled contact search: edge-only and corner-only voxel contacts, and bridge boxes as grid cells.

Kept apart so that numba is imported only when a mesh is made.
"""

from __future__ import annotations

import numpy as np
from numba import njit


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


@njit(cache=True)
def paint_boxes(colour, lo, hi):  # pragma: no cover - compiled
    """Give the empty cells (colour 0) of each box ``lo[b] .. hi[b]`` the colour most of its other cells have.

    Ties go to the smaller colour; a box with no coloured cell stays as it is.
    """
    count = np.zeros(256, dtype=np.int64)
    for b in range(lo.shape[0]):
        count[:] = 0
        for x in range(lo[b, 0], hi[b, 0]):
            for y in range(lo[b, 1], hi[b, 1]):
                for z in range(lo[b, 2], hi[b, 2]):
                    count[colour[x, y, z]] += 1
        m = 0
        for c in range(1, 256):
            if count[c] > 0 and (m == 0 or count[c] > count[m]):
                m = c
        if m == 0:
            continue
        for x in range(lo[b, 0], hi[b, 0]):
            for y in range(lo[b, 1], hi[b, 1]):
                for z in range(lo[b, 2], hi[b, 2]):
                    if colour[x, y, z] == 0:
                        colour[x, y, z] = m
