"""An independent check of a zipper net: its cut edges, read off the surface, form one simple path."""

from __future__ import annotations

import numpy as np

from voxfab.shape import surface_graph


def cuts_form_one_path(grid: np.ndarray, net) -> bool:  # noqa: ANN001
    """Whether the surface edges that are not folds of ``net`` form one path through the surface's vertices."""
    sg = surface_graph(grid)
    folded = {tuple(sorted(p)) for p in net.folds.tolist()}
    cut = []
    for a in range(sg.face_count):
        for k in range(4):
            b, kb = int(sg.neighbor[a, k]), int(sg.neighbor_edge[a, k])
            if (a, k) < (b, kb) and (min(a, b), max(a, b)) not in folded:
                cut.append((int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])))
    deg: dict[int, int] = {}
    for u, v in cut:
        deg[u], deg[v] = deg.get(u, 0) + 1, deg.get(v, 0) + 1
    if not cut or max(deg.values()) > 2 or len(cut) != len(deg) - 1:
        return False
    adj: dict[int, set[int]] = {}
    for u, v in cut:
        adj.setdefault(u, set()).add(v)
        adj.setdefault(v, set()).add(u)
    seen, todo = {cut[0][0]}, [cut[0][0]]
    while todo:
        for v in adj[todo.pop()]:
            if v not in seen:
                seen.add(v)
                todo.append(v)
    return len(seen) == len(deg)
