"""A legend for printed pages: a short sample line and the name of each line layer used."""

from __future__ import annotations

import dataclasses

from ._font import text_polylines
from ._model import Page
from ._polylines import Polylines

#: Layers a legend explains, right to left along the bottom edge.
LEGEND_LAYERS = ("CUT", "SCORE", "MOUNTAIN", "VALLEY", "GRID")


@dataclasses.dataclass(frozen=True)
class Legend:
    """Where a legend goes: baseline ``y`` and gap ``right`` from the page's lower-right corner, text ``height``, mm."""

    y: float = 11.0
    right: float = 10.0
    height: float = 2.0


def legend_layers(page: Page, legend: Legend) -> dict[str, Polylines]:
    """Sample lines with their layer names, right-aligned along the bottom of ``page``.

    Parameters
    ----------
    page : Page
        Only its used layers get an entry.
    legend : Legend
        Position and text size.

    Returns
    -------
    dict of str to Polylines
        Lines to add per layer (names go on LABEL).
    """
    out: dict[str, list[Polylines]] = {}
    x = page.width - legend.right
    y = legend.y
    h = legend.height
    used = set(page.used_layers())
    for layer in reversed(LEGEND_LAYERS):
        if layer not in used:
            continue
        width = (len(layer) - 1) * h + h * 4 / 6
        x -= width
        out.setdefault("LABEL", []).append(text_polylines([layer], [(x, y)], [(1.0, 0.0)], h))
        x -= 4.5 * h
        out.setdefault(layer, []).append(Polylines.from_segments([(x, y + h / 2)], [(x + 4.0 * h, y + h / 2)]))
        x -= 2.0 * h
    return {k: Polylines.concat(v) for k, v in out.items()}
