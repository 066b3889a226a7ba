"""The smallest of a row of boxes a one-piece net is found in: the search behind a sheet's automatic face size.

The boxes are the sheet's cells at growing face sizes, so each is no larger
than the one before.  The bisection probes a box with a few boards (seeds and
both ways round) grown in turn, a short run of steps at a time, until one holds
every face or all have spent their steps: on a crowded box the time a board
takes varies by a factor of ten from seed to seed, so a few boards side by side
find a net far sooner than one board given their steps.  Budgets are counted in
growth steps, so the result depends on the seed alone (unless the clock runs
out first).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence

import numpy.typing as npt

from voxfab.errors import InvalidShapeError
from voxfab.shape import surface_graph

from ._constraints import EdgeConstraints, check_one_piece, resolve
from ._job import Job, Pieces, Strategy, orientations, seed_of, surface_parts
from ._net import Net
from ._search import _check_fit, _prepare, _refuse_parts
from ._searchboard import SearchBoard

__all__ = ["BOX_BOARDS", "BOX_STEPS_PER_FACE", "smallest_box"]

#: Boards grown side by side in one box, and the growth steps per face each may spend there.
BOX_BOARDS = 4
BOX_STEPS_PER_FACE = 60
#: Steps per face a board runs before the next board's turn.
_TURN_STEPS_PER_FACE = 15


def smallest_box(grid: npt.ArrayLike, boxes: Sequence[tuple[int, int]], *, rng: int,
                 strategy: str = "default", timeout: float = 60.0, tab_aware: bool = True, fill: bool = False,
                 constraints: EdgeConstraints | None = None) -> tuple[int, Net] | None:
    """The last of ``boxes`` (each no larger than the one before) found to hold a one-piece net, and that net.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
    boxes : sequence of (int, int)
        Boxes in cells, each fitting inside the one before (the net may lie in it turned).
    rng : int
        Seed.
    strategy : {"default", "paper"}
        How the boards grow (the exact strategy proves boxes one by one instead: not here).

    Returns
    -------
    (index, Net) or None
        None when no box is found to hold a net.  The net lies in ``boxes[index]``
        (turned or not), its seams given tab room as :func:`unfold` gives them.
    """
    strat = Strategy(strategy)
    if strat is Strategy.EXACT:
        raise InvalidShapeError("smallest_box: the exact strategy proves one box at a time (unfold(fit=...))")
    seed = seed_of(rng)
    g = _prepare(grid, fill, Pieces.ONE)
    sg = surface_graph(g)
    resolved = resolve(constraints, sg)
    parts = surface_parts(sg)
    if len(parts) > 1:
        _refuse_parts(g, len(parts))
    check_one_piece(sg, resolved)
    faces = parts[0]
    n = int(faces.size)
    job = Job(g, sg, seed, strat, None, tab_aware, False, time.monotonic() + float(timeout), float(timeout),
              constraints)
    gw = job.growth(n)
    lo, hi = -1, len(boxes)
    # Boxes with fewer cells than faces hold no net: never probed.
    while hi > 0 and _area(boxes[hi - 1]) < n:
        hi -= 1
    found: SearchBoard | None = None
    while hi - lo > 1:
        mid = (lo + hi) // 2
        board = _probe(job, faces, resolved, _check_fit(boxes[mid]), gw)
        if board is None:
            hi = mid
            continue
        found, lo = board, mid
        w, h = board.extent()  # a net smaller than its box may fit later boxes too
        while lo + 1 < hi and _holds(boxes[lo + 1], (w, h)):
            lo += 1
        if time.monotonic() > job.deadline:
            break
    if found is None:
        return None
    if tab_aware and strat is Strategy.DEFAULT:
        found.anneal(gw, job.deadline)
    return lo, found.net(job, faces)


def _area(box: tuple[int, int]) -> int:
    return int(box[0]) * int(box[1])


def _holds(box: tuple[int, int], extent: tuple[int, int]) -> bool:
    w, h = extent
    return (w <= box[0] and h <= box[1]) or (h <= box[0] and w <= box[1])


def _probe(job: Job, faces: npt.NDArray, resolved: object, box: tuple[int, int], gw: object) -> SearchBoard | None:
    """The first of :data:`BOX_BOARDS` boards grown in turn in ``box`` to hold every face, or None."""
    n = int(faces.size)
    turns = orientations(box)
    boards = [SearchBoard(job.sg, faces, [job.seed, 7000 + k], turns[k % len(turns)], resolved)
              for k in range(BOX_BOARDS)]
    turn = _TURN_STEPS_PER_FACE * n
    for _ in range(math.ceil(BOX_STEPS_PER_FACE / _TURN_STEPS_PER_FACE)):
        for b in boards:
            if b.grow(gw, job.deadline, turn):
                return b
        if time.monotonic() > job.deadline:
            break
    return None

