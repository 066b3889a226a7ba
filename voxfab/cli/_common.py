"""Helpers shared by the subcommands: shape arguments and output."""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path
from typing import Any

from voxfab.shape import VoxelShape

#: A repository name: 5-digit volume, a dot, 3-digit rank.
NAME_PATTERN = re.compile(r"^\d{5}\.\d{3}$")
DEFAULT_REPOSITORY = Path("output") / "repository.sqlite"


def add_shape_argument(parser: argparse.ArgumentParser) -> None:
    """Add the SHAPE positional (a file or a repository name) and ``--repo``."""
    parser.add_argument("shape", metavar="SHAPE", help="a shape file, or a repository name such as 00797.001")
    add_repository_option(parser)


def add_repository_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--repo PATH`` (default ``output/repository.sqlite``)."""
    parser.add_argument(
        "--repo", type=Path, default=DEFAULT_REPOSITORY, metavar="PATH",
        help=f"repository database (default {DEFAULT_REPOSITORY})",
    )


def load_shape(spec: str, repository: Path | None = None, **options: Any) -> tuple[VoxelShape, str | None, list[str]]:
    """Load SHAPE from a file or the repository.

    Returns
    -------
    shape, name, notes
        ``name`` is the repository name when the shape was loaded by name.
    """
    from voxfab import io

    if NAME_PATTERN.match(spec) and not Path(spec).exists():
        from voxfab.repo import Repository

        with Repository(repository or DEFAULT_REPOSITORY, create=False) as repo:
            grid = repo.get(spec)
        return VoxelShape(grid), spec, []
    result = io.read(spec, **options)
    return VoxelShape(result.grid, result.pitch or 1.0), None, list(result.notes)


def print_notes(notes: list[str]) -> None:
    """Print reader notes to stderr, one per line."""
    for note in notes:
        print(f"voxfab: note: {note}", file=sys.stderr)


def print_json(data: Any) -> None:
    """Print exactly one JSON object on stdout."""
    print(json.dumps(data, sort_keys=True))
