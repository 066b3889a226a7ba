"""voxfab net: unfold a shape's surface into a one-piece net (JSON or drawings)."""

from __future__ import annotations

import argparse
import math
import re
import sys
from pathlib import Path

from voxfab.errors import InvalidShapeError, UnknownFormatError

from ._common import add_shape_argument, load_shape, print_json, print_notes

HELP = "unfold the surface into a one-piece paper net (JSON, or drawings .svg .dxf .pdf .png)"

_FIT = re.compile(r"^\s*(\d+(?:\.\d*)?)\s*[xX×]\s*(\d+(?:\.\d*)?)\s*$")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``net`` options."""
    add_shape_argument(parser)
    parser.add_argument("-o", "--output", action="append", required=True, metavar="PATH",
                        help="NET.json, or a drawing (.svg .dxf .pdf .png); repeat for several files "
                             "of the same net")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument("--count", type=int, default=1, metavar="N",
                        help="write N distinct nets as NAME-1.ext ... NAME-N.ext")
    parser.add_argument("--strategy", choices=["default", "paper"], default="default",
                        help="search strategy (default: ruin-and-recreate with tab room)")
    parser.add_argument("--timeout", type=float, default=60.0, metavar="S",
                        help="search budget in seconds per net (default 60)")
    parser.add_argument("--fit", metavar="WxH",
                        help="JSON nets: keep the net inside W×H (voxels, or mm with a face size); "
                             "drawings always fit their sheet")
    parser.add_argument("--face-size", type=float, metavar="MM",
                        help="edge of one paper face in mm; drawings pick the largest at which the net "
                             "fits the sheet when omitted")
    parser.add_argument("--pitch", type=float, metavar="MM", help="the face size, when --face-size is not given")
    parser.add_argument("--pieces", choices=["one", "auto"], default="one",
                        help="auto: when no one-piece net fits the sheet, the fewest pieces, packed on as "
                             "few sheets as possible")
    parser.add_argument("--fill", action="store_true", help="fill enclosed cavities first")
    parser.add_argument("--compact", action="store_true",
                        help="prefer a small bounding box (slower)")
    try:
        from voxfab.fabricate import netdraw
    except ImportError:
        return
    netdraw.add_drawing_arguments(parser)


def _fit(text: str | None, face_size: float | None) -> tuple[int, int] | None:
    if text is None:
        return None
    m = _FIT.match(text)
    if not m:
        raise InvalidShapeError(f"--fit: expected WxH such as 40x30, got {text!r}")
    w, h = float(m.group(1)), float(m.group(2))
    if face_size is not None:
        return math.floor(w / face_size + 1e-9), math.floor(h / face_size + 1e-9)
    if w != int(w) or h != int(h):
        raise InvalidShapeError(f"--fit: whole voxels expected without a face size, got {text!r}")
    return int(w), int(h)


def _named(path: Path, *tags: str) -> Path:
    tags = tuple(t for t in tags if t)
    if not tags:
        return path
    return path.with_name(f"{path.stem}-{'-'.join(tags)}{path.suffix}")


def _face_size(args: argparse.Namespace) -> float | None:
    face = args.face_size if args.face_size is not None else args.pitch
    if face is not None and not (math.isfinite(face) and face > 0):
        raise InvalidShapeError(f"--face-size: expected a positive number of mm, got {face}")
    return face


def _search(args: argparse.Namespace, shape, drawings: list[Path], face: float | None, netdraw):  # noqa: ANN001, ANN202
    """Nets as lists of pieces, the drawing options (None without drawings) and notes."""
    from voxfab.unfold import unfold, unfold_many

    search = dict(strategy=args.strategy, timeout=args.timeout, fill=args.fill, compact=args.compact)
    if drawings:
        if args.fit is not None:
            raise InvalidShapeError("--fit: drawings fit their sheet (--sheet); --fit is for JSON nets only")
        args.pitch = face
        found = netdraw.find_sheet_nets(shape.grid, netdraw.options_from_args(args), rng=args.seed,
                                        pieces=args.pieces, count=args.count, **search)
        return found.nets, found.options, found.notes
    fit = _fit(args.fit, face)
    if args.count > 1:
        return [[n] for n in unfold_many(shape.grid, count=args.count, rng=args.seed, fit=fit, **search)], None, []
    found = unfold(shape.grid, rng=args.seed, pieces=args.pieces, fit=fit, **search)
    return [found if isinstance(found, list) else [found]], None, []


def run(args: argparse.Namespace) -> int:
    """Search, validate and write the nets."""
    from voxfab._shared.atomic import write_text
    from voxfab.shape import fill_cavities
    from voxfab.unfold import validate

    face = _face_size(args)
    if args.count < 1:
        raise InvalidShapeError(f"--count: expected an integer >= 1, got {args.count}")
    if args.count > 1 and args.pieces != "one":
        raise InvalidShapeError("--count: several nets need --pieces one")
    outputs = [Path(p) for p in args.output]
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
        bad = [p for p in drawings if p.suffix.lower() not in netdraw.drawing_formats()]
        if bad:
            raise UnknownFormatError(f"{bad[0]}: unknown drawing format; expected .json or one of "
                                     f"{', '.join(netdraw.drawing_formats())}")
        netdraw.options_from_args(args)  # bad drawing options fail before the search
    shape, name, notes = load_shape(args.shape, args.repo)
    print_notes(notes)
    results, options, found_notes = _search(args, shape, drawings, face, netdraw)
    print_notes(found_notes)
    grid = fill_cavities(shape.grid) if args.fill else shape.grid
    title = name or Path(args.shape).stem
    written, summary, warnings = [], [], []
    for t, pieces in enumerate(results):
        validate(grid, pieces if len(pieces) > 1 else pieces[0])
        tag = str(t + 1) if len(results) > 1 else ""
        record = {"seed": pieces[0].seed, "faces": sum(n.face_count for n in pieces), "pieces": len(pieces),
                  "seams_without_tab_room": sum(n.seams_without_tab_room for n in pieces)}
        for path in outputs:
            if path in drawings:
                result = netdraw.write_net_drawing(grid, pieces, _named(path, tag), options, title=title)
                for line in result.report:
                    print(f"voxfab: {_named(path, tag).name}: {line}", file=sys.stderr)
                written += result.files
                record["face_size"] = result.face_size
                record["fill"] = [round(f, 4) for f in result.fill]
                warnings += [w for w in result.warnings if w not in warnings]
                continue
            for q, net in enumerate(pieces):
                target = _named(path, tag, f"piece{q + 1}" if len(pieces) > 1 else "")
                write_text(target, net.to_json())
                written.append(str(target))
        summary.append(record)
    for w in warnings:
        print(f"voxfab: warning: {w}", file=sys.stderr)
    print_json({"written": written, "nets": summary, "warnings": warnings})
    return 0
