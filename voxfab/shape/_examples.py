"""Reference shapes used by tests, benchmarks and the literature's fixtures."""

from __future__ import annotations

import numpy as np

from voxfab._shared.rng import as_rng
from voxfab._shared.typing import BoolGrid
from voxfab.errors import InvalidShapeError

from ._ops import GRID_SIDE, fill_cavities, largest_component

__all__ = ["ball", "box", "tunnel_cube", "torus", "vase", "random_shape"]


def ball(radius: int) -> BoolGrid:
    """Digital ball ``x² + y² + z² ≤ r²`` centred on a voxel, in a ``(2r+1)³`` grid."""
    r = int(radius)
    if r < 0:
        raise InvalidShapeError(f"radius: expected >= 0, got {radius}")
    c = np.arange(-r, r + 1)
    return c[:, None, None] ** 2 + c[None, :, None] ** 2 + c[None, None, :] ** 2 <= r * r


def box(nx: int, ny: int, nz: int) -> BoolGrid:
    """A full ``nx × ny × nz`` box."""
    if min(nx, ny, nz) < 1:
        raise InvalidShapeError(f"box: sides must be >= 1, got {(nx, ny, nz)}")
    return np.ones((nx, ny, nz), dtype=bool)


def tunnel_cube(side: int) -> BoolGrid:
    """An odd ``side``³ cube pierced by straight tunnels at every odd row and column.

    ``tunnel_cube(5)``: four tunnels through each face, 81 voxels, 270 faces.
    ``tunnel_cube(9)``: sixteen tunnels through each face, 425 voxels, 1350 faces.
    """
    if side < 3 or side % 2 == 0:
        raise InvalidShapeError(f"side: expected an odd number >= 3, got {side}")
    odd = (np.arange(side) % 2 == 1).astype(np.int8)
    count = odd[:, None, None] + odd[None, :, None] + odd[None, None, :]
    return count < 2


def torus(major: float, minor: float) -> BoolGrid:
    """Solid torus ``(√(x²+y²) − R)² + z² ≤ r²`` about the z axis, voxel-centred."""
    if not 0 < minor < major:
        raise InvalidShapeError(f"torus: expected 0 < minor < major, got {minor}, {major}")
    h = int(np.ceil(major + minor))
    v = int(np.ceil(minor))
    x = np.arange(-h, h + 1)[:, None, None]
    y = np.arange(-h, h + 1)[None, :, None]
    z = np.arange(-v, v + 1)[None, None, :]
    return (np.sqrt(x**2 + y**2) - major) ** 2 + z**2 <= minor**2


def vase(height: int = GRID_SIDE) -> BoolGrid:
    """A filled vase: a solid of revolution with a wavy profile, ``height`` voxels tall."""
    if height < 4:
        raise InvalidShapeError(f"height: expected >= 4, got {height}")
    t = np.linspace(0.0, 1.0, height)
    radius = height * (0.18 + 0.12 * np.sin(2.0 * np.pi * (t * 0.9 + 0.1)) + 0.1 * t)
    h = int(np.ceil(radius.max()))
    c = np.arange(-h, h + 1)
    rho = np.sqrt(c[:, None] ** 2 + c[None, :] ** 2)
    return rho[:, :, None] <= radius[None, None, :]


def random_shape(rng: np.random.Generator | int, *, side: int = GRID_SIDE, fill: float = 0.25) -> BoolGrid:
    """A random well-formed shape: one 6-connected piece spanning ``side`` along z.

    A random lateral walk from the bottom to the top layer is grown by random
    face-neighbour additions until about ``fill`` of the grid is filled; enclosed
    cavities are filled.
    """
    gen = as_rng(rng)
    from scipy import ndimage

    g = np.zeros((side, side, side), dtype=bool)
    x, y = side // 2, side // 2
    for z in range(side):
        g[x, y, z] = True
        for _ in range(int(gen.integers(0, 3))):
            dx, dy = [(1, 0), (-1, 0), (0, 1), (0, -1)][int(gen.integers(4))]
            x, y = int(np.clip(x + dx, 0, side - 1)), int(np.clip(y + dy, 0, side - 1))
            g[x, y, z] = True
    target = int(fill * side**3)
    structure = ndimage.generate_binary_structure(3, 1)
    while g.sum() < target:
        shell = ndimage.binary_dilation(g, structure) & ~g
        g |= shell & (gen.random(g.shape) < 0.3)
    # Random growth closes off pockets; a shape meant for printing and nets has none.
    return fill_cavities(largest_component(g))
