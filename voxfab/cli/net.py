"""voxfab net: unfold a shape's surface into a one-piece net (JSON or drawings)."""

from __future__ import annotations

import argparse
import math
import re
import sys
from pathlib import Path

from voxfab.errors import InvalidShapeError, UnknownFormatError

from ._common import add_pitch_option, add_shape_argument, load_scaled_shape, print_json, print_notes
from ._options import add_option_arguments, options_from_args

HELP = "unfold the surface into a one-piece paper net (JSON, or drawings .svg .dxf .pdf)"

_FIT = re.compile(r"^\s*(\d+(?:\.\d*)?)\s*[xX×]\s*(\d+(?:\.\d*)?)\s*$")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``net`` options."""
    from voxfab.fabricate.netdraw import NetOptions

    add_shape_argument(parser)
    parser.add_argument("-o", "--output", action="append", required=True, metavar="PATH",
                        help="NET.json, or a drawing (.svg .dxf .pdf); repeat for several files "
                             "of the same net")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument("--fit", metavar="WxH",
                        help="keep the net inside W×H (voxels, or mm when the face size is known)")
    add_pitch_option(parser)
    add_option_arguments(parser, NetOptions)
    parser.add_argument("--constraints", metavar="FILE.json",
                        help='edges to cut or keep folded: {"cut": [[[x,y,z,"+z"],[x,y,z,"+x"]], ...], '
                             '"keep": [...]}')
    try:
        from voxfab.fabricate import netdraw
    except ImportError:
        return
    netdraw.add_drawing_arguments(parser)


def _fit(text: str | None, pitch: float | None) -> tuple[int, int] | None:
    if text is None:
        return None
    m = _FIT.match(text)
    if not m:
        raise InvalidShapeError(f"--fit: expected WxH such as 40x30, got {text!r}")
    w, h = float(m.group(1)), float(m.group(2))
    if pitch is not None:
        return math.floor(w / pitch + 1e-9), math.floor(h / pitch + 1e-9)
    if w != int(w) or h != int(h):
        raise InvalidShapeError(f"--fit: whole voxels expected without --pitch, got {text!r}")
    return int(w), int(h)


#: Largest constraints file read (a 25³ surface has under 40 000 edges).
_MAX_CONSTRAINTS_BYTES = 8 << 20


def _constraints(path: str | None):
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


def _named(path: Path, *tags: str) -> Path:
    tags = tuple(t for t in tags if t)
    if not tags:
        return path
    return path.with_name(f"{path.stem}-{'-'.join(tags)}{path.suffix}")


def run(args: argparse.Namespace) -> int:
    """Search, validate and write the nets."""
    from voxfab._shared.atomic import atomic_files, check_output, write_text
    from voxfab.fabricate.netdraw import NetOptions
    from voxfab.unfold import unfold, unfold_many, validate

    search = options_from_args(NetOptions, args)
    outputs = [Path(p) for p in args.output]
    for p in outputs:
        check_output(p)  # before the search, which may take minutes
    drawings = [p for p in outputs if p.suffix.lower() != ".json"]
    netdraw = None
    if drawings:
        try:
            from voxfab.fabricate import netdraw
        except ImportError:
            raise UnknownFormatError(
                f"{drawings[0]}: drawings need voxfab.fabricate.netdraw, which is not "
                "installed; write a .json net"
            ) from None
    # The paper scale: --face-size, else the shape's pitch (--pitch or the file's own); a shape
    # with neither is drawn at the largest face size that puts the net on the sheet (None).
    shape_pitch = args.pitch
    face_size = search.face_size if search.face_size is not None else shape_pitch
    fit = _fit(args.fit, face_size)
    if netdraw is not None:
        args.pitch = face_size  # the drawing options read the face size as `pitch`
        netdraw.options_from_args(args)  # check the drawing options before the search
    shape, name, notes, scaled = load_scaled_shape(args.shape, args.repo, pitch=shape_pitch)
    print_notes(notes)
    if face_size is None and scaled:
        face_size = args.pitch = shape.pitch
        fit = _fit(args.fit, face_size)
    constraints = _constraints(args.constraints)
    options = dict(strategy=search.strategy, timeout=search.timeout, fit=fit, fill=search.fill,
                   compact=search.compact, constraints=constraints)
    if search.count > 1:
        if search.pieces != "one":
            raise InvalidShapeError("--count: several nets need --pieces one")
        results = [[n] for n in unfold_many(shape.grid, count=search.count, rng=args.seed, **options)]
    else:
        found = unfold(shape.grid, rng=args.seed, pieces=search.pieces, **options)
        results = [found if isinstance(found, list) else [found]]
    from voxfab.shape import VoxelShape, fill_cavities

    grid = fill_cavities(shape.grid) if search.fill else shape.grid
    drawn = VoxelShape(grid, face_size if face_size is not None else shape.pitch)
    title = name or Path(args.shape).stem
    summary = []
    # Every file is published at the end, replacing the whole earlier set (no stale t-3.svg).
    with atomic_files(*outputs) as fileset:
        for t, pieces in enumerate(results):
            validate(grid, pieces if len(pieces) > 1 else pieces[0], constraints=constraints)
            for q, net in enumerate(pieces):
                tags = (str(t + 1) if len(results) > 1 else "", f"piece{q + 1}" if len(pieces) > 1 else "")
                for path in outputs:
                    target = _named(path, *tags)
                    if path in drawings:
                        for line in netdraw.write_drawing(drawn, net, target, args, title=title):
                            print(f"voxfab: {target.name}: {line}", file=sys.stderr)
                    else:
                        write_text(target, net.to_json())
                summary.append({"seed": net.seed, "faces": net.face_count,
                                "seams_without_tab_room": net.seams_without_tab_room})
    written = [str(p) for p in fileset.written]
    print_json({"written": written, "nets": summary})
    return 0
