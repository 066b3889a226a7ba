"""``voxfab repo``: add, list, show, export and remove shapes of the repository."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from voxfab.cli._common import add_repository_option, print_json, print_notes

if TYPE_CHECKING:
    from voxfab.repo import Repository

HELP = "manage the shape repository (add, list, show, export, remove)"


def _subparser(sub: argparse._SubParsersAction, name: str, help_text: str) -> argparse.ArgumentParser:
    p = sub.add_parser(name, help=help_text, description=help_text)
    p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="show tracebacks on errors")
    add_repository_option(p)
    return p


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``add``, ``list``, ``show``, ``export`` and ``remove`` actions."""
    sub = parser.add_subparsers(dest="_repo_action", metavar="ACTION", required=True)

    p = _subparser(sub, "add", "store shapes and print their names (NAME created / NAME exists)")
    p.add_argument("shapes", nargs="+", metavar="SHAPE", type=Path, help="shape files to add")
    p.add_argument("--symmetric", action="store_true",
                   help="treat rotated and mirrored copies (48 cube symmetries) as the same shape")
    p.add_argument("--draft", action="store_true",
                   help="store a shape that is not well formed as an unnamed draft instead of refusing it")

    p = _subparser(sub, "list", "list the stored shapes by volume, then the drafts")
    p.add_argument("--json", action="store_true", help="print one JSON object")

    p = _subparser(sub, "show", "show what is stored about one shape")
    p.add_argument("name", metavar="NAME", help="a name such as 00797.001, or draft-N")
    p.add_argument("--json", action="store_true", help="print one JSON object")

    p = _subparser(sub, "export", "write a stored shape to a file (format by extension)")
    p.add_argument("name", metavar="NAME", help="a name such as 00797.001, or draft-N")
    p.add_argument("out", metavar="OUT", type=Path, help="the file to write")

    p = _subparser(sub, "remove", "delete a shape (the other names do not change)")
    p.add_argument("name", metavar="NAME", help="a name such as 00797.001, or draft-N")


def run(args: argparse.Namespace) -> int:
    """Run the chosen action; return 0."""
    from voxfab.repo import Repository

    action = args._repo_action
    if action == "add":
        return _add(args)
    with Repository(args.repo, create=False) as repo:
        if action == "list":
            _list(repo, as_json=args.json)
        elif action == "show":
            _show(repo, args.name, as_json=args.json)
        elif action == "export":
            repo.export(args.name, args.out)
            print(f"{args.name} -> {args.out}")
        else:
            repo.remove(args.name)
            print(f"{args.name} removed")
    return 0


def _add(args: argparse.Namespace) -> int:
    from voxfab import io
    from voxfab._shared.progress import progress
    from voxfab.errors import RepositoryError
    from voxfab.repo import Repository
    from voxfab.shape import well_formed_reasons

    with Repository(args.repo, create=True) as repo:
        for path in progress(args.shapes, total=len(args.shapes), desc="adding"):
            result = io.read(path)
            print_notes([f"{path}: {n}" for n in result.notes])
            meta: dict[str, object] = {"source": str(path)}
            if result.pitch is not None:
                meta["pitch"] = result.pitch
            if not args.draft:
                reasons = well_formed_reasons(result.grid)
                if reasons:
                    raise RepositoryError(
                        f"{path}: not well formed: {'; '.join(reasons)} (use --draft to store it as a draft)"
                    )
            added = repo.add(result.grid, symmetric=args.symmetric, draft=args.draft, meta=meta)
            print(f"{added.name} {'created' if added.created else 'exists'}", flush=True)
            if added.reasons:
                print_notes([f"{path}: stored as a draft: {'; '.join(added.reasons)}"])
    return 0


def _list(repo: Repository, *, as_json: bool) -> None:
    entries = repo.list()
    if as_json:
        print_json({
            "repository": str(repo.path),
            "shapes": [
                {"name": e.name, "volume": e.volume, "extents": list(e.extents), "draft": e.draft}
                for e in entries
            ],
        })
        return
    for e in entries:
        extents = "x".join(map(str, e.extents))
        print(f"{e.name:<12} {e.volume:>6} {extents:<9}{'  draft' if e.draft else ''}".rstrip())


def _show(repo: Repository, name: str, *, as_json: bool) -> None:
    info = repo.show(name)
    if as_json:
        print_json(info)
        return
    print(f"name: {info['name']}")
    print(f"volume: {info['volume']}")
    print(f"rank: {info['rank'] if info['rank'] is not None else '-'}")
    print(f"extents: {'x'.join(map(str, info['extents']))}")
    print(f"draft: {'yes' if info['draft'] else 'no'}")
    for reason in info["reasons"]:
        print(f"reason: {reason}")
    print(f"key: {info['key']}")
    print(f"symmetric key: {info['symmetric_key']}")
    for k, v in sorted((info["meta"] or {}).items()):
        print(f"meta.{k}: {v}")
