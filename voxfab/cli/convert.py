"""``voxfab convert IN OUT``: read a shape in one format and write it in another."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from voxfab.cli._common import add_frame_option, print_notes, reader_options
from voxfab.cli._options import integer_argument

HELP = "convert a shape between formats (meshes and PNG slice folders are read only)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``IN``, ``OUT``, ``--resolution`` and ``--threshold``."""
    parser.add_argument(
        "input", metavar="IN", type=Path,
        help="a shape file (.npy .npz .txt .vox .binvox .png .stl .obj .ply .3mf .glb) or a folder of PNG slices",
    )
    parser.add_argument(
        "output", metavar="OUT", help="the file to write (.npy .npz .txt .vox .binvox), or a folder/ of PNG slices "
        "(a path ending in /)"
    )
    parser.add_argument(
        "--resolution", type=integer_argument, default=None, metavar="N",
        help="for a mesh: voxels along its longest side (default 25)",
    )
    add_frame_option(parser)
    parser.add_argument(
        "--threshold", type=integer_argument, default=None, metavar="T",
        help="for PNG slices: grey level below which a pixel is filled (default 128)",
    )


def run(args: argparse.Namespace) -> int:
    """Convert ``args.input`` to ``args.output``; print the reader's notes; return 0."""
    from voxfab import io
    from voxfab._shared.atomic import check_output

    # Checked before reading, so a slow mesh voxelization is not wasted.
    folder = io.writer_for(args.output) == "/"
    check_output(Path(args.output), folder=folder)  # an existing folder, before the reading
    options: dict[str, Any] = reader_options(args)
    if args.resolution is not None:
        options["resolution"] = args.resolution
    if args.threshold is not None:
        options["threshold"] = args.threshold
    result = io.read(args.input, **options)
    print_notes(list(result.notes))
    io.write(result.shape(), args.output)
    shape = "x".join(str(s) for s in result.grid.shape)
    print(f"{args.output}: {shape} grid, {int(result.grid.sum())} voxels")
    return 0
