"""What ``POST /api/fits`` asks, "does it fit this sheet?", answered by the exact strategy as a job.

The request is ``{"grid": ..., "options": {"sheet": "A4", "face_size": 10, "timeout": 20}}`` (the
gallery's options, checked by the same dataclasses; no face size: the smallest legible one); the
answer is a job (the search may take up to ``timeout`` seconds) whose result is
:func:`voxfab.fabricate.fits.fits_sheet`'s: ``answer`` (``yes``, ``no``, proved,
or ``undecided``), the box of faces, the message in plain words (``detail``: the
library's), and with ``yes`` the net as a gallery's net (layout, fit, placement).
That net is the job's net 0, so ``/api/make`` draws it and ``/api/nets/edit``
edits it when asked for ``{"job": ID, "index": 0}``.  The route is in :mod:`._routes.net`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np

    from ._jobs import Job

__all__ = ["fits_answer", "FITS_DEFAULTS", "MAX_FITS_SECONDS"]

#: Longest exact search the page may ask for, seconds.
MAX_FITS_SECONDS = 120.0
#: What the question takes unless the body says otherwise: the gallery's short search.
FITS_DEFAULTS = {"timeout": 5.0}


def fits_answer(job: Job, grid: np.ndarray, *, net: Any, drawing: Any) -> None:
    """Answer "does one piece of ``grid`` fit the sheet?" as ``job``'s result, its net (if any) kept as net 0.

    ``net`` and ``drawing`` are the gallery's checked options (``NetOptions``, ``DrawingOptions``).
    """
    from voxfab.fabricate.fits import fits_sheet
    from voxfab.fabricate.netdraw import gallery_face_size

    from ._netedit import net_item
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
