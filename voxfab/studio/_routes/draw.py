"""The Draw tab: a drawn shape's voxels, its recipe, and a tube's animation.

``POST /api/preview`` (the shape, made through the recipe path as ``voxfab build``
makes it), ``POST /api/recipe`` (the recipe to download) and ``POST /api/animate``
(the frames of a tube's profile turning along its spine).
"""

from __future__ import annotations

import shutil
import time
from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import Route

from .. import _bodies, _grid, _specs
from .._http import download_type, read_json, read_object
from .._session import Session


async def preview(session: Session, request: Request) -> dict[str, Any]:
    """The drawn shape centred in the editor, its facts, and the milliseconds it took."""
    spec = await read_json(request)

    def run() -> dict[str, Any]:
        t0 = time.perf_counter()
        grid, _ = _specs.make_grid(spec, session.work)
        grid = _grid.centred(grid)
        return {"grid": _grid.pack(grid), "facts": _grid.facts(grid),
                "ms": round(1000 * (time.perf_counter() - t0), 1)}

    return await run_in_threadpool(run)


async def recipe(session: Session, request: Request) -> Response:
    """The drawing's recipe as a download: its TOML, or a zip with the drawn curves and bitmaps beside it."""
    data = await read_object(request, _bodies.RECIPE, example='{"shape": ..., "name": ..., "pitch": MM}')
    name = data.get("name") or "studio"
    pitch = _bodies.pitch(data.get("pitch"))

    def run() -> tuple[str, bytes]:
        # made once here, so a recipe that fails to build is never handed out
        _specs.make_grid(data.get("shape"), session.work)
        return _specs.drawing_recipe(data.get("shape"), name=name, pitch=pitch).download()

    fname, raw = await run_in_threadpool(run)
    return Response(raw, media_type=download_type(fname),
                    headers={"Content-Disposition": f'attachment; filename="{fname}"'})


async def animate(session: Session, request: Request) -> dict[str, Any]:
    """The frames of a drawn tube's profile turning along its spine, as packed grids."""
    data = await read_object(request, _bodies.ANIMATE, example='{"shape": ..., "steps": N}')
    steps = _bodies.steps(data.get("steps", 24))

    def run() -> dict[str, Any]:
        from voxfab.render import tube_frames

        params, folder = _specs.tube_params(data.get("shape"), session.work)
        try:
            frames = tube_frames(params, steps=int(steps), base_dir=folder)
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        return {"frames": [_grid.pack(f) for f in frames]}

    return await run_in_threadpool(run)


def routes(session: Session) -> list[Route]:
    """The Draw tab's routes."""
    return [
        Route("/api/preview", session.api(preview), methods=["POST"]),
        Route("/api/recipe", session.api(recipe), methods=["POST"]),
        Route("/api/animate", session.api(animate), methods=["POST"]),
    ]
