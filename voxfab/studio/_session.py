"""What every route of one running studio shares: its settings, work folder, jobs and thumbnails.

Requests carry the whole shape (25³ bits are 2 kB), so the session keeps no
shape state: only the jobs of the session (nets to pick from, files to
download) in memory and in its work folder.  The routes (:mod:`._routes`) are
module functions that take the :class:`Session` as their first argument;
:meth:`Session.api` binds one to the session and turns its errors into one line.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
import threading
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voxfab.errors import InvalidShapeError, VoxfabError

from . import _grid
from ._http import error_response

if TYPE_CHECKING:
    from starlette.requests import Request
    from starlette.responses import Response

    from voxfab.repo import Repository

    from ._jobs import Job, Jobs

#: A job's id as :class:`._jobs.Jobs` makes them: anything else names no job.
JOB_ID = re.compile(r"^[0-9a-f]{16}$")

#: A route: the session and the request in, JSON-ready data or a response out.
Handler = Callable[["Session", "Request"], Awaitable[Any]]


@dataclass(frozen=True)
class Settings:
    """How the studio runs.

    Attributes
    ----------
    repo : Path
        The repository database (created on the first save).
    hosts : frozenset of str
        Accepted ``Host`` values (``host:port``); ``Origin`` must be ``http://`` one of them.
    work : Path or None
        The session's work folder (a fresh temporary folder when None, removed at shutdown).
    warm_up : bool
        Compile the numba kernels in the background at start (see :func:`_work.warm_kernels_here`).
    initial : InitialShape or None
        The shape the page opens with (``voxfab studio SHAPE``); None: the page starts from its drawing.
    """

    repo: Path
    hosts: frozenset[str]
    work: Path | None = None
    warm_up: bool = True
    initial: _grid.InitialShape | None = None


#: The name of a session's temporary work folder: this prefix, the studio's pid, ``-`` and random letters.
WORK_PREFIX = "voxfab-studio-"
_WORK_NAME = re.compile(re.escape(WORK_PREFIX) + r"([0-9]{1,10})-[A-Za-z0-9_]+")


def sweep_dead_sessions(folder: Path | None = None) -> list[Path]:
    """Remove the work folders that studios no longer running left in ``folder`` (default the temporary folder).

    A studio killed outright (SIGKILL, a power cut) cannot clean up after itself;
    the next one does.  Only folders named with the pid of a process that is gone
    are removed: a studio running beside this one keeps its own.
    """
    from voxfab._shared.atomic import _alive

    where = Path(folder or tempfile.gettempdir())
    removed = []
    try:
        names = [e.name for e in os.scandir(where) if e.name.startswith(WORK_PREFIX) and e.is_dir(follow_symlinks=False)]
    except OSError:
        return removed
    for name in names:
        m = _WORK_NAME.fullmatch(name)
        if m and not _alive(int(m.group(1))):
            shutil.rmtree(where / name, ignore_errors=True)
            removed.append(where / name)
    return removed


class Session:
    """The state one studio's routes share, made on first use: the work folder and its jobs.

    Parameters
    ----------
    settings : Settings
        How the studio runs.

    Attributes
    ----------
    settings : Settings
    thumbnails : dict of str to bytes
        PNG pictures of repository shapes by name, oldest first (see :mod:`._routes.keep`).
    """

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.thumbnails: dict[str, bytes] = {}
        self._made: tuple[Path, Jobs] | None = None  # the work folder and its jobs, once made
        self._lock = threading.Lock()  # the first requests may ask for the folder from two threads at once

    def start(self) -> None:
        """Make the work folder and its job workers now, before the first request (the server's start)."""
        self._open()

    def _open(self) -> tuple[Path, Jobs]:
        with self._lock:
            if self._made is None:
                from ._jobs import Jobs

                if self.settings.work is None:
                    sweep_dead_sessions()
                # The pid in the name: the next studio clears the folder of one that died (see sweep_dead_sessions).
                folder = self.settings.work or Path(tempfile.mkdtemp(prefix=f"{WORK_PREFIX}{os.getpid()}-"))
                folder.mkdir(parents=True, exist_ok=True)
                self._made = folder, Jobs(folder)
            return self._made

    @property
    def work(self) -> Path:
        """The session's work folder (the settings' one, else a fresh temporary folder), made on first use."""
        return self._open()[0]

    @property
    def jobs(self) -> Jobs:
        """The session's job table, running in its work folder."""
        return self._open()[1]

    def job(self, job_id: str) -> Job:
        """The session's job ``job_id``, or a one-line error naming what was asked for."""
        job = self.jobs.get(job_id) if JOB_ID.match(job_id) else None
        if job is None:
            raise InvalidShapeError(f"job: no job {job_id[:20]!r} in this session")
        return job

    def repository(self) -> Repository:
        """The repository, opened (and made, on the first save) for one request."""
        from voxfab.repo import Repository

        return Repository(self.settings.repo)

    def private(self, message: str) -> str:
        """The message with the repository named, not its folder: the page never learns paths on disk."""
        repo = self.settings.repo
        for path in sorted({str(repo.resolve()), str(repo)}, key=len, reverse=True):
            message = message.replace(path, repo.name)
        return message

    def api(self, handler: Handler) -> Callable[[Request], Awaitable[Response]]:
        """The endpoint of ``handler`` on this session: its data as JSON, any error as one line.

        A :class:`~voxfab.errors.VoxfabError` is the request's fault (400, the library's
        message); anything else is the server's (500, the exception's one line, never a traceback).
        """
        from starlette.responses import JSONResponse, Response

        async def endpoint(request: Request) -> Response:
            try:
                out = await handler(self, request)
            except VoxfabError as exc:
                return error_response(400, self.private(str(exc)))
            except Exception as exc:  # noqa: BLE001 - one line for the page, never a traceback
                return error_response(500, self.private(f"internal error ({type(exc).__name__}): {exc}"))
            return out if isinstance(out, Response) else JSONResponse(out)

        return endpoint

    def cancel_jobs(self) -> None:
        """Ask every job to stop, without waiting or locking (called from a signal handler)."""
        if self._made is not None:
            self._made[1].cancel_all()

    def close(self) -> None:
        """Stop the jobs and remove the work folder if the session made it (a second call finds nothing to do)."""
        if self._made is None:
            return
        folder, jobs = self._made
        jobs.shutdown()
        if self.settings.work is None:
            # A job or the warm-up still running on its thread may write in the folder while it goes
            # (and make its own sub-folders again): removed until it stays gone.
            for _ in range(5):
                shutil.rmtree(folder, ignore_errors=True)
                if not folder.exists():
                    break
