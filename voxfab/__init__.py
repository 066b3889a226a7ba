"""voxfab: fabrication CAD for voxel shapes.

Subpackages
-----------
shape      voxel grids ``[x, y, z]`` (z up): measures, components, symmetries, surface graph
io         file formats, one module per format, found by extension
digitize   shape makers: k-flakes, surfaces of revolution, swept tubes, focal shapes
repo       the SQLite repository of named shapes ``VVVVV.NNN``
recipe     TOML recipes: a shape source, operations and outputs
unfold     single-piece paper nets of voxel surfaces, and their validator
fabricate  print meshes, net drawings, slice plates
render     pictures: 3D renders, slice sheets, nets, triptychs, animations
cli        the ``voxfab`` command
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ._shared.lazy import lazy_names
from ._version import __version__

if TYPE_CHECKING:
    from .shape import VoxelShape

# The shapes (and numpy) load on first use of ``voxfab.VoxelShape``: ``voxfab --version`` needs neither.
__getattr__, __dir__ = lazy_names(__name__, {"VoxelShape": "shape"}, globals())

__all__ = ["__version__", "VoxelShape", "load", "save"]


def load(path: Any, **options: Any) -> VoxelShape:
    """Read a shape from any readable format (see :func:`voxfab.io.read`)."""
    from . import io

    return io.read(path, **options).shape()


def save(shape: VoxelShape | Any, path: Any) -> None:
    """Write a shape (or a bool grid) in the format named by the extension, with its pitch and
    colours where the format keeps them."""
    from . import io

    io.write(shape, path)
