"""``.binvox``: a text header, then the grid run-length encoded.

Layout (https://www.patrickmin.com/binvox/binvox.html)::

    #binvox 1
    dim DX DY DZ
    translate TX TY TZ
    scale S
    data
    (value, count) byte pairs, value 0 or 1, count 1..255

The runs cover the grid with y varying fastest, then z, then x ("x-z-y" order:
index ``x·DZ·DY + z·DY + y``), and ``dim`` lists the sizes along x, y, z.  This is
the convention of the binvox tool and of ``trimesh.exchange.binvox`` (whose
``axis_order="xzy"`` default reads voxfab's files as the same ``[x, y, z]`` grid).

``translate`` and ``scale`` place the grid in the source model's units, which the
format does not name, so the reader does not turn them into a pitch; the writer
puts the grid at the origin with one unit per voxel (``scale`` = largest side).
"""

from __future__ import annotations

import math

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.numbers import is_digits
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE, as_grid
from voxfab.errors import FormatError, InvalidShapeError

from ._registry import ReadResult, register

__all__ = ["read_binvox", "binvox_bytes", "write_binvox"]

# The header is a handful of short lines; anything longer is not a binvox file.
_MAX_HEADER_LINES = 16
_MAX_LINE = 256


def _encode_runs(flat: np.ndarray) -> bytes:
    """Run-length encode a flat bool array as (value, count ≤ 255) byte pairs."""
    v = flat.astype(np.uint8)
    starts = np.flatnonzero(np.concatenate(([True], v[1:] != v[:-1])))
    lengths = np.diff(np.append(starts, len(v)))
    values = v[starts]
    # A run longer than 255 becomes ceil(n/255) pairs: 255, 255, ..., remainder.
    pieces = -(-lengths // 255)
    run_values = np.repeat(values, pieces)
    counts = np.full(int(pieces.sum()), 255, dtype=np.int64)
    last = np.cumsum(pieces) - 1
    counts[last] = lengths - 255 * (pieces - 1)
    pairs = np.empty((len(counts), 2), dtype=np.uint8)
    pairs[:, 0] = run_values
    pairs[:, 1] = counts
    return pairs.tobytes()


def binvox_bytes(grid: BoolGrid) -> bytes:
    """Return the ``.binvox`` content of a grid ``[x, y, z]`` (deterministic).

    Parameters
    ----------
    grid : (X, Y, Z) bool ndarray

    Returns
    -------
    bytes
        Header with ``dim X Y Z``, ``translate 0 0 0``, ``scale max(X, Y, Z)``,
        then the runs in x-z-y order.
    """
    g = as_grid(grid, name="shape", allow_empty=True)
    nx, ny, nz = g.shape
    header = f"#binvox 1\ndim {nx} {ny} {nz}\ntranslate 0 0 0\nscale {max(g.shape)}\ndata\n"
    return header.encode("ascii") + _encode_runs(np.transpose(g, (0, 2, 1)).ravel())


def write_binvox(grid: BoolGrid, path: PathLike) -> None:
    """Write a grid as ``.binvox``, atomically."""
    write_bytes(path, binvox_bytes(grid))


def _parse_header(data: bytes, path: PathLike) -> tuple[tuple[int, int, int], int]:
    """Return ``dim`` and the offset of the first run."""
    pos = 0
    dims: tuple[int, int, int] | None = None
    for lineno in range(1, _MAX_HEADER_LINES + 1):
        end = data.find(b"\n", pos, pos + _MAX_LINE)
        if end < 0:
            raise FormatError(f"{path}: truncated or corrupt binvox header at line {lineno}")
        try:
            line = data[pos:end].decode("ascii").strip()
        except UnicodeDecodeError:
            raise FormatError(f"{path}: line {lineno} of the binvox header is not text") from None
        pos = end + 1
        words = line.split()
        if lineno == 1:
            if len(words) != 2 or words[0] != "#binvox" or not is_digits(words[1]):
                raise FormatError(f"{path}: not a binvox file (the first line is not '#binvox N')")
            continue
        if not words or words[0].startswith("#"):
            continue
        key, values = words[0], words[1:]
        if key == "data":
            if dims is None:
                raise FormatError(f"{path}: the binvox header has no 'dim' line")
            return dims, pos
        try:
            if key == "dim" and len(values) == 3:
                dims = (int(values[0]), int(values[1]), int(values[2]))
                continue
            if key == "translate" and len(values) == 3 and all(math.isfinite(float(v)) for v in values):
                continue
            if key == "scale" and len(values) == 1 and math.isfinite(float(values[0])):
                continue
        except ValueError:
            pass
        raise FormatError(f"{path}: line {lineno} of the binvox header is not valid: {line!r}")
    raise FormatError(f"{path}: the binvox header has no 'data' line")


def read_binvox(path: PathLike) -> ReadResult:
    """Read a ``.binvox`` file into a grid ``[x, y, z]``.

    Raises
    ------
    FormatError
        On a bad header, run values other than 0/1, or runs that do not cover
        the grid exactly (truncated or padded data).
    InvalidShapeError
        When ``dim`` is over 256 on a side.
    """
    with open(path, "rb") as fh:
        data = fh.read()
    dims, start = _parse_header(data, path)
    if min(dims) < 1:
        raise FormatError(f"{path}: binvox dim {dims} has a side below 1")
    if max(dims) > MAX_SIDE:
        raise InvalidShapeError(
            f"{path}: grid {'x'.join(map(str, dims))} is over the limit of {MAX_SIDE} voxels per side"
        )
    runs = np.frombuffer(data, dtype=np.uint8, offset=start)
    if len(runs) % 2:
        raise FormatError(f"{path}: truncated binvox data (an odd number of run bytes)")
    values, counts = runs[0::2], runs[1::2].astype(np.int64)
    if values.size and values.max() > 1:
        raise FormatError(f"{path}: corrupt binvox data (a run value {int(values.max())} is not 0 or 1)")
    total = int(counts.sum())
    expected = dims[0] * dims[1] * dims[2]
    if total != expected:
        raise FormatError(
            f"{path}: binvox runs cover {total} voxels, the grid {dims} has {expected} "
            f"({'truncated' if total < expected else 'corrupt'} data)"
        )
    flat = np.repeat(values.astype(bool), counts)
    grid = np.ascontiguousarray(flat.reshape(dims[0], dims[2], dims[1]).transpose(0, 2, 1))
    return ReadResult(grid)


register(".binvox", reader=read_binvox, writer=write_binvox)
