"""Write outputs under a temporary name and rename them, so no half output is ever left.

Three primitives cover every output of voxfab:

- :func:`atomic_open` (and :func:`write_bytes`, :func:`write_text`): one file,
  written to a hidden temporary beside it and renamed over it on success;
- :func:`atomic_dir`: a folder assembled under a temporary name and swapped in
  whole on success (``build``, ``slices``);
- :func:`atomic_files`: a set of files (numbered sheets, several nets) whose
  temporaries are all renamed at the end, and which replaces the whole earlier
  set: files of an earlier run named like the set (``t-3.svg``) and not written
  again are removed, so no stale sheet survives.

Temporaries are named ``.NAME.PID-<8 random characters>.tmp``.  They are removed when the run
fails, is interrupted (SIGINT) or terminated (SIGTERM: the CLI turns it into an
exception).  A run killed outright (SIGKILL, power cut) leaves them behind; the
next run writing into the same folder removes those whose process is gone
(:func:`sweep`; a long-running process sweeps a folder once a minute at most).

An output the user names must go in an existing folder: a mistyped ``-o
/nonexistent/dir/x.json`` is refused by :func:`check_output`, which each command
calls before its work, instead of creating folders.  A command creates only the
output folder it makes itself, one level below an existing folder (``build -o
DIR``).  Library callers (recipe outputs writing ``DIR/slices/``) may name new
folders: :func:`atomic_open` creates them.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import re
import shutil
import tempfile
import time
from collections.abc import Iterator
from contextvars import ContextVar
from pathlib import Path
from typing import IO

from voxfab.errors import OutputError

from .typing import PathLike

__all__ = [
    "atomic_open",
    "write_bytes",
    "write_text",
    "atomic_dir",
    "atomic_files",
    "FileSet",
    "check_output",
    "sweep",
]

# ".NAME.PID-RANDOM.tmp": the process id tells a live run's temporary from a dead one's.
_TEMPORARY = re.compile(r"^\..+\.(?P<pid>\d+)-[A-Za-z0-9_]+\.tmp$")


@dataclasses.dataclass
class FileSet:
    """The files of one :func:`atomic_files` block.

    Attributes
    ----------
    written : list of Path
        After the block: the files published, in the order written.  Only files
        that exist are listed, so a report built from it names no missing file.
    removed : list of Path
        Files of an earlier run of the set that were removed.
    """

    families: tuple[Path, ...]
    pending: list[tuple[str, Path]] = dataclasses.field(default_factory=list)
    written: list[Path] = dataclasses.field(default_factory=list)
    removed: list[Path] = dataclasses.field(default_factory=list)


_FILE_SET: ContextVar[FileSet | None] = ContextVar("voxfab_file_set", default=None)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _publish(tmp: str | Path, *, directory: bool = False) -> None:
    """Give a temporary file or folder the permissions a plain open() would have.

    mkstemp and mkdtemp create private entries (0600/0700); outputs are meant to be
    shared with slicers, laser software and other users.
    """
    os.chmod(tmp, (0o777 if directory else 0o666) & ~_umask())


def _prefix(target: Path) -> str:
    return f".{target.name}.{os.getpid()}-"


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # EPERM: the process exists but belongs to someone else
        return True
    return True


def _remove(path: Path) -> None:
    with contextlib.suppress(OSError):
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path, ignore_errors=True)
        else:
            path.unlink()


def sweep(folder: PathLike) -> list[Path]:
    """Remove the temporaries that killed runs left in ``folder``; return them.

    Only entries named as this module names temporaries, whose process no longer
    runs, are removed: a concurrent run's temporaries are left alone.
    """
    removed = []
    try:
        with os.scandir(folder) as listing:  # a census's nets folder holds 100,000 files: no Path per entry
            names = [e.name for e in listing if e.name.startswith(".") and e.name.endswith(".tmp")]
    except OSError:
        return removed
    for name in names:
        m = _TEMPORARY.match(name)
        if m and not _alive(int(m.group("pid"))):
            entry = Path(folder) / name
            _remove(entry)
            removed.append(entry)
    return removed


#: When this process last swept each folder it writes into (``time.monotonic()``).
_SWEPT: dict[str, float] = {}
#: A folder is swept again after this many seconds: a run killed meanwhile leaves its temporaries
#: for a while at most, and a worker writing thousands of files into one folder lists it once a minute.
SWEEP_EVERY = 60.0


def _sweep_once_in_a_while(folder: Path) -> None:
    key = os.path.abspath(folder)
    now = time.monotonic()
    if now - _SWEPT.get(key, -SWEEP_EVERY) >= SWEEP_EVERY:
        sweep(folder)
        _SWEPT[key] = now


def _make_folder(target: Path) -> Path:
    """The folder ``target`` goes in, created when missing (library callers may name new folders)."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{target}: cannot create its folder: {exc.strerror or exc}") from None
    return target.parent


def check_output(path: PathLike, *, folder: bool = False, parents: bool = False, marker: str | None = None) -> None:
    """Refuse an output the user named, before any work: its folder must exist.

    Parameters
    ----------
    path : path
        The output file (or folder, with ``folder=True``).
    folder : bool
        ``path`` names a folder (written with :func:`atomic_dir`), not a file.
    parents : bool
        The command makes the folder ``path`` goes in itself, one level below an
        existing folder (``build -o DIR`` makes ``DIR``).
    marker : str, optional
        As for :func:`atomic_dir`.

    Raises
    ------
    OutputError
        Its folder does not exist, it is a folder where a file is expected (or
        the reverse), or it is a folder of someone's files.
    """
    target = Path(path)
    parent = target.parent
    if parent.exists() and not parent.is_dir():
        raise OutputError(f"{target}: {parent} is not a folder")
    # With parents=True the command makes its output folder itself, one level down.
    if not parent.is_dir() and not (parents and parent.parent.is_dir()):
        raise OutputError(f"{target}: the folder {parent} does not exist")
    if folder:
        if target.exists() and not target.is_dir():
            raise OutputError(f"{target}: exists and is not a folder")
        if marker is not None and target.is_dir() and any(target.iterdir()) and not (target / marker).exists():
            raise OutputError(
                f"{target}: the folder holds files that are not an earlier output (no {marker}); "
                "choose another folder or empty it"
            )
    elif target.is_dir():
        raise OutputError(f"{target}: is a folder, expected a file name")


@contextlib.contextmanager
def atomic_open(path: PathLike, mode: str = "wb") -> Iterator[IO]:
    """Open a temporary file beside ``path``; rename it over ``path`` on success.

    On an exception the temporary file is removed and ``path`` is untouched.
    Inside :func:`atomic_files` the rename waits for the end of that block.
    Missing folders are created, as a library caller asks; commands check the
    outputs the user names with :func:`check_output` first, which refuses them.

    Raises
    ------
    OutputError
        When ``path`` is a folder.
    """
    target = Path(path)
    if target.is_dir():
        raise OutputError(f"{target}: is a folder, expected a file name")
    folder = _make_folder(target)
    _sweep_once_in_a_while(folder)
    try:
        fd, tmp = tempfile.mkstemp(prefix=_prefix(target), suffix=".tmp", dir=folder)
    except OSError as exc:
        raise OutputError(f"{target}: cannot write: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, mode) as fh:
            yield fh
        _publish(tmp)
        pending = _FILE_SET.get()
        if pending is not None:
            pending.pending.append((tmp, target))
        else:
            os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_bytes(path: PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically."""
    with atomic_open(path, "wb") as fh:
        fh.write(data)


def write_text(path: PathLike, text: str) -> None:
    """Write UTF-8 ``text`` with ``\\n`` line ends to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def _family(base: Path) -> re.Pattern[str]:
    """Names of the files an output ``base`` may stand for.

    ``t.svg``, ``t-2.svg`` (net 2), ``t-1-piece2.svg`` (a piece), ``t.sheet-3.svg``
    (sheet 3 of a drawing) and their combinations.
    """
    tags = r"(?:-(?:\d+|piece\d+)|\.sheet-\d+)*"
    return re.compile(rf"^{re.escape(base.stem)}{tags}{re.escape(base.suffix)}$")


@contextlib.contextmanager
def atomic_files(*families: PathLike) -> Iterator[FileSet]:
    """Publish every file written atomically in the block together, replacing the earlier set.

    Parameters
    ----------
    *families : path
        The outputs as the user named them (``t.svg``).  Files beside them named
        ``t.svg``, ``t-N.svg``, ``t-N-pieceM.svg`` or ``t.sheet-N.svg`` that the block did not write
        are left from an earlier run: they are removed after a successful block.

    Yields
    ------
    FileSet
        Its ``written`` list is filled when the block ends without error.

    Notes
    -----
    Each file is complete before any is renamed, so a failure or an interrupt
    anywhere in the block leaves every earlier file as it was.
    """
    fileset = FileSet(tuple(Path(f) for f in families))
    token = _FILE_SET.set(fileset)
    try:
        yield fileset
    except BaseException:
        for tmp, _ in fileset.pending:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)
        raise
    finally:
        _FILE_SET.reset(token)
    for tmp, target in fileset.pending:
        os.replace(tmp, target)
        if target not in fileset.written:
            fileset.written.append(target)
    kept = {os.path.abspath(t) for t in fileset.written}
    for base in fileset.families:
        pattern = _family(base)
        folder = base.parent
        with contextlib.suppress(OSError):
            for entry in sorted(folder.iterdir()):
                if pattern.match(entry.name) and entry.is_file() and os.path.abspath(entry) not in kept:
                    entry.unlink()
                    fileset.removed.append(entry)


@contextlib.contextmanager
def atomic_dir(path: PathLike, *, marker: str | None = None) -> Iterator[Path]:
    """Yield a temporary folder that replaces ``path`` only on success.

    Parameters
    ----------
    path : path
        The folder to make.  Missing folders above it are created, as a library
        caller asks; commands check the folder the user names with
        :func:`check_output` first.
    marker : str, optional
        A file every output of this kind holds (``plates.json``).  An existing
        non-empty folder without it is refused rather than replaced: it is not an
        earlier output but someone's files.

    Raises
    ------
    OutputError
        When ``path`` is a file, or holds files that are not an earlier output.
    """
    target = Path(path)
    folder = _make_folder(target)
    check_output(target, folder=True, marker=marker)
    _sweep_once_in_a_while(folder)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=_prefix(target), suffix=".tmp", dir=folder))
    except OSError as exc:
        raise OutputError(f"{target}: cannot create a folder: {exc.strerror or exc}") from None
    try:
        yield tmp
        _publish(tmp, directory=True)
        if target.exists():
            # The old folder moves aside under a temporary name, so a kill between
            # the two renames leaves something the next run sweeps.
            old = Path(tempfile.mkdtemp(prefix=_prefix(target), suffix=".tmp", dir=folder))
            os.replace(target, old)
            os.replace(tmp, target)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.replace(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
