"""Heavy work off the event loop: numbered jobs on a small thread pool, with progress the page polls."""

from __future__ import annotations

import queue
import secrets
import shutil
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from voxfab.errors import VoxfabError

from ._words import plain

#: Jobs kept for polling and downloads; the oldest finished ones (and their files) go first.
MAX_JOBS = 64


@dataclass
class Job:
    """One piece of heavy work and what the page may learn about it.

    Attributes
    ----------
    id : str
        Random hex id (unguessable, so another page cannot fetch a job's files).
    kind : str
        ``"nets"`` or ``"make"``.
    folder : Path
        The job's own folder under the session's work folder.
    state : str
        ``"queued"``, ``"running"``, ``"done"``, ``"error"`` or ``"cancelled"``.
    done, total : int
        Progress in the job's own units.
    message : str
        What runs now, or the error in the artist's words (see ``_words.plain``).
    detail : str
        The error's technical line, when it has other words.
    result : dict
        JSON-ready result for the page.
    files : list of (str, Path)
        Download name and path of each file the job made.
    items : list of dict
        JSON-ready results made so far, in order (a gallery's nets, each as soon as it is made):
        the page reads them while the job runs (``status(since=n)``).
    data : dict
        Objects kept for later requests (nets to draw), never sent.
    cancel : threading.Event
        Set to stop the job: the library's long loops check it (``voxfab._shared.progress.check_cancelled``).
    """

    id: str
    kind: str
    folder: Path
    state: str = "queued"
    done: int = 0
    total: int = 1
    message: str = "waiting for a free worker"
    result: dict[str, Any] = field(default_factory=dict)
    files: list[tuple[str, Path]] = field(default_factory=list)
    items: list[dict[str, Any]] = field(default_factory=list)
    data: dict[str, Any] = field(default_factory=dict)
    started: float = field(default_factory=time.monotonic)
    seconds: float = 0.0
    cancel: threading.Event = field(default_factory=threading.Event)
    place: int = 0
    detail: str = ""
    counted: bool = False  # the job reports progress in steps of its own (more than one)

    def step(self, done: int, total: int, message: str = "") -> None:
        """Report progress (called from the worker thread; plain attribute writes)."""
        self.done, self.total = done, max(total, 1)
        self.counted = self.counted or total > 1
        if message:
            self.message = message

    def heard(self, done: int, total: int | None, desc: str) -> None:
        """The library's own progress (its outermost meter), shown unless the job counts in steps of its own."""
        if self.counted or not total:
            return
        self.done, self.total = min(done, total), total
        self.message = desc

    @property
    def ended(self) -> bool:
        """Whether the job is over (done, failed or cancelled)."""
        return self.state in ("done", "error", "cancelled")

    def status(self, since: int | None = None) -> dict[str, Any]:
        """What ``GET /api/jobs/ID`` answers; ``place`` is 0 once running, n for the n-th in the queue.

        ``made`` counts the items made so far; with ``since``, ``items`` are those from index
        ``since`` on (the page asks for the ones it has not drawn yet).
        """
        made = len(self.items)  # read once: the worker may append meanwhile
        out: dict[str, Any] = {
            "id": self.id, "kind": self.kind, "state": self.state, "place": self.place if self.state == "queued" else 0,
            "done": self.done, "total": self.total, "message": self.message,
            "seconds": round(self.seconds or time.monotonic() - self.started, 3), "made": made,
        }
        if since is not None:
            out["items"] = self.items[since:made]
        if self.state == "error" and self.detail != self.message:
            out["detail"] = self.detail  # the technical line behind the plain message
        if self.state == "error":
            out["ways_out"] = self.result.get("ways_out", [])
        if self.state == "done":
            out["result"] = self.result
            out["files"] = [{"index": i, "name": name, "bytes": path.stat().st_size}
                            for i, (name, path) in enumerate(self.files)]
        return out


class Jobs:
    """Worker threads, their queue, and the table of recent jobs.

    The workers are daemon threads (not a ``ThreadPoolExecutor``, whose threads
    the interpreter joins at exit): a server stopping with Ctrl-C cancels its
    jobs and goes, even if one is inside a step that cannot be cut short (numba
    compiling a kernel, the exact solver).
    """

    def __init__(self, work: Path, workers: int = 2) -> None:
        self._work = work
        self._jobs: OrderedDict[str, Job] = OrderedDict()
        self._queue: list[Job] = []  # submitted, not started, in order
        self._lock = threading.Lock()
        self._closed = False
        self._tasks: queue.SimpleQueue[Callable[[], None] | None] = queue.SimpleQueue()
        self._workers = [threading.Thread(target=self._serve, name=f"studio-job-{i}", daemon=True)
                         for i in range(workers)]
        for t in self._workers:
            t.start()

    def _serve(self) -> None:
        while (task := self._tasks.get()) is not None:
            task()

    def submit(self, kind: str, work: Callable[[Job], None]) -> Job:
        """Queue ``work(job)``; it fills ``job.result`` and ``job.files``; errors become the job's message."""
        from voxfab._shared.progress import cancel_scope

        job = Job(secrets.token_hex(8), kind, self._work / "jobs" / "pending")
        job.folder = self._work / "jobs" / job.id
        job.folder.mkdir(parents=True)

        def run() -> None:
            with self._lock:
                if job in self._queue:
                    self._queue.remove(job)
                self._renumber()
                if job.cancel.is_set():
                    job.state, job.message = "cancelled", "cancelled before it started"
                    return
                job.state, job.message = "running", ""
            job.started = time.monotonic()
            try:
                with cancel_scope(job.cancel, report=job.heard):
                    work(job)
                if job.cancel.is_set():  # it ended before it saw the cancel: its result is not wanted
                    job.message, job.state = "cancelled", "cancelled"
                else:
                    job.state = "done"
            except VoxfabError as exc:
                if job.cancel.is_set():
                    job.message, job.state = "cancelled", "cancelled"
                else:
                    job.detail = " ".join(str(exc).split())
                    job.message = plain(job.detail)
                    # A net that does not fit says what would (the page's one-click ways out).
                    ways = job.result.get("ways_out") or getattr(exc, "ways_out", None) or []
                    job.result = {**job.result, "ways_out": list(ways)}
                    job.state = "error"
            except Exception as exc:  # noqa: BLE001 - the page gets one line, never a traceback
                job.detail = f"internal error ({type(exc).__name__}): {' '.join(str(exc).split())}"
                job.message = plain(job.detail)  # plain words; the exception stays in the tooltip
                job.state = "error"
            finally:
                job.seconds = time.monotonic() - job.started

        with self._lock:
            self._jobs[job.id] = job
            self._queue.append(job)
            self._renumber()
            self._prune()
            self._tasks.put(run)
        return job

    def get(self, job_id: str) -> Job | None:
        """The job with this id, or None."""
        with self._lock:
            return self._jobs.get(job_id)

    def cancel(self, job: Job) -> None:
        """Stop ``job``: a queued one never starts, a running one stops at the search's next check (milliseconds)."""
        with self._lock:
            if job.ended:
                return
            job.cancel.set()
            if job.state == "queued":
                job.state, job.message = "cancelled", "cancelled before it started"
                if job in self._queue:
                    self._queue.remove(job)
                self._renumber()
            else:
                job.message = "cancelling"

    def cancel_all(self) -> None:
        """Ask every job to stop, without waiting and without the table's lock (safe in a signal handler)."""
        for job in list(self._jobs.values()):
            job.cancel.set()

    def _renumber(self) -> None:
        for i, queued in enumerate(self._queue):
            queued.place = i + 1

    def _prune(self) -> None:
        while len(self._jobs) > MAX_JOBS:
            old = next((j for j in self._jobs.values() if j.ended), None)
            if old is None:
                break
            del self._jobs[old.id]
            shutil.rmtree(old.folder, ignore_errors=True)

    def shutdown(self, wait: float = 1.0) -> None:
        """Cancel every job, stop the workers, and wait up to ``wait`` seconds for the running jobs to stop.

        Once only: a second call (the server's own after its application's) returns at once.
        """
        with self._lock:
            if self._closed:
                return
            self._closed = True
            jobs = [j for j in self._jobs.values() if not j.ended]
        for job in jobs:
            self.cancel(job)
        for _ in self._workers:
            self._tasks.put(None)
        end = time.monotonic() + wait
        for job in jobs:
            while not job.ended and time.monotonic() < end:
                time.sleep(0.02)
