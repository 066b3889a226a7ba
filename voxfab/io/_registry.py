"""The format registry: each format module registers readers and writers by extension."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import struct
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from voxfab._shared.limits import check_regular_file
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import as_grid
from voxfab.errors import FormatError, InvalidShapeError, UnknownFormatError, VoxfabError

if TYPE_CHECKING:
    from voxfab.shape import VoxelShape
    from voxfab.shape._colour import VoxelColours

#: Modules that register formats; imported on first use so `import voxfab` stays light.
FORMAT_MODULES = (
    "voxfab.io.npy",
    "voxfab.io.text",
    "voxfab.io.vox",
    "voxfab.io.binvox",
    "voxfab.io.png",
    "voxfab.io.mesh",
)

Reader = Callable[..., "ReadResult"]
#: ``writer(grid, path, **carried)``: a writer that keeps a shape's pitch or colours takes
#: them as the keywords ``pitch`` and ``colours``; the others get the grid alone.
Writer = Callable[..., None]


@dataclasses.dataclass(frozen=True)
class ReadResult:
    """What a reader returns: the grid and notes about what it did.

    Attributes
    ----------
    grid : (X, Y, Z) bool ndarray
    pitch : float or None
        Millimetres per voxel, when the file says so.
    notes : tuple of str
        Things the user should know (a model skipped, voxels dropped, ...).
    colours : VoxelColours or None
        The colour of each voxel, when the file has colours.
    """

    grid: BoolGrid
    pitch: float | None = None
    notes: tuple[str, ...] = ()
    colours: VoxelColours | None = None

    def shape(self, pitch: float | None = None) -> VoxelShape:
        """The shape read, at ``pitch``, else the file's own pitch, else 1 mm."""
        from voxfab.shape import VoxelShape

        return VoxelShape(self.grid, pitch or self.pitch or 1.0, self.colours)


_READERS: dict[str, Reader] = {}
_WRITERS: dict[str, Writer] = {}
_loaded = False


def register(extension: str, *, reader: Reader | None = None, writer: Writer | None = None) -> None:
    """Register a reader and/or writer for a file extension (with its dot, lower case)."""
    ext = extension.lower()
    if reader is not None:
        _READERS[ext] = reader
    if writer is not None:
        _WRITERS[ext] = writer


def _load_all(until: str | None = None) -> None:
    """Import the format modules in order: all of them, or only until one has registered a reader of the
    extension ``until`` (reading a ``.npy`` loads no mesh or image code)."""
    global _loaded
    if _loaded:
        return
    for name in FORMAT_MODULES:
        if until is not None and until in _READERS:
            return
        try:
            importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name != name:
                raise  # a format module that exists but lacks a dependency is a bug
    _loaded = True


def _extension(path: PathLike) -> str:
    p = Path(path)
    if p.is_dir():
        return "/"  # a folder is a PNG slice stack
    return p.suffix.lower()


def readable_formats() -> list[str]:
    """Extensions that can be read (``"/"`` stands for a folder of PNG slices)."""
    _load_all()
    return sorted(_READERS)


def writable_formats() -> list[str]:
    """Extensions that can be written."""
    _load_all()
    return sorted(_WRITERS)


def _check_options(reader: Reader, options: dict[str, Any], path: PathLike, ext: str) -> None:
    """Refuse options the reader does not take (e.g. ``resolution`` for a ``.vox``)."""
    params = inspect.signature(reader).parameters.values()
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params):
        return
    accepted = {p.name for p in params if p.kind is inspect.Parameter.KEYWORD_ONLY}
    unknown = sorted(set(options) - accepted)
    if unknown:
        kind = "a folder of PNG slices" if ext == "/" else f"{ext} files"
        raise InvalidShapeError(
            f"{path}: option{'s' if len(unknown) > 1 else ''} {', '.join(unknown)} "
            f"do{'' if len(unknown) > 1 else 'es'} not apply to {kind}"
            + (f" (options: {', '.join(sorted(accepted))})" if accepted else "")
        )


def read(path: PathLike, **options: Any) -> ReadResult:
    """Read a voxel grid from a file, choosing the format by extension.

    Raises
    ------
    UnknownFormatError
        For an extension no module registered.
    FormatError
        For a missing, corrupt or truncated file.
    InvalidShapeError
        For an option the format does not take, or a grid that is empty or
        over 256 voxels per side.
    """
    ext = _extension(path)
    _load_all(until=ext)
    if not ext and not Path(path).exists():
        raise FormatError(f"{path}: no such file or folder")
    if ext not in _READERS:
        raise UnknownFormatError(
            f"{path}: unknown extension {ext or '(none)'!r}; readable: "
            + ", ".join("a folder of PNG slices" if e == "/" else e for e in readable_formats())
        )
    if not Path(path).exists():
        raise FormatError(f"{path}: no such file")
    if ext != "/":
        # A FIFO would block the reader forever, a device never end.
        check_regular_file(path, what=f"a {ext} file")
    _check_options(_READERS[ext], options, path, ext)
    try:
        result = _READERS[ext](path, **options)
    except VoxfabError:
        raise
    except (OSError, ValueError, KeyError, IndexError, EOFError, StopIteration, struct.error, zlib.error) as exc:
        # Third-party parsers raise many kinds of errors on corrupt data; the user
        # only needs to know that this file could not be read.
        raise FormatError(f"{path}: cannot read as {ext}: {exc or type(exc).__name__}") from exc
    grid = as_grid(result.grid, name=str(path))
    if result.colours is not None and not result.colours.matches(grid):
        raise FormatError(f"{path}: the colours do not cover exactly the filled voxels")
    return dataclasses.replace(result, grid=grid)


def carries(extension: str) -> frozenset[str]:
    """What a format keeps besides the voxels: ``{"pitch", "colours"}`` or a part of it."""
    _load_all()
    writer = _WRITERS.get(extension.lower())
    if writer is None:
        return frozenset()
    params = inspect.signature(writer).parameters
    return frozenset(k for k in ("pitch", "colours") if k in params)


def writer_for(path: PathLike) -> str:
    """The format ``path`` is written in: its extension, or ``"/"`` for a folder of PNG slices (an existing
    folder, or a path ending in a separator).

    Raises
    ------
    UnknownFormatError
        For an extension no module writes, listing those that are written.
    """
    _load_all()
    # An existing folder counts only without an extension: "d.npy/" that is a folder is refused as one.
    folder = str(path).endswith(("/", "\\")) or (Path(path).is_dir() and not Path(path).suffix)
    ext = "/" if folder else Path(path).suffix.lower()
    if ext not in _WRITERS:
        raise UnknownFormatError(
            f"{path}: cannot write {ext or '(no extension)'!r}; writable: "
            + ", ".join("a folder/ of PNG slices" if e == "/" else e for e in writable_formats())
        )
    return ext


def write(shape: VoxelShape | np.ndarray, path: PathLike) -> None:
    """Write a shape (or a bare grid), choosing the format by extension. Written atomically.

    A format that keeps the pitch or the colours (``.npz``, ``.vox``, PNG slices) gets
    them from a :class:`~voxfab.shape.VoxelShape`; :func:`carries` tells which.
    """
    ext = writer_for(path)
    grid = getattr(shape, "grid", shape)
    kept = {k: getattr(shape, k) for k in carries(ext) if hasattr(shape, k)}
    _WRITERS[ext](as_grid(grid, name="shape"), path, **kept)
