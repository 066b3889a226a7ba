"""VoxelShape: an immutable bool grid with a pitch, wrapping the pure functions."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from functools import cached_property

import numpy as np
import numpy.typing as npt

from voxfab._shared.typing import BoolGrid
from voxfab._shared.validate import as_grid, check_positive
from voxfab.errors import InvalidShapeError

from . import _ops
from ._canonical import canonical_key
from ._colour import VoxelColours
from ._join import Join, join_parts


@dataclasses.dataclass(frozen=True, eq=False, init=False)
class VoxelShape:
    """A voxel shape: a read-only bool grid ``[x, y, z]`` (z up), a pitch, and maybe colours.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        Filled voxels. Copied and made read-only.
    pitch : float
        Edge length of one voxel in millimetres (used by fabrication outputs).
    colours : VoxelColours, optional
        The colour of each filled voxel (an index grid and a palette); None for
        an uncoloured shape, which every output draws in its own plain colours.
        Every method that moves voxels moves their colours with them.

    Examples
    --------
    >>> import numpy as np
    >>> s = VoxelShape(np.ones((2, 2, 2), bool))
    >>> s.volume, s.exposed_faces
    (8, 24)
    """

    grid: BoolGrid
    pitch: float
    colours: VoxelColours | None

    def __init__(self, grid: npt.ArrayLike, pitch: float = 1.0, colours: VoxelColours | None = None) -> None:
        g = np.array(as_grid(grid, allow_empty=True), dtype=bool, copy=True)
        g.flags.writeable = False
        if colours is not None and not colours.matches(g):
            raise InvalidShapeError("colours: the coloured voxels are not the shape's filled voxels")
        object.__setattr__(self, "grid", g)
        object.__setattr__(self, "pitch", check_positive(pitch, name="pitch"))
        object.__setattr__(self, "colours", colours)

    # Equality is by voxels, pitch and colours; the generated __eq__ would compare arrays.
    def __eq__(self, other: object) -> bool:
        if not isinstance(other, VoxelShape):
            return NotImplemented
        return (
            self.pitch == other.pitch
            and self.grid.shape == other.grid.shape
            and bool(np.array_equal(self.grid, other.grid))
            and self.colours == other.colours
        )

    def __hash__(self) -> int:
        return hash((self.grid.shape, self.pitch, np.packbits(self.grid).tobytes(), self.colours))

    def __repr__(self) -> str:
        colours = "" if self.colours is None else f", colours={self.colours.count}"
        return (f"VoxelShape(grid={'x'.join(map(str, self.grid.shape))}, volume={self.volume}, "
                f"pitch={self.pitch}{colours})")

    def _new(self, grid: npt.ArrayLike) -> VoxelShape:
        """A shape of other voxels: the colours follow the voxels kept, new ones take their nearest's."""
        g = np.asarray(grid, dtype=bool)
        if self.colours is None:
            return VoxelShape(g, self.pitch)
        if g.shape != self.grid.shape:
            raise InvalidShapeError("colours: a coloured shape's new grid must keep its size")
        return VoxelShape(g, self.pitch, self.colours.fitted(g))

    def _moved(self, move: Callable[[np.ndarray], np.ndarray]) -> VoxelShape:
        """The shape with ``move`` (a crop, rotation, mirror, shift) applied to its voxels and colours alike."""
        colours = None if self.colours is None else self.colours.with_index(move(self.colours.index))
        return VoxelShape(move(self.grid), self.pitch, colours)

    def joined(self) -> tuple[VoxelShape, list[Join]]:
        """The shape made one 6-connected piece with the fewest voxels found, each in a neighbour's
        colour, and where they were added (:func:`voxfab.shape.join_parts`)."""
        grid, joins = join_parts(self.grid)
        return self._new(grid), joins

    def with_colours(self, colours: VoxelColours | None) -> VoxelShape:
        """The same voxels with other colours (None: uncoloured)."""
        return VoxelShape(self.grid, self.pitch, colours)

    def painted(self, rgba: tuple[int, int, int, int], where: npt.ArrayLike | None = None) -> VoxelShape:
        """The shape with the voxels of ``where`` (default: all) in one colour, the others as they were.

        An uncoloured shape's other voxels become white, the colour paper and plain filament show.
        """
        mask = self.grid if where is None else self.grid & np.asarray(where, dtype=bool)
        rgba_grid = np.array(_rgba_or_white(self), copy=True)
        rgba_grid[mask] = rgba
        return self.with_colours(VoxelColours.from_rgba(self.grid, rgba_grid))

    @cached_property
    def volume(self) -> int:
        """Number of filled voxels."""
        return _ops.volume(self.grid)

    @cached_property
    def extents(self) -> tuple[int, int, int]:
        """Bounding-box size along x, y, z in voxels."""
        return _ops.extents(self.grid)

    @cached_property
    def exposed_faces(self) -> int:
        """Number of exposed voxel faces."""
        return _ops.exposed_faces(self.grid)

    @cached_property
    def components(self) -> int:
        """Number of 6-connected components."""
        return _ops.component_count(self.grid)

    @cached_property
    def reasons(self) -> list[str]:
        """Why the shape is not well formed (empty when it is)."""
        return _ops.well_formed_reasons(self.grid)

    @property
    def well_formed(self) -> bool:
        """Whether the shape follows the artist's protocol."""
        return not self.reasons

    def key(self, *, symmetric: bool = False) -> str:
        """Canonical hash, see :func:`voxfab.shape.canonical_key`."""
        return canonical_key(self.grid, symmetric=symmetric, colours=self.colours)

    def crop(self) -> VoxelShape:
        """The shape cut to its bounding box."""
        lo, hi = _ops.bounding_box(self.grid)
        return self._moved(lambda g: g[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].copy())

    def pad_to(self, size: tuple[int, int, int], *, center: bool = True) -> VoxelShape:
        """The shape placed in a larger empty grid of ``size`` (centred by default)."""
        return self._moved(lambda g: _ops.pad_to(g, size, center=center))

    def largest_component(self) -> VoxelShape:
        """Only the largest 6-connected piece."""
        return self._new(_ops.largest_component(self.grid))

    def fill_cavities(self) -> VoxelShape:
        """Enclosed cavities filled."""
        return self._new(_ops.fill_cavities(self.grid))

    def rotate(self, axis: str = "z", quarter_turns: int = 1) -> VoxelShape:
        """Rotated by quarter turns about an axis."""
        return self._moved(lambda g: _ops.rotate(g, axis, quarter_turns))

    def mirror(self, axis: str = "x") -> VoxelShape:
        """Mirrored across a plane normal to ``axis``."""
        return self._moved(lambda g: _ops.mirror(g, axis))

    def translate(self, offset: tuple[int, int, int]) -> VoxelShape:
        """Shifted inside the same grid."""
        return self._moved(lambda g: _ops.translate(g, offset))

    def with_pitch(self, pitch: float) -> VoxelShape:
        """The same voxels with another pitch (mm per voxel)."""
        return VoxelShape(self.grid, pitch, self.colours)

    def __or__(self, other: VoxelShape) -> VoxelShape:
        union = _ops.union(self.grid, other.grid)
        if self.colours is None and other.colours is None:
            return VoxelShape(union, self.pitch)
        # Where both have a voxel, this shape's colour wins; a side without colours is white.
        a, b = self.pad_to(union.shape, center=False), other.pad_to(union.shape, center=False)
        rgba = np.where(a.grid[..., None], _rgba_or_white(a), _rgba_or_white(b))
        return VoxelShape(union, self.pitch, VoxelColours.from_rgba(union, rgba))

    # The other operators keep this shape's colours (a voxel only ``other`` adds takes its nearest's).
    def __and__(self, other: VoxelShape) -> VoxelShape:
        result = _ops.intersection(self.grid, other.grid)
        return self.pad_to(result.shape, center=False)._new(result)

    def __sub__(self, other: VoxelShape) -> VoxelShape:
        result = _ops.difference(self.grid, other.grid)
        return self.pad_to(result.shape, center=False)._new(result)

    def __xor__(self, other: VoxelShape) -> VoxelShape:
        a, b = _ops._same_shape(self.grid, other.grid)
        return self.pad_to(a.shape, center=False)._new(a ^ b)


def _rgba_or_white(shape: VoxelShape) -> np.ndarray:
    """Each voxel's RGBA, white for an uncoloured shape."""
    if shape.colours is not None:
        return shape.colours.rgba
    return np.repeat(shape.grid[..., None], 4, axis=-1).astype(np.uint8) * np.uint8(255)
