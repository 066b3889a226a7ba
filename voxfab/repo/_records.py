"""What the repository stores per shape, computed before any lock is taken."""

from __future__ import annotations

import dataclasses
import json
import re
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab._shared.limits import parse_json
from voxfab._shared.typing import BoolGrid
from voxfab._shared.validate import MAX_SIDE, as_grid
from voxfab.errors import RepositoryError, VoxfabError
from voxfab.shape import VoxelColours, VoxelShape, canonical_key, crop, well_formed_reasons

__all__ = [
    "MAX_RANK",
    "NAME_PATTERN",
    "DRAFT_PATTERN",
    "RANGE_PATTERN",
    "MEMBER_PATTERN",
    "Record",
    "check_grid",
    "encode_meta",
    "prepare",
    "encode_bits",
    "decode_bits",
    "decode_row",
    "decode_colours",
    "decode_reasons",
    "decode_meta",
    "format_name",
    "draft_name",
    "check_name",
    "check_range_name",
    "is_shape_name",
]

#: Ranks run 001..999 per volume.
MAX_RANK = 999
# The patterns are matched whole (``fullmatch``): ``$`` would also match before a final newline,
# and ASCII digits only (``\d`` takes any script's digits).
#: A repository name: 5-digit zero-padded volume, a dot, 3-digit rank.
NAME_PATTERN = re.compile(r"([0-9]{5})\.([0-9]{3})")
#: The id of a draft (a stored shape that is not well formed).
DRAFT_PATTERN = re.compile(r"draft-([0-9]+)")
#: The name of a range: lowercase letters, digits, ``-`` and ``_``, starting with a letter.
RANGE_PATTERN = re.compile(r"[a-z][a-z0-9_-]{0,39}")
#: A member of a range: ``RANGE:MEMBER`` (``polycubes-9:08-000001``).
MEMBER_PATTERN = re.compile(r"([a-z][a-z0-9_-]{0,39}):([0-9a-z][0-9a-z_-]{0,39})")
#: What a user writing a repository name writes: text a file name would not be mistaken for
#: (checked as a name, never tried as a path).
NAME_LIKE = re.compile(r"[0-9]{5}\.[0-9]+|draft-[^./]*|[a-z][a-z0-9_-]*:[^./]*", re.DOTALL)


@dataclasses.dataclass(frozen=True)
class Record:
    """One shape ready to insert.

    Attributes
    ----------
    volume : int
        Number of filled voxels.
    extents : (int, int, int)
        Size of the cropped grid along x, y, z in voxels.
    bits : bytes
        ``np.packbits`` of the cropped grid raveled in C order.
    key, symmetric_key : str
        :func:`voxfab.shape.canonical_key` up to translation, and up to the 48 cube symmetries.
    reasons : tuple of str
        Why the shape is not well formed (empty when it is).
    meta : str or None
        The metadata as JSON text with sorted keys.
    colours : bytes or None
        The RGBA of each voxel of the cropped grid in C order (None: uncoloured).
    """

    volume: int
    extents: tuple[int, int, int]
    bits: bytes
    key: str
    symmetric_key: str
    reasons: tuple[str, ...]
    meta: str | None
    colours: bytes | None = None


def encode_bits(cropped: BoolGrid) -> bytes:
    """Pack a bool grid (C order) into bytes, 8 voxels per byte."""
    return np.packbits(np.ascontiguousarray(cropped).ravel()).tobytes()


def decode_bits(bits: bytes, extents: tuple[int, int, int]) -> BoolGrid:
    """Inverse of :func:`encode_bits`: a writable ``extents``-shaped bool grid.

    Raises
    ------
    RepositoryError
        When ``bits`` is not bytes of exactly the length the extents need:
        ``np.unpackbits(count=n)`` on a short buffer would make up the rest.
    """
    if not isinstance(bits, (bytes, bytearray, memoryview)):
        raise RepositoryError("bits: not stored as a blob")
    if len(extents) != 3 or not all(type(n) is int and 0 < n <= MAX_SIDE for n in extents):
        raise RepositoryError(f"extents: {extents!r} is not three sizes of 1 to {MAX_SIDE} voxels")
    n = extents[0] * extents[1] * extents[2]
    if len(bits) != (n + 7) // 8:
        raise RepositoryError(
            f"bits: {len(bits)} bytes stored, a {extents[0]}x{extents[1]}x{extents[2]} box needs {(n + 7) // 8}"
        )
    flat = np.unpackbits(np.frombuffer(bytes(bits), dtype=np.uint8), count=n)
    return flat.astype(bool).reshape(extents)


def _corrupt(name: str, detail: str) -> RepositoryError:
    return RepositoryError(f"{name}: corrupt repository row ({detail}); 'voxfab repo check' lists every bad row")


def decode_row(
    name: str,
    bits: object,
    extents: tuple[object, object, object],
    volume: object,
    key: object = None,
    symmetric_key: object = None,
    colours: object = None,
) -> BoolGrid:
    """Decode a stored row's grid after checking it against what the row says of it.

    The blob must have the length of its box, the grid must hold ``volume``
    voxels and fill its box (the stored grid is cropped), and when given, ``key``
    and ``symmetric_key`` (32-byte blobs) must be the decoded grid's canonical keys.
    A row that fails any of these is never taken for a shape.

    Raises
    ------
    RepositoryError
        Naming the shape and what is wrong with its row.
    """
    try:
        grid = decode_bits(bits, tuple(extents))  # type: ignore[arg-type]
    except RepositoryError as exc:
        raise _corrupt(name, str(exc)) from None
    if type(volume) is not int:
        raise _corrupt(name, f"volume stored as {type(volume).__name__}")
    count = int(np.count_nonzero(grid))
    if count != volume:
        raise _corrupt(name, f"{count} voxels stored, volume says {volume}")
    if count == 0 or crop(grid).shape != grid.shape:
        raise _corrupt(name, "the stored grid does not fill its box")
    for label, stored, symmetric in (("key", key, False), ("symmetric_key", symmetric_key, True)):
        if stored is None:
            continue
        if not isinstance(stored, bytes) or len(stored) != 32:
            raise _corrupt(name, f"{label} is not a 32-byte blob")
        if canonical_key(grid, symmetric=symmetric, colours=decode_colours(name, colours, grid)) != stored.hex():
            raise _corrupt(name, f"{label} does not match the stored voxels")
    return grid


def _decode_json(name: str, field: str, text: object) -> Any:
    if not isinstance(text, str):
        raise _corrupt(name, f"{field} stored as {type(text).__name__}, expected JSON text")
    try:
        return parse_json(text, name=field)
    except VoxfabError as exc:
        raise _corrupt(name, str(exc)) from None


def decode_reasons(name: str, text: object) -> tuple[str, ...]:
    """The stored ``reasons`` of ``name``: a JSON list of strings, checked."""
    reasons = _decode_json(name, "reasons", text)
    if not isinstance(reasons, list) or not all(isinstance(r, str) for r in reasons):
        raise _corrupt(name, "reasons is not a JSON list of strings")
    return tuple(reasons)


def decode_meta(name: str, text: object) -> dict[str, Any] | None:
    """The stored ``meta`` of ``name``: None, or a JSON object, checked."""
    if text is None:
        return None
    meta = _decode_json(name, "meta", text)
    if not isinstance(meta, dict):
        raise _corrupt(name, "meta is not a JSON object")
    return meta


def encode_meta(meta: Mapping[str, Any] | None) -> str | None:
    """Return ``meta`` as JSON text (sorted keys), or None."""
    if meta is None:
        return None
    if not isinstance(meta, Mapping):
        raise RepositoryError(f"meta: expected a mapping of JSON values, got {type(meta).__name__}")
    try:
        return json.dumps(dict(meta), sort_keys=True, allow_nan=False, separators=(",", ":"))
    except (TypeError, ValueError) as exc:
        raise RepositoryError(f"meta: cannot store as JSON ({exc})") from None


def check_grid(grid: npt.ArrayLike, *, name: str = "shape") -> BoolGrid:
    """Return ``grid`` as a bool grid that has at least one filled voxel.

    Raises
    ------
    InvalidShapeError
        For a wrong dtype or a grid over the size limit.
    RepositoryError
        For an empty grid (nothing to store, not even as a draft).
    """
    g = as_grid(grid, name=name, allow_empty=True)
    if not g.any():
        raise RepositoryError(f"{name}: the grid is empty; an empty shape cannot be stored")
    return g


def prepare(
    grid: BoolGrid,
    *,
    meta: str | None = None,
    key: str | None = None,
    symmetric_key: str | None = None,
    reasons: tuple[str, ...] | None = None,
    colours: VoxelColours | None = None,
) -> Record:
    """Compute everything stored for a grid checked by :func:`check_grid`, and its ``colours``.

    ``meta`` is JSON text from :func:`encode_meta`; ``key``, ``symmetric_key`` and
    ``reasons`` (from :func:`voxfab.shape.well_formed_reasons`) may be passed when
    already computed.  A coloured shape's keys cover its colours: the same voxels in
    other colours are another shape.
    """
    shape = VoxelShape(grid, 1.0, colours).crop()
    c, cc = shape.grid, shape.colours
    return Record(
        volume=int(np.count_nonzero(c)),
        extents=(int(c.shape[0]), int(c.shape[1]), int(c.shape[2])),
        bits=encode_bits(c),
        key=key or canonical_key(c, colours=cc),
        symmetric_key=symmetric_key or canonical_key(c, symmetric=True, colours=cc),
        reasons=tuple(well_formed_reasons(c)) if reasons is None else tuple(reasons),
        meta=meta,
        colours=None if cc is None else cc.rgba[c].tobytes(),
    )


def decode_colours(name: str, blob: object, grid: BoolGrid) -> VoxelColours | None:
    """The colours stored for ``grid`` (the RGBA of each voxel in C order), or None; a bad blob is a corrupt row."""
    if blob is None:
        return None
    if not isinstance(blob, (bytes, bytearray)) or len(blob) != 4 * int(np.count_nonzero(grid)):
        raise _corrupt(name, "colours is not 4 bytes of RGBA per voxel")
    rgba = np.zeros((*grid.shape, 4), dtype=np.uint8)
    rgba[grid] = np.frombuffer(bytes(blob), dtype=np.uint8).reshape(-1, 4)
    try:
        return VoxelColours.from_rgba(grid, rgba)
    except VoxfabError as exc:
        raise _corrupt(name, str(exc)) from None


def format_name(volume: int, rank: int) -> str:
    """Return ``VVVVV.NNN`` for a volume and a rank (1..999)."""
    return f"{volume:05d}.{rank:03d}"


def draft_name(row_id: int) -> str:
    """Return the id of the draft stored in row ``row_id``."""
    return f"draft-{row_id}"


def is_shape_name(text: str) -> bool:
    """Whether ``text`` has the form of a stored shape's name: ``VVVVV.NNN``, ``draft-N`` or ``RANGE:MEMBER``."""
    return isinstance(text, str) and any(p.fullmatch(text) for p in (NAME_PATTERN, DRAFT_PATTERN, MEMBER_PATTERN))


def check_name(name: object) -> str:
    """Return ``name`` if it looks like a shape name, a draft id or a range member, else raise RepositoryError."""
    if not isinstance(name, str) or not is_shape_name(name):
        raise RepositoryError(
            f"{name!r}: not a shape name (expected VVVVV.NNN such as 00797.001, draft-N, or RANGE:MEMBER "
            "such as polycubes-8:08-000001)"
        )
    return name


def check_range_name(name: object) -> str:
    """Return ``name`` if it can name a range, else raise RepositoryError."""
    if not isinstance(name, str) or not RANGE_PATTERN.fullmatch(name):
        raise RepositoryError(
            f"{name!r}: not a range name (expected lowercase letters, digits, '-' and '_', starting with a "
            "letter, at most 40 characters, such as polycubes-8)"
        )
    return name
