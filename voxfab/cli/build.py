"""``voxfab build``: turn recipes into folders of fabrication files."""

from __future__ import annotations

import argparse
from pathlib import Path

from ._common import add_strict_option, print_warnings

HELP = "build recipes (TOML) into DIR/<name>/ with the shape, its outputs and a manifest"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("recipes", nargs="+", metavar="RECIPE", type=Path, help="recipe files (.toml)")
    parser.add_argument("-o", "--output", type=Path, default=Path("output"), metavar="DIR",
                        help="output folder (default: output)")
    parser.add_argument("--check", action="store_true", help="validate the recipes only, build nothing")
    parser.add_argument("--allow-outside", action="store_true",
                        help="let recipes read files outside their own folder (refused by default)")
    add_strict_option(parser)


def run(args: argparse.Namespace) -> int:
    import json

    from voxfab.recipe import build, load_recipe

    # Validate every recipe first, so a typo in the last one does not waste a long build.
    recipes = [load_recipe(path, allow_outside=args.allow_outside) for path in args.recipes]
    names = [r.name for r in recipes]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        from voxfab.errors import RecipeError

        raise RecipeError(f"several recipes share the name {duplicates[0]!r}; names must be unique")
    if args.check:
        for r in recipes:
            print(f"{r.path}: ok ({r.name})")
        return 0
    warnings = []
    for recipe in recipes:
        folder = build(recipe, args.output)
        manifest = json.loads((folder / "manifest.json").read_text())
        print(f"{folder}: {len(manifest['files'])} files")
        mesh_report = folder / "mesh.json"
        if "mesh" in manifest["outputs"] and mesh_report.exists():
            from voxfab.fabricate.mesh import estimate_line, filaments_line

            figures = json.loads(mesh_report.read_text())
            print(f"  print: {estimate_line(figures)}")
            if "colours" in figures:
                print(f"  colours: {filaments_line(figures['colours'])}")
        warnings += [f"{recipe.name}: {w}" for w in manifest["warnings"]]
    return print_warnings(warnings, strict=args.strict)
