"""A plain-text layer format for hand editing and diffs.

One block per z layer (every layer, an empty one too), bottom first, each headed
``z = K``; then one row per y (highest y first, as on a map), each row one
character per x: ``#`` filled, ``.`` empty.  Blank lines separate blocks; lines
starting with ``;`` are comments.

Voxel art in colour: a line ``; colour C #rrggbb`` (after the header, maybe
followed by a name) makes the character ``C`` a filled voxel of that colour, so a
coloured figure can be drawn and read in any text editor; ``#`` is then a white
voxel.  Up to 85 colours, one character each (letters, digits and punctuation
other than ``#``, ``.`` and ``;``).

Example, a 2x2x1 L, one voxel red::

    ; voxfab layers 2 2 1
    ; colour r #c03020
    z = 0
    r.
    ##
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

import numpy as np

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError

from ._registry import ReadResult, register

if TYPE_CHECKING:
    from voxfab.shape import VoxelColours

_HEADER = re.compile(r"^;\s*voxfab layers\s+(\d+)\s+(\d+)\s+(\d+)\s*$")
_COLOUR = re.compile(r"^;\s*colour\s+(\S)\s+(#[0-9a-fA-F]{6})(\s+.*)?$")
#: The characters colours are written with, in order: ``#``, ``.`` and ``;`` keep their meanings.
_COLOUR_CHARS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789!$%&*+-=?@^~<>()[]{}/|:"
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
    # Each cell's character code; the colour lines name the characters of coloured voxels.
    cells = np.zeros((nx, ny, nz), dtype=np.uint8)
    colours: dict[str, tuple[int, int, int, int]] = {}
    for lineno, raw in enumerate(lines[1:], start=2):
        m = _COLOUR.match(raw.strip())
        if m:
            if m.group(1) in "#.;" or m.group(1) in colours:
                raise FormatError(f"{path}:{lineno}: colour character {m.group(1)!r} is reserved or given twice")
            rgb = bytes.fromhex(m.group(2)[1:])
            colours[m.group(1)] = (rgb[0], rgb[1], rgb[2], 255)
    allowed = {"#", "."} | set(colours)
    z: int | None = None
    rows: list[tuple[int, str]] = []
    seen: set[int] = set()

    def flush() -> None:
        if z is None:
            return
        if len(rows) != ny:
            raise FormatError(f"{path}: layer z = {z} has {len(rows)} rows, expected {ny}")
        for r, (lineno, row) in enumerate(rows):
            if len(row) != nx or set(row) - allowed:
                given = "'#' or '.'" if not colours else f"'#', '.' or a colour ({''.join(sorted(colours))})"
                raise FormatError(f"{path}:{lineno}: expected {nx} characters of {given}, got {row!r}")
            codes = np.frombuffer(row.encode(), dtype=np.uint8)
            grid[:, ny - 1 - r, z] = codes != ord(".")
            cells[:, ny - 1 - r, z] = codes

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
    if not colours:
        return ReadResult(grid)
    table = np.zeros((256, 4), dtype=np.uint8)
    table[ord("#")] = (255, 255, 255, 255)
    for char, rgba in colours.items():
        table[ord(char)] = rgba
    from voxfab.shape import VoxelColours

    return ReadResult(grid, None, (), VoxelColours.from_rgba(grid, table[cells]))


def format_text(grid: BoolGrid, colours: VoxelColours | None = None) -> str:
    """Return the layer text of a grid (every layer, bottom first), its voxels in their colours when given.

    Raises
    ------
    InvalidShapeError
        For more colours than the format has characters (80).
    """
    nx, ny, nz = grid.shape
    out = [f"; voxfab layers {nx} {ny} {nz}"]
    if colours is None:
        chars = np.array([ord("."), ord("#")], dtype=np.uint8)
        cells = grid.astype(np.uint8)
    else:
        used = [int(i) for i in colours.used]
        if len(used) > len(_COLOUR_CHARS):
            raise InvalidShapeError(f"shape: {len(used)} colours; the text format writes at most "
                                    f"{len(_COLOUR_CHARS)} (use .vox or .npz)")
        chars = np.full(256, ord("."), dtype=np.uint8)
        for char, index in zip(_COLOUR_CHARS, used):
            chars[index] = ord(char)
            out.append(f"; colour {char} {colours.hex(index)}")
        cells = colours.index
    for z in range(nz):
        out.append(f"z = {z}")
        layer = chars[cells[:, ::-1, z].T]
        out.extend(row.tobytes().decode() for row in layer)
        out.append("")
    return "\n".join(out)


def write_text_layers(grid: BoolGrid, path: PathLike, *, colours: VoxelColours | None = None) -> None:
    """Write the layer format (in colour when the shape has colours)."""
    write_text(path, format_text(grid, colours))


register(".txt", reader=read_text, writer=write_text_layers)
