"""The search's shared terms: strategies, piece modes, the job every step reads, and small helpers on them."""

from __future__ import annotations

import dataclasses
import enum

import numpy as np
import numpy.typing as npt

from voxfab._shared.rng import as_rng, check_seed
from voxfab.errors import UnfoldError
from voxfab.shape import SurfaceGraph

from ._constraints import EdgeConstraints, Resolved, resolve
from ._params import MODE_PAPER, MODE_RUIN, Growth

__all__ = ["NoFitError", "Pieces", "Strategy"]

#: Growth steps per face one try to lay a net in a box may spend.
FIT_STEPS_PER_FACE = 200
#: pieces="auto": the smallest piece as a share of the largest (by faces).
MIN_SHARE = 0.1


class Strategy(enum.StrEnum):
    """Search strategies."""

    DEFAULT = "default"
    PAPER = "paper"
    EXACT = "exact"


class Pieces(enum.StrEnum):
    """How many pieces a result may have."""

    ONE = "one"
    AUTO = "auto"
    FLAT = "flat"
    BANDS = "bands"


def growth_settings(strategy: Strategy, faces: int) -> Growth:
    """How a strategy grows a net of this many faces."""
    if strategy is Strategy.PAPER:
        return Growth(MODE_PAPER, 1, 0, 0.0, max(50, faces // 4))
    return Growth(MODE_RUIN, 3, 3, 0.05, 0)


def tab_growth(gw: Growth) -> Growth:
    """``gw`` for a net grown for tab room (a sparse board) and annealed on it.

    Of 24 candidates, the one touching the fewest placed faces is laid next:
    on the 2600-face blobs of ``bench/bench_unfold.py`` the grown net starts
    with about a third fewer seams without tab room than with 3 candidates,
    and annealing (whose moves regrow the same way) needs a fifth of the moves
    and far fewer fresh nets to fix them all.
    """
    return gw._replace(tour=24)


def orientations(fit: tuple[int, int]) -> list[tuple[int, int]]:
    """The box, and the box turned a quarter turn unless it is square."""
    w, h = fit
    return [(w, h)] if w == h else [(w, h), (h, w)]


def surface_parts(sg: SurfaceGraph, faces: npt.NDArray[np.int64] | None = None) -> list[npt.NDArray[np.int64]]:
    """Face indices of each connected part of the surface (or of ``faces``), in order of first face."""
    f = sg.face_count
    inside = np.ones(f, dtype=bool)
    if faces is not None:
        inside[:] = False
        inside[faces] = True
    nb = sg.neighbor
    joined = inside[:, None] & inside[nb]
    # Each face takes the smallest label among itself and its neighbours, with
    # pointer jumping; plain numpy keeps scipy.sparse out of the start-up time.
    label = np.arange(f)
    while True:
        new = np.minimum(label, np.where(joined, label[nb], f).min(axis=1))
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    chosen = np.flatnonzero(inside)
    return [chosen[label[chosen] == lab] for lab in dict.fromkeys(label[chosen].tolist())]


def seed_of(rng: np.random.Generator | int) -> int:
    """The int seed of ``rng``: the seed itself, or one drawn from the generator."""
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        return check_seed(rng)
    return int(as_rng(rng).integers(0, 2**31 - 1))


class NoFitError(UnfoldError):
    """No one-piece net fits the requested box within the budget.

    Attributes
    ----------
    best_extent : (int, int)
        Sides in cells of the most compact net layout found, the shorter first.
    """

    def __init__(self, message: str, best_extent: tuple[int, int]) -> None:
        super().__init__(message)
        self.best_extent = best_extent


@dataclasses.dataclass(frozen=True)
class Job:
    """One search: the shape, its surface and the options every step reads."""

    grid: npt.NDArray[np.bool_]
    sg: SurfaceGraph
    seed: int
    strategy: Strategy
    fit: tuple[int, int] | None
    tab_aware: bool
    compact: bool
    deadline: float
    timeout: float
    constraints: EdgeConstraints | None
    flat: bool = False
    bands: bool = False

    def growth(self, faces: int):
        return growth_settings(self.strategy, faces)

    def resolved(self, faces: npt.NDArray[np.int64]) -> Resolved | None:
        return resolve(self.constraints, self.sg, faces)
