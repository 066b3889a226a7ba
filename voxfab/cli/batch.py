"""``voxfab batch``: build outputs for many repository shapes on Dask distributed."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from voxfab.cli._common import add_repository_option, path_argument
from voxfab.cli._options import integer_argument, number_argument

HELP = "build the outputs of many repository shapes on Dask workers (local or a cluster), with an index"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_repository_option(parser)
    parser.add_argument("--outputs", type=Path, required=True, metavar="FILE.toml",
                        help="[outputs.*] tables as in a recipe; pitch and seed may be given too")
    parser.add_argument("-o", "--output", type=path_argument, required=True, metavar="DIR",
                        help="batch folder: DIR/<name>/ per shape, DIR/batch.json, DIR/index.html")
    parser.add_argument("--names", metavar="A:B", help="the shapes named A to B (inclusive), e.g. 00100.001:00200.999")
    parser.add_argument("--limit", type=integer_argument, metavar="N", help="the first N selected shapes in name order")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running Dask scheduler, e.g. tcp://host:8786 (its workers must see DIR)")
    where.add_argument("--workers", type=integer_argument, default=2, metavar="N",
                       help="worker processes of the local cluster (default 2)")
    parser.add_argument("--connect-timeout", type=number_argument, default=30.0, metavar="S",
                        help="seconds to wait for the scheduler and its first worker (default 30)")
    parser.add_argument("--dashboard", default=":0", metavar="[HOST]:PORT",
                        help="local cluster dashboard address (default :0, a free port; needs bokeh)")
    parser.add_argument("--no-dashboard", action="store_true", help="run the local cluster without a dashboard")
    parser.add_argument("--no-index", action="store_true", help="skip the thumbnails, index.html and contact sheet")


def run(args: argparse.Namespace) -> int:
    from voxfab._shared.progress import meter
    from voxfab.batch import run_batch
    from voxfab.errors import FabricationError

    dashboard = None if args.no_dashboard else args.dashboard
    if dashboard is not None and args.scheduler is None:
        try:
            import bokeh  # noqa: F401
        except ImportError:
            print("voxfab: note: no dashboard: it needs bokeh (pip install bokeh)", file=sys.stderr)
            dashboard = None
    state: dict[str, object] = {}

    def start(count: int, skipped: int, link: str | None) -> None:
        print(f"{count} shapes to build, {skipped} already built in {args.output}", flush=True)
        if link:
            print(f"dashboard: {link}", flush=True)
        bar = meter(count, desc="batch")
        state["bar"] = bar.__enter__()
        state["cm"] = bar

    def outcome(o: object) -> None:
        bar = state.get("bar")
        if bar is not None:
            bar.update()  # type: ignore[attr-defined]
        for note in getattr(o, "notes", ()):
            print(f"voxfab: note: {o.name}: {note}", file=sys.stderr, flush=True)  # type: ignore[attr-defined]
        if getattr(o, "status", "") == "failed":
            print(f"voxfab: note: {o.name} failed: {o.error}", file=sys.stderr, flush=True)  # type: ignore[attr-defined]

    try:
        report = run_batch(args.repo, args.outputs, args.output, names=args.names, limit=args.limit,
                           scheduler=args.scheduler, workers=args.workers, dashboard=dashboard,
                           thumbnails=not args.no_index, timeout=args.connect_timeout, on_start=start,
                           on_outcome=outcome)
    finally:
        if "cm" in state:
            state["cm"].__exit__(None, None, None)  # type: ignore[attr-defined]
    print(f"{report.built} built, {report.skipped} skipped (built before), {report.failed} failed "
          f"in {report.seconds:.1f} s on {report.workers} workers ({report.rate:.1f} shapes/min)")
    if report.hunt is not None:
        net, zipper = report.hunt.counts()["net"], report.hunt.counts()["zipper"]
        print(f"hunt of {report.hunt.shapes} shapes: one-piece net found by the random engine {net['random']}, "
              f"only by the exact strategy {net['exact']}, proved none {net['none']}, undecided {net['undecided']}; "
              f"zipper net found {zipper['found']}, proved none {zipper['none']}, undecided {zipper['undecided']}")
    if not args.no_index:
        print(f"index: {report.index}")
    if report.failed:
        raise FabricationError(
            f"{report.failed} of {report.built + report.failed} shapes failed "
            f"(first: {report.failures[0][0]}: {report.failures[0][1]}); see {args.output / 'batch.json'}"
        )
    return 0
