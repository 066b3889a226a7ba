"""A hand-built net for tests: breadth-first unfolding of the surface graph.

Each face is laid beside its parent across their shared edge, exactly as the
surface graph joins them; :func:`tree_net` refuses a tree that overlaps.
"""

from collections import deque

import numpy as np

from voxfab.shape import surface_graph
from voxfab.unfold import Net


def tree_net(grid, root=0, order=(0, 1, 2, 3)):
    g = surface_graph(grid)
    n = g.face_count
    c2 = np.zeros((n, 4, 2), dtype=np.int64)
    placed = np.zeros(n, dtype=bool)
    c2[root] = [[0, 0], [1, 0], [1, 1], [0, 1]]
    placed[root] = True
    folds = []
    queue = deque([root])
    while queue:
        f = queue.popleft()
        for k in order:
            j, kk = int(g.neighbor[f, k]), int(g.neighbor_edge[f, k])
            if placed[j]:
                continue
            p, q = c2[f, k], c2[f, (k + 1) % 4]
            out = np.rint(2 * ((p + q) / 2 - c2[f].mean(axis=0))).astype(np.int64)
            c = np.zeros((4, 2), dtype=np.int64)
            c[kk], c[(kk + 1) % 4], c[(kk + 2) % 4], c[(kk + 3) % 4] = q, p, p + out, q + out
            c2[j] = c
            placed[j] = True
            folds.append((f, j))
            queue.append(j)
    cells = {tuple(x) for x in c2.min(axis=1).tolist()}
    assert len(cells) == n, "this tree overlaps"
    return Net(voxel=g.voxel, normal=g.normal, corners3d=g.corners, corners2d=c2, folds=np.array(folds),
               seed=0, strategy="bfs")
