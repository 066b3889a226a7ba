"""Nets laid out by hand for tests, independent of the net engine.

Each face is laid beside its parent across their shared edge, exactly as the
surface graph joins them; a face whose cell is taken waits for another parent.
"""

from collections import deque

import numpy as np

from voxfab.shape import surface_graph
from voxfab.unfold import Net


def tree_net(grid, tree=None, *, root=0, order=(0, 1, 2, 3), seed=7):
    """A net of ``grid``: the given spanning ``tree`` (fold pairs, parents first),
    or a breadth-first one from face ``root`` visiting edges in ``order``."""
    sg = surface_graph(grid)
    nf = sg.face_count
    c2 = np.zeros((nf, 4, 2), dtype=np.int64)
    c2[root] = [(0, 0), (1, 0), (1, 1), (0, 1)]
    placed = np.zeros(nf, dtype=bool)
    placed[root] = True
    cells = {(0, 0)}
    folds: list[tuple[int, int]] = []

    def attach(f: int, k: int) -> bool:
        g, kk = int(sg.neighbor[f, k]), int(sg.neighbor_edge[f, k])
        p0, p1 = c2[f, k], c2[f, (k + 1) % 4]
        d = p1 - p0
        n = np.array([d[1], -d[0]])
        gc = np.zeros((4, 2), dtype=np.int64)
        gc[kk], gc[(kk + 1) % 4], gc[(kk + 2) % 4], gc[(kk + 3) % 4] = p1, p0, p0 + n, p1 + n
        cell = tuple(gc.min(axis=0).tolist())
        if cell in cells:
            return False
        cells.add(cell)
        c2[g] = gc
        placed[g] = True
        folds.append((f, g))
        return True

    if tree is not None:
        for f, g in tree:
            k = int(np.flatnonzero(sg.neighbor[f] == g)[0])
            assert placed[f] and not placed[g] and attach(f, k), "this tree overlaps"
    else:
        queue = deque([root])
        while queue:
            f = queue.popleft()
            for k in order:
                g = int(sg.neighbor[f, k])
                if not placed[g] and attach(f, k):
                    queue.append(g)
    assert placed.all() and len(cells) == nf, "no net laid out"
    kinds = np.array([sg.fold[f, int(np.flatnonzero(sg.neighbor[f] == g)[0])] for f, g in folds])
    return Net(voxel=sg.voxel, normal=sg.normal, corners3d=sg.corners, corners2d=c2, folds=np.array(folds),
               seed=seed, strategy="layout", mountain=int((kinds == 1).sum()), valley=int((kinds == -1).sum()),
               flat=int((kinds == 0).sum()))
