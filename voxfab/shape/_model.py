"""VoxelShape: an immutable bool grid with a pitch, wrapping the pure functions."""

from __future__ import annotations

import dataclasses
from functools import cached_property

import numpy as np
import numpy.typing as npt

from voxfab._shared.typing import BoolGrid
from voxfab._shared.validate import as_grid, check_positive

from . import _ops
from ._canonical import canonical_key


@dataclasses.dataclass(frozen=True, eq=False, init=False)
class VoxelShape:
    """A voxel shape: a read-only bool grid ``[x, y, z]`` (z up) and a pitch.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        Filled voxels. Copied and made read-only.
    pitch : float
        Edge length of one voxel in millimetres (used by fabrication outputs).

    Examples
    --------
    >>> import numpy as np
    >>> s = VoxelShape(np.ones((2, 2, 2), bool))
    >>> s.volume, s.exposed_faces
    (8, 24)
    """

    grid: BoolGrid
    pitch: float

    def __init__(self, grid: npt.ArrayLike, pitch: float = 1.0) -> None:
        g = np.array(as_grid(grid, allow_empty=True), dtype=bool, copy=True)
        g.flags.writeable = False
        object.__setattr__(self, "grid", g)
        object.__setattr__(self, "pitch", check_positive(pitch, name="pitch"))

    # Equality is by voxels and pitch; the generated __eq__ would compare arrays.
    def __eq__(self, other: object) -> bool:
        if not isinstance(other, VoxelShape):
            return NotImplemented
        return (
            self.pitch == other.pitch
            and self.grid.shape == other.grid.shape
            and bool(np.array_equal(self.grid, other.grid))
        )

    def __hash__(self) -> int:
        return hash((self.grid.shape, self.pitch, np.packbits(self.grid).tobytes()))

    def __repr__(self) -> str:
        return f"VoxelShape(grid={'x'.join(map(str, self.grid.shape))}, volume={self.volume}, pitch={self.pitch})"

    def _new(self, grid: npt.ArrayLike) -> VoxelShape:
        return VoxelShape(grid, self.pitch)

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
        return canonical_key(self.grid, symmetric=symmetric)

    def crop(self) -> VoxelShape:
        """The shape cut to its bounding box."""
        return self._new(_ops.crop(self.grid))

    def largest_component(self) -> VoxelShape:
        """Only the largest 6-connected piece."""
        return self._new(_ops.largest_component(self.grid))

    def fill_cavities(self) -> VoxelShape:
        """Enclosed cavities filled."""
        return self._new(_ops.fill_cavities(self.grid))

    def rotate(self, axis: str = "z", quarter_turns: int = 1) -> VoxelShape:
        """Rotated by quarter turns about an axis."""
        return self._new(_ops.rotate(self.grid, axis, quarter_turns))

    def mirror(self, axis: str = "x") -> VoxelShape:
        """Mirrored across a plane normal to ``axis``."""
        return self._new(_ops.mirror(self.grid, axis))

    def translate(self, offset: tuple[int, int, int]) -> VoxelShape:
        """Shifted inside the same grid."""
        return self._new(_ops.translate(self.grid, offset))

    def with_pitch(self, pitch: float) -> VoxelShape:
        """The same voxels with another pitch (mm per voxel)."""
        return VoxelShape(self.grid, pitch)

    def __or__(self, other: VoxelShape) -> VoxelShape:
        return self._new(_ops.union(self.grid, other.grid))

    def __and__(self, other: VoxelShape) -> VoxelShape:
        return self._new(_ops.intersection(self.grid, other.grid))

    def __sub__(self, other: VoxelShape) -> VoxelShape:
        return self._new(_ops.difference(self.grid, other.grid))

    def __xor__(self, other: VoxelShape) -> VoxelShape:
        a, b = _ops._same_shape(self.grid, other.grid)
        return self._new(a ^ b)
