"""``voxfab mesh``: a checked, print-ready solid as 3MF, STL, OBJ, GLB or PLY, in the shape's colours."""

from __future__ import annotations

import argparse
from pathlib import Path

from ._common import (
    add_pitch_option,
    add_shape_argument,
    add_strict_option,
    load_command_shape,
    print_json,
    print_notes,
    print_scale_note,
    print_warnings,
    shape_pitch,
)

HELP = "write a print-ready solid (3MF, STL, OBJ, GLB or PLY), checked edge by edge, in the shape's colours"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    from voxfab.fabricate.mesh import MeshOptions

    from ._options import add_option_arguments

    add_shape_argument(parser)
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="OUT",
                        help="output file: .3mf (default choice for slicers, in colour), .stl (one colour), "
                        ".obj (with a .mtl of its colours), .glb or .ply")
    add_pitch_option(parser)
    add_option_arguments(parser, MeshOptions, exclude=("label",))
    parser.add_argument("--label", nargs="?", const="{name}", default=None, metavar="TEXT",
                        help="engrave TEXT on the bottom (without TEXT: the repository name or file name)")
    parser.add_argument("--json", action="store_true", help="print the mesh figures as one JSON object")
    add_strict_option(parser)


def run(args: argparse.Namespace) -> int:
    from voxfab._shared.atomic import check_output
    from voxfab.errors import InvalidShapeError
    from voxfab.fabricate.mesh import MeshOptions, estimate_line, fabricate_mesh, filaments_line, format_for

    from ._options import options_from_args

    format_for(args.output)  # refuse an unknown extension before any work
    check_output(args.output)  # and a folder that does not exist
    options = options_from_args(MeshOptions, args, label=args.label)
    if args.pitch is not None and options.size is not None:
        raise InvalidShapeError("--pitch and --size: give one of them, not both")
    if options.label is not None:
        from voxfab._shared.deps import require_extra

        require_extra("cad", "--label (an engraved label)")
    shape, name, scaled = load_command_shape(args, pitch=shape_pitch(args))
    made = fabricate_mesh(shape, options, args.output, name=name)
    info = made.report
    if args.json:
        print_json({**info, "output": str(args.output)})
    else:
        size = " x ".join(f"{s:g}" for s in info["size_mm"])
        print(
            f"{args.output}: {info['triangles']} triangles, {info['parts']} part(s), "
            f"{size} mm, {info['volume_mm3']:g} mm³, {info['bridges']} bridge(s)"
        )
        print(f"  print: {estimate_line(info)}")
        if "colours" in info:
            print(f"  colours: {filaments_line(info['colours'])}")
    print_notes(list(info.get("notes", [])))
    print_scale_note(args, scaled or options.size is not None)
    return print_warnings(made.warnings, strict=args.strict)
