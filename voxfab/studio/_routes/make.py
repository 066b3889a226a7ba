"""The Make tab: ``POST /api/make``, one fabrication file of the shape (or of a chosen net) as a job.

The files are the table of outputs' own (:func:`voxfab.fabricate.outputs`), each
made by the pipeline ``voxfab build`` runs (:func:`.._work.make_files`); the
body's options are checked by the output's options dataclass, as a recipe's.
"""

from __future__ import annotations

import re
from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.routing import Route

from voxfab.errors import InvalidShapeError

from .. import _bodies, _grid, _specs, _work
from .._http import only_fields, read_object
from .._session import Session

#: A title the files are named after.
TITLE = re.compile(r"[A-Za-z0-9_.\- ]{1,64}")


def chosen_net(session: Session, artefact: str, pick: Any) -> Any:
    """The net ``{"job": ID, "index": N}`` names, for an artefact drawn from a net; None when none is picked."""
    if pick is None:
        return None
    from voxfab.fabricate import output_for_download

    if "net" not in output_for_download(artefact).uses:  # the outputs drawn from a net, as the table declares
        raise InvalidShapeError(f"net: {artefact} is made from the shape, not from a chosen net")
    if not isinstance(pick, dict) or not isinstance(pick.get("job"), str):
        raise InvalidShapeError("net: expected {\"job\": ID, \"index\": N}")
    only_fields(pick, _bodies.NET_PICK, where="net")
    chosen = session.job(pick["job"]).data.get("nets", [])
    if not chosen:
        raise InvalidShapeError("net: that gallery has no nets")
    return chosen[_bodies.whole(pick.get("index"), name="net.index", lo=0, hi=len(chosen) - 1)]


async def make(session: Session, request: Request) -> dict[str, Any]:
    """Start making one artefact: the job's id."""
    data = await read_object(request, _bodies.MAKE, example='{"grid": ..., "artefact": ...}')
    artefact = data.get("artefact")
    if artefact not in _work.artefacts():
        raise InvalidShapeError(f"artefact: expected one of {', '.join(_work.artefacts())}, got {artefact!r:.40}")
    # the shape with its colours: every output the library colours gets them
    shape = _grid.unpack_shape(data.get("grid"), pitch=_bodies.pitch(data.get("pitch")))
    _grid.require_voxels(shape.grid)
    title = data.get("title") or "studio"
    if not isinstance(title, str) or not TITLE.fullmatch(title):
        raise InvalidShapeError(f"title: letters, digits, space, _ . - (at most 64), got {str(title)[:70]!r}")
    opts = data.get("options") or {}
    if not isinstance(opts, dict):
        raise InvalidShapeError("options: expected an object")
    # Checked now, by the output's own options dataclass: the same bounds and words as the CLI.
    settings = _work.download_settings(artefact, opts)
    net = chosen_net(session, artefact, data.get("net"))
    placement = data.get("placement")
    kept = None if placement is not None or net is None else session.job(data["net"]["job"]).data.get("placement")
    if kept is not None and hasattr(settings, "drawing"):
        from voxfab.fabricate.netdraw._placement import Placement as Kept

        # an edited net's files as the editor laid it out (its job keeps the placement it showed), on its paper
        placement = kept if Kept.from_dict(kept).suits(settings.drawing) else None
    if placement is not None:
        if net is None:
            raise InvalidShapeError("placement: pick a net first (\"net\": {\"job\": ID, \"index\": N})")
        from voxfab.fabricate.netdraw._placement import Placement

        placement = Placement.from_dict(placement)
    tube = None
    if artefact != "animation.gif" and data.get("shape") is not None:
        raise InvalidShapeError(f"shape: only animation.gif remakes the drawn shape; {artefact} is made from "
                                "\"grid\"")
    if artefact == "animation.gif":
        tube = await run_in_threadpool(_specs.tube_params, data.get("shape"), session.work)
    job = session.jobs.submit("make", lambda j: _work.make_files(
        j, shape, artefact=artefact, title=title, net=net, settings=settings, tube=tube,
        placement=placement))
    return {"job": job.id}


def routes(session: Session) -> list[Route]:
    """The Make tab's routes."""
    return [Route("/api/make", session.api(make), methods=["POST"])]
