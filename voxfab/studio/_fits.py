"""``POST /api/fits``: "does it fit this sheet?", answered by the exact strategy as a job.

The request is ``{"grid": ..., "options": {"sheet": "A4", "face_size": 10, "timeout": 20}}`` (the
gallery's options, checked by the same dataclasses; no face size: the smallest legible one); the
answer is a job (the search may take up to ``timeout`` seconds) whose result is
:func:`voxfab.fabricate.fits.fits_sheet`'s: ``answer`` (``yes``, ``no``, proved,
or ``undecided``), the box of faces, the message in plain words (``detail``: the
library's), and with ``yes`` the net as a gallery's net (layout, fit, placement).
That net is the job's net 0, so ``/api/make`` draws it and ``/api/nets/edit``
edits it when asked for ``{"job": ID, "index": 0}``.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any

from starlette.requests import Request

from voxfab.errors import InvalidShapeError

from . import _bodies, _grid
from ._http import read_object
from ._jobs import Jobs

__all__ = ["endpoint", "MAX_FITS_SECONDS"]

#: Longest exact search the page may ask for, seconds.
MAX_FITS_SECONDS = 120.0
#: What the question takes unless the body says otherwise: the gallery's short search.
FITS_DEFAULTS = {"timeout": 5.0}


def endpoint(jobs: Callable[[], Jobs]) -> Callable[[Request], Awaitable[dict[str, Any]]]:
    """The handler of ``POST /api/fits`` on the session's ``jobs``."""

    async def fits(request: Request) -> dict[str, Any]:
        from voxfab.shape import well_formed_reasons

        data = await read_object(request, _bodies.FITS,
                                 example='{"grid": ..., "options": {"sheet": "A4", "face_size": 10}}')
        grid = _grid.unpack(data.get("grid"))
        # Only the options the question reads, each checked by its declaration (the CLI's bounds and words).
        net, drawing = _bodies.fits_options(data.get("options"), defaults=FITS_DEFAULTS)
        if net.timeout > MAX_FITS_SECONDS:
            raise InvalidShapeError(f"options.timeout: expected at most {MAX_FITS_SECONDS:g} s for the page's "
                                    f"question, got {net.timeout:g}")
        reasons = well_formed_reasons(grid)
        if any("piece" in r for r in reasons) or not grid.any():
            raise InvalidShapeError("shape: a net needs one piece of face-connected voxels: "
                                    + "; ".join(reasons or ["the shape is empty"]))
        job = jobs().submit("fits", lambda j: _answer(j, grid, net=net, drawing=drawing))
        return {"job": job.id}

    return fits


def _answer(job: Any, grid: Any, *, net: Any, drawing: Any) -> None:
    from voxfab.fabricate.fits import fits_sheet
    from voxfab.fabricate.netdraw import gallery_face_size

    from ._edit import net_item
    from ._words import explained

    # No face size asked for: the smallest with legible marks, as the gallery takes it.
    drawing, _ = gallery_face_size(grid, net, drawing)
    sheet, face = drawing.sheet, float(drawing.pitch)
    job.step(0, 1, f"looking for a one-piece net on {sheet} at {face:g} mm faces")
    fit = fits_sheet(grid, sheet, face, timeout=net.timeout, drawing=drawing)
    job.data["nets"] = [fit.net] if fit.net is not None else []
    job.data["grid"] = grid
    job.data["options"] = (net, drawing)  # an edit of the net found keeps its sheet and marks
    said = explained(fit.message)
    result: dict[str, Any] = {"answer": fit.answer, "box": list(fit.box), "faces": fit.faces, "sheet": sheet,
                              "face_size": face, "message": said["text"], **({"detail": said["detail"]} if "detail" in said else {})}
    if fit.net is not None:
        # The net found, as a gallery's net: the page opens it in the editor, on its sheets, ready for its files.
        x0, y0, x1, y1 = fit.net.bounds()
        item = net_item(grid, fit.net, None, history=0, extra={}, drawing=drawing)
        result["net"] = {**item, "extent": [x1 - x0, y1 - y0]}
    job.result = result
    job.step(1, 1, said["text"])
