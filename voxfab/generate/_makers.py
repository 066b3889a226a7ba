"""Random shapes: face-connected growth, and random parameters for the existing makers.

Every candidate is a pure function of ``(seed, index)``: its random numbers come
from ``numpy.random.SeedSequence([seed, index])``, so candidate ``i`` of a run is
the same whatever was drawn before it, and an exploration is reproducible by seed.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np

from voxfab._shared.typing import BoolGrid
from voxfab.digitize import random_makers, rounded_param
from voxfab.errors import InvalidShapeError, VoxfabError
from voxfab.shape import GRID_SIDE

__all__ = ["Candidate", "candidate", "generators", "growth"]

#: Volumes the growth aims at when no range is given: a spine of 25 up to a quarter of the grid's side².
DEFAULT_GROWTH_VOLUME = (GRID_SIDE, GRID_SIDE * GRID_SIDE)


def generators() -> tuple[str, ...]:
    """The generators ``explore`` takes: growth, each maker of the table with a random form, and ``mix``.

    ``mix`` draws one of the others per candidate.  Read from the makers table at each call, so a
    row added to it is a generator at once.
    """
    return ("growth", *random_makers(), "mix")


def _mix() -> tuple[tuple[str, float], ...]:
    """Mix's odds: growth is cheap and varied, the makers add smooth solids and share the rest equally."""
    makers = random_makers()
    return (("growth", 0.55), *((name, 0.45 / len(makers)) for name in makers))


@dataclasses.dataclass(frozen=True)
class Candidate:
    """One generated grid and how to make it again.

    Attributes
    ----------
    grid : (25, 25, 25) bool ndarray
    generator : str
        ``growth``, or a maker of the makers table with a random form (``revolution``, ``tube``, ``focal``, ...).
    params : dict
        JSON-compatible: the growth's target volume and wander, or the maker's
        keyword arguments (``voxfab.digitize.get_maker(generator)(**params)``).
    """

    grid: BoolGrid
    generator: str
    params: dict[str, Any]


def growth(seed: int, volume: int, *, wander: float = 0.3, side: int = GRID_SIDE) -> BoolGrid:
    """Grow a random face-connected shape of ``volume`` voxels spanning ``side`` along z.

    Parameters
    ----------
    seed : int
        0 <= seed < 2**64; the same seed gives the same shape.
    volume : int
        Filled voxels, at least ``side`` (the spine from bottom to top).
    wander : float
        Probability (0..1) that the spine steps sideways rather than up.

    Returns
    -------
    (side, side, side) bool ndarray
        Well formed: one 6-connected piece touching the bottom and the top.
    """
    from ._kernels import grow

    volume = int(volume)
    if not side <= volume <= side**3:
        raise InvalidShapeError(f"volume: a growth spanning {side} voxels needs {side}..{side**3} voxels, got {volume}")
    flat = grow(np.uint64(int(seed) % 2**64), volume, int(side), float(min(max(wander, 0.0), 1.0)))
    return flat.reshape(side, side, side)


def _growth(rng: np.random.Generator, volume: tuple[int, int] | None) -> Candidate:
    lo, hi = volume if volume is not None else DEFAULT_GROWTH_VOLUME
    lo, hi = max(lo, GRID_SIDE), min(hi, GRID_SIDE**3)
    if lo > hi:
        raise InvalidShapeError(f"volume: a growth spanning the grid needs {GRID_SIDE}..{GRID_SIDE**3} voxels")
    target = int(rng.integers(lo, hi + 1))
    wander = rounded_param(rng.uniform(0.0, 0.6))
    seed = int(rng.integers(0, 2**63))
    return Candidate(growth(seed, target, wander=wander), "growth",
                     {"seed": seed, "volume": target, "wander": wander})


def candidate(generator: str, seed: int, index: int, *, volume: tuple[int, int] | None = None) -> Candidate | None:
    """Return candidate ``index`` of an exploration seeded ``seed``, or None when a maker failed.

    The candidate is not checked for well-formedness or volume: the caller does.
    A maker may refuse its random parameters (a curve whose region is unbounded at
    this sampling, say); that candidate is None.
    """
    rng = np.random.default_rng([int(seed), int(index)])
    if generator == "mix":
        names, weights = zip(*_mix())
        generator = str(rng.choice(names, p=weights))
    if generator == "growth":
        return _growth(rng, volume)
    from voxfab.digitize import get_maker, get_random_params

    params = get_random_params(generator)(rng)
    try:
        grid = get_maker(generator)(base_dir=Path("."), **params)
    except VoxfabError:
        return None
    return Candidate(np.asarray(grid, dtype=bool), generator, params)
