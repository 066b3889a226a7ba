"""One-piece search: a net grown in one piece, free or inside a box, made compact, then given tab room."""

from __future__ import annotations

import time

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import meter
from voxfab.errors import UnfoldError

from ._constraints import Resolved
from ._job import FIT_STEPS_PER_FACE, Job, NoFitError, Strategy, orientations
from ._net import Net
from ._searchboard import SearchBoard

#: Fitting a box: tries, alternating the two orientations.
_FIT_TRIES = 6
#: Compactness: box-shrinking trials, and growth steps per face each trial may use.
_COMPACT_TRIES = 24
_COMPACT_STEPS_PER_FACE = 100


def one_piece(job: Job, faces: npt.NDArray[np.int64]) -> Net:
    """A one-piece net of the faces of one surface part, in the job's box if it has one.

    Raises UnfoldError (NoFitError for a box) when none is found within the budget.
    """
    p = job.growth(faces.size)
    resolved = job.resolved(faces)
    if job.fit is not None:
        b = _grow_to_fit(job, faces, resolved)
    else:
        b = SearchBoard(job.sg, faces, job.seed, None, resolved, tab_restarts=True)
        with meter(int(faces.size), desc="net: faces placed") as bar:
            grown = b.grow(p, job.deadline, bar=bar)
        if not grown:
            raise UnfoldError(
                f"no one-piece net of the {faces.size}-face surface in {job.timeout:g} s with "
                f"strategy {job.strategy.value!r}: {int(b.cnt[b.k.C_DEADENDS])} dead ends repaired, "
                f"{int(b.cnt[b.k.C_RESTARTS])} restarts, best partial net {b.best} of "
                f"{faces.size} faces; raise the timeout, try another seed, or allow several "
                "pieces (pieces='auto', CLI --pieces auto)"
            )
    if job.compact:
        b = _compact(job, faces, b, resolved)
    if job.tab_aware and job.strategy is Strategy.DEFAULT:
        with meter(b.anneal_budget(), desc="net: tab room, moves (at most)") as bar:
            b.anneal(p, job.deadline, bar=bar)
    return b.net(job, faces)


def _grow_to_fit(job: Job, faces: npt.NDArray[np.int64], resolved: Resolved | None) -> SearchBoard:
    """Grow a net inside the fit box (either way round); NoFitError when none fits.

    The box's walls steer growth: ruin-and-recreate packs the faces into it.
    Each try has a fixed budget of growth steps, so the outcome depends on the
    seed alone unless the clock runs out first.
    """
    n = int(faces.size)
    p = job.growth(n)
    fit = job.fit
    if fit[0] * fit[1] >= n:
        with meter(_FIT_TRIES, desc="net: tries to fit the box") as bar:
            for t in range(_FIT_TRIES):
                box = orientations(fit)[t % len(orientations(fit))]
                trial = SearchBoard(job.sg, faces, job.seed if t == 0 else [job.seed, 1000 + t], box, resolved)
                if trial.grow(p, job.deadline, FIT_STEPS_PER_FACE * n):
                    return trial
                bar.update()
                if time.monotonic() > job.deadline:
                    break
    extent = _best_extent(job, faces, resolved)
    why = (f"the surface has {n} faces, more than the {fit[0]}x{fit[1]} = {fit[0] * fit[1]} cells "
           "of the box" if fit[0] * fit[1] < n else
           f"no one-piece net of the {n}-face surface fits {fit[0]}x{fit[1]} cells (either way "
           "round) within the budget")
    raise NoFitError(
        f"{why}; the most compact net found spans {extent[0]}x{extent[1]} cells: use a larger "
        "sheet, smaller faces, or several pieces (pieces='auto')", extent)


def _best_extent(job: Job, faces: npt.NDArray[np.int64], resolved: Resolved | None) -> tuple[int, int]:
    """Sides (shorter first) of the most compact net found within the budget."""
    free = SearchBoard(job.sg, faces, job.seed, None, resolved)
    if not free.grow(job.growth(faces.size), job.deadline):
        raise UnfoldError(
            f"no one-piece net of the {faces.size}-face surface in {job.timeout:g} s, so none "
            f"that fits {job.fit[0]}x{job.fit[1]}; raise the timeout or try another seed")
    w, h = _compact(job, faces, free, resolved).extent()
    return (min(w, h), max(w, h))


def _compact(job: Job, faces: npt.NDArray[np.int64], board: SearchBoard, resolved: Resolved | None) -> SearchBoard:
    """Shrink the net's bounding box while a fixed growth budget still fits it.

    Each trial grows a new net inside the current box with its longer side cut
    by about a tenth; two failures in a row end the search.  Budgets are counted
    in growth steps, so the result depends on the seed alone (unless the clock
    runs out first).
    """
    p = job.growth(faces.size)
    best = board
    failures = 0
    for t in range(_COMPACT_TRIES):
        w, h = best.extent()
        if (w >= h) != (failures % 2 == 1):
            w = min(w - 1, int(w * 0.9))
        else:
            h = min(h - 1, int(h * 0.9))
        if w < 1 or h < 1 or w * h < faces.size or time.monotonic() > job.deadline:
            break
        trial = SearchBoard(job.sg, faces, [job.seed, t + 1], (w, h), resolved)
        if trial.grow(p, job.deadline, _COMPACT_STEPS_PER_FACE * int(faces.size)):
            best, failures = trial, 0
        else:
            failures += 1
            if failures == 2:
                break
    return best
