"""A progress bar that appears only when work takes longer than a second."""

from __future__ import annotations

import sys
import time
from collections.abc import Iterable, Iterator
from typing import TypeVar

T = TypeVar("T")

#: Set by the CLI; library code stays silent unless it is on.
ENABLED = False


def progress(items: Iterable[T], *, total: int | None = None, desc: str = "") -> Iterator[T]:
    """Yield ``items``, drawing a bar on stderr once a second has passed.

    The bar is drawn only when :data:`ENABLED` is set (by the CLI) and stderr is
    a terminal, so library calls and tests stay quiet.
    """
    if not ENABLED or not sys.stderr.isatty():
        yield from items
        return
    from tqdm import tqdm  # lazy: only the CLI on a terminal pays for it

    start = time.monotonic()
    bar = None
    n = total if total is not None else (len(items) if hasattr(items, "__len__") else None)  # type: ignore[arg-type]
    done = 0
    try:
        for item in items:
            yield item
            done += 1
            if bar is None and time.monotonic() - start > 1.0:
                bar = tqdm(total=n, desc=desc, initial=done, file=sys.stderr, leave=False)
            elif bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
