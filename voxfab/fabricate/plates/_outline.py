"""Voxel layers → exact outlines: one polygon with holes per 4-connected piece.

Layers are taken along a slicing axis and the grid is cropped to its bounding
box first, so layer 1 is the lowest filled layer.  The in-plane axes ``(u, v)``
are chosen so that ``u × v`` points along the slicing axis (right-handed): the
plates are drawn as seen from above the stack.
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid, check_choice, check_positive
from voxfab.shape import crop


class Axis(enum.Enum):
    """The slicing axis; plates stack along it."""

    X = "x"
    Y = "y"
    Z = "z"


#: Axis → transpose that moves the slicing axis first and keeps (u, v, w) right-handed.
_TRANSPOSE: dict[Axis, tuple[int, int, int]] = {
    Axis.X: (0, 1, 2),  # layers [x], u = y, v = z
    Axis.Y: (1, 2, 0),  # layers [y], u = z, v = x
    Axis.Z: (2, 0, 1),  # layers [z], u = x, v = y
}


@dataclasses.dataclass(frozen=True, eq=False)
class Piece:
    """One 4-connected piece of one layer.

    Attributes
    ----------
    layer : int
        1-based layer number, counted from the bottom of the stack.
    index : int
        1-based piece number inside the layer (order of the first cell in
        ``(u, v)`` raster order).
    cells : (N, 2) int ndarray
        The piece's cells as ``(u, v)`` indices, sorted.
    outline : shapely.Polygon
        Exact voxel outline in cell units (one unit = one pitch), exterior
        counter-clockwise, holes clockwise, no collinear vertices.
    """

    layer: int
    index: int
    cells: npt.NDArray[np.int64]
    outline: object

    @property
    def id(self) -> str:
        """The piece number ``"layer-piece"``."""
        return f"{self.layer}-{self.index}"


def axis_value(axis: str | Axis) -> Axis:
    """Return ``axis`` as an :class:`Axis` (``'x'``, ``'y'`` or ``'z'``)."""
    return check_choice(axis, Axis, name="axis")


def layer_stack(grid: npt.ArrayLike, *, axis: str | Axis = "z") -> npt.NDArray[np.bool_]:
    """Return the cropped grid as layers ``[w, u, v]`` along ``axis``.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The voxel shape.
    axis : {'x', 'y', 'z'}
        Slicing axis.

    Returns
    -------
    layers : (L, U, V) bool ndarray
        ``layers[k]`` is layer ``k + 1`` from the bottom.
    """
    g = crop(as_grid(grid, name="shape"))
    return np.ascontiguousarray(g.transpose(_TRANSPOSE[axis_value(axis)]))


def label_layer(layer: npt.NDArray[np.bool_]) -> tuple[npt.NDArray[np.int32], int]:
    """Label the 4-connected pieces of a 2D layer (0 = empty, 1..n = piece)."""
    from scipy import ndimage

    labels, n = ndimage.label(layer)  # the default structure is 4-connectivity in 2D
    return labels.astype(np.int32), int(n)


def cells_outline(cells: npt.NDArray[np.int64]) -> object:
    """Exact outline of a set of unit cells ``(u, v)`` as a shapely geometry.

    The cells are unioned as a coverage, which is exact on the integer
    lattice; collinear lattice vertices are dropped and rings are oriented
    (exterior counter-clockwise).  Cells of one 4-connected piece give one
    Polygon; other cell sets may give a MultiPolygon.
    """
    import shapely

    c = np.asarray(cells, dtype=np.float64)
    boxes = shapely.box(c[:, 0], c[:, 1], c[:, 0] + 1.0, c[:, 1] + 1.0)
    union = shapely.simplify(shapely.coverage_union_all(boxes), 0.0)
    return shapely.orient_polygons(union)


def layer_pieces(labels: npt.NDArray[np.int32], n: int, layer: int) -> tuple[Piece, ...]:
    """Build the :class:`Piece` of each label ``1..n`` of one labelled layer."""
    if n == 0:
        return ()
    flat = labels.ravel()
    order = np.argsort(flat, kind="stable")
    counts = np.bincount(flat, minlength=n + 1)
    starts = np.cumsum(counts)
    uv = np.stack(np.unravel_index(order, labels.shape), axis=1).astype(np.int64)
    pieces = []
    for k in range(1, n + 1):
        cells = uv[starts[k - 1]:starts[k]]
        pieces.append(Piece(layer=layer, index=k, cells=cells, outline=cells_outline(cells)))
    return tuple(pieces)


def slice_layers(grid: npt.ArrayLike, *, axis: str | Axis = "z") -> tuple[tuple[Piece, ...], ...]:
    """Slice a shape into layers of pieces with exact outlines (cell units).

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The voxel shape.
    axis : {'x', 'y', 'z'}
        Slicing axis (default ``'z'``).

    Returns
    -------
    layers : tuple of tuple of Piece
        One tuple per layer from the bottom of the cropped grid; an empty
        layer in the middle of a shape gives an empty tuple.

    Examples
    --------
    >>> import numpy as np
    >>> g = np.zeros((2, 2, 1), bool); g[0, 0, 0] = g[1, 1, 0] = True
    >>> [p.id for p in slice_layers(g)[0]]
    ['1-1', '1-2']
    """
    return slice_stack(grid, axis=axis)[1]


def slice_stack(
    grid: npt.ArrayLike, *, axis: str | Axis = "z"
) -> tuple[npt.NDArray[np.int32], tuple[tuple[Piece, ...], ...]]:
    """Like :func:`slice_layers`, also returning the piece labels.

    Returns
    -------
    labels : (L, U, V) int32 ndarray
        ``labels[k, u, v]`` is the piece index of that cell in layer ``k + 1``
        (0 = empty).
    layers : tuple of tuple of Piece
        As :func:`slice_layers`.
    """
    stack = layer_stack(grid, axis=axis)
    labels = np.zeros(stack.shape, dtype=np.int32)
    out = []
    for k in range(stack.shape[0]):
        labels[k], n = label_layer(stack[k])
        out.append(layer_pieces(labels[k], n, k + 1))
    return labels, tuple(out)


def scaled(geometry: object, factor: float) -> object:
    """Return a shapely geometry scaled by ``factor`` about the origin."""
    import shapely

    check_positive(factor, name="factor")
    return shapely.transform(geometry, lambda xy: xy * factor)
