"""``POST /api/fits``: "does it fit this sheet?", answered by the exact strategy as a job.

The request is ``{"grid": ..., "sheet": "A4", "face_mm": 10, "timeout": 20}``; the
answer is a job (the search may take up to ``timeout`` seconds) whose result is
:func:`voxfab.fabricate.fits.fits_sheet`'s: ``answer`` (``yes``, ``no``, proved,
or ``undecided``), the box of faces, the message, and with ``yes`` the net's
layout.  That net is the job's net 0, so ``/api/make`` draws it when asked for
``{"net": {"job": ID, "index": 0}}``.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any

from starlette.requests import Request

from voxfab.errors import InvalidShapeError

from . import _grid, _work
from ._jobs import Jobs

__all__ = ["endpoint", "MAX_FITS_SECONDS"]

#: Longest exact search the page may ask for, seconds.
MAX_FITS_SECONDS = 120.0


def endpoint(jobs: Callable[[], Jobs]) -> Callable[[Request], Awaitable[dict[str, Any]]]:
    """The handler of ``POST /api/fits`` on the session's ``jobs``."""

    async def fits(request: Request) -> dict[str, Any]:
        from voxfab.fabricate.netdraw import parse_sheet
        from voxfab.shape import well_formed_reasons

        from ._app import _json

        data = await _json(request)
        if not isinstance(data, dict):
            raise InvalidShapeError('request: expected {"grid": ..., "sheet": "A4", "face_mm": 10}')
        grid = _grid.unpack(data.get("grid"))
        sheet = data.get("sheet", "A4")
        if not isinstance(sheet, str):
            raise InvalidShapeError("sheet: expected A4, A3, Letter or WxH in mm")
        parse_sheet(sheet)
        face_mm = _work.check_number(data.get("face_mm", 10.0), name="face_mm", lo=1.0, hi=500.0)
        timeout = _work.check_number(data.get("timeout", 20.0), name="timeout", lo=0.5, hi=MAX_FITS_SECONDS)
        reasons = well_formed_reasons(grid)
        if any("piece" in r for r in reasons) or not grid.any():
            raise InvalidShapeError("shape: a net needs one piece of face-connected voxels: "
                                    + "; ".join(reasons or ["the shape is empty"]))
        job = jobs().submit("fits", lambda j: _answer(j, grid, sheet=sheet, face_mm=face_mm, timeout=timeout))
        return {"job": job.id}

    return fits


def _answer(job: Any, grid: Any, *, sheet: str, face_mm: float, timeout: float) -> None:
    from voxfab.fabricate.fits import fits_sheet

    job.step(0, 1, f"exact search on {sheet} at {face_mm:g} mm")
    fit = fits_sheet(grid, sheet, face_mm, timeout=timeout)
    job.data["nets"] = [fit.net] if fit.net is not None else []
    result: dict[str, Any] = {"answer": fit.answer, "box": list(fit.box), "faces": fit.faces, "sheet": sheet,
                              "face_mm": face_mm, "message": fit.message}
    if fit.net is not None:
        x0, y0, x1, y1 = fit.net.bounds()
        result["net"] = {"index": 0, "extent": [x1 - x0, y1 - y0], "layout": _work.net_layout(fit.net, grid)}
    job.result = result
    job.step(1, 1, fit.message)
