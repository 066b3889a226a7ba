"""A shape by file name or repository name, at its scale: what every command, the studio and batch runs load."""

from __future__ import annotations

import os
from typing import Any, NamedTuple

from voxfab._shared.typing import PathLike
from voxfab.shape import VoxelShape

from ._records import NAME_LIKE, check_name


class LoadedShape(NamedTuple):
    """A loaded shape and where its scale came from.

    Attributes
    ----------
    shape : VoxelShape
        The voxels at their pitch (mm per voxel).
    name : str or None
        The repository name, when the shape was loaded by name.
    notes : list of str
        The file reader's notes (a mesh's resolution, a cropped margin).
    scaled : bool
        Whether the pitch was given (by ``pitch`` or the file itself) rather than
        the 1 mm default: an output that can choose a scale itself (a net fitted to
        its sheet) does so only when it was not.
    """

    shape: VoxelShape
    name: str | None
    notes: list[str]
    scaled: bool


def load_shape(source: str, repository: PathLike | None = None, *, pitch: float | None = None,
               **options: Any) -> LoadedShape:
    """Load ``source``, a shape file or a repository name (``VVVVV.NNN``, ``draft-N``, ``RANGE:MEMBER``), at its scale.

    Parameters
    ----------
    source : str
        A file any reader of :mod:`voxfab.io` takes, or a repository name; an
        existing file of that name wins.
    repository : path, optional
        The repository database (default ``output/repository.sqlite``); it must exist.
    pitch : float, optional
        mm per voxel; default the file's own, else 1 mm.
    **options
        Reader options (a mesh's ``resolution``).
    """
    from voxfab import io
    from voxfab.shape import ShapeOptions

    ShapeOptions(pitch=pitch)  # checked before reading
    # A name is checked as a name (one line for a malformed one) before it is tried as a path;
    # an existing file of that name still wins.
    if NAME_LIKE.fullmatch(source) and not _exists(source, quiet=True):
        check_name(source)
        from ._repository import DEFAULT_PATH, Repository

        with Repository(repository or DEFAULT_PATH, create=False) as repo:
            shape = repo.shape(source, pitch or 1.0)
        return LoadedShape(shape, source, [], pitch is not None)
    _exists(source)  # a path no system call can look up is one line, not an OSError
    result = io.read(source, **options)
    own = pitch if pitch is not None else result.pitch
    return LoadedShape(result.shape(own), None, list(result.notes), own is not None)


def _exists(source: str, *, quiet: bool = False) -> bool:
    """Whether a file or folder ``source`` exists.

    A path the system cannot even look up (a name over 255 bytes, a NUL byte) is
    refused in one line, or with ``quiet`` counts as missing.
    """
    from voxfab.errors import FormatError

    try:
        os.stat(source)
    except (FileNotFoundError, NotADirectoryError):
        return False
    except (OSError, ValueError) as exc:
        if quiet:
            return False
        detail = getattr(exc, "strerror", None) or exc
        raise FormatError(f"{source[:80]!r}{'...' if len(source) > 80 else ''}: cannot read: {detail}") from None
    return True
