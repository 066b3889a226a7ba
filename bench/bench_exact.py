"""Benchmark of the exact strategy: what it decides within a time limit.

Run ``python bench/bench_exact.py`` (``--help`` for options).  Each row is one
question, ``unfold(grid, strategy="exact", ...)`` with ``--timeout`` seconds:

* a box ``WxH``: a net found, "none (proved)", or "undecided" at the time-out;
* ``min``: the least-area box (every smaller area proved to have no net).

Proofs that no net exists are what limit the strategy (a net in a roomy box
comes from the growth hint in about a second, even at a thousand faces), so
the small boxes dominate the run time: about 10 minutes with the default
questions and a 60 s limit.  ``--smoke`` asks the unit cube's questions only, with a 10 s limit.
Wall-clock on a shared machine: noisy.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _table import Table, add_save_option

from voxfab.errors import NoNetExistsError, UnfoldError
from voxfab.shape import examples, surface_graph
from voxfab.unfold import unfold, validate


def _box(*sides: int) -> np.ndarray:
    return np.ones(sides, dtype=bool)


#: (name, shape, questions): a question is "WxH" or "min".
QUESTIONS = [
    ("unit cube", _box(1, 1, 1), ["3x3", "min"]),
    ("1x1x2 box", _box(1, 1, 2), ["3x4", "min"]),
    ("1x1x3 box", _box(1, 1, 3), ["min"]),
    ("1x2x2 box", _box(1, 2, 2), ["3x6", "min"]),
    ("2x2x2 cube", _box(2, 2, 2), ["2x12", "3x8", "min"]),
    ("8x8x2 plate", _box(8, 8, 2), ["40x40"]),
    ("ball r=3", examples.ball(3), ["30x30"]),
    ("ball r=6", examples.ball(6), ["40x40"]),
    ("ball r=8", examples.ball(8), ["50x50"]),
]


def ask(grid: np.ndarray, question: str, timeout: float) -> str:
    """The answer to one question, in words."""
    try:
        if question == "min":
            net = unfold(grid, rng=0, strategy="exact", min_box=True, timeout=timeout)
        else:
            w, h = (int(v) for v in question.split("x"))
            net = unfold(grid, rng=0, strategy="exact", fit=(w, h), timeout=timeout)
    except NoNetExistsError:
        return "none (proved)"
    except UnfoldError as exc:
        return "undecided" if str(exc).startswith("undecided") else f"error: {exc}"
    validate(grid, net)
    x0, y0, x1, y1 = net.bounds()
    return f"found, {x1 - x0}x{y1 - y0}"


def main() -> None:
    """Print one markdown row per question."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per question (default 60)")
    parser.add_argument("--smoke", action="store_true", help="the unit cube's questions only, 10 s each")
    add_save_option(parser)
    args = parser.parse_args()
    questions = QUESTIONS[:1] if args.smoke else QUESTIONS
    timeout = min(args.timeout, 10.0) if args.smoke else args.timeout
    table = Table("exact", ["surface", "faces", "question", "answer", "time"])
    for name, grid, asked in questions:
        faces = surface_graph(grid).face_count
        for q in asked:
            start = time.monotonic()
            answer = ask(grid, q, timeout)
            table.row(name, faces, q, answer, f"{time.monotonic() - start:.1f} s")
    table.save(args.save)


if __name__ == "__main__":
    main()
