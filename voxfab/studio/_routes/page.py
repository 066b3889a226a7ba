"""The page, its files, and what it asks at start: ``/``, ``/static/...``, ``/api/info``, ``/api/initial``.

No URL maps onto the file system: the page's files are a fixed table read once
from the package.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path
from typing import Any

from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import Route

from .. import _grid, _specs, _work
from .._guard import MAX_BODY
from .._http import plain_response
from .._session import Session

#: Media types of the page's files; a file of another kind is not served.
STATIC_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
                ".css": "text/css; charset=utf-8", ".png": "image/png", ".svg": "image/svg+xml"}


def static_table() -> dict[str, tuple[bytes, str]]:
    """The page's files, read once from the package: the only files a URL can reach besides downloads."""
    root = resources.files("voxfab.studio") / "static"
    table: dict[str, tuple[bytes, str]] = {}

    def walk(node: Any, prefix: str) -> None:
        for child in node.iterdir():
            if child.is_dir():
                walk(child, f"{prefix}{child.name}/")
            elif Path(child.name).suffix in STATIC_TYPES:
                table[prefix + child.name] = (child.read_bytes(), STATIC_TYPES[Path(child.name).suffix])

    walk(root, "")
    return table


async def info(session: Session, request: Request) -> dict[str, Any]:
    """What the page needs to know of the server: its limits, sheets, downloads and the makers table."""
    from voxfab._version import __version__
    from voxfab.fabricate.netdraw import SHEETS

    try:
        from voxfab.unfold import EdgeConstraints  # noqa: F401

        constraints = True
    except ImportError:
        constraints = False
    return {"version": __version__, "repository": session.settings.repo.name, "side": _grid.SIDE,
            "max_body": MAX_BODY, "constraints": constraints, "artefacts": _work.artefacts(),
            "max_nets": _work.MAX_NETS, "sheets": {k: list(v) for k, v in SHEETS.items()},
            "makers": _specs.maker_table()}


async def initial(session: Session, request: Request) -> dict[str, Any]:
    """The shape the page opens with (``voxfab studio SHAPE``), or None."""
    shape = session.settings.initial
    return {"shape": None if shape is None else shape.answer()}


def routes(session: Session) -> list[Route]:
    """The page's routes, its files read now."""
    static = static_table()

    async def page(request: Request) -> Response:
        body, kind = static["index.html"]
        return Response(body, media_type=kind)

    async def static_file(request: Request) -> Response:
        hit = static.get(request.path_params["name"])
        if hit is None:
            return plain_response(404, "not found")
        return Response(hit[0], media_type=hit[1], headers={"Cache-Control": "no-cache"})

    return [
        Route("/", page),
        Route("/favicon.ico", lambda request: Response(status_code=204)),
        Route("/static/{name:path}", static_file),
        Route("/api/info", session.api(info)),
        Route("/api/initial", session.api(initial)),
    ]
