"""Exploration: draw candidates by seed and store the new well-formed ones in the repository."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

from voxfab._shared.limits import MAX_EXPLORE_ATTEMPTS, MAX_EXPLORE_COUNT, check_count
from voxfab._shared.options import SeedOptions
from voxfab.errors import InvalidShapeError, RepositoryError
from voxfab.shape import GRID_SIDE, crop, well_formed_reasons

from ._keys import symmetric_key
from ._makers import candidate, generators

__all__ = ["ExploreReport", "check_explore", "explore", "volume_bins", "parse_volume_range"]

#: Candidates drawn, keyed and looked up before one write transaction.
_CHUNK = 512


@dataclasses.dataclass(frozen=True)
class ExploreReport:
    """What :func:`explore` did.

    Attributes
    ----------
    added : tuple of (str, int)
        Name and volume of each stored shape, in storage order.
    attempts : int
        Candidates drawn (indexes ``0 .. attempts - 1`` of the seed).
    duplicates : int
        Candidates equal, up to translation and the 48 cube symmetries, to a stored
        shape or to an earlier candidate.
    rejected : int
        Candidates a maker refused, not well formed, outside the volume range, or of
        a volume whose 999 ranks are all given.
    """

    added: tuple[tuple[str, int], ...]
    attempts: int
    duplicates: int
    rejected: int


def parse_volume_range(text: str) -> tuple[int, int]:
    """Parse ``MIN:MAX`` (inclusive; either side may be left empty) into a volume range."""
    lo_text, sep, hi_text = str(text).partition(":")
    if not (lo_text.strip() or hi_text.strip()):
        raise InvalidShapeError(f"volume: expected MIN:MAX, MIN: or :MAX, got {text!r}")
    from voxfab._shared.numbers import parse_int

    try:
        lo = parse_int(lo_text.strip()) if lo_text.strip() else 1
        hi = parse_int(hi_text.strip()) if hi_text.strip() else GRID_SIDE**3
    except ValueError:
        raise InvalidShapeError(f"volume: expected MIN:MAX with whole numbers, got {text!r}") from None
    if not sep:
        hi = lo
    if not 1 <= lo <= hi <= GRID_SIDE**3:
        raise InvalidShapeError(f"volume: expected 1 <= MIN <= MAX <= {GRID_SIDE**3}, got {text!r}")
    return lo, hi


def volume_bins(volumes: list[int], *, bins: int = 10) -> list[tuple[int, int, int]]:
    """Count ``volumes`` in at most ``bins`` ranges of a round width.

    Returns
    -------
    list of (int, int, int)
        ``(low, high, count)`` per non-empty range, low to high, both ends inclusive.
    """
    if not volumes:
        return []
    lo, hi = min(volumes), max(volumes)
    raw = max(1.0, (hi - lo + 1) / bins)
    # A width of 1, 2 or 5 times a power of ten reads well in a table.
    power = 10 ** math.floor(math.log10(raw))
    width = next(m * power for m in (1, 2, 5, 10) if m * power >= raw)
    start = (lo // width) * width
    counts = np.bincount((np.asarray(volumes) - start) // width)
    return [(start + i * width, start + (i + 1) * width - 1, int(n)) for i, n in enumerate(counts) if n]


def check_explore(
    count: int,
    *,
    seed: int,
    generator: str = "growth",
    volume: tuple[int, int] | None = None,
    max_attempts: int | None = None,
) -> int:
    """Check :func:`explore`'s arguments before any work; return the candidate limit.

    Raises
    ------
    InvalidShapeError
        For a bad count, seed, generator, volume range or number of attempts.
    LimitError
        For a count or a number of attempts over the limits table's.
    """
    if generator not in generators():
        raise InvalidShapeError(f"generator: expected one of {', '.join(generators())}, got {generator!r}")
    for name, value in (("count", count), ("max_attempts", max_attempts)):
        if value is not None and (isinstance(value, bool) or int(value) != value or value < 1):
            raise InvalidShapeError(f"{name}: expected a whole number >= 1, got {value!r}")
    check_count(int(count), MAX_EXPLORE_COUNT, name="count")
    SeedOptions(seed=seed)  # the one declaration of a seed's type and range
    if volume is not None and int(volume[1]) < GRID_SIDE:
        raise InvalidShapeError(
            f"volume: a well-formed shape spans {GRID_SIDE} voxels, so MAX must be at least {GRID_SIDE}"
        )
    if max_attempts is None:
        return min(max(2000, 50 * int(count)), MAX_EXPLORE_ATTEMPTS)
    return check_count(int(max_attempts), MAX_EXPLORE_ATTEMPTS, name="max_attempts")


def explore(
    repo: object,
    count: int,
    *,
    seed: int,
    generator: str = "growth",
    volume: tuple[int, int] | None = None,
    max_attempts: int | None = None,
    on_added: Callable[[int], None] | None = None,
) -> ExploreReport:
    """Generate ``count`` new well-formed shapes and store them in ``repo``.

    Candidates ``0, 1, 2, ...`` of ``seed`` are drawn in order
    (:func:`voxfab.generate.candidate`); each one that is well formed, within
    ``volume``, and not equal up to translation and the 48 cube symmetries to a
    stored shape or an earlier candidate is stored, until ``count`` are.  The same
    seed on the same repository stores the same shapes under the same names: a
    shape's rank is its order of storage within its volume.

    Parameters
    ----------
    repo : voxfab.repo.Repository
    count : int
        Shapes to add (at least 1).
    seed : int
        Seed of the candidates (>= 0).
    generator : str
        One of :func:`voxfab.generate.generators`.
    volume : (int, int), optional
        Keep the volumes in ``[min, max]``; growth aims inside it (at least 25).
    max_attempts : int, optional
        Give up after this many candidates (default ``max(2000, 50 * count)``).
    on_added : callable, optional
        Called with the number of shapes stored by each write (for a progress bar).

    Raises
    ------
    RepositoryError
        When ``max_attempts`` candidates did not give ``count`` new shapes (those
        found are stored; the message says how many).
    InvalidShapeError
        For a bad count, seed, generator or volume range.
    """
    from voxfab.repo import MAX_RANK

    limit = check_explore(count, seed=seed, generator=generator, volume=volume, max_attempts=max_attempts)
    if volume is not None:
        volume = (int(volume[0]), int(volume[1]))
    ranks = repo.last_ranks()  # type: ignore[attr-defined]
    seen: set[str] = set()
    added: list[tuple[str, int]] = []
    index = duplicates = rejected = 0
    while len(added) < count and index < limit:
        grids: list[np.ndarray] = []
        keys: list[str] = []
        metas: list[dict[str, object]] = []
        pending: dict[int, int] = {}
        while len(added) + len(grids) < count and len(grids) < _CHUNK and index < limit:
            i, index = index, index + 1
            c = candidate(generator, seed, i, volume=volume)
            if c is None:
                rejected += 1
                continue
            if not c.grid.any():
                rejected += 1
                continue
            # Everything below works on the bounding box: a growth fills a few percent of the grid.
            g = crop(c.grid)
            v = int(np.count_nonzero(g))
            full = ranks.get(v, 0) + pending.get(v, 0) >= MAX_RANK
            outside = volume is not None and not volume[0] <= v <= volume[1]
            # Growth is well formed by construction (one face-connected piece from the
            # bottom layer to the top one): only the makers' shapes are checked.
            if full or outside or (c.generator != "growth" and well_formed_reasons(g)):
                rejected += 1
                continue
            key = symmetric_key(g)
            if key in seen:
                duplicates += 1
                continue
            seen.add(key)
            pending[v] = pending.get(v, 0) + 1
            grids.append(g)
            keys.append(key)
            metas.append({"generator": c.generator, "seed": seed, "index": i, "params": c.params})
        if not grids:
            continue
        results = repo.add_many(  # type: ignore[attr-defined]
            grids, symmetric=True, metas=metas, keys=keys, reasons=[()] * len(grids)
        )
        new = 0
        for r, g in zip(results, grids):
            if not r.created:
                duplicates += 1
                continue
            v = int(np.count_nonzero(g))
            ranks[v] = ranks.get(v, 0) + 1
            added.append((r.name, v))
            new += 1
        if on_added is not None:
            on_added(new)
    if len(added) < count:
        raise RepositoryError(
            f"explore: only {len(added)} of {count} new shapes after {index} candidates "
            f"({duplicates} duplicates, {rejected} rejected); try another seed, generator or volume range"
        )
    return ExploreReport(tuple(added), index, duplicates, rejected)
