"""A plain-text layer format for hand editing and diffs.

One block per z layer (every layer, an empty one too), bottom first, each headed
``z = K``; then one row per y (highest y first, as on a map), each row one
character per x: ``#`` filled, ``.`` empty.  Blank lines separate blocks; lines
starting with ``;`` are comments.

Example, a 2x2x1 L::

    ; voxfab layers 2 2 1
    z = 0
    #.
    ##
"""

from __future__ import annotations

import re

import numpy as np

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError

from ._registry import ReadResult, register

_HEADER = re.compile(r"^;\s*voxfab layers\s+(\d+)\s+(\d+)\s+(\d+)\s*$")
_LAYER = re.compile(r"^z\s*=\s*(\d+)\s*$")


def read_text(path: PathLike) -> ReadResult:
    """Read the layer format; the header fixes the grid size."""
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except UnicodeDecodeError:
        raise FormatError(f"{path}: not a UTF-8 text file") from None
    lines = text.splitlines()
    if not lines or not _HEADER.match(lines[0]):
        raise FormatError(f"{path}:1: expected the header '; voxfab layers X Y Z'")
    nx, ny, nz = (int(v) for v in _HEADER.match(lines[0]).groups())  # type: ignore[union-attr]
    # Check the sizes before allocating: a typo must not ask for terabytes.
    if min(nx, ny, nz) < 1:
        raise FormatError(f"{path}:1: grid size {nx} {ny} {nz} has a side below 1")
    if max(nx, ny, nz) > MAX_SIDE:
        raise InvalidShapeError(
            f"{path}:1: grid {nx}x{ny}x{nz} is over the limit of {MAX_SIDE} voxels per side"
        )
    grid = np.zeros((nx, ny, nz), dtype=bool)
    z: int | None = None
    rows: list[tuple[int, str]] = []
    seen: set[int] = set()

    def flush() -> None:
        if z is None:
            return
        if len(rows) != ny:
            raise FormatError(f"{path}: layer z = {z} has {len(rows)} rows, expected {ny}")
        for r, (lineno, row) in enumerate(rows):
            if len(row) != nx or set(row) - {"#", "."}:
                raise FormatError(
                    f"{path}:{lineno}: expected {nx} characters of '#' or '.', got {row!r}"
                )
            grid[:, ny - 1 - r, z] = np.frombuffer(row.encode(), dtype=np.uint8) == ord("#")

    for lineno, raw in enumerate(lines[1:], start=2):
        line = raw.strip()
        if not line or line.startswith(";"):
            continue
        m = _LAYER.match(line)
        if m:
            flush()
            z, rows = int(m.group(1)), []
            if z >= nz or z in seen:
                raise FormatError(f"{path}:{lineno}: layer z = {z} is repeated or out of range 0..{nz - 1}")
            seen.add(z)
        elif z is None:
            raise FormatError(f"{path}:{lineno}: a row before any 'z = K' line")
        else:
            rows.append((lineno, line))
    flush()
    missing = sorted(set(range(nz)) - seen)
    if missing:
        # Every layer is written, even an empty one, so a missing layer means a cut file.
        shown = ", ".join(map(str, missing[:5])) + (", ..." if len(missing) > 5 else "")
        raise FormatError(f"{path}: {len(missing)} of {nz} layers missing (z = {shown}); truncated file?")
    return ReadResult(grid)


def format_text(grid: BoolGrid) -> str:
    """Return the layer text of a grid (every layer, bottom first)."""
    nx, ny, nz = grid.shape
    out = [f"; voxfab layers {nx} {ny} {nz}"]
    chars = np.array([ord("."), ord("#")], dtype=np.uint8)
    for z in range(nz):
        out.append(f"z = {z}")
        layer = chars[grid[:, ::-1, z].T.astype(np.uint8)]
        out.extend(row.tobytes().decode() for row in layer)
        out.append("")
    return "\n".join(out)


def write_text_layers(grid: BoolGrid, path: PathLike) -> None:
    """Write the layer format."""
    write_text(path, format_text(grid))


register(".txt", reader=read_text, writer=write_text_layers)
