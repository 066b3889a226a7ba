"""Helpers shared by the subcommands: shape arguments and output."""

from __future__ import annotations

import argparse
import contextlib
import json
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from voxfab.repo import Repository
    from voxfab.shape import VoxelShape

#: The repository the commands use by default: ``voxfab.repo.DEFAULT_PATH``, named here so that
#: parsing arguments does not import the repository (sqlite3).
DEFAULT_REPOSITORY = Path("output") / "repository.sqlite"

#: Exit status of a command run with ``--strict`` that ended with warnings.
STRICT_EXIT = 11


def path_argument(text: str) -> Path:
    """An argparse ``type`` for a path the user names: an empty one is refused, not taken as ``.``."""
    if not text.strip():
        raise argparse.ArgumentTypeError("expected a path, got ''")
    return Path(text)


def add_shape_argument(parser: argparse.ArgumentParser) -> None:
    """Add the SHAPE positional (a file or a repository name) and ``--repo``."""
    parser.add_argument("shape", metavar="SHAPE", help="a shape file, or a repository name such as 00797.001")
    add_frame_option(parser)
    add_join_option(parser)
    add_repository_option(parser)


def add_join_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--join``: join a shape's parts into one piece (read by :func:`joined_if_asked`)."""
    parser.add_argument("--join", action="store_true",
                        help="join parts that touch only by edges or corners (voxel art) into one piece, adding "
                             "the fewest voxels found, each in a neighbour's colour; says where")


def add_frame_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--frame K``: the animation frame of a ``.vox`` to read."""
    from voxfab.cli._options import integer_argument

    parser.add_argument("--frame", type=integer_argument, default=None, metavar="K",
                        help="for an animated .vox: the frame to read, from 1 (default the first)")


def reader_options(args: argparse.Namespace) -> dict[str, Any]:
    """The reader options the command line gave (only those given, so other formats are not refused)."""
    return {} if getattr(args, "frame", None) is None else {"frame": args.frame}


def add_repository_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--repo PATH`` (default ``output/repository.sqlite``)."""
    parser.add_argument(
        "--repo", type=Path, default=DEFAULT_REPOSITORY, metavar="PATH",
        help=f"repository database (default {DEFAULT_REPOSITORY})",
    )


def check_repository_path(path: Path) -> None:
    """Refuse ``--repo PATH`` at start unless it is a voxfab repository or can become one.

    An existing file must open as a repository of a schema this voxfab reads (not
    a folder, another SQLite file or a newer schema); a new one must go in an
    existing folder (only the default ``output/`` folder is made).
    """
    from voxfab._shared.atomic import check_output
    from voxfab.repo import Repository

    if path.exists():
        Repository(path, create=False).close()
    else:
        check_output(path, parents=path == DEFAULT_REPOSITORY)


@contextlib.contextmanager
def open_repository_for_writing(path: Path) -> Iterator[Repository]:
    """Open (or create) the repository a command stores shapes in.

    A file at a path the user names must go in an existing folder (only the
    default ``output/`` folder is made), and a file this run created is removed
    again when the run fails before storing anything: a refusal leaves no empty
    repository behind.
    """
    from voxfab.repo import Repository

    existed = path.exists()
    check_repository_path(path)
    made_folder = not path.parent.exists()
    repo = Repository(path, create=True)
    try:
        yield repo
    except BaseException:
        empty = not existed and len(repo) == 0
        repo.close()
        if empty:
            for leftover in (path, path.with_name(path.name + "-wal"), path.with_name(path.name + "-shm")):
                leftover.unlink(missing_ok=True)
            if made_folder:
                with contextlib.suppress(OSError):
                    path.parent.rmdir()
        raise
    repo.close()


def add_pitch_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--pitch MM``: the shape's scale, read by every artefact."""
    from voxfab.cli._options import add_option_arguments
    from voxfab.shape import ShapeOptions

    add_option_arguments(parser, ShapeOptions)


def shape_pitch(args: argparse.Namespace) -> float | None:
    """The ``--pitch`` given, checked before any file is read (a bad value names the flag)."""
    from voxfab.cli._options import options_from_args
    from voxfab.shape import ShapeOptions

    return options_from_args(ShapeOptions, args).pitch


def load_command_shape(args: argparse.Namespace, *, pitch: float | None = None) -> tuple[VoxelShape, str, bool]:
    """The shape SHAPE names (a file, or a name in ``--repo``) at ``pitch``, its reader's notes printed.

    Returns
    -------
    shape : VoxelShape
    title : str
        Its repository name, else the file's stem (a build's shape file: its recipe's name): the name its
        artefacts carry.
    scaled : bool
        Whether its scale is known (``pitch``, or the file's own).
    """
    from voxfab.repo import load_shape

    shape, name, notes, scaled = load_shape(args.shape, args.repo, pitch=pitch, **reader_options(args))
    shape = joined_if_asked(args, shape, notes)
    print_notes(notes)
    return shape, name or file_title(args.shape), scaled


def file_title(path: str) -> str:
    """The name a shape file's artefacts carry: its stem, or its recipe's name for a build's shape file."""
    if (Path(path).parent / "manifest.json").is_file():  # a build's folder: only then load the recipe code
        from voxfab.recipe import built_shape_name

        return built_shape_name(path) or Path(path).stem
    return Path(path).stem


def joined_if_asked(args: argparse.Namespace, shape: VoxelShape, notes: list[str]) -> VoxelShape:
    """The shape joined into one piece when ``--join`` was given, with a note per join added to ``notes``."""
    if not getattr(args, "join", False):
        return shape
    joined, joins = shape.joined()
    notes += [join.describe() for join in joins] or ["--join: the shape is one piece already"]
    return joined


def print_scale_note(args: argparse.Namespace, scaled: bool) -> None:
    """After an object whose size comes from the pitch (a print, plates) was made from a shape
    with no scale, say so in one line, and how to give it one."""
    if not scaled:
        print_notes([f"{args.shape} holds no scale: made at 1 mm per voxel (give --pitch MM, or the shape.npz "
                     "a build wrote, which keeps its pitch)"])


def print_warnings(warnings: Sequence[str], *, strict: bool = False) -> int:
    """End a command with the warnings a maker must read, one line each.

    Returns
    -------
    int
        The exit status: 0, or 11 when ``strict`` and there are warnings.
    """
    if warnings:
        print(f"voxfab: {len(warnings)} warning(s) to read before making this:", file=sys.stderr)
    for w in warnings:
        print(f"voxfab: warning: {w}", file=sys.stderr)
    return STRICT_EXIT if strict and warnings else 0


def add_strict_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--strict``: warnings make the command fail."""
    parser.add_argument("--strict", action="store_true",
                        help=f"exit with status {STRICT_EXIT} when there are warnings (for scripts and CI)")


def print_notes(notes: list[str]) -> None:
    """Print reader notes to stderr, one per line."""
    for note in notes:
        print(f"voxfab: note: {note}", file=sys.stderr)


def print_json(data: Any) -> None:
    """Print exactly one JSON object on stdout."""
    print(json.dumps(data, sort_keys=True))
