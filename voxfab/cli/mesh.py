"""``voxfab mesh``: a checked, print-ready solid as 3MF, STL, OBJ or GLB."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ._common import add_shape_argument, load_shape, print_json, print_notes

HELP = "write a print-ready solid (3MF, STL, OBJ or GLB), checked edge by edge"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_shape_argument(parser)
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="OUT",
                        help="output file: .3mf (default choice for slicers), .stl, .obj or .glb")
    scale = parser.add_mutually_exclusive_group()
    scale.add_argument("--pitch", type=float, metavar="MM", help="millimetres per voxel (default: the shape's, or 1)")
    scale.add_argument("--size", type=float, metavar="MM", help="length of the longest side in mm")
    parser.add_argument("--contacts", choices=["bridge", "split", "error"], default="bridge",
                        help="voxels touching only along an edge or at a corner: bridge them (default), "
                             "keep separate shells, or refuse")
    parser.add_argument("--bridge-width", type=float, metavar="MM",
                        help="width of contact bridges (default 1 mm, at most 0.6 × pitch)")
    parser.add_argument("--keep-cavities", action="store_true", help="do not fill enclosed cavities")
    parser.add_argument("--hollow", type=int, default=0, metavar="N",
                        help="hollow with walls N voxels thick and a drain hole per cavity")
    parser.add_argument("--label", nargs="?", const="", default=None, metavar="TEXT",
                        help="engrave TEXT on the bottom (without TEXT: the repository name or file name)")
    parser.add_argument("--engrave-depth", type=float, default=0.6, metavar="MM", help="label depth (default 0.6)")
    parser.add_argument("--base", type=float, default=0.0, metavar="MM", help="add a flat base plate this thick")
    parser.add_argument("--magnet", metavar="DxH", help="round magnet pocket in the bottom, e.g. 6x3 (mm)")
    parser.add_argument("--no-merge", action="store_true", help="two triangles per voxel face (no coplanar merging)")
    parser.add_argument("--json", action="store_true", help="print the mesh figures as one JSON object")


def run(args: argparse.Namespace) -> int:
    from voxfab._shared.atomic import check_output
    from voxfab.fabricate.mesh import build_mesh, format_for, report_dict, write_mesh

    format_for(args.output)  # refuse an unknown extension before any work
    check_output(args.output)  # and a folder that does not exist
    shape, repo_name, notes = load_shape(args.shape, args.repo)
    print_notes(notes)
    name = repo_name or Path(args.shape).stem
    label = args.label if args.label else (name if args.label == "" else None)
    result = build_mesh(
        shape,
        pitch=args.pitch,
        size=args.size,
        contacts=args.contacts,
        bridge_width=args.bridge_width,
        fill=not args.keep_cavities,
        hollow=args.hollow,
        label=label,
        engrave_depth=args.engrave_depth,
        base=args.base,
        magnet=args.magnet,
        merge=not args.no_merge,
        name=name,
    )
    for w in result.warnings:
        print(f"voxfab: warning: {w}", file=sys.stderr)
    write_mesh(args.output, result.mesh, name=name)
    info = report_dict(result, name=name)
    if args.json:
        print_json({**info, "output": str(args.output)})
    else:
        size = " x ".join(f"{s:g}" for s in info["size_mm"])  # type: ignore[union-attr]
        print(
            f"{args.output}: {info['triangles']} triangles, {info['parts']} part(s), "
            f"{size} mm, {info['volume_mm3']:g} mm³, {info['bridges']} bridge(s)"
        )
    return 0
