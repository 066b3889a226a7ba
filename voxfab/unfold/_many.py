"""unfold_many: several nets of one shape that look different on the sheet."""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from voxfab._shared.progress import meter
from voxfab.errors import InvalidShapeError, UnfoldError

from ._job import NoFitError, Strategy, seed_of
from ._net import Net
from ._outline import outline_key
from ._search import unfold

__all__ = ["unfold_many"]

#: Default overall budget of ``unfold_many`` in seconds.
DEFAULT_BUDGET = 60.0


def unfold_many(
    grid: npt.ArrayLike,
    *,
    count: int,
    rng: np.random.Generator | int,
    budget: float = DEFAULT_BUDGET,
    progress: Callable[[int, int], None] | None = None,
    **options: object,
) -> list[Net]:
    """Find up to ``count`` nets that look different on the sheet.

    Net ``t`` is ``unfold(grid, rng=seed_t, **options)`` for seeds drawn from
    ``rng``; a net whose outline (the cells it covers and where it is folded or
    cut, see :func:`outline_key`) matches an earlier one's under the 8 rotations
    and mirrors of the sheet is skipped.  ``timeout`` (in ``options``) bounds
    each net, ``budget`` the whole call.

    Parameters
    ----------
    count : int
        Nets wanted.
    budget : float
        Seconds for the whole call.  The search also stops after ``4 * count +
        8`` seeds, so a surface with few nets ends early.
    progress : callable, optional
        ``progress(found, count)`` after each new net.

    Returns
    -------
    list of Net
        Between 1 and ``count`` nets with pairwise different outlines; its
        length says how many were found.

    Raises
    ------
    UnfoldError
        Not a single net was found within the budget.
    """
    n = _check_count(count)
    if not float(budget) > 0:
        raise InvalidShapeError(f"budget: expected a positive number of seconds, got {budget!r}")
    if options.get("pieces", "one") != "one":
        raise InvalidShapeError("unfold_many: pieces must be 'one'")
    if str(options.get("strategy", "default")) == Strategy.EXACT.value:
        raise InvalidShapeError("strategy 'exact' gives one net, the same every run: ask for one net")
    gen = np.random.default_rng(seed_of(rng))
    end = time.monotonic() + float(budget)
    timeout = float(options.pop("timeout", 60.0))  # type: ignore[arg-type]
    nets: list[Net] = []
    seen: set[bytes] = set()
    tries = 0
    last_error: UnfoldError | None = None
    with meter(n, desc="nets") as bar:
        while len(nets) < n and tries < 4 * n + 8:
            left = end - time.monotonic()
            if left <= 0:
                break
            tries += 1
            seed = int(gen.integers(0, 2**31 - 1))
            try:
                net = unfold(grid, rng=seed, timeout=min(timeout, left), **options)  # type: ignore[arg-type]
            except NoFitError:
                raise
            except UnfoldError as exc:
                last_error = exc
                continue
            key = outline_key(net)
            if key in seen:
                continue
            seen.add(key)
            nets.append(net)
            bar.update()
            if progress is not None:
                progress(len(nets), n)
    if not nets:
        raise last_error or UnfoldError(f"no net found within the budget of {budget:g} s")
    return nets


def _check_count(count: object) -> int:
    if not isinstance(count, (int, np.integer)) or isinstance(count, bool) or count < 1:
        raise InvalidShapeError(f"count: expected an integer >= 1, got {count!r}")
    return int(count)
