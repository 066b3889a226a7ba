"""Join the parts of voxel art into one 6-connected piece with as few added voxels as can be found.

Voxel art is rarely one piece of face-connected cubes: arms touch a body along an
edge, a feather touches a hat at a corner.  No one-piece net and no one-body print
exists for it.  :func:`join_parts` adds voxels in empty cells until every part is
face-connected to the largest one, by the shortest-path heuristic for Steiner trees
(Takahashi and Matsuyama, 1980): from the piece grown so far, a breadth-first search
through empty cells finds the nearest other part; the cells of that path are filled;
repeat.  Parts that touch along an edge are joined by one voxel and parts that
touch at a corner by two, which is the fewest possible for each such contact.
"""

from __future__ import annotations

import dataclasses
from collections import deque

import numpy as np
import numpy.typing as npt

from voxfab._shared.typing import BoolGrid
from voxfab._shared.validate import as_grid

from ._ops import label_components

__all__ = ["Join", "join_parts", "describe_parts"]

#: Parts of at most this many voxels are listed by place: single-voxel eyes, buttons, a feather.
SMALL_PART = 8

_STEPS = ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1))


@dataclasses.dataclass(frozen=True)
class Join:
    """Voxels added to join one part to the piece.

    Attributes
    ----------
    part_voxels : int
        The size of the part joined (in voxels).
    part_at : (int, int, int)
        One voxel of that part, to find it.
    added : tuple of (int, int, int)
        The voxels added, from the piece to the part.
    """

    part_voxels: int
    part_at: tuple[int, int, int]
    added: tuple[tuple[int, int, int], ...]

    def describe(self) -> str:
        """One line: which part, and where the voxels went."""
        where = ", ".join(f"({x}, {y}, {z})" for x, y, z in self.added)
        s = "s" if len(self.added) > 1 else ""
        return (f"joined the part of {self.part_voxels} voxel{'s' * (self.part_voxels > 1)} at "
                f"({', '.join(map(str, self.part_at))}) with {len(self.added)} voxel{s} at {where}")


def join_parts(grid: npt.ArrayLike) -> tuple[BoolGrid, list[Join]]:
    """The shape made one 6-connected piece by filling empty cells, and what was added.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        Any shape; its parts are its 6-connected components.

    Returns
    -------
    joined : (X, Y, Z) bool ndarray
        ``grid`` with the added voxels (the same array size: cells outside it are never used).
    joins : list of Join
        One per part joined, in the order joined (empty for a shape already in one piece).

    Notes
    -----
    Each step is a breadth-first search over the grid's cells, so a shape of ``P``
    parts costs at most ``P - 1`` searches of at most ``X * Y * Z`` cells (a path
    that passes by a further part joins it too).
    """
    g = np.array(as_grid(grid), dtype=bool, copy=True)
    labels, count = label_components(g)
    if count <= 1:
        return g, []
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    piece = labels == int(np.argmax(sizes))
    joins: list[Join] = []
    while (g & ~piece).any():
        path, reached = _nearest_part(piece, g, labels)
        for cell in path:
            g[cell] = True
        part = labels == reached
        piece |= part
        for cell in path:
            piece[cell] = True
        at = tuple(int(v) for v in np.argwhere(part)[0])
        joins.append(Join(int(sizes[reached]), at, tuple(path)))  # type: ignore[arg-type]
        # A path may touch further parts on its way: they are in the piece now too.
        piece = _grow_into_touching(piece, g)
    return g, joins


def _nearest_part(piece: np.ndarray, filled: np.ndarray, labels: np.ndarray) -> tuple[list, int]:
    """The empty cells of a shortest path from ``piece`` to a voxel of another part, and that part's label."""
    shape = piece.shape
    parent: dict[tuple[int, int, int], tuple[int, int, int] | None] = {}
    queue: deque[tuple[int, int, int]] = deque()
    # The first layer: empty cells next to the piece, in a fixed order so the result never varies.
    for cell in map(tuple, np.argwhere(piece)):
        for step in _STEPS:
            nxt = (cell[0] + step[0], cell[1] + step[1], cell[2] + step[2])
            if all(0 <= nxt[a] < shape[a] for a in range(3)) and not filled[nxt] and nxt not in parent:
                parent[nxt] = None
                queue.append(nxt)  # type: ignore[arg-type]
    while queue:
        cell = queue.popleft()
        for step in _STEPS:
            nxt = (cell[0] + step[0], cell[1] + step[1], cell[2] + step[2])
            if not all(0 <= nxt[a] < shape[a] for a in range(3)) or nxt in parent:
                continue
            if filled[nxt] and not piece[nxt]:
                path = [cell]
                while parent[path[-1]] is not None:
                    path.append(parent[path[-1]])  # type: ignore[arg-type]
                return [tuple(int(v) for v in c) for c in reversed(path)], int(labels[nxt])
            if not filled[nxt]:
                parent[nxt] = cell
                queue.append(nxt)
    raise AssertionError("a grid with several parts always has a path between them")


def _grow_into_touching(piece: np.ndarray, filled: np.ndarray) -> np.ndarray:
    """``piece`` with every filled voxel face-connected to it."""
    labels, _ = label_components(filled)
    keep = np.unique(labels[piece])
    return np.isin(labels, keep[keep > 0])


def describe_parts(grid: npt.ArrayLike) -> str:
    """One line on a shape's 6-connected parts: how many, the largest, and the small ones by place."""
    labels, count = label_components(as_grid(grid))
    sizes = np.bincount(labels.ravel())[1:]
    small = [(int(sizes[i]), tuple(int(v) for v in np.argwhere(labels == i + 1)[0]))
             for i in range(count) if sizes[i] <= SMALL_PART]
    line = f"{count} part{'s' * (count > 1)} (largest {int(sizes.max())} voxels)"
    if small:
        listed = ", ".join(f"{n} at ({', '.join(map(str, at))})" for n, at in small[:12])
        more = f" and {len(small) - 12} more" if len(small) > 12 else ""
        line += f"; small parts (voxels at): {listed}{more}"
    return line
