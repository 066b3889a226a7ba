"""voxfab net: unfold a shape's surface into a one-piece net (JSON or drawings)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ._common import (
    add_pitch_option,
    add_shape_argument,
    add_strict_option,
    load_command_shape,
    print_json,
    print_notes,
    print_warnings,
    shape_pitch,
)
from ._options import add_option_arguments, options_from_args

HELP = "unfold the surface into a one-piece paper net (JSON, or drawings .svg .dxf .pdf .png)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``net`` options."""
    from voxfab._shared.options import SeedOptions
    from voxfab.fabricate.netdraw import DrawingOptions, NetOptions

    add_shape_argument(parser)
    parser.add_argument("-o", "--output", action="append", required=True, metavar="PATH",
                        help="NET.json, or a drawing (.svg .dxf laser files, .pdf .png to look at and print); "
                             "repeat for several files of the same net")
    add_option_arguments(parser, SeedOptions)
    parser.add_argument("--fit", "--box", metavar="WxH",
                        help="JSON nets: keep the net inside W×H (voxels, or mm when the face size is known); "
                             "drawings always fit their sheet")
    add_pitch_option(parser)
    add_option_arguments(parser, NetOptions)
    parser.add_argument("--constraints", metavar="FILE.json",
                        help='edges to cut or keep folded: {"cut": [[[x,y,z,"+z"],[x,y,z,"+x"]], ...], '
                             '"keep": [...]}')
    add_strict_option(parser)
    add_option_arguments(parser, DrawingOptions, title="drawings (-o with .svg, .dxf, .pdf or .png)")


#: Largest constraints file read (a 25³ surface has under 40 000 edges).
_MAX_CONSTRAINTS_BYTES = 8 << 20


def _constraints(path: str | None):  # noqa: ANN202 - EdgeConstraints or None
    if path is None:
        return None
    from voxfab.errors import FormatError
    from voxfab.unfold import EdgeConstraints

    p = Path(path)
    if not p.is_file():
        raise FormatError(f"--constraints: {path}: not a readable file")
    if p.stat().st_size > _MAX_CONSTRAINTS_BYTES:
        raise FormatError(f"--constraints: {path}: larger than {_MAX_CONSTRAINTS_BYTES >> 20} MB")
    try:
        return EdgeConstraints.from_json(p.read_bytes())
    except OSError as exc:
        raise FormatError(f"--constraints: {path}: {exc.strerror}") from None


def run(args: argparse.Namespace) -> int:
    """Search, validate and write the nets: :func:`voxfab.fabricate.netdraw.net_files`."""
    from voxfab._shared.options import SeedOptions
    from voxfab.fabricate import netdraw

    seed = options_from_args(SeedOptions, args).seed
    search = options_from_args(netdraw.NetOptions, args)
    from voxfab._shared.options import option_specs

    given = [s.name for s in option_specs(netdraw.DrawingOptions) if s.cli and getattr(args, s.name, None) is not None]
    # before loading the shape; every drawing option given must be read by an output
    netdraw.check_request(search, args.output, box=args.fit is not None, drawing_given=given)
    # The paper scale: --face-size, else the shape's pitch (--pitch or the file's own); a shape
    # with neither is drawn at the largest face size that puts the net on the sheet (None).
    pitch = shape_pitch(args)
    face_size = search.face_size if search.face_size is not None else pitch
    drawing = options_from_args(netdraw.DrawingOptions, args, pitch=face_size)  # checked before the search
    shape, title, scaled = load_command_shape(args, pitch=pitch)
    if face_size is None and scaled:
        face_size = shape.pitch
        drawing = drawing.replace(pitch=face_size)
    made = netdraw.net_files(shape, search, drawing, args.output, title=title,
                             seed=seed, constraints=_constraints(args.constraints),
                             box=netdraw.parse_box(args.fit, face_size))
    print_notes(made.notes)
    for file, line in made.report:
        print(f"voxfab: {file}: {line}", file=sys.stderr)
    print_json({"written": made.written, "nets": made.nets, "warnings": made.warnings})
    return print_warnings(made.warnings, strict=args.strict)
