"""The scale of a shape, declared once (the CLI's ``--pitch``, the recipe's ``pitch``)."""

from __future__ import annotations

import dataclasses

from voxfab._shared.options import Options, option

#: Largest pitch accepted, mm per voxel (a 25-voxel shape is then 25 m long).
MAX_PITCH = 1000.0


@dataclasses.dataclass(frozen=True)
class ShapeOptions(Options):
    """The physical scale of a shape: every artefact (print, net, plates) reads it."""

    pitch: float | None = option(None, help="millimetres per voxel of the object (default: the file's own, or 1)",
                                 unit="mm", low=0.0, low_open=True, high=MAX_PITCH)
