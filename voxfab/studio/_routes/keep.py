"""The Keep tab: the repository of named shapes.

``GET /api/repo`` (a page of names, by volume), ``POST /api/repo`` (keep a shape),
``GET /api/repo/shape?name=`` (open one) and ``GET /api/repo/thumb?name=`` (its
picture).  A shape is asked for by its repository name only, checked against the
repository's own patterns, so no request reaches a file: the library's
``load_shape`` would read a file of that name first.
"""

from __future__ import annotations

from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import Route

from voxfab._shared.numbers import is_digits, parse_int
from voxfab.errors import InvalidShapeError

from .. import _bodies, _grid
from .._http import read_object
from .._session import Session

#: Thumbnails kept in memory (oldest dropped first).
MAX_THUMBS = 2000


def shape_name(request: Request, key: str = "name") -> str:
    """The repository name in the query's ``key`` (``VVVVV.NNN``, ``draft-N``, ``RANGE:MEMBER``), or a one-line error."""
    from voxfab.repo import is_shape_name

    name = request.query_params.get(key, "")
    if not is_shape_name(name):
        raise InvalidShapeError(f"{key}: expected a repository name such as 00797.001, got {name[:40]!r}")
    return name


async def listing(session: Session, request: Request) -> dict[str, Any]:
    """Up to ``limit`` shapes after the name ``after``, and whether more follow."""
    after = request.query_params.get("after") or None
    if after is not None:
        after = shape_name(request, "after")
    text = request.query_params.get("limit", "120")
    # at most 4 digits read: int() of a 5000-digit string would be an error of its own
    limit = _bodies.whole(parse_int(text) if is_digits(text) and len(text) <= 4 else text, name="limit", lo=1,
                          hi=500)

    def run() -> dict[str, Any]:
        if not session.settings.repo.exists():
            return {"shapes": [], "more": False}
        with session.repository() as repo:
            # one page more than asked tells whether another page follows
            entries = repo.list(after=after, limit=int(limit) + 1)
        # named shapes by volume, as the repository orders them; drafts after them
        return {"shapes": [{"name": e.name, "volume": e.volume, "extents": list(e.extents), "draft": e.draft}
                           for e in entries[: int(limit)]], "more": len(entries) > limit}

    return await run_in_threadpool(run)


async def shape(session: Session, request: Request) -> dict[str, Any]:
    """One kept shape, centred in the editor, with its facts."""
    name = shape_name(request)

    def run() -> dict[str, Any]:
        with session.repository() as repo:
            grid = _grid.centred(repo.get(name))
        return {"name": name, "grid": _grid.pack(grid), "facts": _grid.facts(grid)}

    return await run_in_threadpool(run)


async def thumbnail(session: Session, request: Request) -> Response:
    """A kept shape's 120-pixel picture (PNG), drawn once per name."""
    name = shape_name(request)
    thumbs = session.thumbnails

    def run() -> bytes:
        from voxfab.render import png_bytes, render

        # names are never given twice, so a name's picture never changes
        if name not in thumbs:
            with session.repository() as repo:
                grid = repo.get(name)
            if len(thumbs) >= MAX_THUMBS:
                thumbs.pop(next(iter(thumbs)))
            thumbs[name] = png_bytes(render(grid, size=120))
        return thumbs[name]

    return Response(await run_in_threadpool(run), media_type="image/png")


async def add(session: Session, request: Request) -> dict[str, Any]:
    """Keep the grid sent (as a draft if asked and not well formed): its name, and whether it is new."""
    data = await read_object(request, _bodies.REPO_ADD, example='{"grid": ..., "draft": false}')
    grid = _grid.unpack(data.get("grid"))
    draft = _bodies.flag(data.get("draft"), name="draft")

    def run() -> dict[str, Any]:
        _grid.require_voxels(grid)
        with session.repository() as repo:
            result = repo.add(grid, draft=draft)
        from .._words import plain

        return {"name": result.name, "created": result.created, "draft": result.draft,
                "reasons": [plain(r) for r in result.reasons]}

    return await run_in_threadpool(run)


def routes(session: Session) -> list[Route]:
    """The Keep tab's routes."""
    return [
        Route("/api/repo", session.api(listing)),
        Route("/api/repo", session.api(add), methods=["POST"]),
        Route("/api/repo/shape", session.api(shape)),
        Route("/api/repo/thumb", session.api(thumbnail)),
    ]
