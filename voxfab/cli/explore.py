"""``voxfab explore``: generate new well-formed shapes and store them in the repository."""

from __future__ import annotations

import argparse

from voxfab.cli._common import add_repository_option, open_repository_for_writing
from voxfab.cli._options import integer_argument

HELP = "generate N new well-formed shapes (distinct up to the 48 cube symmetries) into the repository"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--count", type=integer_argument, required=True, metavar="N", help="new shapes to store")
    from voxfab._shared.options import SeedOptions
    from voxfab.cli._options import add_option_arguments
    from voxfab.digitize import random_makers
    from voxfab.generate import generators

    add_option_arguments(parser, SeedOptions)  # the same seed on the same repository stores the same shapes
    parser.add_argument("--generator", default="growth", choices=generators(),
                        help=f"growth: random face-connected growth spanning the grid; {', '.join(random_makers())}: "
                             "random parameters for that maker; mix: a blend (default growth)")
    parser.add_argument("--volume", metavar="MIN:MAX",
                        help="keep volumes in MIN..MAX (inclusive); growth aims inside it (default: growth aims "
                             "at 25..625, the makers' shapes keep any volume)")
    parser.add_argument("--max-attempts", type=integer_argument, metavar="N",
                        help="give up after N candidates (default max(2000, 50 x count))")
    add_repository_option(parser)


def run(args: argparse.Namespace) -> int:
    from voxfab._shared.options import SeedOptions
    from voxfab._shared.progress import meter
    from voxfab.cli._options import options_from_args
    from voxfab.generate import check_explore, explore, parse_volume_range, volume_bins

    seed = options_from_args(SeedOptions, args).seed
    volume = parse_volume_range(args.volume) if args.volume is not None else None
    check_explore(args.count, seed=seed, generator=args.generator, volume=volume,
                  max_attempts=args.max_attempts)  # before the repository is made
    with open_repository_for_writing(args.repo) as repo, meter(args.count, desc="exploring") as bar:
        report = explore(repo, args.count, seed=seed, generator=args.generator, volume=volume,
                         max_attempts=args.max_attempts, on_added=bar.update)
    volumes = [v for _, v in report.added]
    print(f"{len(report.added)} new shapes in {args.repo} ({report.attempts} candidates, "
          f"{report.duplicates} duplicates, {report.rejected} rejected)")
    print(f"first {report.added[0][0]}, last {report.added[-1][0]}")
    for lo, hi, n in volume_bins(volumes):
        print(f"volume {lo:>5}-{hi:<5} {n:>7}")
    return 0
