"""The studio's HTTP API and page, on Starlette: the routes of :mod:`._routes` over one :class:`._session.Session`.

Security, as a local server must have it:

* only requests whose ``Host`` is the server's own address get through, and a
  request with an ``Origin`` must come from the server's own page (DNS
  rebinding, cross-site forms) (:class:`._guard.Guard`);
* request bodies are limited (:data:`._guard.MAX_BODY`);
* no request names a file: the page is a fixed table of packaged files, shapes
  come from the repository by ``VVVVV.NNN`` name, downloads by job id and index;
* every input goes through the CLI's validation and comes back as
  ``{"error": "one line"}`` with status 400; an unexpected failure is a 500
  with one line, never a traceback (:meth:`._session.Session.api`).
"""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import Response

from . import _work
from ._guard import Guard
from ._http import error_response, plain_response
from ._routes import draw, edit, jobs, keep, make, net, page
from ._session import Session, Settings

__all__ = ["create_app"]


async def not_found(request: Request, exc: Exception) -> Response:
    """404: JSON for the API, one line of text elsewhere."""
    if request.url.path.startswith("/api/"):
        return error_response(404, f"no such endpoint: {request.method} {request.url.path[:80]}")
    return plain_response(404, "not found")


async def method_not_allowed(request: Request, exc: Exception) -> Response:
    return error_response(405, f"{request.method} is not allowed on {request.url.path[:80]}")


async def server_error(request: Request, exc: Exception) -> Response:
    return error_response(500, f"internal error ({type(exc).__name__})")


def create_app(settings: Settings) -> Starlette:
    """The studio application for ``settings`` (see :class:`Settings`).

    The application's state has ``cleanup`` (stop the jobs, remove the session's
    folder) and ``cancel_jobs`` (safe in a signal handler), for the server.
    """
    session = Session(settings)

    @asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        session.start()
        if settings.warm_up:
            import threading

            threading.Thread(target=_work.warm_kernels_here, args=(session.work,), name="studio-warm-up",
                             daemon=True).start()
        try:
            yield
        finally:
            session.close()

    routes = [*page.routes(session), *draw.routes(session), *edit.routes(session), *keep.routes(session),
              *net.routes(session), *make.routes(session), *jobs.routes(session)]
    app = Starlette(routes=routes, lifespan=lifespan,
                    exception_handlers={404: not_found, 405: method_not_allowed, 500: server_error})
    app.state.cleanup = session.close
    app.state.cancel_jobs = session.cancel_jobs
    return Guard(app, settings.hosts)  # type: ignore[return-value]
