"""``voxfab slices``: a shape as stacked laser-cut plates nested on sheets."""

from __future__ import annotations

import argparse
from pathlib import Path

from voxfab.cli._common import add_shape_argument, load_shape, print_json, print_notes

HELP = "slice a shape into stacked laser-cut plates with dowel holes, nested on sheets (DXF, SVG, PDF)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``slices`` options."""
    add_shape_argument(parser)
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="DIR", help="output folder")
    parser.add_argument("--axis", choices=("x", "y", "z"), default="z", help="slicing axis (default z)")
    parser.add_argument("--pitch", type=float, default=3.0, metavar="MM",
                        help="voxel edge in mm, i.e. the sculpture's scale (default 3)")
    parser.add_argument("--thickness", type=float, default=3.0, metavar="MM",
                        help="measured plate thickness in mm; a layer takes round(pitch/thickness) plates "
                        "and the height drift is reported (default 3)")
    parser.add_argument("--sheet", default="600x400", metavar="WxH", help="sheet size in mm (default 600x400)")
    parser.add_argument("--margin", type=float, default=5.0, metavar="MM", help="sheet border in mm (default 5)")
    parser.add_argument("--spacing", type=float, default=2.0, metavar="MM", help="gap between parts in mm (default 2)")
    parser.add_argument("--kerf", type=float, default=0.0, metavar="MM",
                        help="laser kerf in mm; outlines grow and holes shrink by half of it (default 0)")
    parser.add_argument("--dowel", type=float, default=3.0, metavar="MM",
                        help="dowel hole diameter in mm, 0 for none (default 3)")
    parser.add_argument("--dowel-margin", type=float, default=1.0, metavar="MM",
                        help="least material between a dowel hole and an edge in mm (default 1)")
    parser.add_argument("--min-width", type=float, default=1.0, metavar="MM",
                        help="narrowest cuttable feature in mm, reported below it (default 1)")
    parser.add_argument("--score", action=argparse.BooleanOptionalAction, default=True,
                        help="score the next layer's outline as a gluing guide (default on)")
    parser.add_argument("--step", action="store_true", help="also write the plate stack as STEP and STL")


def run(args: argparse.Namespace) -> int:
    """Slice, nest and write; print the report as JSON."""
    from voxfab._shared.atomic import atomic_dir, check_output
    from voxfab.fabricate.plates import make_slices, write_slices

    check_output(args.output, folder=True, marker="plates.json")
    shape, name, notes = load_shape(args.shape, args.repo)
    print_notes(notes)
    title = name or Path(args.shape).stem
    result = make_slices(
        shape,
        pitch=args.pitch,
        axis=args.axis,
        thickness=args.thickness,
        sheet=args.sheet,
        margin=args.margin,
        spacing=args.spacing,
        kerf=args.kerf,
        dowel=args.dowel,
        dowel_margin=args.dowel_margin,
        score=args.score,
        min_width=args.min_width,
    )
    with atomic_dir(args.output, marker="plates.json") as tmp:  # the whole folder, or nothing
        files = write_slices(result, tmp, name=title, step=args.step)
    print_json({**result.report.to_json(), "files": [str(args.output / f.path) for f in files]})
    return 0
