"""The jobs the other routes start, as the page follows them, and their files.

``GET /api/jobs/ID`` (the job's state, with ``?since=N`` the items made after the
first N), ``POST /api/jobs/ID/cancel`` and ``GET /api/files/ID/INDEX`` (a file the
job made).  A job is found by its unguessable id only (:meth:`.._session.Session.job`).
"""

from __future__ import annotations

from typing import Any

from starlette.requests import Request
from starlette.responses import FileResponse, Response
from starlette.routing import Route

from voxfab._shared.numbers import is_digits, parse_int
from voxfab.errors import InvalidShapeError

from .._http import download_type
from .._session import Session


async def status(session: Session, request: Request) -> dict[str, Any]:
    """The job's state and progress; with ``since``, the items the page has not drawn yet."""
    job = session.job(request.path_params["job"])
    since = request.query_params.get("since")
    if since is None:
        return job.status()
    # The items the page has not drawn yet: a gallery's nets, each as soon as it is made.
    if not is_digits(since) or len(since) > 6:
        raise InvalidShapeError(f"since: expected the number of items already read, got {since[:20]!r}")
    return job.status(since=parse_int(since))


async def cancel(session: Session, request: Request) -> dict[str, Any]:
    """Stop the job; its state after the request."""
    job = session.job(request.path_params["job"])
    session.jobs.cancel(job)
    return job.status()


async def download(session: Session, request: Request) -> Response:
    """File ``index`` of a finished job, under the name the job gave it."""
    job = session.job(request.path_params["job"])
    index = request.path_params["index"]
    if job.state != "done" or not 0 <= index < len(job.files):
        raise InvalidShapeError(f"file: job {job.id} has no file {index}")
    name, path = job.files[index]
    return FileResponse(path, filename=name, media_type=download_type(name))


def routes(session: Session) -> list[Route]:
    """The jobs' routes."""
    return [
        Route("/api/jobs/{job}", session.api(status)),
        Route("/api/jobs/{job}/cancel", session.api(cancel), methods=["POST"]),
        Route("/api/files/{job}/{index:int}", session.api(download)),
    ]
