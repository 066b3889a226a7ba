"""Assembly instructions as PDF: the stack order as a grid of layers.

Each panel shows one voxel layer from above: its pieces filled and numbered,
the layer below as a dashed outline (where to glue it) and the dowel holes.
Panels run left to right, top to bottom, from the bottom layer up.  The PDF
metadata carries no dates, so equal stacks give equal bytes.
"""

from __future__ import annotations

import io
import math

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike

from ._outline import cells_outline, scaled
from ._stack import PlateStack

__all__ = ["PANELS_PER_PAGE", "assembly_pdf", "write_assembly_pdf"]

#: Layers drawn per page (a 5 × 5 grid fits the artist's 25 layers on one page).
PANELS_PER_PAGE = 25


def _rings(geometry: object) -> list[np.ndarray]:
    out = []
    for poly in getattr(geometry, "geoms", [geometry]):
        if poly.is_empty:
            continue
        out.append(np.asarray(poly.exterior.coords))
        out.extend(np.asarray(r.coords) for r in poly.interiors)
    return out


def _layer_art(stack: PlateStack, k: int, unions: list[object | None], offset: np.ndarray, art: dict[str, list]) -> None:
    """Collect the drawing of layer ``k`` (mm, moved by ``offset``) into ``art``."""
    from shapely.ops import polylabel

    pitch = stack.pitch
    if k > 0 and unions[k - 1] is not None:
        art["below"].extend(r + offset for r in _rings(scaled(unions[k - 1], pitch)))
    for piece in stack.layers[k]:
        poly = scaled(piece.outline, pitch)
        art["pieces"].append([r + offset for r in _rings(poly)])
        c = polylabel(poly, tolerance=0.05 * pitch)
        art["ids"].append((c.x + offset[0], c.y + offset[1], piece.id))
    for d in stack.dowels:
        if int(d.lower.split("-")[0]) == k + 1 or int(d.upper.split("-")[0]) == k + 1:
            art["holes"].append((d.x + offset[0], d.y + offset[1]))


def assembly_pdf(stack: PlateStack, *, title: str = "") -> bytes:
    """Return the assembly PDF of ``stack`` as bytes (one page per 25 layers).

    Each page is a single set of axes with the layer panels side by side on a
    common scale (faster and more regular than one axes per panel).
    """
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.collections import LineCollection, PatchCollection
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, PathPatch
    from matplotlib.path import Path as MplPath

    unions = [cells_outline(np.concatenate([p.cells for p in pcs])) if pcs else None for pcs in stack.layers]
    lo = np.array([np.inf, np.inf])
    hi = -lo
    for u in unions:
        if u is not None:
            x0, y0, x1, y1 = u.bounds
            lo = np.minimum(lo, (x0, y0))
            hi = np.maximum(hi, (x1, y1))
    lo, hi = lo * stack.pitch, hi * stack.pitch
    size = hi - lo
    gap = 0.15 * float(np.max(size))
    cell = size + gap  # panel pitch: drawing plus room for the title
    n = len(stack.layers)
    buf = io.BytesIO()
    metadata = {"Creator": "voxfab", "Producer": None, "CreationDate": None, "Title": title or "plate stack"}
    with PdfPages(buf, metadata=metadata) as pdf:
        for start in range(0, n, PANELS_PER_PAGE):
            count = min(PANELS_PER_PAGE, n - start)
            cols = math.ceil(math.sqrt(count))
            rows = math.ceil(count / cols)
            fig = Figure(figsize=(8.27, 11.69))
            fig.suptitle(
                f"{title + ': ' if title else ''}stack order, layer 1 (bottom) to {n} (top), axis {stack.axis}; "
                f"{stack.plates_per_layer} plate(s) of {stack.thickness:g} mm per layer\n"
                "filled: this layer with its piece numbers; dashed: the layer below; circles: dowel holes",
                fontsize=8,
            )
            ax = fig.add_axes((0.03, 0.03, 0.94, 0.9))
            ax.set_axis_off()
            art: dict[str, list] = {"below": [], "pieces": [], "ids": [], "holes": []}
            for i in range(count):
                k = start + i
                r, c = divmod(i, cols)
                offset = np.array([c * cell[0], -r * cell[1]]) - lo
                _layer_art(stack, k, unions, offset, art)
                first = k * stack.plates_per_layer + 1
                last = first + stack.plates_per_layer - 1
                plates = f"plate {first}" if first == last else f"plates {first}-{last}"
                ax.text(c * cell[0] + size[0] / 2, -r * cell[1] + size[1] + 0.3 * gap,
                        f"layer {k + 1} ({plates})", ha="center", va="bottom", fontsize=6)
            if art["below"]:
                ax.add_collection(LineCollection(art["below"], colors="0.55", linewidths=0.6, linestyles=(0, (3, 2))))
            patches = []
            for rings in art["pieces"]:
                verts = np.concatenate(rings)
                codes = np.concatenate(
                    [[MplPath.MOVETO] + [MplPath.LINETO] * (len(q) - 2) + [MplPath.CLOSEPOLY] for q in rings]
                )
                patches.append(PathPatch(MplPath(verts, codes)))
            ax.add_collection(PatchCollection(patches, facecolors="#f2c48d", edgecolors="#b02020", linewidths=0.6))
            if art["holes"]:
                rad = stack.dowel_diameter / 2.0
                ax.add_collection(PatchCollection([Circle(h, rad) for h in art["holes"]],
                                                  facecolors="white", edgecolors="black", linewidths=0.4))
            for x, y, text in art["ids"]:
                ax.text(x, y, text, ha="center", va="center", fontsize=3.5)
            ax.set_xlim(-0.5 * gap, cols * cell[0])
            ax.set_ylim(-(rows - 1) * cell[1] - 0.5 * gap, size[1] + gap)
            ax.set_aspect("equal")
            pdf.savefig(fig)
    return buf.getvalue()


def write_assembly_pdf(stack: PlateStack, path: PathLike, *, title: str = "") -> None:
    """Write the assembly PDF of ``stack`` to ``path`` (atomically)."""
    write_bytes(path, assembly_pdf(stack, title=title))
