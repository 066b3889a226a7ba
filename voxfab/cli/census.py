"""``voxfab census N -o DIR``: every polycube of 1..N cubes, unfolded and unzipped, into census.json and a page."""

from __future__ import annotations

import argparse
import sys

from voxfab.census._task import CensusSettings
from voxfab.cli._common import add_repository_option, check_repository_path, path_argument
from voxfab.cli._options import add_option_arguments, integer_argument, number_argument, options_from_args

HELP = ("census every polycube of 1..N cubes: an edge unfolding and an edge-unzipping of each "
        "(DIR/census.json, DIR/census.html, DIR/nets/)")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("n", type=integer_argument, metavar="N", help="the largest number of cubes (1 to 11)")
    parser.add_argument("-o", "--output", type=path_argument, required=True, metavar="DIR",
                        help="output folder; an earlier census there with the same settings is resumed (its records "
                             "checked, a larger N kept whole); one with other settings is said and censused again")
    add_option_arguments(parser, CensusSettings)
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="a running Dask scheduler (tcp://HOST:PORT); default: --workers local processes")
    parser.add_argument("--workers", type=integer_argument, default=2, metavar="K",
                        help="local Dask worker processes; 0 runs in this process (default 2)")
    parser.add_argument("--store", metavar="RANGE",
                        help="also store every polycube in the repository (--repo) as the named range RANGE, "
                             "members named by census id (RANGE:08-000001)")
    add_repository_option(parser)
    parser.add_argument("--connect-timeout", type=number_argument, default=30.0, metavar="S",
                        help="seconds to wait for the scheduler and a first worker (default 30)")


def run(args: argparse.Namespace) -> int:
    from voxfab._shared.progress import meter
    from voxfab.census import CensusInterrupted, check_census_size, run_census

    check_census_size(args.n)
    if args.store is not None:
        from voxfab.repo._records import check_range_name

        check_range_name(args.store)
        check_repository_path(args.repo)  # before the enumeration, not after it
    settings = options_from_args(CensusSettings, args)
    with meter(None, desc="census") as bar:
        def progress(done: int, total: int) -> None:
            bar.total = total
            bar.update(done - bar.done)

        try:
            report = run_census(args.n, args.output, settings=settings, scheduler=args.scheduler,
                                workers=args.workers, connect_timeout=args.connect_timeout, on_progress=progress,
                                store=args.store, repository=args.repo)
        except CensusInterrupted as stop:
            print(f"voxfab: census: stopped; what was done is saved in {stop.path} ({stop.saved} polycubes), "
                  "and the same command resumes it", file=sys.stderr)
            raise
    print(f"{report.censused} polycubes censused, {report.kept} kept from an earlier run, in "
          f"{report.seconds:.1f} s on {report.workers} worker(s)")
    print(f"{'n':>3} {'1-sided':>7} {'free':>7} {'unfold':>16} {'unzip':>16} {'outside':>8}")
    for r in report.rows:
        outside = r["edge_touching"] + r["vertex_touching"] + r["handle"]
        print(f"{r['n']:>3} {r['one_sided']:>7} {r['free']:>7} "
              f"{r['unfold_found']:>6}/{r['unfold_none']}/{r['unfold_undecided']:<6} "
              f"{r['unzip_found']:>6}/{r['unzip_none']}/{r['unzip_undecided']:<6} {outside:>8}")
    print("(1-sided: up to rotation, the polycubes censused; free: mirror images as one; unfold and unzip: "
          "found/none/undecided; outside: touchings and handles, not unzipped)")
    print(f"wrote {report.path} and {report.page}")
    if args.store:
        print(f"stored as the range {args.store} in {args.repo} (voxfab repo list --range {args.store})")
    return 0
