"""Grids on the wire: packed bits in base64, and the facts the page shows about a shape."""

from __future__ import annotations

import base64
import binascii
from dataclasses import dataclass
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError

#: The editor's grid side: every shape the page holds is centred in 25³.
SIDE = 25


def pack(grid: np.ndarray) -> dict[str, Any]:
    """``{"dims": [X, Y, Z], "bits": base64}``; bit ``(x * Y + y) * Z + z``, most significant bit first."""
    g = np.ascontiguousarray(grid, dtype=bool)
    return {"dims": list(g.shape), "bits": base64.b64encode(np.packbits(g.reshape(-1)).tobytes()).decode("ascii")}


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
    """

    grid: np.ndarray
    label: str
    name: str | None = None
    pitch: float | None = None

    @classmethod
    def of(cls, grid: np.ndarray, *, label: str, name: str | None = None,
           pitch: float | None = None) -> InitialShape:
        """The shape centred in the editor; one line when it is empty or larger than the editor."""
        if not np.asarray(grid).any():
            raise InvalidShapeError(f"{label}: the shape is empty; nothing to open")
        return cls(centred(np.asarray(grid, dtype=bool)), label, name, pitch)

    def answer(self) -> dict[str, Any]:
        """What ``GET /api/initial`` sends: the grid, its facts, and how to name it."""
        return {"grid": pack(self.grid), "facts": facts(self.grid), "label": self.label, "name": self.name,
                "pitch": self.pitch}
