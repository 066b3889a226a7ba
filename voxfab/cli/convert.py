"""``voxfab convert IN OUT``: read a shape in one format and write it in another."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from voxfab.cli._common import print_notes
from voxfab.cli._options import integer_argument

HELP = "convert a shape between formats (meshes and PNG slice folders are read only)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``IN``, ``OUT``, ``--resolution`` and ``--threshold``."""
    parser.add_argument(
        "input", metavar="IN", type=Path,
        help="a shape file (.npy .npz .txt .vox .binvox .png .stl .obj .ply .3mf) or a folder of PNG slices",
    )
    parser.add_argument(
        "output", metavar="OUT", type=Path, help="the file to write (.npy .npz .txt .vox .binvox)"
    )
    parser.add_argument(
        "--resolution", type=integer_argument, default=None, metavar="N",
        help="for a mesh: voxels along its longest side (default 25)",
    )
    parser.add_argument(
        "--threshold", type=integer_argument, default=None, metavar="T",
        help="for PNG slices: grey level below which a pixel is filled (default 128)",
    )


def run(args: argparse.Namespace) -> int:
    """Convert ``args.input`` to ``args.output``; print the reader's notes; return 0."""
    from voxfab import io
    from voxfab._shared.atomic import check_output
    from voxfab.errors import UnknownFormatError

    out_ext = args.output.suffix.lower()
    if out_ext not in io.writable_formats():
        # Checked before reading, so a slow mesh voxelization is not wasted.
        raise UnknownFormatError(
            f"{args.output}: cannot write {out_ext or '(no extension)'!r}; "
            f"writable: {', '.join(io.writable_formats())}"
        )
    check_output(args.output)  # an existing folder, before the reading
    options: dict[str, Any] = {}
    if args.resolution is not None:
        options["resolution"] = args.resolution
    if args.threshold is not None:
        options["threshold"] = args.threshold
    result = io.read(args.input, **options)
    print_notes(list(result.notes))
    io.write(result.grid, args.output)
    shape = "x".join(str(s) for s in result.grid.shape)
    print(f"{args.output}: {shape} grid, {int(result.grid.sum())} voxels")
    return 0
