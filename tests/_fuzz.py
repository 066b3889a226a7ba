"""Run the CLI in-process on hostile input and check the promise of issue 14.

Every run either succeeds or fails with exactly one ``voxfab: error:`` line and
no traceback, within a time bound.  A non-voxfab exception escaping ``main`` is a
bug: it propagates to the test, with its traceback.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import signal
import threading
import time
from collections.abc import Iterator, Sequence

from voxfab.cli import main

#: Seconds one CLI run may take in the fuzz tests (shared 2-core machine: generous).
RUN_SECONDS = 30.0


class RunTimeout(Exception):
    """A run went over its time bound."""


@contextlib.contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`RunTimeout` in the main thread after ``seconds`` (SIGALRM)."""
    if threading.current_thread() is not threading.main_thread():  # pragma: no cover
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise RunTimeout(f"over {seconds} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


@dataclasses.dataclass(frozen=True)
class Outcome:
    """What one CLI run did."""

    argv: tuple[str, ...]
    code: int
    out: str
    err: str
    seconds: float
    usage: bool = False  # argparse refused the command line (exit 2, usage text)

    @property
    def error_lines(self) -> list[str]:
        return [line for line in self.err.splitlines() if line.startswith("voxfab: error:")]


def run_cli(argv: Sequence[object], *, seconds: float = RUN_SECONDS) -> Outcome:
    """Run ``voxfab ARGV`` in this process and capture its output."""
    args = tuple(str(a) for a in argv)
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    usage = False
    with time_limit(seconds), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(args))
        except SystemExit as exc:  # argparse: a usage error (2) or --help (0)
            code = exc.code if isinstance(exc.code, int) else 2
            usage = True
    return Outcome(args, code, out.getvalue(), err.getvalue(), time.perf_counter() - start, usage)


def check_outcome(o: Outcome, *, seconds: float = RUN_SECONDS) -> Outcome:
    """Assert the promise: success, or one clean error line; no traceback; in time."""
    assert "Traceback" not in o.err, (o.argv, o.err)
    assert o.seconds < seconds, (o.argv, o.seconds)
    if o.code == 0:
        return o
    if o.usage:
        # argparse's own refusal: usage lines and one "error:" line.
        assert o.code == 2 and len([x for x in o.err.splitlines() if ": error: " in x]) == 1, (o.argv, o.err)
        return o
    assert len(o.error_lines) == 1, (o.argv, o.err)
    assert len(o.error_lines[0]) <= 700, (o.argv, o.error_lines[0][:200])
    return o


def refused(argv: Sequence[object], *, seconds: float = RUN_SECONDS) -> str:
    """Run ``argv``, assert it fails cleanly, and return its error line."""
    o = check_outcome(run_cli(argv, seconds=seconds), seconds=seconds)
    assert o.code != 0 and not o.usage, (o.argv, o.out[-300:], o.err[-300:])
    return o.error_lines[0]
