"""The polylines of a DXF as written by voxfab, read back with ezdxf whatever its version.

R12 files hold LINE and POLYLINE (with VERTEX) entities, R2000 files LINE and
LWPOLYLINE; the tests compare geometry, so they read both through one helper.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np


def entity_points(e: Any) -> tuple[np.ndarray, bool] | None:
    """The 2D points of a LINE, POLYLINE or LWPOLYLINE and whether it is closed; None for other entities."""
    kind = e.dxftype()
    if kind == "LINE":
        return np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]], float), False
    if kind == "POLYLINE":
        return np.array([tuple(v.dxf.location)[:2] for v in e.vertices], float), bool(e.is_closed)
    if kind == "LWPOLYLINE":
        return np.array([tuple(p)[:2] for p in e.get_points("xy")], float), bool(e.closed)
    return None


def polylines(doc: Any, layer: str | None = None) -> Iterator[tuple[str, np.ndarray, bool]]:
    """(layer, points, closed) of every line and polyline of the modelspace, optionally of one layer."""
    for e in doc.modelspace():
        if layer is not None and e.dxf.layer != layer:
            continue
        got = entity_points(e)
        if got is not None:
            yield e.dxf.layer, got[0], got[1]


def closed_rings(doc: Any, layer: str = "CUT") -> list[np.ndarray]:
    """The closed polylines of one layer (the outlines and holes of cut parts)."""
    return [pts for _, pts, closed in polylines(doc, layer) if closed and len(pts) >= 3]
