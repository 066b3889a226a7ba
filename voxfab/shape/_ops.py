"""Pure functions over 3D bool grids indexed ``[x, y, z]`` (z up)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import numpy.typing as npt

from voxfab._shared.typing import BoolGrid
from voxfab._shared.validate import as_grid
from voxfab.errors import InvalidShapeError

__all__ = [
    "volume",
    "bounding_box",
    "extents",
    "crop",
    "pad_to",
    "label_components",
    "component_count",
    "largest_component",
    "fill_cavities",
    "cavity_count",
    "exposed_faces",
    "union",
    "intersection",
    "difference",
    "translate",
    "rotations",
    "rotation_matrices",
    "rotate",
    "mirror",
    "symmetries",
    "well_formed_reasons",
    "is_well_formed",
    "GRID_SIDE",
]

#: The artist's grid side: a well-formed shape fits in GRID_SIDE³ and spans it once.
GRID_SIDE = 25

# 6-connectivity structuring element: face neighbours only.
_FACE_STRUCTURE = np.zeros((3, 3, 3), dtype=bool)
_FACE_STRUCTURE[1, 1, :] = _FACE_STRUCTURE[1, :, 1] = _FACE_STRUCTURE[:, 1, 1] = True


def volume(grid: npt.ArrayLike) -> int:
    """Return the number of filled voxels."""
    return int(np.count_nonzero(as_grid(grid, allow_empty=True)))


def bounding_box(grid: npt.ArrayLike) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
    """Return ``(lo, hi)``: the inclusive-exclusive index box of the filled voxels.

    Raises
    ------
    InvalidShapeError
        If the grid is empty.
    """
    g = as_grid(grid)
    lo, hi = [], []
    for axis in range(3):
        other = tuple(a for a in range(3) if a != axis)
        idx = np.flatnonzero(g.any(axis=other))
        lo.append(int(idx[0]))
        hi.append(int(idx[-1]) + 1)
    return (lo[0], lo[1], lo[2]), (hi[0], hi[1], hi[2])


def extents(grid: npt.ArrayLike) -> tuple[int, int, int]:
    """Return the size of the bounding box along x, y and z, in voxels."""
    lo, hi = bounding_box(grid)
    return (hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2])


def _cells(grid: npt.ArrayLike, *, allow_empty: bool = True) -> npt.NDArray:
    """A bool grid checked, or a colour index grid (3D ``uint8``) as it is: the moves of the
    voxels (crop, pad, shift, rotate, mirror) move their colours with the same code."""
    a = np.asarray(grid)
    if a.dtype == np.uint8 and a.ndim == 3:
        if not allow_empty and not a.any():
            raise InvalidShapeError("shape: the grid is empty (no filled voxel)")
        return a
    return as_grid(a, allow_empty=allow_empty)


def crop(grid: npt.ArrayLike) -> BoolGrid:
    """Return the grid cut down to its bounding box (a colour index grid is cut the same way)."""
    g = _cells(grid, allow_empty=False)
    lo, hi = bounding_box(g != 0)
    return g[lo[0] : hi[0], lo[1] : hi[1], lo[2] : hi[2]].copy()


def pad_to(grid: npt.ArrayLike, size: tuple[int, int, int], *, center: bool = True) -> BoolGrid:
    """Return the grid placed in a larger empty grid of ``size`` (centred by default)."""
    g = _cells(grid)
    if any(s < t for s, t in zip(size, g.shape)):
        raise InvalidShapeError(f"size: {size} is smaller than the grid {g.shape}")
    out = np.zeros(size, dtype=g.dtype)
    off = [((s - t) // 2 if center else 0) for s, t in zip(size, g.shape)]
    out[off[0] : off[0] + g.shape[0], off[1] : off[1] + g.shape[1], off[2] : off[2] + g.shape[2]] = g
    return out


#: Grids up to this many cells are labelled in numpy: importing scipy.ndimage costs
#: about 0.3 s, more than labelling a 25³ grid, and `voxfab info` must start fast.
_NUMPY_LABEL_LIMIT = 64**3


def _label_numpy(g: BoolGrid) -> tuple[npt.NDArray[np.int32], int]:
    """6-connected labelling by min-label hooking with pointer jumping (O(log n) rounds)."""
    idx = np.flatnonzero(g.ravel())
    n = idx.size
    out = np.zeros(g.size, dtype=np.int32)
    if n == 0:
        return out.reshape(g.shape), 0
    pos = np.full(g.size, -1, dtype=np.int64)
    pos[idx] = np.arange(n)
    pos = pos.reshape(g.shape)
    us, vs = [], []
    for axis in range(g.ndim):
        lo = tuple(slice(None, -1) if a == axis else slice(None) for a in range(g.ndim))
        hi = tuple(slice(1, None) if a == axis else slice(None) for a in range(g.ndim))
        both = g[lo] & g[hi]
        us.append(pos[lo][both])
        vs.append(pos[hi][both])
    u, v = np.concatenate(us), np.concatenate(vs)
    parent = np.arange(n)
    while True:
        pu, pv = parent[u], parent[v]
        small, big = np.minimum(pu, pv), np.maximum(pu, pv)
        differ = small != big
        if not differ.any():
            break
        np.minimum.at(parent, big[differ], small[differ])
        while True:
            jumped = parent[parent]
            if np.array_equal(jumped, parent):
                break
            parent = jumped
    # Roots are the smallest index of each component, so labels follow scan order.
    roots, labels = np.unique(parent, return_inverse=True)
    out[idx] = labels + 1
    return out.reshape(g.shape), int(roots.size)


def label_components(grid: npt.ArrayLike) -> tuple[npt.NDArray[np.int32], int]:
    """Label the 6-connected components.

    Returns
    -------
    labels : (X, Y, Z) int32 ndarray
        0 for empty voxels, 1..n for the components, numbered in scan order.
    n : int
        The number of components.
    """
    return _label(as_grid(grid, allow_empty=True))


def _label(g: BoolGrid) -> tuple[npt.NDArray[np.int32], int]:
    if g.size <= _NUMPY_LABEL_LIMIT:
        return _label_numpy(g)
    from scipy import ndimage

    labels, n = ndimage.label(g, structure=_FACE_STRUCTURE)
    return labels.astype(np.int32, copy=False), int(n)


def component_count(grid: npt.ArrayLike) -> int:
    """Return the number of 6-connected components."""
    return label_components(grid)[1]


def largest_component(grid: npt.ArrayLike) -> BoolGrid:
    """Return only the largest 6-connected component (the first one on a tie)."""
    labels, n = label_components(grid)
    if n <= 1:
        return labels > 0
    sizes = np.bincount(labels.ravel())[1:]
    return labels == (int(np.argmax(sizes)) + 1)


def _outside(g: BoolGrid) -> BoolGrid:
    """Empty voxels 6-connected to the outside of the grid."""
    padded = np.pad(~g, 1, constant_values=True)
    # The padded grid may exceed the user-facing size limit by two, so skip as_grid.
    labels, _ = _label(padded)
    return (labels == labels[0, 0, 0])[1:-1, 1:-1, 1:-1]


def fill_cavities(grid: npt.ArrayLike) -> BoolGrid:
    """Fill every empty region not 6-connected to the outside of the grid.

    An empty region reached from outside only through an edge or a corner is a
    cavity: it is closed to face-connected paths, as it is to water in a print.
    """
    g = as_grid(grid, allow_empty=True)
    return ~_outside(g)


def cavity_count(grid: npt.ArrayLike) -> int:
    """Return the number of enclosed empty regions (6-connected)."""
    g = as_grid(grid, allow_empty=True)
    cavities = ~g & ~_outside(g)
    return component_count(cavities) if cavities.any() else 0


def exposed_faces(grid: npt.ArrayLike) -> int:
    """Return the number of voxel faces between a filled and an empty voxel."""
    g = as_grid(grid, allow_empty=True).astype(np.int8)
    p = np.pad(g, 1)
    return int(sum(np.count_nonzero(np.diff(p, axis=a)) for a in range(3)))


def _same_shape(a: npt.ArrayLike, b: npt.ArrayLike) -> tuple[BoolGrid, BoolGrid]:
    ga = as_grid(a, name="a", allow_empty=True)
    gb = as_grid(b, name="b", allow_empty=True)
    if ga.shape != gb.shape:
        shape = tuple(max(s, t) for s, t in zip(ga.shape, gb.shape))
        ga, gb = pad_to(ga, shape, center=False), pad_to(gb, shape, center=False)
    return ga, gb


def union(a: npt.ArrayLike, b: npt.ArrayLike) -> BoolGrid:
    """Return ``a | b`` (grids of different sizes are aligned at index 0)."""
    ga, gb = _same_shape(a, b)
    return ga | gb


def intersection(a: npt.ArrayLike, b: npt.ArrayLike) -> BoolGrid:
    """Return ``a & b`` (grids of different sizes are aligned at index 0)."""
    ga, gb = _same_shape(a, b)
    return ga & gb


def difference(a: npt.ArrayLike, b: npt.ArrayLike) -> BoolGrid:
    """Return ``a & ~b`` (grids of different sizes are aligned at index 0)."""
    ga, gb = _same_shape(a, b)
    return ga & ~gb


def translate(grid: npt.ArrayLike, offset: tuple[int, int, int]) -> BoolGrid:
    """Shift the content by ``offset`` voxels inside the same grid.

    Raises
    ------
    InvalidShapeError
        If a filled voxel would leave the grid.
    """
    g = _cells(grid)
    if not g.any():
        return g.copy()
    lo, hi = bounding_box(g != 0)
    for axis, d in enumerate(offset):
        if lo[axis] + d < 0 or hi[axis] + d > g.shape[axis]:
            raise InvalidShapeError(f"offset: {tuple(offset)} moves filled voxels out of the grid")
    out = np.zeros_like(g)
    src = tuple(slice(lo[a], hi[a]) for a in range(3))
    dst = tuple(slice(lo[a] + offset[a], hi[a] + offset[a]) for a in range(3))
    out[dst] = g[src]
    return out


@lru_cache(maxsize=1)
def rotation_matrices() -> tuple[npt.NDArray[np.int64], ...]:
    """The 24 proper rotations of the cube as signed permutation matrices, in a fixed order."""
    import itertools

    mats = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1, -1), repeat=3):
            m = np.zeros((3, 3), dtype=np.int64)
            for row, (col, s) in enumerate(zip(perm, signs)):
                m[row, col] = s
            if round(np.linalg.det(m)) == 1:
                mats.append(m)
    return tuple(mats)


@lru_cache(maxsize=1)
def _rotation_moves() -> tuple[tuple[tuple[int, ...], tuple[int, ...]], ...]:
    """Each rotation as (axis order, axes to flip), the form numpy applies directly."""
    moves = []
    for m in rotation_matrices():
        # New axis `row` reads old axis `perm[row]`, reversed where the sign is negative.
        perm = tuple(int(np.flatnonzero(m[row])[0]) for row in range(3))
        flips = tuple(row for row in range(3) if m[row, perm[row]] < 0)
        moves.append((perm, flips))
    return tuple(moves)


def _apply_move(g: BoolGrid, move: tuple[tuple[int, ...], tuple[int, ...]]) -> BoolGrid:
    perm, flips = move
    out = np.transpose(g, perm)
    if flips:
        out = np.flip(out, axis=flips)
    return np.ascontiguousarray(out)


def rotations(grid: npt.ArrayLike) -> list[BoolGrid]:
    """Return the 24 rotations of the grid (the identity first)."""
    g = as_grid(grid, allow_empty=True)
    return [_apply_move(g, move) for move in _rotation_moves()]


def rotate(grid: npt.ArrayLike, axis: str = "z", quarter_turns: int = 1) -> BoolGrid:
    """Rotate by ``quarter_turns`` × 90° counter-clockwise about ``axis`` (x, y or z)."""
    g = _cells(grid)
    axes = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}
    if axis not in axes:
        raise InvalidShapeError(f"axis: expected one of 'x', 'y', 'z', got {axis!r}")
    return np.ascontiguousarray(np.rot90(g, k=int(quarter_turns) % 4, axes=axes[axis]))


def mirror(grid: npt.ArrayLike, axis: str = "x") -> BoolGrid:
    """Reflect the grid across a plane normal to ``axis`` (x, y or z)."""
    g = _cells(grid)
    if axis not in ("x", "y", "z"):
        raise InvalidShapeError(f"axis: expected one of 'x', 'y', 'z', got {axis!r}")
    return np.ascontiguousarray(np.flip(g, axis="xyz".index(axis)))


def symmetries(grid: npt.ArrayLike, *, reflections: bool = False) -> list[BoolGrid]:
    """Return the 24 rotations, or all 48 cube symmetries with ``reflections``."""
    rots = rotations(grid)
    if reflections:
        rots += rotations(mirror(grid, "x"))
    return rots


def well_formed_reasons(grid: npt.ArrayLike, *, side: int = GRID_SIDE) -> list[str]:
    """Return why the grid breaks the artist's protocol (empty list: well formed).

    The protocol: one 6-connected piece, fits in ``side``³, and spans the full
    ``side`` along at least one axis.
    """
    g = as_grid(grid, allow_empty=True)
    if not g.any():
        return ["the grid is empty"]
    reasons = []
    n = component_count(g)
    if n != 1:
        reasons.append(f"{n} 6-connected pieces, expected 1")
    ext = extents(g)
    if any(e > side for e in ext):
        reasons.append(f"extents {ext} do not fit in {side}x{side}x{side}")
    elif side not in ext:
        reasons.append(f"extents {ext}: none is {side}, so the shape touches no two opposite sides")
    return reasons


def is_well_formed(grid: npt.ArrayLike, *, side: int = GRID_SIDE) -> bool:
    """Return whether the grid follows the artist's protocol."""
    return not well_formed_reasons(grid, side=side)
