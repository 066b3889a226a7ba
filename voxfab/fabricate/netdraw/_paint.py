"""Coloured nets: each face printed in its voxel's colour, marks legible over it, tinted tabs and a bleed.

A net face is a face of one voxel (``Net.voxel``), so its colour is that
voxel's.  Over the fills, folds, seam labels and piece numbers are printed in
black on light faces and white on dark ones, split by CIELAB lightness
(:data:`INK_SPLIT`), so every mark differs from its face by at least 50 L*.
A fold runs between two faces, whose lightness may fall on both sides of the
split: it takes the ink of the pair's mean lightness and a halo of the other,
which keeps it clear of both.

A glue tab is hidden under the face across its seam once glued, so it takes a
light tint of that face's colour (the face across the edge on the shape, which
for a seam to another piece is on that piece).

The bleed carries the colour past the cut line, so a print cut a little off
its register shows no white edge.  Each face's fill is grown outward across
its edges on the cut outline (square corners included), each tab's fill
across its sides.  The bleed is painted first, under every face and tab fill:
where it reaches other paper (a neighbour's tab, a slit's other side, a piece
packed close by) that paper's own colour covers it, so it shows only outside
the cut lines.  Slits (cuts between faces side by side in the plane) get no
bleed: the paper on the far side is the neighbour's face.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab.drawing import Fill, Polylines
from voxfab.shape import SurfaceGraph
from voxfab.shape._colour import VoxelColours, hex_colour, srgb_to_lab
from voxfab.unfold import Net

from ._geometry import face_map

_NEXT = np.array([1, 2, 3, 0])
_PREV = np.array([3, 0, 1, 2])

#: CIELAB lightness from which a fill takes black marks; darker fills take white ones.
INK_SPLIT = 50.0
#: Ink codes: 0 the layer's own colour (uncoloured nets), then black and white.
BLACK, WHITE = 1, 2
#: Colour and halo of each ink.
INKS = {BLACK: ("#000000", "#ffffff"), WHITE: ("#ffffff", "#000000")}
#: Share of white in a tab's tint of the face it glues under.
TINT = 0.7


@dataclasses.dataclass(frozen=True, eq=False)
class Paint:
    """The colours of a net's faces, ready to draw.

    Attributes
    ----------
    face : (F, 3) uint8 ndarray
        RGB of each net face (its voxel's colour).
    across : (F, 4, 3) uint8 ndarray
        RGB of the face across each edge on the shape (what a tab on that edge glues under).
    light : (F,) float ndarray
        CIELAB L* of each face's colour.
    ink : (F,) int ndarray
        :data:`BLACK` or :data:`WHITE`, the marks' ink on each face.
    bleed : float
        How far the colour runs past the cut lines, mm.
    """

    face: npt.NDArray[np.uint8]
    across: npt.NDArray[np.uint8]
    light: npt.NDArray[np.float64]
    ink: npt.NDArray[np.int64]
    bleed: float

    def edge_ink(self, partner: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
        """``(F, 4)`` ink of the line on each edge: by the mean lightness of the face and ``partner``
        (the face across it in the net, -1 for none)."""
        light = self.light
        other = np.where(partner >= 0, light[np.maximum(partner, 0)], light[:, None])
        return ink_of_lightness((light[:, None] + other) / 2)


def lightness(rgb: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """CIELAB L* of sRGB colours ``(..., 3)``."""
    return srgb_to_lab(np.asarray(rgb))[..., 0]


def ink_of_lightness(light: npt.NDArray[np.float64]) -> npt.NDArray[np.int64]:
    """:data:`BLACK` where ``light`` is at least :data:`INK_SPLIT`, else :data:`WHITE`."""
    return np.where(light >= INK_SPLIT, BLACK, WHITE).astype(np.int64)


def net_paint(graph: SurfaceGraph, net: Net, colours: VoxelColours, bleed: float) -> Paint:
    """The colours of ``net`` (a net, or pieces joined, of the surface ``graph``) from the voxels' ``colours``."""
    face = colours.at(net.voxel)[:, :3]
    across_face = graph.neighbor[face_map(graph, net)]
    across = colours.at(graph.voxel[across_face.ravel()])[:, :3].reshape(-1, 4, 3)
    light = lightness(face)
    return Paint(face, across, light, ink_of_lightness(light), float(bleed))


def tint(rgb: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """A light tint of ``rgb`` (``(..., 3)``): :data:`TINT` of white mixed in."""
    c = np.asarray(rgb, dtype=np.float64)
    return np.round(c + (255.0 - c) * TINT).astype(np.uint8)


def grown_squares(pos: npt.NDArray[np.float64], grow: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Faces ``(n, 4, 2)`` (counter-clockwise squares) with edge ``k`` moved out by ``grow[:, k]`` mm."""
    d = pos[:, _NEXT] - pos
    d = d / np.linalg.norm(d, axis=2, keepdims=True)
    out = np.stack([d[..., 1], -d[..., 0]], axis=2) * grow[..., None]  # outward normal times the growth
    return pos + out + out[:, _PREV]


def grown_polygons(poly: npt.NDArray[np.float64], by: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Convex polygons ``(n, m, 2)`` (either orientation) with edge ``k`` (corner ``k`` to ``k + 1``)
    moved out by ``by[:, k]`` mm, the corners where the moved edges meet."""
    if not poly.shape[0]:
        return poly
    m = poly.shape[1]
    nxt, prv = (np.arange(m) + 1) % m, (np.arange(m) - 1) % m
    x, y = poly[..., 0], poly[..., 1]
    ccw = np.sign((x * y[:, nxt] - x[:, nxt] * y).sum(axis=1))[:, None, None]
    d = poly[:, nxt] - poly
    d = d / np.maximum(np.linalg.norm(d, axis=2, keepdims=True), 1e-12)
    n = np.stack([d[..., 1], -d[..., 0]], axis=2) * ccw
    # Corner k moves by the v with n[k-1]·v = by[k-1] and n[k]·v = by[k].
    rows = np.stack([n[:, prv], n], axis=2)
    return poly + np.linalg.solve(rows, np.stack([by[:, prv], by], axis=2)[..., None])[..., 0]


def _hex(rgb: npt.NDArray[np.uint8]) -> tuple[str, ...]:
    """``#rrggbb`` of each colour ``(n, 3)``, formatted once per distinct colour."""
    if not rgb.shape[0]:
        return ()
    used, inverse = np.unique(rgb, axis=0, return_inverse=True)
    text = [hex_colour(c) for c in used]
    return tuple(text[i] for i in inverse.ravel().tolist())


def _rings(rings: npt.NDArray[np.float64], rgb: npt.NDArray[np.uint8], names: list[str],
           nonzero: bool = True) -> tuple[Fill, ...]:
    """``rings`` (n, m, 2), each an area of its own in its colour ``rgb`` (n, 3) with its id, as one fill."""
    n, m = rings.shape[:2]
    if not n:
        return ()
    lines = Polylines(rings.reshape(-1, 2), np.arange(0, m * n + 1, m), np.ones(n, dtype=bool))
    return (Fill(lines, "#000000", nonzero=nonzero, colors=_hex(rgb), names=tuple(names)),)


def sheet_fills(faces: npt.NDArray[np.float64], face_rgb: npt.NDArray[np.uint8], names: list[str],
                outline: npt.NDArray[np.bool_], tabs: npt.NDArray[np.float64], tab_rgb: npt.NDArray[np.uint8],
                bleed: float) -> tuple[Fill, ...]:
    """The fills of one sheet of a coloured net, in painting order: bleed, tabs, faces.

    Parameters
    ----------
    faces : (n, 4, 2) float ndarray
        The faces on the sheet, mm, counter-clockwise.
    face_rgb : (n, 3) uint8 ndarray
    names : list of str
        Each face's id (``face-I``, its index in the net's JSON).
    outline : (n, 4) bool ndarray
        Edges on the cut outline (not folds, not slits).
    tabs : (t, 4, 2) float ndarray
        The glue tabs on the sheet, mm.
    tab_rgb : (t, 3) uint8 ndarray
        Their tints.
    bleed : float
        mm.
    """
    under: tuple[Fill, ...] = ()
    if bleed > 0:
        out = outline.any(axis=1)  # faces on the outline: the others need no bleed
        grown = [grown_squares(faces[out], np.where(outline[out], bleed, 0.0))]
        # A tab's fold stays put (the face covers it); its three cut sides bleed.
        grow = np.where(np.arange(4) == 0, 0.0, bleed)[None, :].repeat(tabs.shape[0], axis=0)
        grown.append(grown_polygons(tabs, grow))
        under = _rings(np.concatenate(grown), np.concatenate([face_rgb[out], tab_rgb]),
                       [f"bleed-{i}" for i in range(int(out.sum()) + tabs.shape[0])])
    tab_names = [f"tabs-{i}" for i in range(tabs.shape[0])]
    return under + _rings(tabs, tab_rgb, tab_names) + _rings(faces, face_rgb, names, nonzero=False)
