"""Progress bars that appear only when work takes longer than a second, and stopping work on request."""

from __future__ import annotations

import contextlib
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any, TypeVar

T = TypeVar("T")

#: Set by the CLI; library code stays silent unless it is on.
ENABLED = False
#: Seconds of work before a bar is drawn: short jobs never show one.
DELAY = 1.0


class Meter:
    """Counts work done; draws a bar on stderr once :data:`DELAY` has passed.

    Drawing needs :data:`ENABLED` (set by the CLI) and a terminal on stderr, so
    library calls and tests stay quiet.  Use :func:`meter` or :func:`progress`.
    """

    def __init__(self, total: int | None, desc: str) -> None:
        self.total = total
        self.desc = desc
        self.done = 0
        self._live = ENABLED and sys.stderr.isatty()
        self._start = time.monotonic()
        self._bar: Any = None
        # Nesting within a cancel_scope: only the outermost meter reports to the scope's watcher.
        self._level = getattr(_local, "depth", 0)
        _local.depth = self._level + 1

    def update(self, n: int = 1) -> None:
        """Add ``n`` units of work done (and stop here if the work was cancelled, see :func:`check_cancelled`)."""
        check_cancelled()
        self.done += n
        report = getattr(_local, "report", None)
        if report is not None and self._level == 0:
            report(self.done, self.total, self.desc)
        if not self._live:
            return
        if self._bar is not None:
            self._bar.update(n)
        elif time.monotonic() - self._start > DELAY:
            from tqdm import tqdm  # lazy: only the CLI on a terminal pays for it

            self._bar = tqdm(total=self.total, desc=self.desc, initial=self.done, file=sys.stderr, leave=False)

    def close(self) -> None:
        _local.depth = self._level
        if self._bar is not None:
            self._bar.close()
            self._bar = None


@contextlib.contextmanager
def meter(total: int | None = None, *, desc: str = "") -> Iterator[Meter]:
    """A :class:`Meter` for work counted by hand, closed on exit."""
    m = Meter(total, desc)
    try:
        yield m
    finally:
        m.close()


def progress(items: Iterable[T], *, total: int | None = None, desc: str = "") -> Iterator[T]:
    """Yield ``items``, counting each one on a :class:`Meter`."""
    n = total if total is not None else (len(items) if hasattr(items, "__len__") else None)  # type: ignore[arg-type]
    with meter(n, desc=desc) as m:
        for item in items:
            yield item
            m.update()


# --- stopping work on request -----------------------------------------------------------------

_local = threading.local()


@contextlib.contextmanager
def cancel_scope(event: threading.Event,
                 report: Callable[[int, int | None, str], None] | None = None) -> Iterator[None]:
    """Within this block, on this thread, :func:`check_cancelled` raises once ``event`` is set.

    The studio runs each job in a scope of its own event; long loops of the
    library (the net search, every :class:`Meter`) call :func:`check_cancelled`
    between chunks of work, so a cancelled job stops within a chunk.
    ``report(done, total, desc)``, if given, hears the outermost meter's progress.
    """
    before = (getattr(_local, "event", None), getattr(_local, "report", None), getattr(_local, "depth", 0))
    _local.event, _local.report, _local.depth = event, report, 0
    try:
        yield
    finally:
        _local.event, _local.report, _local.depth = before


def check_cancelled() -> None:
    """Raise :class:`~voxfab.errors.CancelledError` when this thread's work was cancelled; cheap otherwise."""
    event = getattr(_local, "event", None)
    if event is not None and event.is_set():
        from voxfab.errors import CancelledError

        raise CancelledError("stopped: cancelled")


def cancel_event() -> threading.Event | None:
    """The event that cancels this thread's work (None outside a :func:`cancel_scope`).

    For work that cannot call :func:`check_cancelled` itself, such as a solver in
    native code: a watcher waits on the event and stops the solver.
    """
    return getattr(_local, "event", None)
