"""voxfab's size limits on input, and the guarded readers that enforce them.

Every input a user hands over is bounded before work starts, so a hostile or
mistaken file fails in milliseconds with a message that gives the count, rather
than exhausting memory, the Python stack or the user's patience.  The limits are
far above what a 25-voxel shape needs; each is documented in the README.

=====================  ============================  ======================================
limit                  value                         applies to
=====================  ============================  ======================================
MAX_EXPRESSION_CHARS   1,000 characters              math expressions (recipes, CLI)
MAX_EXPRESSION_DEPTH   100 levels                    nesting of an expression's syntax tree
MAX_NESTING            64 levels                     JSON drawings/points, TOML recipes
MAX_INTEGER_DIGITS     30 digits                     integers in JSON files
MAX_PIXELS             16,777,216 (4096 x 4096)      bitmaps (drawings, profiles, PNG slices)
MAX_SAMPLES            100,000                       samples of a maker's curve (tube spine)
MAX_FOCI               256                           foci of the focal maker
MAX_SEARCH_CELLS       16,777,216                    cells of the tube maker's search grid
MAX_TRIANGLES          1,000,000                     triangles read from a mesh file
MAX_MESH_BYTES         64 MiB                        size of a mesh file (3MF: unpacked)
MAX_RAY_TESTS          60,000,000                    triangle-column tests to voxelize a mesh
MAX_TEXT_BYTES         16 MiB                        drawings, point lists, recipes
MAX_EXPLORE_COUNT      1,000,000                     new shapes of one ``explore`` run
MAX_EXPLORE_ATTEMPTS   100,000,000                   candidates of one ``explore`` run
MAX_BATCH_WORKERS      256                           local Dask workers of ``batch --workers``
MAX_WAIT_SECONDS       3,600 s                       any wait a user sets (``--connect-timeout``)
=====================  ============================  ======================================

Only regular files are read (:func:`check_regular_file`): a FIFO, a device or a
socket would block or never end.
"""

from __future__ import annotations

import json
import os
import stat
import threading
from pathlib import Path
from typing import Any

from voxfab.errors import FormatError, LimitError, VoxfabError

__all__ = [
    "MAX_EXPRESSION_CHARS",
    "MAX_EXPRESSION_DEPTH",
    "MAX_NESTING",
    "MAX_INTEGER_DIGITS",
    "MAX_PIXELS",
    "MAX_SAMPLES",
    "MAX_FOCI",
    "MAX_SEARCH_CELLS",
    "MAX_TRIANGLES",
    "MAX_MESH_BYTES",
    "MAX_RAY_TESTS",
    "MAX_TEXT_BYTES",
    "MAX_EXPLORE_COUNT",
    "MAX_EXPLORE_ATTEMPTS",
    "MAX_BATCH_WORKERS",
    "MAX_WAIT_SECONDS",
    "check_regular_file",
    "read_input_bytes",
    "parse_json",
    "parse_toml",
    "nesting_depth",
    "check_count",
    "check_pixels",
]

#: Characters in a math expression.  CPython's parser runs out of stack on a few
#: thousand nested operators, so the text is bounded before it is parsed.
MAX_EXPRESSION_CHARS = 1_000
#: Nesting depth of an expression's syntax tree (``-(-(-x))`` is 4 deep).
MAX_EXPRESSION_DEPTH = 100
#: Nesting of arrays/objects in a JSON file and of tables/arrays in a TOML recipe.
MAX_NESTING = 64
#: Digits of an integer in a JSON file: coordinates need a handful, and Python
#: refuses to parse more than 4300.
MAX_INTEGER_DIGITS = 30
#: Pixels of a bitmap (drawing, tube profile, PNG slice).  Pillow itself refuses
#: images over about 179 million pixels with a traceback; this is lower and clean.
MAX_PIXELS = 4096 * 4096
#: Samples along a maker's parametric curve (the tube spine).
MAX_SAMPLES = 100_000
#: Foci of the focal maker: each adds one distance field to every evaluation.
MAX_FOCI = 256
#: Cells of the tube maker's search grid, one per profile radius along the spine's
#: box: a profile a billion times smaller than its spine would need petabytes.
MAX_SEARCH_CELLS = 1 << 24
#: Triangles read from a mesh file.
MAX_TRIANGLES = 1_000_000
#: Bytes of a mesh file (a binary STL of 1,000,000 triangles takes 50 MB).
MAX_MESH_BYTES = 64 * 1024 * 1024
#: (triangle, voxel column) pairs the mesh voxelizer tests; a few million per second.
MAX_RAY_TESTS = 60_000_000
#: Bytes of a text input: a drawing, a point list or a recipe.
MAX_TEXT_BYTES = 16 * 1024 * 1024
#: New shapes one ``explore`` run stores: the repository names at most 999 per
#: volume, and a million at the measured rate is already a run of hours.
MAX_EXPLORE_COUNT = 1_000_000
#: Candidates one ``explore`` run draws before giving up (the default is 50 per shape).
MAX_EXPLORE_ATTEMPTS = 100_000_000
#: Local Dask workers of one batch run: each is a process of its own.
MAX_BATCH_WORKERS = 256
#: Seconds of any wait the user sets (connecting to a scheduler, waiting for workers).
MAX_WAIT_SECONDS = 3600.0


_PIL_LOCK = threading.Lock()


def _size(n: int) -> str:
    return f"{n:,}"


def check_regular_file(path: str | os.PathLike[str], *, what: str = "input") -> os.stat_result:
    """Return the ``stat`` of ``path`` after checking it is a regular file (symlinks followed).

    Raises
    ------
    FormatError
        When ``path`` does not exist, or is a folder, FIFO, device or socket:
        opening a FIFO blocks until someone writes to it.
    """
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise FormatError(f"{path}: no such file") from None
    except OSError as exc:
        raise FormatError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        kind = (
            "a folder" if stat.S_ISDIR(st.st_mode)
            else "a FIFO" if stat.S_ISFIFO(st.st_mode)
            else "a socket" if stat.S_ISSOCK(st.st_mode)
            else "a device" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
            else "not a regular file"
        )
        raise FormatError(f"{path}: is {kind}, not a regular file; only regular files are read as {what}")
    return st


def read_input_bytes(path: str | os.PathLike[str], *, what: str = "input", limit: int = MAX_TEXT_BYTES) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes.

    Raises
    ------
    FormatError
        Not a regular file, or unreadable.
    LimitError
        Larger than ``limit``.
    """
    st = check_regular_file(path, what=what)
    if st.st_size > limit:
        raise LimitError(
            f"{path}: {_size(st.st_size)} bytes is over the limit of {_size(limit)} bytes for {what}"
        )
    try:
        with open(path, "rb") as fh:
            # Read one byte more than allowed: a file that grew after stat() is caught too.
            data = fh.read(limit + 1)
    except OSError as exc:
        raise FormatError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if len(data) > limit:
        raise LimitError(f"{path}: over the limit of {_size(limit)} bytes for {what}")
    return data


def nesting_depth(value: Any, *, limit: int = MAX_NESTING) -> int:
    """Depth of nested lists/dicts in ``value`` (a scalar is 0), counted without recursion.

    Stops counting at ``limit + 1``.
    """
    deepest = 0
    stack: list[tuple[Any, int]] = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, (list, tuple, dict)):
            depth += 1
            deepest = max(deepest, depth)
            if deepest > limit:
                return deepest
            stack.extend((v, depth) for v in (item.values() if isinstance(item, dict) else item))
    return deepest


def _bracket_depth(text: str, opening: bytes, closing: bytes) -> int:
    """Deepest nesting of bracket characters in ``text`` outside double-quoted strings.

    A cheap scan run before the parser, whose recursion would overflow on deep
    input.  Single-quoted text and comments count as structure: an overestimate
    only errs on the safe side.
    """
    import re

    import numpy as np

    bare = re.sub(r'"(?:[^"\\\n]|\\.)*"', "", text).encode("utf-8", "replace")
    b = np.frombuffer(bare, dtype=np.uint8)
    step = np.isin(b, np.frombuffer(opening, np.uint8)).astype(np.int64)
    step -= np.isin(b, np.frombuffer(closing, np.uint8))
    return int(np.cumsum(step).max(initial=0))


def _too_deep(name: str, kind: str, depth: int | None = None) -> LimitError:
    if depth is None:
        return LimitError(f"{name}: {kind} nested deeper than the limit of {MAX_NESTING} levels")
    return LimitError(f"{name}: {kind} nested {depth} levels, over the limit of {MAX_NESTING} levels")


def _parse_int(text: str) -> int:
    digits = len(text.lstrip("-"))
    if digits > MAX_INTEGER_DIGITS:
        raise LimitError(f"an integer of {digits} digits is over the limit of {MAX_INTEGER_DIGITS} digits")
    return int(text)


def parse_json(text: str, *, name: str) -> Any:
    """Parse JSON text within :data:`MAX_NESTING` and :data:`MAX_INTEGER_DIGITS`.

    Raises
    ------
    FormatError
        On invalid JSON (with line and column).
    LimitError
        On nesting or an integer over the limits.
    """
    if len(text) > MAX_TEXT_BYTES:
        raise LimitError(f"{name}: {_size(len(text))} characters is over the limit of {_size(MAX_TEXT_BYTES)}")
    depth = _bracket_depth(text, b"[{", b"]}")
    if depth > MAX_NESTING:
        raise _too_deep(name, "JSON", depth)
    try:
        return json.loads(text, parse_int=_parse_int)
    except LimitError as exc:
        raise LimitError(f"{name}: {exc}") from None
    except json.JSONDecodeError as exc:
        raise FormatError(f"{name}: not valid JSON: {exc}") from None
    except RecursionError:  # pragma: no cover - the scan above bounds the depth
        raise _too_deep(name, "JSON") from None
    except ValueError as exc:  # e.g. a float the decoder cannot convert
        raise FormatError(f"{name}: not valid JSON: {exc}") from None


def parse_toml(text: str, *, name: str) -> dict[str, Any]:
    """Parse TOML text within :data:`MAX_NESTING` (tomllib recurses on nested arrays and tables).

    Raises
    ------
    FormatError
        On invalid TOML.
    LimitError
        On nesting over the limit, inline (``a = [[[...]]]``) or by dotted keys.
    """
    import tomllib

    depth = _bracket_depth(text, b"[{", b"]}")
    if depth > MAX_NESTING:
        raise _too_deep(name, "TOML", depth)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise FormatError(f"{name}: invalid TOML: {exc}") from None
    except RecursionError:  # pragma: no cover - the scan above bounds the depth
        raise _too_deep(name, "TOML") from None
    if nesting_depth(data) > MAX_NESTING:
        raise _too_deep(name, "TOML")
    return data


def check_count(value: Any, limit: int, *, name: str, least: int = 1) -> int:
    """Return ``value`` as an int after checking ``least <= value <= limit``.

    Raises
    ------
    LimitError
        Over the limit (the message gives both numbers).
    VoxfabError
        Not an integer, or below ``least`` (an :class:`InvalidShapeError`).
    """
    from voxfab.errors import InvalidShapeError

    if isinstance(value, bool) or not isinstance(value, int):
        try:
            import numpy as np

            ok = isinstance(value, np.integer)
        except ImportError:  # pragma: no cover
            ok = False
        if not ok:
            raise InvalidShapeError(f"{name}: expected an integer, got {type(value).__name__}")
    n = int(value)
    if n < least:
        raise InvalidShapeError(f"{name}: expected an integer >= {least}, got {n}")
    if n > limit:
        raise LimitError(f"{name}: {_size(n)} is over the limit of {_size(limit)}")
    return n


def check_pixels(width: int, height: int, *, name: str) -> None:
    """Refuse a bitmap over :data:`MAX_PIXELS` before its pixels are decoded."""
    if width * height > MAX_PIXELS:
        raise LimitError(
            f"{name}: image of {width}x{height} = {_size(width * height)} pixels is over the limit of "
            f"{_size(MAX_PIXELS)} pixels"
        )


def open_image(path: str | os.PathLike[str], *, name: str) -> Any:
    """Open a bitmap with Pillow after checking the file and its pixel count.

    Returns the opened (not yet decoded) ``PIL.Image.Image``; use it as a context
    manager.  Pillow's decompression-bomb check raises on its own when the pixels
    are later decoded, so the size is checked here first, from the header.

    Raises
    ------
    FormatError
        Not a regular file or not an image Pillow can read.
    LimitError
        More than :data:`MAX_PIXELS` pixels.
    """
    import warnings

    from PIL import Image

    check_regular_file(path, what="an image")
    try:
        # Pillow's own bomb check would raise at open(), before the size can be
        # reported; it is switched off only while the header is read.
        with _PIL_LOCK, warnings.catch_warnings():
            warnings.simplefilter("ignore")
            pillow_limit, Image.MAX_IMAGE_PIXELS = Image.MAX_IMAGE_PIXELS, None
            try:
                im = Image.open(Path(path))
            finally:
                Image.MAX_IMAGE_PIXELS = pillow_limit
    except VoxfabError:
        raise
    except Exception as exc:  # noqa: BLE001
        # Pillow raises UnidentifiedImageError, DecompressionBombError, SyntaxError,
        # struct errors... on corrupt headers: all mean "not a readable image".
        raise FormatError(f"{name}: cannot read image {Path(path).name} ({type(exc).__name__})") from None
    try:
        check_pixels(*im.size, name=name)
    except LimitError:
        im.close()
        raise
    return im
