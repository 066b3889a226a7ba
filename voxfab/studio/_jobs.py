"""Heavy work off the event loop: numbered jobs on a small thread pool, with progress the page polls."""

from __future__ import annotations

import secrets
import shutil
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from voxfab.errors import VoxfabError

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
        ``"running"``, ``"done"`` or ``"error"``.
    done, total : int
        Progress in the job's own units.
    message : str
        What runs now, or the error.
    result : dict
        JSON-ready result for the page.
    files : list of (str, Path)
        Download name and path of each file the job made.
    data : dict
        Objects kept for later requests (nets to draw), never sent.
    """

    id: str
    kind: str
    folder: Path
    state: str = "running"
    done: int = 0
    total: int = 1
    message: str = ""
    result: dict[str, Any] = field(default_factory=dict)
    files: list[tuple[str, Path]] = field(default_factory=list)
    data: dict[str, Any] = field(default_factory=dict)
    started: float = field(default_factory=time.monotonic)
    seconds: float = 0.0

    def step(self, done: int, total: int, message: str = "") -> None:
        """Report progress (called from the worker thread; plain attribute writes)."""
        self.done, self.total = done, max(total, 1)
        if message:
            self.message = message

    def status(self) -> dict[str, Any]:
        """What ``GET /api/jobs/ID`` answers."""
        out: dict[str, Any] = {
            "id": self.id, "kind": self.kind, "state": self.state, "done": self.done, "total": self.total,
            "message": self.message, "seconds": round(self.seconds or time.monotonic() - self.started, 3),
        }
        if self.state == "error":
            out["ways_out"] = self.result.get("ways_out", [])
        if self.state == "done":
            out["result"] = self.result
            out["files"] = [{"index": i, "name": name, "bytes": path.stat().st_size}
                            for i, (name, path) in enumerate(self.files)]
        return out


class Jobs:
    """A thread pool and the table of recent jobs."""

    def __init__(self, work: Path, workers: int = 2) -> None:
        self._work = work
        self._pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="studio-job")
        self._jobs: OrderedDict[str, Job] = OrderedDict()
        self._lock = threading.Lock()

    def submit(self, kind: str, work: Callable[[Job], None]) -> Job:
        """Start ``work(job)``; it fills ``job.result`` and ``job.files``; errors become the job's message."""
        job = Job(secrets.token_hex(8), kind, self._work / "jobs" / "pending")
        job.folder = self._work / "jobs" / job.id
        job.folder.mkdir(parents=True)
        with self._lock:
            self._jobs[job.id] = job
            self._prune()

        def run() -> None:
            try:
                work(job)
                job.state = "done"
            except VoxfabError as exc:
                job.message = " ".join(str(exc).split())
                # A net that does not fit says what would (the page's one-click ways out).
                job.result = {"ways_out": list(getattr(exc, "ways_out", []))}
                job.state = "error"
            except Exception as exc:  # noqa: BLE001 - the page gets one line, never a traceback
                job.message = f"internal error ({type(exc).__name__}): {' '.join(str(exc).split())}"
                job.state = "error"
            finally:
                job.seconds = time.monotonic() - job.started

        self._pool.submit(run)
        return job

    def get(self, job_id: str) -> Job | None:
        """The job with this id, or None."""
        with self._lock:
            return self._jobs.get(job_id)

    def _prune(self) -> None:
        while len(self._jobs) > MAX_JOBS:
            old = next((j for j in self._jobs.values() if j.state != "running"), None)
            if old is None:
                break
            del self._jobs[old.id]
            shutil.rmtree(old.folder, ignore_errors=True)

    def shutdown(self) -> None:
        """Stop taking work; running jobs finish in their threads."""
        self._pool.shutdown(wait=False, cancel_futures=True)
