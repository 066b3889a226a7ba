"""``voxfab repo``: add, list, show, export and remove shapes of the repository."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from voxfab.cli._common import (
    add_frame_option,
    add_repository_option,
    open_repository_for_writing,
    print_json,
    print_notes,
    reader_options,
)
from voxfab.cli._options import integer_argument

if TYPE_CHECKING:
    from voxfab.repo import Repository

HELP = "manage the shape repository (add, list, stats, show, export, remove, check)"


def _subparser(sub: argparse._SubParsersAction, name: str, help_text: str) -> argparse.ArgumentParser:
    from voxfab.cli._reference import help_link

    p = sub.add_parser(name, help=help_text, description=help_text, epilog=help_link(f"repo {name}"))
    p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="show tracebacks on errors")
    add_repository_option(p)
    return p


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``add``, ``list``, ``ranges``, ``stats``, ``show``, ``export``, ``remove``, ``remove-range``
    and ``check`` actions."""
    sub = parser.add_subparsers(dest="_repo_action", metavar="ACTION", required=True)

    p = _subparser(sub, "add", "store shapes and print their names (NAME created / NAME exists)")
    p.add_argument("shapes", nargs="+", metavar="SHAPE", type=Path, help="shape files to add")
    add_frame_option(p)
    p.add_argument("--symmetric", action="store_true",
                   help="treat rotated and mirrored copies (48 cube symmetries) as the same shape")
    p.add_argument("--draft", action="store_true",
                   help="store a shape that is not well formed as an unnamed draft instead of refusing it")

    p = _subparser(sub, "list", "list the stored shapes by volume, then the drafts")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--volume", metavar="MIN:MAX", help="only volumes MIN..MAX (inclusive; MIN: or :MAX open)")
    p.add_argument("--limit", type=integer_argument, metavar="N", help="at most N shapes (one page)")
    p.add_argument("--after", metavar="NAME",
                   help="start after this name (the last of the previous page; JSON gives it as 'next_after')")
    p.add_argument("--no-drafts", action="store_true", help="leave the drafts out")
    p.add_argument("--range", metavar="RANGE", help="list the members of this range instead, in stored order")

    _subparser(sub, "ranges", "list the named ranges (a census's polycubes) and their sizes")

    p = _subparser(sub, "stats", "count the stored shapes per volume")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--volume", metavar="MIN:MAX", help="only volumes MIN..MAX (inclusive)")
    p.add_argument("--bins", type=integer_argument, metavar="N",
                   help="group the volumes into at most N ranges of a round width instead of one line per volume")

    p = _subparser(sub, "show", "show what is stored about one shape")
    p.add_argument("name", metavar="NAME", help="a name such as 00797.001, draft-N, or RANGE:MEMBER")
    p.add_argument("--json", action="store_true", help="print one JSON object")

    p = _subparser(sub, "export", "write a stored shape to a file (format by extension)")
    p.add_argument("name", metavar="NAME", help="a name such as 00797.001, draft-N, or RANGE:MEMBER")
    p.add_argument("out", metavar="OUT", type=Path, help="the file to write")

    p = _subparser(sub, "remove", "delete a shape or a range member (the other names do not change)")
    p.add_argument("name", metavar="NAME", help="a name such as 00797.001, draft-N, or RANGE:MEMBER")

    p = _subparser(sub, "remove-range", "delete a named range and the drafts only it holds")
    p.add_argument("range", metavar="RANGE", help="a range name such as polycubes-8")

    _subparser(sub, "check", "check every row of the file; list the bad ones (an error when any)")


def run(args: argparse.Namespace) -> int:
    """Run the chosen action; return 0."""
    from voxfab.repo import Repository

    action = args._repo_action
    if action == "add":
        return _add(args)
    with Repository(args.repo, create=False) as repo:
        if action == "list":
            _list(repo, args)
        elif action == "stats":
            _stats(repo, args)
        elif action == "show":
            _show(repo, args.name, as_json=args.json)
        elif action == "export":
            from voxfab._shared.atomic import check_output

            check_output(args.out)  # an existing folder: no folders made on the way
            repo.export(args.name, args.out)
            print(f"{args.name} -> {args.out}")
        elif action == "check":
            return _check(repo)
        elif action == "ranges":
            for r in repo.ranges():
                print(f"{r.name:<24} {r.count:>8}")
        elif action == "remove-range":
            print(f"{args.range}: {repo.remove_range(args.range)} members removed")
        else:
            repo.remove(args.name)
            print(f"{args.name} removed")
    return 0


def _add(args: argparse.Namespace) -> int:
    from voxfab import io
    from voxfab._shared.progress import progress
    from voxfab.errors import RepositoryError
    from voxfab.shape import well_formed_reasons

    with open_repository_for_writing(args.repo) as repo:
        for path in progress(args.shapes, total=len(args.shapes), desc="adding"):
            result = io.read(path, **reader_options(args))
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
            added = repo.add(result.shape(), symmetric=args.symmetric, draft=args.draft, meta=meta)
            print(f"{added.name} {'created' if added.created else 'exists'}", flush=True)
            if added.reasons:
                print_notes([f"{path}: stored as a draft: {'; '.join(added.reasons)}"])
    return 0


def _check(repo: Repository) -> int:
    from voxfab.errors import RepositoryError

    problems = repo.check()
    for problem in problems:
        print(problem)
    if problems:
        raise RepositoryError(f"{repo.path}: {len(problems)} problem(s) found")
    print(f"{repo.path}: {len(repo)} rows, all sound")
    return 0


def _volume(text: str | None) -> tuple[int, int] | None:
    from voxfab.generate import parse_volume_range

    return None if text is None else parse_volume_range(text)


def _list(repo: Repository, args: argparse.Namespace) -> None:
    from voxfab.errors import RepositoryError

    if args.limit is not None and args.limit < 1:
        raise RepositoryError(f"--limit: expected at least 1, got {args.limit}")
    if args.range is not None:
        if args.volume is not None or args.no_drafts:
            raise RepositoryError("--range lists a whole range: it takes --after and --limit, not --volume or "
                                  "--no-drafts")
        entries = repo.list_range(args.range, after=args.after, limit=args.limit)
    else:
        entries = repo.list(volume=_volume(args.volume), after=args.after, limit=args.limit,
                            drafts=not args.no_drafts)
    if args.json:
        data: dict[str, object] = {
            "repository": str(repo.path),
            "shapes": [
                {"name": e.name, "volume": e.volume, "extents": list(e.extents), "draft": e.draft}
                for e in entries
            ],
        }
        if args.limit is not None:
            # A full page may have a next one; the name to pass as --after.
            data["next_after"] = entries[-1].name if len(entries) == args.limit else None
        print_json(data)
        return
    for e in entries:
        extents = "x".join(map(str, e.extents))
        print(f"{e.name:<12} {e.volume:>6} {extents:<9}{'  draft' if e.draft else ''}".rstrip())


def _stats(repo: Repository, args: argparse.Namespace) -> None:
    from voxfab.errors import RepositoryError
    from voxfab.generate import volume_bins

    info = repo.stats(volume=_volume(args.volume))
    if args.bins is not None:
        if args.bins < 1:
            raise RepositoryError(f"--bins: expected at least 1, got {args.bins}")
        volumes = [row["volume"] for row in info["volumes"] for _ in range(row["count"])]
        info["ranges"] = [{"min": lo, "max": hi, "count": n} for lo, hi, n in volume_bins(volumes, bins=args.bins)]
    if args.json:
        print_json({"repository": str(repo.path), **info})
        return
    print(f"shapes: {info['shapes']}")
    print(f"drafts: {info['drafts']}")
    for r in info["named_ranges"]:
        print(f"range {r['name']}: {r['count']} members")
    print(f"volumes: {len(info['volumes'])}")
    if "ranges" in info:
        for r in info["ranges"]:
            print(f"volume {r['min']:>5}-{r['max']:<5} {r['count']:>8}")
        return
    for row in info["volumes"]:
        print(f"volume {row['volume']:>5} {row['count']:>8}")


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
    print(f"colours: {info['colours']}")  # 0: stored without colours
    for reason in info["reasons"]:
        print(f"reason: {reason}")
    print(f"key: {info['key']}")
    print(f"symmetric key: {info['symmetric_key']}")
    for k, v in sorted((info["meta"] or {}).items()):
        print(f"meta.{k}: {v}")
