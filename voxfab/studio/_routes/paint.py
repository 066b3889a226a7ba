"""Colours and the shape as a file: painting's palette, joining parts, and opening and saving ``.vox`` / ``.npz``.

``GET /api/palette`` (MagicaVoxel's default palette), ``POST /api/paint/fit`` (colours
for voxels that have none, from their nearest coloured voxel), ``POST /api/join`` (the
shape's parts joined into one piece, and where voxels were added), ``POST /api/shape/file``
(the shape as a ``.vox`` or ``.npz`` download, in its colours) and ``POST /api/shape/open``
(a ``.vox``, ``.npz`` or ``.npy`` file the artist chose, read as every command reads it).
The painting itself happens in the page (``static/js/paint.js``); each of these is the
library's own function behind one endpoint.
"""

from __future__ import annotations

import re
import uuid
from pathlib import Path
from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import Route

from voxfab.errors import InvalidShapeError

from .. import _bodies, _grid
from .._http import download_type, read_object
from .._session import Session

#: Files the page may open: the shape formats read without a mesh's voxelization (seconds of work).
OPENED = (".vox", ".npz", ".npy")
#: Files the page may save the shape as: those that keep its colours (and, .npz, its scale).
SAVED = ("vox", "npz")
#: A file name the page sends: a name, never a path.
FILE_NAME = re.compile(r"[A-Za-z0-9_. ()\-]{1,80}")
TITLE = re.compile(r"[A-Za-z0-9_.\- ]{1,64}")


async def palette(session: Session, request: Request) -> dict[str, Any]:
    """MagicaVoxel's default palette: row ``i`` is colour index ``i``, ``[r, g, b, a]``."""
    from voxfab.shape import default_palette

    return {"palette": default_palette().tolist()}


async def fit(session: Session, request: Request) -> dict[str, Any]:
    """The grid sent with a colour for every voxel: those without one take their nearest coloured voxel's."""
    data = await read_object(request, _bodies.PAINT_FIT, example='{"grid": ...}')
    shape = await run_in_threadpool(_grid.unpack_shape, data.get("grid"))
    return {"grid": _grid.pack_shape(shape)}


async def join(session: Session, request: Request) -> dict[str, Any]:
    """The shape's parts joined into one piece (:meth:`voxfab.shape.VoxelShape.joined`): the new grid in its
    colours, its facts, and each join in words with the voxels it added."""
    data = await read_object(request, _bodies.JOIN, example='{"grid": ...}')
    shape = _grid.unpack_shape(data.get("grid"))
    _grid.require_voxels(shape.grid)

    def run() -> dict[str, Any]:
        joined, joins = shape.joined()
        return {"grid": _grid.pack_shape(joined), "facts": _grid.facts(joined.grid),
                "joins": [{"words": j.describe(), "added": [list(v) for v in j.added]} for j in joins]}

    return await run_in_threadpool(run)


async def shape_file(session: Session, request: Request) -> Response:
    """The shape as a ``.vox`` (MagicaVoxel: its colours) or ``.npz`` (voxfab: its scale and colours) download,
    cut to its own box."""
    from voxfab import io

    data = await read_object(request, _bodies.SHAPE_FILE, example='{"grid": ..., "format": "vox", "title": ...}')
    kind = data.get("format")
    if kind not in SAVED:
        raise InvalidShapeError(f"format: expected one of {', '.join(SAVED)}, got {str(kind)[:20]!r}")
    title = data.get("title") or "studio"
    if not isinstance(title, str) or not TITLE.fullmatch(title):
        raise InvalidShapeError(f"title: letters, digits, space, _ . - (at most 64), got {str(title)[:70]!r}")
    shape = _grid.unpack_shape(data.get("grid"), pitch=_bodies.pitch(data.get("pitch")))
    _grid.require_voxels(shape.grid)
    name = f"{title.replace(' ', '_')}.{kind}"

    def run() -> bytes:
        path = session.work / f"shape-{uuid.uuid4().hex}.{kind}"
        try:
            io.write(shape.crop(), path)
            return path.read_bytes()
        finally:
            path.unlink(missing_ok=True)

    raw = await run_in_threadpool(run)
    return Response(raw, media_type=download_type(name), headers={"Content-Disposition": f'attachment; filename="{name}"'})


async def shape_open(session: Session, request: Request) -> dict[str, Any]:
    """A shape file the artist chose (the body's bytes, ``?name=`` its file name): centred in the editor, in its
    colours, with its facts and its own scale if it has one."""
    from voxfab import io

    name = request.query_params.get("name", "")
    suffix = Path(name).suffix.lower()
    if not FILE_NAME.fullmatch(name) or suffix not in OPENED:
        raise InvalidShapeError(f"file: the studio opens {', '.join(OPENED)} files, got {name[:60]!r}")
    raw = await request.body()
    if not raw:
        raise InvalidShapeError(f"{name}: the file is empty")

    def run() -> dict[str, Any]:
        from voxfab.errors import VoxfabError

        # a name of the session's own: the artist's file name never reaches the file system
        path = session.work / f"open-{uuid.uuid4().hex}{suffix}"
        path.write_bytes(raw)
        try:
            result = io.read(path)
        except VoxfabError as exc:  # the reader's words name the file as the artist knows it
            raise InvalidShapeError(str(exc).replace(str(path), name).replace(path.name, name)) from None
        finally:
            path.unlink(missing_ok=True)
        shape = _grid.InitialShape.of(result.grid, label=name, pitch=result.pitch, colours=result.colours)
        return {**shape.answer(), "notes": [n.replace(str(path), name).replace(path.name, name) for n in result.notes]}

    return await run_in_threadpool(run)


def routes(session: Session) -> list[Route]:
    """The routes of painting and of the shape as a file."""
    return [
        Route("/api/palette", session.api(palette)),
        Route("/api/paint/fit", session.api(fit), methods=["POST"]),
        Route("/api/join", session.api(join), methods=["POST"]),
        Route("/api/shape/file", session.api(shape_file), methods=["POST"]),
        Route("/api/shape/open", session.api(shape_open), methods=["POST"]),
    ]
