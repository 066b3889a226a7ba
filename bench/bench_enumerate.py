"""Benchmark of the polycube enumeration: counts and seconds per n, against OEIS.

Run ``python bench/bench_enumerate.py [--n 10] [--smoke]`` (``--smoke``: up to 6 cubes).  It grows every polycube of
1..n cubes up to rotation (canonical growth, :func:`voxfab.census.polycube_levels`),
counts them up to rotation and up to rotation and reflection, and prints each
count beside OEIS A000162 and A038119 with the CPU seconds of that level.
"""

from __future__ import annotations

import argparse
import time

# OEIS A000162 (up to rotation) and A038119 (up to rotation and reflection), n = 1..10.
FREE = [1, 1, 2, 8, 29, 166, 1023, 6922, 48311, 346543]
FREE_MIRROR = [1, 1, 2, 7, 23, 112, 607, 3811, 25413, 178083]


def main() -> None:
    from voxfab.census import count_free, polycube_levels

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=10, choices=range(1, 11), metavar="N",
                        help="largest number of cubes, 1 to 10 (default 10)")
    parser.add_argument("--smoke", action="store_true", help="up to 6 cubes")
    args = parser.parse_args()
    if args.smoke:
        args.n = 6
    print(f"{'n':>3} {'free':>9} {'A000162':>9} {'mirror':>9} {'A038119':>9} {'CPU s':>7}")
    cpu = time.process_time()
    for n, forms in polycube_levels(args.n):
        free, mirror = count_free(n, forms)
        now = time.process_time()
        ok = "" if (free, mirror) == (FREE[n - 1], FREE_MIRROR[n - 1]) else "  MISMATCH"
        print(f"{n:>3} {free:>9} {FREE[n - 1]:>9} {mirror:>9} {FREE_MIRROR[n - 1]:>9} {now - cpu:>7.1f}{ok}",
              flush=True)
        cpu = now


if __name__ == "__main__":
    main()
