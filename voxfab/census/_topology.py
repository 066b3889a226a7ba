"""Which polycubes the unzipping model of Demaine, Demaine, Eppstein and O'Rourke (2020) takes.

The paper's polycubes have a surface that is a 2-manifold of genus 0: no two
cubes meet only along an edge or only at a vertex (in the cubes or in the empty
space around them), and the surface has no handle.  Its vertices are every cube
corner on the surface; a vertex with four squares (360 degrees) is *flat*, any
other (three, five or six squares) a *corner*.
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import numpy.typing as npt

__all__ = ["SURFACE_KINDS", "Topology", "grid_of", "topology"]

#: How a polycube's surface is classified: the paper's model takes ``manifold`` (genus 0) only.
SURFACE_KINDS = ("manifold", "edge touching", "vertex touching", "handle")


def grid_of(cells: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    """The bool grid ``[x, y, z]`` of a list of cells, translated to the origin."""
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 3)
    c = c - c.min(axis=0)
    g = np.zeros(tuple((c.max(axis=0) + 1).tolist()), dtype=bool)
    g[tuple(c.T)] = True
    return g


def _octant_table() -> npt.NDArray[np.bool_]:
    """For each of the 256 fillings of the 8 cubes round a lattice point: is the surface a disk there?

    It is when the filled cubes and the empty ones are each one face-connected
    group inside the 2 x 2 x 2 block (or the point is inside or outside).
    """
    octants = list(itertools.product((0, 1), repeat=3))
    pairs = [(i, j) for i, j in itertools.combinations(range(8), 2)
             if sum(abs(a - b) for a, b in zip(octants[i], octants[j])) == 1]

    def connected(members: list[int]) -> bool:
        if not members:
            return True
        seen, todo = {members[0]}, [members[0]]
        while todo:
            a = todo.pop()
            for i, j in pairs:
                for x, y in ((i, j), (j, i)):
                    if x == a and y in members and y not in seen:
                        seen.add(y)
                        todo.append(y)
        return len(seen) == len(members)

    table = np.zeros(256, dtype=bool)
    for mask in range(256):
        full = [i for i in range(8) if mask >> i & 1]
        empty = [i for i in range(8) if not mask >> i & 1]
        table[mask] = connected(full) and connected(empty)
    return table


_DISK = _octant_table()


@dataclasses.dataclass(frozen=True)
class Topology:
    """The surface of one polycube as the paper sees it.

    Attributes
    ----------
    kind : str
        One of :data:`SURFACE_KINDS`.
    genus : int
        Handles of the surface (0 unless ``kind`` is ``handle``; -1 when not a manifold).
    corners, flats : (int, int)
        Corner and flat vertices of each lattice colour (``x + y + z`` even, odd).
    """

    kind: str
    genus: int
    corners: tuple[int, int]
    flats: tuple[int, int]


def topology(grid: npt.ArrayLike) -> Topology:
    """Classify a 6-connected polycube's surface and count its vertices by kind and colour."""
    g = np.pad(np.asarray(grid, dtype=bool), 1)
    # Each lattice point of the padded grid with its 8 cubes, as an 8-bit filling.
    mask = np.zeros(tuple(s - 1 for s in g.shape), dtype=np.int64)
    for bit, (dx, dy, dz) in enumerate(itertools.product((0, 1), repeat=3)):
        mask |= g[dx:dx + mask.shape[0], dy:dy + mask.shape[1], dz:dz + mask.shape[2]].astype(np.int64) << bit
    on_surface = (mask != 0) & (mask != 255)
    # Two cubes on one diagonal of the 2 x 2 square round an edge, the other two empty: an edge touching.
    edge = False
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        p00, p11, p01, p10 = (_shifted(g, b, c, ob, oc) for ob, oc in ((0, 0), (1, 1), (0, 1), (1, 0)))
        edge |= bool(((p00 & p11 & ~p01 & ~p10) | (p01 & p10 & ~p00 & ~p11)).any())
    points = np.argwhere(on_surface)
    # mask[i, j, k] is the point between padded cubes i and i + 1 ...: the lattice point (i, j, k) of the grid.
    colour = points.sum(axis=1) % 2
    # Squares round a lattice point of a manifold surface: 3 (1 or 7 cubes), 4 (2 in a row, 4 in a slab,
    # 6 round a notch...), 5 or 6; count them from the faces of the cubes at that point.
    squares = _squares_at(mask[on_surface])
    flat = squares == 4
    corners = (int((~flat & (colour == 0)).sum()), int((~flat & (colour == 1)).sum()))
    flats = (int((flat & (colour == 0)).sum()), int((flat & (colour == 1)).sum()))
    if edge:
        return Topology("edge touching", -1, corners, flats)
    if not _DISK[mask[on_surface]].all():
        return Topology("vertex touching", -1, corners, flats)
    faces = int(sum((g & ~np.roll(g, sh, axis=ax)).sum() for ax in range(3) for sh in (1, -1)))
    euler = points.shape[0] - 2 * faces + faces  # V - E + F, with E = 2F (each square has 4 edges, each shared)
    genus = (2 - euler) // 2
    return Topology("manifold" if genus == 0 else "handle", genus, corners, flats)


def _shifted(g: npt.NDArray[np.bool_], b: int, c: int, ob: int, oc: int) -> npt.NDArray[np.bool_]:
    """``g`` seen from offset ``(ob, oc)`` along axes ``b`` and ``c``: the four cubes round each edge along the third axis."""
    s = [slice(None)] * 3
    s[b] = slice(ob, g.shape[b] - 1 + ob)
    s[c] = slice(oc, g.shape[c] - 1 + oc)
    return g[tuple(s)]


def _square_table() -> npt.NDArray[np.int64]:
    """Unit squares of the surface that meet at the centre of a 2 x 2 x 2 block, for each of its 256 fillings."""
    octants = list(itertools.product((0, 1), repeat=3))
    out = np.zeros(256, dtype=np.int64)
    for mask in range(256):
        count = 0
        for i, j in itertools.combinations(range(8), 2):
            if sum(abs(a - b) for a, b in zip(octants[i], octants[j])) == 1:
                count += (mask >> i & 1) != (mask >> j & 1)  # a square between a filled and an empty cube
        out[mask] = count
    return out


_SQUARES = _square_table()


def _squares_at(masks: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    return _SQUARES[masks]
