"""``voxfab warmup``: compile the numba kernels once, after an install, so the first build does not."""

from __future__ import annotations

import argparse
import time

from ._common import print_json

HELP = "compile the numba kernels now (after an install), so the first build does not pay for it"


def _positive(text: str) -> int:
    from voxfab._shared.numbers import parse_int

    try:
        value = parse_int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text[:80]!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected at least 1, got {value}")
    return value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``warmup`` options."""
    from voxfab.warmup import GROUPS

    parser.add_argument("--group", action="append", choices=list(GROUPS), metavar="GROUP",
                        help=f"a kernel group to compile ({', '.join(GROUPS)}); repeat for several "
                             "(default all)")
    parser.add_argument("--processes", type=_positive, metavar="N",
                        help="groups compiled side by side (default: one per core)")


def run(args: argparse.Namespace) -> int:
    """Compile the groups and print how long each took."""
    from voxfab.warmup import warm_up

    start = time.perf_counter()
    times = warm_up(args.group, processes=args.processes)
    print_json({"groups": {t.group: t.seconds for t in times}, "seconds": round(time.perf_counter() - start, 3)})
    return 0
