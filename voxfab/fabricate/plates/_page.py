"""A nested sheet of plates as a drawing page: cut rings and dowel holes, scores, labels."""

from __future__ import annotations

import numpy as np

from voxfab.drawing import Page, Polylines

from ._nest import PlateSheet


def sheet_page(sheet: PlateSheet) -> Page:
    """The drawing page of one sheet (mm, lower-left corner at the origin).

    Cut rings (outlines and voxel holes) and dowel circles go on CUT, the
    next layer's outline on SCORE, the plate numbers on LABEL.
    """
    rings = [r[:-1] for part in sheet.parts for r in part.cut]
    score = [line for part in sheet.parts for line in part.score]
    labels = [line for part in sheet.parts for line in part.engrave]
    circles = [part.circles for part in sheet.parts if len(part.circles)]
    return Page(
        float(sheet.width), float(sheet.height),
        layers={
            "CUT": Polylines.from_list(rings, [True] * len(rings)),
            "SCORE": Polylines.from_list(score, [False] * len(score)),
            "LABEL": Polylines.from_list(labels, [False] * len(labels)),
        },
        circles={"CUT": np.concatenate(circles) if circles else np.zeros((0, 3))},
        title=f"sheet {sheet.index}" + (f", {sheet.colour}" if sheet.colour else ""),
    )
