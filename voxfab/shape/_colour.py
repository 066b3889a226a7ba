"""The colour of each voxel: an index grid into a palette of RGBA colours, as MagicaVoxel keeps it.

A coloured shape keeps two arrays beside its bool grid:

- ``index``, a ``uint8`` grid ``[x, y, z]``: 0 where the grid is empty, the
  voxel's colour index (1..255) where it is filled;
- ``palette``, a ``(256, 4) uint8`` table: row ``i`` is the RGBA of colour index
  ``i`` (row 0 belongs to no voxel).

This is ``.vox``'s own model (there, the file's RGBA entry ``i`` is index ``i + 1``),
so a round trip through MagicaVoxel keeps every index and every colour.  The index
grid is a grid like the bool one, so every move of the voxels (crop, pad, rotate,
mirror, shift) moves it with the same functions of :mod:`voxfab.shape._ops`.
"""

from __future__ import annotations

import dataclasses
import re
from functools import cached_property, lru_cache

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

__all__ = [
    "VoxelColours",
    "default_palette",
    "parse_colour",
    "hex_colour",
    "srgb_to_lab",
    "PALETTE_SIZE",
]

#: Rows of a palette: colour index 0 (no voxel) and the 255 indices a ``.vox`` voxel can hold.
PALETTE_SIZE = 256

_HEX = re.compile(r"#?([0-9a-fA-F]{6})([0-9a-fA-F]{2})?")
_NAMED = {
    "white": "#ffffff", "black": "#000000", "red": "#e03030", "green": "#30a040", "blue": "#3060d0",
    "yellow": "#f0d020", "orange": "#f08020", "purple": "#8040a0", "grey": "#808080", "gray": "#808080",
    "brown": "#805030", "pink": "#f080b0", "cyan": "#30c0d0", "magenta": "#d030c0",
}


@lru_cache(maxsize=1)
def default_palette() -> npt.NDArray[np.uint8]:
    """MagicaVoxel's default palette, used by a ``.vox`` file with no ``RGBA`` chunk.

    Returns
    -------
    (256, 4) uint8 ndarray, read-only
        Row ``i`` is colour index ``i``: indices 1..215 are the web-safe cube
        (red slowest, blue fastest, from ``ff`` down to ``00``, black left out),
        then ramps of ten of red, green, blue and grey (``ee`` down to ``11``).
    """
    levels = (0xFF, 0xCC, 0x99, 0x66, 0x33, 0x00)
    rows = [(0, 0, 0, 0)]
    rows += [(r, g, b, 255) for r in levels for g in levels for b in levels][:-1]
    ramp = (0xEE, 0xDD, 0xBB, 0xAA, 0x88, 0x77, 0x55, 0x44, 0x22, 0x11)
    rows += [(v, 0, 0, 255) for v in ramp] + [(0, v, 0, 255) for v in ramp]
    rows += [(0, 0, v, 255) for v in ramp] + [(v, v, v, 255) for v in ramp]
    table = np.array(rows, dtype=np.uint8)
    table.flags.writeable = False
    return table


def parse_colour(text: str, *, name: str = "colour") -> tuple[int, int, int, int]:
    """An RGBA colour from ``"#rrggbb"``, ``"#rrggbbaa"`` (alpha above 00) or a plain colour name.

    Raises
    ------
    InvalidShapeError
        For anything else, naming the parameter.
    """
    if not isinstance(text, str):
        raise InvalidShapeError(f"{name}: expected '#rrggbb' or a plain colour name (red, blue, white...), got {text!r}")
    word = _NAMED.get(text.strip().lower(), text.strip())
    m = _HEX.fullmatch(word)
    if m is None:
        raise InvalidShapeError(
            f"{name}: expected '#rrggbb' or a plain colour name (red, blue, white...), got {text!r}"
        )
    rgb = bytes.fromhex(m.group(1))
    alpha = int(m.group(2), 16) if m.group(2) else 255
    if alpha == 0:  # alpha 0 marks an empty voxel in every RGBA grid and file: the colour would erase it
        raise InvalidShapeError(f"{name}: {text!r} is fully transparent: alpha 00 marks an empty voxel")
    return rgb[0], rgb[1], rgb[2], alpha


def hex_colour(rgba: npt.ArrayLike) -> str:
    """``"#rrggbb"`` of an RGB or RGBA colour (alpha is left out)."""
    r, g, b = (int(v) for v in np.asarray(rgba)[:3])
    return f"#{r:02x}{g:02x}{b:02x}"


def srgb_to_lab(rgb: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """CIELAB (D65) of sRGB colours given as 0..255 values, shape ``(..., 3)``.

    Distances in Lab follow what people see, so colours are merged and contrasted there.
    """
    c = np.asarray(rgb, dtype=np.float64)[..., :3] / 255.0
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    to_xyz = np.array([[0.4124564, 0.3575761, 0.1804375],
                       [0.2126729, 0.7151522, 0.0721750],
                       [0.0193339, 0.1191920, 0.9503041]])
    xyz = linear @ to_xyz.T / np.array([0.95047, 1.0, 1.08883])
    eps = 216 / 24389
    f = np.where(xyz > eps, np.cbrt(xyz), (24389 / 27 * xyz + 16) / 116)
    return np.stack([116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])], axis=-1)


def _as_palette(palette: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    p = np.asarray(palette)
    if p.ndim != 2 or p.shape[1] not in (3, 4) or not 1 <= p.shape[0] <= PALETTE_SIZE:
        raise InvalidShapeError(f"palette: expected up to {PALETTE_SIZE} rows of RGBA, got shape {p.shape}")
    if p.dtype.kind not in "iu" or p.size and (p.min() < 0 or p.max() > 255):
        raise InvalidShapeError("palette: expected integers 0..255")
    out = np.zeros((PALETTE_SIZE, 4), dtype=np.uint8)
    out[:, 3] = 255
    out[: p.shape[0], : p.shape[1]] = p
    out[0] = 0
    out.flags.writeable = False
    return out


@dataclasses.dataclass(frozen=True, eq=False, init=False)
class VoxelColours:
    """The colour of every filled voxel of a grid.

    Parameters
    ----------
    index : (X, Y, Z) integer array_like
        0 where empty, the colour index 1..255 where filled. Copied, read-only, uint8.
    palette : (N, 3 or 4) integer array_like, N <= 256
        Row ``i`` is the colour of index ``i``; missing rows are opaque black,
        row 0 is ignored.

    Examples
    --------
    >>> import numpy as np
    >>> c = VoxelColours.uniform(np.ones((2, 1, 1), bool), (200, 40, 30, 255))
    >>> c.count, c.hex(1)
    (1, '#c8281e')
    """

    index: npt.NDArray[np.uint8]
    palette: npt.NDArray[np.uint8]

    def __init__(self, index: npt.ArrayLike, palette: npt.ArrayLike) -> None:
        a = np.asarray(index)
        if a.ndim != 3:
            raise InvalidShapeError(f"colour index: expected a 3D grid, got {a.ndim}D")
        if a.dtype.kind not in "iub" or a.size and (a.min() < 0 or a.max() >= PALETTE_SIZE):
            raise InvalidShapeError("colour index: expected integers 0..255")
        idx = np.array(a, dtype=np.uint8, copy=True)
        idx.flags.writeable = False
        object.__setattr__(self, "index", idx)
        object.__setattr__(self, "palette", _as_palette(palette))

    @classmethod
    def uniform(cls, grid: npt.ArrayLike, rgba: tuple[int, int, int, int]) -> VoxelColours:
        """Every filled voxel of ``grid`` in one colour (index 1)."""
        return cls(np.asarray(grid, dtype=bool).astype(np.uint8), np.array([(0, 0, 0, 0), rgba]))

    @classmethod
    def from_rgba(cls, grid: npt.ArrayLike, rgba: npt.ArrayLike) -> VoxelColours:
        """Colours from an RGBA per voxel, ``(X, Y, Z, 4)``; each distinct colour gets an index.

        Raises
        ------
        InvalidShapeError
            When the filled voxels use more than 255 colours (merge them first).
        """
        g = np.asarray(grid, dtype=bool)
        colours = np.asarray(rgba, dtype=np.uint8).reshape(*g.shape, -1)
        if colours.shape[-1] == 3:
            colours = np.concatenate([colours, np.full((*g.shape, 1), 255, np.uint8)], axis=-1)
        used, inverse = np.unique(colours[g], axis=0, return_inverse=True)
        if len(used) > PALETTE_SIZE - 1:
            raise InvalidShapeError(f"colours: {len(used)} distinct colours, a palette holds at most 255")
        index = np.zeros(g.shape, dtype=np.uint8)
        index[g] = inverse.reshape(-1) + 1
        return cls(index, np.concatenate([np.zeros((1, 4), np.uint8), used]))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, VoxelColours):
            return NotImplemented
        return self.index.shape == other.index.shape and bool(np.array_equal(self.rgba, other.rgba))

    def __hash__(self) -> int:
        return hash((self.index.shape, self.rgba.tobytes()))

    def __repr__(self) -> str:
        return f"VoxelColours(grid={'x'.join(map(str, self.index.shape))}, colours={self.count})"

    @cached_property
    def rgba(self) -> npt.NDArray[np.uint8]:
        """``(X, Y, Z, 4)`` RGBA of each voxel (zeros where empty)."""
        out = self.palette[self.index]
        out[self.index == 0] = 0
        out.flags.writeable = False
        return out

    @cached_property
    def used(self) -> npt.NDArray[np.uint8]:
        """The colour indices the voxels use, ascending."""
        used = np.flatnonzero(np.bincount(self.index.ravel(), minlength=PALETTE_SIZE)[1:]) + 1
        return used.astype(np.uint8)

    @cached_property
    def count(self) -> int:
        """Number of distinct colours the voxels use (two indices of one RGBA count once)."""
        return len(np.unique(self.palette[self.used], axis=0)) if len(self.used) else 0

    def hex(self, index: int) -> str:
        """``"#rrggbb"`` of one colour index."""
        return hex_colour(self.palette[index])

    def at(self, voxels: npt.ArrayLike) -> npt.NDArray[np.uint8]:
        """RGBA of the voxels at integer coordinates ``(N, 3)``."""
        v = np.asarray(voxels, dtype=np.intp).reshape(-1, 3)
        return self.palette[self.index[v[:, 0], v[:, 1], v[:, 2]]]

    def matches(self, grid: npt.ArrayLike) -> bool:
        """Whether the filled voxels are exactly those of ``grid``."""
        g = np.asarray(grid, dtype=bool)
        return g.shape == self.index.shape and bool(np.array_equal(self.index != 0, g))

    def fitted(self, grid: npt.ArrayLike, *, fill: int | None = None) -> VoxelColours:
        """These colours on ``grid``: voxels ``grid`` adds take their nearest coloured voxel's index
        (or ``fill``), voxels it removes lose theirs.

        The studio's edits, a join and filled cavities change the voxels; the colours follow.
        """
        g = np.asarray(grid, dtype=bool)
        if g.shape != self.index.shape:
            raise InvalidShapeError(f"grid: shape {g.shape} differs from the colours' {self.index.shape}")
        index = np.where(g, self.index, 0).astype(np.uint8)
        missing = g & (index == 0)
        if missing.any():
            if fill is not None or not self.index.any():
                index[missing] = fill if fill is not None else 1
            else:
                from scipy import ndimage

                # Each new voxel takes the colour of the nearest voxel that had one.
                _, (ix, iy, iz) = ndimage.distance_transform_edt(self.index == 0, return_indices=True)
                index[missing] = self.index[ix[missing], iy[missing], iz[missing]]
        return VoxelColours(index, self.palette)

    def with_index(self, index: npt.ArrayLike) -> VoxelColours:
        """The same palette over another index grid (a moved or cropped one)."""
        return VoxelColours(index, self.palette)
