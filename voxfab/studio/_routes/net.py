"""The Net tab: a gallery of nets to choose from, edits of a chosen net, and "does it fit this sheet?".

``POST /api/nets`` starts a gallery job, ``POST /api/fits`` an exact search for one
piece on a sheet (:mod:`.._fits`), and ``POST /api/nets/edit`` cuts or joins one
edge of a net of either, or takes the last edit back (:mod:`.._netedit`).  Each
answers with a job the page follows through :mod:`.jobs`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.routing import Route

from voxfab.errors import InvalidShapeError

from .. import _bodies, _fits, _grid, _netedit, _work
from .._http import only_fields, read_json, read_object
from .._session import Session


def require_one_piece(grid: np.ndarray) -> None:
    """Refuse, before any job, a shape no net of the page can be made of: empty, or in several pieces."""
    from voxfab.shape import well_formed_reasons

    reasons = well_formed_reasons(grid)
    if any("piece" in r for r in reasons) or not grid.any():
        raise InvalidShapeError("shape: a net needs one piece of face-connected voxels: "
                                + "; ".join(reasons or ["the shape is empty"]))


async def gallery(session: Session, request: Request) -> dict[str, Any]:
    """Start a gallery of distinct nets of the grid sent: the job's id."""
    data = await read_json(request)
    if not isinstance(data, dict):
        raise InvalidShapeError("request: expected {\"grid\": ..., \"count\": N, \"options\": {...}}")
    only_fields(data, _bodies.NETS, where="request", hint='net and drawing options go in "options"')
    grid = _grid.unpack(data.get("grid"))
    # Checked by the library's option declarations: the CLI's bounds and words.
    count = _bodies.count(data.get("count", 8), _work.MAX_NETS)
    seed = _bodies.seed(data.get("seed", 0))
    net, drawing = _bodies.gallery_options(data.get("options"), defaults=_work.GALLERY_DEFAULTS)
    constraints = _work.edge_constraints(data.get("constraints"))
    require_one_piece(grid)
    job = session.jobs.submit("nets", lambda j: _work.net_gallery(
        j, grid, count=int(count), seed=int(seed), net=net, drawing=drawing, constraints=constraints))
    return {"job": job.id}


async def edit(session: Session, request: Request) -> dict[str, Any]:
    """Cut or join one edge of a chosen net, or undo: the new job holding the result, and the net for the page."""
    data = await read_json(request)
    if not isinstance(data, dict) or not isinstance(data.get("job"), str):
        raise InvalidShapeError("request: expected {\"job\": ID, \"index\": N, \"cut\" | \"join\": [face, face]"
                                " | \"undo\": true}")
    only_fields(data, _bodies.EDIT, where="request")
    source = session.job(data["job"])
    # an edit's job holds its net from the start (the pool only marks it done), a gallery each net once made
    if source.state != "done" and source.kind != "edit" and not (source.kind == "nets" and source.items):
        raise InvalidShapeError(f"job: job {source.id} has not finished")
    made = await run_in_threadpool(_netedit.apply_edit, source, data)
    record, item = made["record"], made["item"]

    def keep(job: Any) -> None:
        job.data.update(record)
        job.result = {"asked": 1, "found": 1, "seconds": item["seconds"], "nets": [item]}

    job = session.jobs.submit("edit", keep)
    keep(job)  # at once too, so /api/make finds the net before the pool has run the job
    return {"job": job.id, "net": item}


async def fits(session: Session, request: Request) -> dict[str, Any]:
    """Start the exact search for one piece of the grid on a sheet: the job's id."""
    data = await read_object(request, _bodies.FITS,
                             example='{"grid": ..., "options": {"sheet": "A4", "face_size": 10}}')
    grid = _grid.unpack(data.get("grid"))
    # Only the options the question reads, each checked by its declaration (the CLI's bounds and words).
    net, drawing = _bodies.fits_options(data.get("options"), defaults=_fits.FITS_DEFAULTS)
    if net.timeout > _fits.MAX_FITS_SECONDS:
        raise InvalidShapeError(f"options.timeout: expected at most {_fits.MAX_FITS_SECONDS:g} s for the page's "
                                f"question, got {net.timeout:g}")
    require_one_piece(grid)
    job = session.jobs.submit("fits", lambda j: _fits.fits_answer(j, grid, net=net, drawing=drawing))
    return {"job": job.id}


def routes(session: Session) -> list[Route]:
    """The Net tab's routes."""
    return [
        Route("/api/nets", session.api(gallery), methods=["POST"]),
        Route("/api/nets/edit", session.api(edit), methods=["POST"]),
        Route("/api/fits", session.api(fits), methods=["POST"]),
    ]
