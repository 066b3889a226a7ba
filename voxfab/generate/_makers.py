"""Random shapes: face-connected growth, and random parameters for the existing makers.

Every candidate is a pure function of ``(seed, index)``: its random numbers come
from ``numpy.random.SeedSequence([seed, index])``, so candidate ``i`` of a run is
the same whatever was drawn before it, and an exploration is reproducible by seed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from voxfab._shared.typing import BoolGrid
from voxfab.errors import InvalidShapeError, VoxfabError
from voxfab.shape import GRID_SIDE

__all__ = ["GENERATORS", "MAKER_GENERATORS", "Candidate", "candidate", "growth"]

#: The generators ``explore`` takes; ``mix`` draws one of the others per candidate.
GENERATORS = ("growth", "revolution", "tube", "focal", "mix")
#: The generators that give random parameters to a maker of :mod:`voxfab.digitize`.
MAKER_GENERATORS = ("revolution", "tube", "focal")
#: Volumes the growth aims at when no range is given: a spine of 25 up to a quarter of the grid's side².
DEFAULT_GROWTH_VOLUME = (GRID_SIDE, GRID_SIDE * GRID_SIDE)
# Mix: growth is cheap and varied, the makers add smooth solids.
_MIX = (("growth", 0.55), ("revolution", 0.15), ("tube", 0.15), ("focal", 0.15))


@dataclasses.dataclass(frozen=True)
class Candidate:
    """One generated grid and how to make it again.

    Attributes
    ----------
    grid : (25, 25, 25) bool ndarray
    generator : str
        ``growth``, ``revolution``, ``tube`` or ``focal``.
    params : dict
        JSON-compatible: the growth's target volume and wander, or the maker's
        keyword arguments (``voxfab.digitize.get_maker(generator)(**params)``).
    """

    grid: BoolGrid
    generator: str
    params: dict[str, Any]


def _round(x: float) -> float:
    # Parameters are stored in the repository's metadata: 4 decimals keep them short
    # and the stored values are exactly the ones used.
    return round(float(x), 4)


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
    wander = _round(rng.uniform(0.0, 0.6))
    seed = int(rng.integers(0, 2**63))
    return Candidate(growth(seed, target, wander=wander), "growth",
                     {"seed": seed, "volume": target, "wander": wander})


def _revolution(rng: np.random.Generator) -> dict[str, Any]:
    kind = int(rng.integers(3))
    if kind == 0:
        curve = "x^2 + y^2 - 1"
    elif kind == 1:
        p, q = (_round(v) for v in rng.choice([1.0, 1.5, 3.0, 4.0], size=2))
        curve = f"abs(x)^{p} + abs(y)^{q} - 1"
    else:
        curve = f"sqrt(x^2 + y^2) - 1 - {_round(rng.uniform(0.1, 0.35))}*cos({int(rng.integers(3, 9))}*atan2(y, x))"
    r0 = _round(rng.uniform(0.35, 1.0))
    amp = _round(rng.uniform(0.0, 0.3) * r0)
    freq, phase, height = _round(rng.uniform(0.5, 5.0)), _round(rng.uniform(0.0, math.tau)), _round(rng.uniform(0.6, 2.5))
    generatrix = f"max(x - ({r0} + {amp}*sin({freq}*y + {phase})), abs(y) - {height})"
    return {"curve": curve, "generatrix": generatrix, "mode": str(rng.choice(["solid", "solid", "surface"]))}


def _tube(rng: np.random.Generator) -> dict[str, Any]:
    if rng.integers(2) == 0:
        turns, r = _round(rng.uniform(0.5, 3.0)), _round(rng.uniform(0.3, 1.5))
        spine = [f"{r}*cos(tau*{turns}*t)", f"{r}*sin(tau*{turns}*t)", "t"]
    else:
        a, b, c = (int(v) for v in rng.integers(1, 5, size=3))
        ph = _round(rng.uniform(0.0, math.tau))
        spine = [f"sin(tau*{a}*t + {ph})", f"sin(tau*{b}*t)", f"t + 0.3*sin(tau*{c}*t)"]
    profile = str(rng.choice(["x^2 + y^2 - 1", "abs(x)^4 + abs(y)^4 - 1", "abs(x) + abs(y) - 1"]))
    return {"spine": spine, "profile": profile, "radius": _round(rng.uniform(0.06, 0.25)),
            "twist": _round(rng.uniform(0.0, 2.0)), "cap": str(rng.choice(["flat", "round"]))}


def _focal(rng: np.random.Generator) -> dict[str, Any]:
    n = int(rng.integers(2, 5))
    foci = np.round(rng.uniform(-1.5, 1.5, size=(n, 3)), 4)
    weights = np.round(rng.uniform(0.5, 3.0, size=n), 4)
    # The level set is empty below the smallest weighted sum, reached at a focus.
    least = min(float(np.sum(weights * np.linalg.norm(foci - f, axis=1))) for f in foci)
    radius = _round(least * rng.uniform(1.05, 1.6) + float(weights.sum()) * rng.uniform(0.2, 1.0))
    return {"foci": foci.tolist(), "weights": weights.tolist(), "radius": radius,
            "mode": str(rng.choice(["solid", "solid", "surface"]))}


_PARAMS: dict[str, Callable[[np.random.Generator], dict[str, Any]]] = {
    "revolution": _revolution, "tube": _tube, "focal": _focal,
}


def candidate(generator: str, seed: int, index: int, *, volume: tuple[int, int] | None = None) -> Candidate | None:
    """Return candidate ``index`` of an exploration seeded ``seed``, or None when a maker failed.

    The candidate is not checked for well-formedness or volume: the caller does.
    A maker may refuse its random parameters (a curve whose region is unbounded at
    this sampling, say); that candidate is None.
    """
    rng = np.random.default_rng([int(seed), int(index)])
    if generator == "mix":
        names, weights = zip(*_MIX)
        generator = str(rng.choice(names, p=weights))
    if generator == "growth":
        return _growth(rng, volume)
    params = _PARAMS[generator](rng)
    from voxfab.digitize import get_maker

    try:
        grid = get_maker(generator)(base_dir=Path("."), **params)
    except VoxfabError:
        return None
    return Candidate(np.asarray(grid, dtype=bool), generator, params)
