"""Grids on the wire: packed bits in base64, with their colours when they have some, and the facts the page shows.

A coloured shape's wire form adds two base64 fields to the bits: ``colours``, the
colour index (1..255) of each filled voxel in the bits' order, one byte each, and
``palette``, the 256 RGBA rows of its palette (row ``i`` is colour index ``i``, as in
:class:`voxfab.shape.VoxelColours`).  An uncoloured shape has neither, and costs nothing.
"""

from __future__ import annotations

import base64
import binascii
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from voxfab.errors import InvalidShapeError

if TYPE_CHECKING:
    from voxfab.shape import VoxelColours, VoxelShape

#: The editor's grid side: every shape the page holds is centred in 25³.
SIDE = 25


def _b64(raw: bytes) -> str:
    return base64.b64encode(raw).decode("ascii")


def pack(grid: np.ndarray, colours: VoxelColours | None = None) -> dict[str, Any]:
    """``{"dims": [X, Y, Z], "bits": base64}``; bit ``(x * Y + y) * Z + z``, most significant bit first.

    With ``colours``, also ``"colours"`` (each filled voxel's index, in bit order) and ``"palette"``.
    """
    g = np.ascontiguousarray(grid, dtype=bool)
    out = {"dims": list(g.shape), "bits": _b64(np.packbits(g.reshape(-1)).tobytes())}
    if colours is not None:
        out["colours"] = _b64(np.ascontiguousarray(colours.index).reshape(-1)[g.reshape(-1)].tobytes())
        out["palette"] = _b64(np.ascontiguousarray(colours.palette).tobytes())
    return out


def pack_shape(shape: VoxelShape) -> dict[str, Any]:
    """:func:`pack` of a shape: its voxels and, when it has them, its colours."""
    return pack(shape.grid, shape.colours)


def _bytes(data: dict[str, Any], key: str, name: str, size: int) -> bytes:
    """The base64 field ``key`` of ``data``, exactly ``size`` bytes, or a one-line error."""
    text = data.get(key)
    if not isinstance(text, str):
        raise InvalidShapeError(f"{name}.{key}: expected base64 text")
    try:
        raw = base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError):
        raise InvalidShapeError(f"{name}.{key}: is not base64") from None
    if len(raw) != size:
        raise InvalidShapeError(f"{name}.{key}: {len(raw)} bytes, expected {size}")
    return raw


def unpack_shape(data: Any, *, pitch: float = 1.0, name: str = "grid") -> VoxelShape:
    """The shape of :func:`pack`'s form: its voxels, and its colours when the page sent them.

    A filled voxel the page left without a colour (index 0: one a drawing added
    to a painted shape) takes its nearest coloured voxel's, as every edit of the library does
    (:meth:`voxfab.shape.VoxelColours.fitted`).
    """
    from voxfab.shape import PALETTE_SIZE, VoxelColours, VoxelShape

    grid = unpack(data, name=name)
    if data.get("colours") is None and data.get("palette") is None:
        return VoxelShape(grid, pitch)
    flat = grid.reshape(-1)
    index = np.zeros(flat.shape, dtype=np.uint8)
    index[flat] = np.frombuffer(_bytes(data, "colours", name, int(flat.sum())), dtype=np.uint8)
    palette = np.frombuffer(_bytes(data, "palette", name, PALETTE_SIZE * 4), dtype=np.uint8).reshape(-1, 4)
    colours = VoxelColours(index.reshape(grid.shape), palette)
    return VoxelShape(grid, pitch, colours.fitted(grid) if grid.any() else colours)


def unpack(data: Any, *, name: str = "grid") -> np.ndarray:
    """The bool grid of :func:`pack`'s form, checked like every shape input and no larger than the editor's box.

    The page holds every shape in the :data:`SIDE`³ editor, so a larger grid is one
    the artist could never open again: it is refused here, at every endpoint.
    """
    from voxfab._shared.validate import as_grid

    if not isinstance(data, dict) or not isinstance(data.get("bits"), str) or not isinstance(data.get("dims"), list):
        raise InvalidShapeError(f"{name}: expected {{\"dims\": [X, Y, Z], \"bits\": base64}}")
    dims = data["dims"]
    if len(dims) != 3 or not all(isinstance(d, int) and not isinstance(d, bool) for d in dims):
        raise InvalidShapeError(f"{name}: dims must be three whole numbers, got {str(dims)[:60]}")
    if not all(1 <= d <= SIDE for d in dims):
        raise InvalidShapeError(f"{name}: dims {'x'.join(map(str, dims))} are larger than the studio's {SIDE}x{SIDE}x{SIDE} "
                                f"box; the page opens shapes of at most {SIDE} voxels a side")
    try:
        raw = base64.b64decode(data["bits"], validate=True)
    except (binascii.Error, ValueError):
        raise InvalidShapeError(f"{name}: bits is not base64") from None
    count = dims[0] * dims[1] * dims[2]
    if len(raw) != (count + 7) // 8:
        raise InvalidShapeError(f"{name}: {len(raw)} bytes of bits for {count} voxels, expected {(count + 7) // 8}")
    g = np.unpackbits(np.frombuffer(raw, dtype=np.uint8))[:count].astype(bool).reshape(dims)
    return np.asarray(as_grid(g, name=name, allow_empty=True))


def require_voxels(grid: np.ndarray) -> None:
    """Refuse an empty shape: there is nothing to keep or make."""
    if not grid.any():
        raise InvalidShapeError("shape: empty; draw or add voxels first")


def centred(grid: np.ndarray, side: int = SIDE) -> np.ndarray:
    """The shape cropped and centred in a ``side``³ grid (the editor's canvas)."""
    from voxfab.shape import crop, pad_to

    if not grid.any():
        return np.zeros((side,) * 3, dtype=bool)
    c = crop(grid)
    if max(c.shape) > side:
        raise InvalidShapeError(f"shape: {'x'.join(map(str, c.shape))} voxels does not fit the {side}³ editor")
    return pad_to(c, (side,) * 3)


def centred_shape(shape: VoxelShape, side: int = SIDE) -> VoxelShape:
    """:func:`centred` of a shape: its colours move with its voxels."""
    from voxfab.shape import VoxelShape

    if shape.colours is None or not shape.grid.any():
        return VoxelShape(centred(shape.grid, side), shape.pitch)
    c = shape.crop()
    if max(c.grid.shape) > side:
        raise InvalidShapeError(f"shape: {'x'.join(map(str, c.grid.shape))} voxels does not fit the {side}³ editor")
    return c.pad_to((side,) * 3)


def facts(grid: np.ndarray) -> dict[str, Any]:
    """Volume, extents and well-formedness with its reasons, as ``voxfab info`` reports them.

    ``reasons`` are in the artist's words; ``terms`` are the same reasons as the library says them.
    """
    from voxfab.shape import VoxelShape

    from ._words import plain

    s = VoxelShape(grid)
    return {
        "volume": s.volume,
        "extents": list(s.extents),
        "well_formed": s.well_formed,
        "reasons": [plain(r) for r in s.reasons],
        "terms": list(s.reasons),
    }


@dataclass(frozen=True)
class InitialShape:
    """The shape ``voxfab studio SHAPE`` opens the page with.

    Attributes
    ----------
    grid : ndarray
        The shape centred in the editor's 25³ grid (see :func:`centred`).
    label : str
        What the page calls it: the file's name or the repository name.
    name : str or None
        Its repository name, when it came from the repository.
    pitch : float or None
        Its own scale in mm per voxel (a file's or ``--pitch``), if it has one.
    colours : VoxelColours or None
        Its colours (a ``.vox``'s, an ``.npz``'s), centred with it.
    """

    grid: np.ndarray
    label: str
    name: str | None = None
    pitch: float | None = None
    colours: VoxelColours | None = None

    @classmethod
    def of(cls, grid: np.ndarray, *, label: str, name: str | None = None,
           pitch: float | None = None, colours: VoxelColours | None = None) -> InitialShape:
        """The shape centred in the editor; one line when it is empty or larger than the editor."""
        from voxfab.shape import VoxelShape

        if not np.asarray(grid).any():
            raise InvalidShapeError(f"{label}: the shape is empty; nothing to open")
        shape = centred_shape(VoxelShape(grid, 1.0, colours))
        return cls(shape.grid, label, name, pitch, shape.colours)

    def answer(self) -> dict[str, Any]:
        """What ``GET /api/initial`` sends: the grid (with its colours), its facts, and how to name it."""
        return {"grid": pack(self.grid, self.colours), "facts": facts(self.grid), "label": self.label,
                "name": self.name, "pitch": self.pitch}
