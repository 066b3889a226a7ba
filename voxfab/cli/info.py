"""``voxfab info``: measures and well-formedness of a shape."""

from __future__ import annotations

import argparse
from typing import Any

from ._common import add_shape_argument, joined_if_asked, print_json, print_notes, reader_options

HELP = "show volume, extents, components, well-formedness and repository name of a shape"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_shape_argument(parser)
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def shape_info(shape: Any) -> dict[str, Any]:
    """The facts ``voxfab info`` reports about a VoxelShape."""
    from voxfab.shape import cavity_count

    return {
        "grid": list(shape.grid.shape),
        "volume": shape.volume,
        "extents": list(shape.extents),
        "components": shape.components,
        "cavities": cavity_count(shape.grid),
        "surface_faces": shape.exposed_faces,
        "colours": 0 if shape.colours is None else shape.colours.count,
        "well_formed": shape.well_formed,
        "reasons": shape.reasons,
    }


def _repository_name(args: argparse.Namespace, shape: Any) -> str | None:
    if not args.repo.exists():
        return None
    from voxfab.repo import Repository

    with Repository(args.repo, create=False) as repo:
        return repo.find(shape)


def run(args: argparse.Namespace) -> int:
    from voxfab.repo import load_shape

    shape, name, notes, _ = load_shape(args.shape, args.repo, **reader_options(args))
    shape = joined_if_asked(args, shape, notes)
    print_notes(notes)
    info = shape_info(shape)
    info["name"] = name or (_repository_name(args, shape) if shape.well_formed else None)
    if args.json:
        print_json(info)
        return 0
    width = max(len(k) for k in info)
    for key, value in info.items():
        if key == "reasons":
            value = "; ".join(value) if value else "-"
        elif isinstance(value, list):
            value = " x ".join(map(str, value))
        print(f"{key:<{width}}  {value if value is not None else '-'}")
    return 0
