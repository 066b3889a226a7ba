"""voxfab net: unfold a shape's surface into a one-piece net (JSON or drawings)."""

from __future__ import annotations

import argparse
import math
import re
import sys
from pathlib import Path

from voxfab.errors import InvalidShapeError, UnknownFormatError

from ._common import (
    add_pitch_option,
    add_shape_argument,
    add_strict_option,
    print_json,
    print_notes,
    print_warnings,
    shape_pitch,
)
from ._options import add_option_arguments, options_from_args

HELP = "unfold the surface into a one-piece paper net (JSON, or drawings .svg .dxf .pdf .png)"

_FIT = re.compile(r"^\s*(\d+(?:\.\d*)?)\s*[xX×]\s*(\d+(?:\.\d*)?)\s*$")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``net`` options."""
    from voxfab.fabricate.netdraw import DrawingOptions, NetOptions

    add_shape_argument(parser)
    parser.add_argument("-o", "--output", action="append", required=True, metavar="PATH",
                        help="NET.json, or a drawing (.svg .dxf laser files, .pdf .png to look at and print); "
                             "repeat for several files of the same net")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
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
        raise InvalidShapeError(f"--fit: whole voxels expected without a face size, got {text!r}")
    return int(w), int(h)


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


def _named(path: Path, *tags: str) -> Path:
    tags = tuple(t for t in tags if t)
    if not tags:
        return path
    return path.with_name(f"{path.stem}-{'-'.join(tags)}{path.suffix}")


def _drawing_formats(drawings: list[Path]) -> None:
    from voxfab.drawing import FORMATS

    for p in drawings:
        if p.suffix.lower() not in FORMATS:
            raise UnknownFormatError(f"{p}: unknown drawing format {p.suffix or '(none)'!r}; expected .json or "
                                     f"one of {', '.join(FORMATS)}")


def run(args: argparse.Namespace) -> int:
    """Search, validate and write the nets."""
    from voxfab._shared.atomic import atomic_files, check_output, write_text
    from voxfab.fabricate import netdraw
    from voxfab.shape import fill_cavities
    from voxfab.unfold import unfold, unfold_many, validate

    search = options_from_args(netdraw.NetOptions, args)
    outputs = [Path(p) for p in args.output]
    for p in outputs:
        check_output(p)  # before the search, which may take minutes
    drawings = [p for p in outputs if p.suffix.lower() != ".json"]
    _drawing_formats(drawings)
    if search.zipper and (drawings or search.count > 1):
        raise InvalidShapeError("--zipper: for one JSON net (NET.json) with --strategy exact")
    if search.min_box and (drawings or args.fit is not None):
        raise InvalidShapeError("--min-box: for JSON nets without --box (drawings fit their sheet)")
    if search.count > 1 and search.pieces != "one":
        raise InvalidShapeError("--count: several nets need --pieces one")
    # The paper scale: --face-size, else the shape's pitch (--pitch or the file's own); a shape
    # with neither is drawn at the largest face size that puts the net on the sheet (None).
    pitch = shape_pitch(args)
    face_size = search.face_size if search.face_size is not None else pitch
    drawing = options_from_args(netdraw.DrawingOptions, args, pitch=face_size)  # checked before the search
    from voxfab.repo import load_shape

    shape, name, notes, scaled = load_shape(args.shape, args.repo, pitch=pitch)
    print_notes(notes)
    if face_size is None and scaled:
        face_size = shape.pitch
        drawing = drawing.replace(pitch=face_size)
    constraints = _constraints(args.constraints)
    options = dict(strategy=search.strategy, timeout=search.timeout, fill=search.fill, compact=search.compact,
                   constraints=constraints)
    if drawings:
        if args.fit is not None:
            raise InvalidShapeError("--fit: drawings fit their sheet (--sheet); --fit is for JSON nets only")
        found = netdraw.find_sheet_nets(shape.grid, drawing, rng=args.seed, pieces=search.pieces,
                                        count=search.count, budget=search.budget, **options)
        results, drawing = found.nets, found.options
        print_notes(found.notes)
    elif search.count > 1:
        results = [[n] for n in unfold_many(shape.grid, count=search.count, rng=args.seed, budget=search.budget,
                                            fit=_fit(args.fit, face_size), **options)]
        if len(results) < search.count:
            print_notes([f"{len(results)} distinct nets found of the {search.count} asked for "
                         f"within the {search.budget:g} s budget"])
    else:
        found = unfold(shape.grid, rng=args.seed, pieces=search.pieces, fit=_fit(args.fit, face_size),
                       min_box=search.min_box, zipper=search.zipper, **options)
        results = [found if isinstance(found, list) else [found]]
    grid = fill_cavities(shape.grid) if search.fill else shape.grid
    title = name or Path(args.shape).stem
    summary, warnings = [], []
    # Every file is published at the end, replacing the whole earlier set (no stale t-3.svg).
    with atomic_files(*outputs) as fileset:
        for t, pieces in enumerate(results):
            validate(grid, pieces if len(pieces) > 1 else pieces[0], constraints=constraints)
            tag = str(t + 1) if len(results) > 1 else ""
            record = {"seed": pieces[0].seed, "faces": sum(n.face_count for n in pieces), "pieces": len(pieces),
                      "seams_without_tab_room": sum(n.seams_without_tab_room for n in pieces)}
            for path in outputs:
                target = _named(path, tag)
                if path in drawings:
                    result = netdraw.write_net_drawing(grid, pieces, target, drawing, title=title)
                    for line in result.report:
                        print(f"voxfab: {target.name}: {line}", file=sys.stderr)
                    record.update(face_size=result.face_size, fill=[round(f, 4) for f in result.fill])
                    # Every drawing of one net says the same: once per net.
                    warnings += [w for w in (f"net {tag}: {x}" if tag else x for x in result.warnings)
                                 if w not in warnings]
                    continue
                for q, net in enumerate(pieces):
                    write_text(_named(target, f"piece{q + 1}" if len(pieces) > 1 else ""), net.to_json())
            summary.append(record)
    written = [str(p) for p in fileset.written]
    print_json({"written": written, "nets": summary, "warnings": warnings})
    return print_warnings(warnings, strict=args.strict)
