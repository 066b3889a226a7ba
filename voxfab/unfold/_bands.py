"""pieces="bands": the surface cut into bands, rows of faces round the shape, which lay flat as straight strips.

Across an axis, the side faces of a layer (faces whose normal is square to
the axis) join edge to edge into closed loops round the shape: across each of
their two edges parallel to the axis lies another side face of the same layer.
A loop cut once folds out into a straight strip one face high, every face
upright (its edge towards the axis's + end on top), since folds across
edges parallel to the axis keep that direction.  Strips are cut to the box's
long side; where the wall goes straight on, the strips of consecutive layers
line up edge to edge and join (:func:`._patches.join_patches`) into
rectangles, which pack on a sheet with little paper lost.  The end faces
(normal along the axis) are flat patches, hung from the strips where they fit;
strips start the pieces.  Of the three axes, with strips loose or not
(:func:`band_pieces`), the cut with the fewest seams is kept.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from voxfab.shape import SurfaceGraph
from voxfab.shape._surface import EDGE_OUT

from ._job import Job
from ._layout import build_net
from ._patches import flat_layouts, join_patches
from ._searchboard import SearchBoard

#: A piece of bands grows until the box is full, not to a quarter of it as flat
#: patches do: the strips of a straight wall then stack into one rectangle as
#: large as the box (a round column's wall: two rectangles of 26x20 on A4).
_BAND_SHARE = 1.0
#: Strips of at least this many faces may lose an edge they could hang from
#: to a strip laid beside it: the rectangles of strips that line up in part.
_LOOSE = 3


def _loops(sg: SurfaceGraph, faces: npt.NDArray[np.int64], axis: int) -> list[list[int]]:
    """The side faces among ``faces`` across ``axis`` as loops, each in order left to right seen from outside.

    Each loop starts at its face of lowest ``(direction, voxel)`` (faces are
    sorted so in the surface graph): a wall that goes straight on starts its
    loops in one column, so their strips line up.
    """
    d = sg.direction
    side = faces[d[faces] // 2 != axis]
    top = np.argmax(EDGE_OUT[d[side]] == 2 * axis, axis=1)  # the edge towards the axis's + end
    right = np.full(sg.face_count, -1, dtype=np.int64)
    # Edges run counter-clockwise, so the edge before the top one is the right one.
    right[side] = sg.neighbor[side, (top + 3) % 4]
    seen = np.zeros(sg.face_count, dtype=bool)
    inside = np.zeros(sg.face_count, dtype=bool)
    inside[faces] = True
    nxt = right.tolist()
    loops = []
    # Surface-graph order is (x, y, z, d): sort by (d, the voxel) for the start of each loop.
    order = side[np.lexsort((sg.voxel[side, 2], sg.voxel[side, 1], sg.voxel[side, 0], d[side]))]
    for f in order.tolist():
        if seen[f]:
            continue
        loop = [f]
        seen[f] = True
        g = nxt[f]
        while g != f and inside[g] and not seen[g]:
            loop.append(g)
            seen[g] = True
            g = nxt[g]
        loops.append(loop)
    return loops


def band_layouts(sg: SurfaceGraph, faces: npt.NDArray[np.int64], axis: int, box: tuple[int, int],
                 pcell: npt.NDArray[np.int64], prot: npt.NDArray[np.int64],
                 ppar: npt.NDArray[np.int64]) -> list[npt.NDArray[np.int64]]:
    """Strips of the loops across ``axis`` (each at most the box's long side) and flat patches of the end faces.

    Writes each patch's layout into ``pcell``, ``prot`` and ``ppar``: a strip
    runs along x from cell (0, 0), each face turned so its top edge lies on
    the cell's top side; a loop longer than the box is cut into strips of
    near-equal length.
    """
    d = sg.direction
    long_side = max(box)
    patches: list[npt.NDArray[np.int64]] = []
    for loop in _loops(sg, faces, axis):
        f = np.array(loop, dtype=np.int64)
        top = np.argmax(EDGE_OUT[d[f]] == 2 * axis, axis=1)
        rot = (2 - top) % 4
        n = math.ceil(f.size / long_side)
        cuts = [round(f.size * t / n) for t in range(n + 1)]
        for a, b in zip(cuts, cuts[1:]):
            strip = f[a:b]
            pcell[strip, 0] = np.arange(b - a)
            pcell[strip, 1] = 0
            prot[strip] = rot[a:b]
            ppar[strip] = np.concatenate([[-1], strip[:-1]])
            patches.append(np.sort(strip))
    ends = faces[d[faces] // 2 == axis]
    if ends.size:
        patches += flat_layouts(sg, ends, min(box), pcell, prot, ppar)
    return patches


def band_pieces(job: Job, faces: npt.NDArray[np.int64], axis: int, loose: bool = True
                ) -> list[tuple[SearchBoard, npt.NDArray[np.int64]]]:
    """Pieces of the bands across ``axis`` (:func:`band_layouts`), joined where they line up.

    With ``loose``, a strip may be laid beside an edge of another strip it does
    not join (strips that line up in part still stack); else only beside
    laid faces, as flat patches are.
    """
    f_all = job.sg.face_count
    pcell = np.zeros((f_all, 2), dtype=np.int64)
    prot = np.zeros(f_all, dtype=np.int64)
    ppar = np.full(f_all, -1, dtype=np.int64)
    patches = band_layouts(job.sg, faces, axis, job.fit, pcell, prot, ppar)
    strips = [bool((job.sg.direction[p] // 2 != axis).all()) for p in patches]
    free = np.zeros(f_all, dtype=bool)
    if loose:
        for p, strip in zip(patches, strips):
            if strip and p.size >= _LOOSE:
                free[p] = True  # a strip: it starts a piece of its own when no edge takes it
    # Strips start the pieces: the strips of a straight wall then stack before an end patch takes them.
    return join_patches(job, patches, pcell, prot, _BAND_SHARE, free, apart=True, seed_first=strips)


def seams_of(job: Job, pieces: list[tuple[SearchBoard, npt.NDArray[np.int64]]]) -> int:
    """The seams (surface edges cut) of pieces laid out on their boards."""
    joined = 0
    for b, placed in pieces:
        net = build_net(job.sg, placed, np.stack([b.pos % b.width, b.pos // b.width], axis=1), b.rot, b.par,
                        seed=0, strategy="")
        joined += len(net.folds)
    return 2 * sum(int(p.size) for _, p in pieces) - joined


def band_cuts(job: Job, faces: npt.NDArray[np.int64]) -> list[list[tuple[SearchBoard, npt.NDArray[np.int64]]]]:
    """The cuts into bands across each axis, strips loose or not, those with fewest seams (then pieces) first."""
    cuts = [band_pieces(job, faces, axis, loose) for axis in range(3) for loose in (True, False)]
    order = sorted(range(len(cuts)), key=lambda t: (seams_of(job, cuts[t]), len(cuts[t]), t))
    return [cuts[t] for t in order]
