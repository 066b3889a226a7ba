"""The Edit tab: ``POST /api/check``, the facts of a shape as the artist edits it (volume, extents, well-formedness)."""

from __future__ import annotations

from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.routing import Route

from .. import _bodies, _grid
from .._http import read_object
from .._session import Session


async def check(session: Session, request: Request) -> dict[str, Any]:
    """The facts of the grid sent, as ``voxfab info`` reports them."""
    data = await read_object(request, _bodies.CHECK, example='{"grid": ...}')
    grid = _grid.unpack(data.get("grid"))
    return {"facts": await run_in_threadpool(_grid.facts, grid)}


def routes(session: Session) -> list[Route]:
    """The Edit tab's routes."""
    return [Route("/api/check", session.api(check), methods=["POST"])]
