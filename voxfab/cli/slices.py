"""``voxfab slices``: a shape as laser-cut plates (stacked, interlocked or radial) nested on sheets."""

from __future__ import annotations

import argparse
from pathlib import Path

from voxfab.cli._common import (
    add_pitch_option,
    add_shape_argument,
    add_strict_option,
    load_command_shape,
    print_json,
    print_scale_note,
    print_warnings,
    shape_pitch,
)

HELP = ("slice a shape into laser-cut plates, stacked with dowel holes or slotted (interlocked, radial), "
        "nested on sheets (DXF, SVG, PDF, assembly.3mf)")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``slices`` options."""
    from voxfab.cli._options import add_option_arguments
    from voxfab.fabricate.plates import PlateOptions

    add_shape_argument(parser)
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="DIR", help="output folder")
    add_pitch_option(parser)
    add_option_arguments(parser, PlateOptions)
    add_strict_option(parser)


def run(args: argparse.Namespace) -> int:
    """Slice, nest and write; print the report as JSON."""
    from voxfab._shared.atomic import check_output
    from voxfab.cli._options import options_from_args
    from voxfab.fabricate.plates import PlateOptions, fabricate_plates

    options = options_from_args(PlateOptions, args)
    check_output(args.output, folder=True, marker="plates.json")  # an existing folder, before the work
    shape, title, scaled = load_command_shape(args, pitch=shape_pitch(args))
    made = fabricate_plates(shape, options, args.output, name=title)
    print_json({**made.report, "files": [str(args.output / f.path) for f in made.files]})
    print_scale_note(args, scaled)
    return print_warnings(made.warnings, strict=args.strict)
