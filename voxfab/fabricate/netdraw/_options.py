"""Net drawing options: sheet sizes, tab shape, perforation and the colour map."""

from __future__ import annotations

import dataclasses
import re
from enum import Enum

from voxfab._shared.validate import check_choice, check_positive
from voxfab.drawing import LayerStyle, parse_colors
from voxfab.drawing.dxf import DxfVersion
from voxfab.errors import InvalidShapeError

#: Paper sizes in mm (portrait).
SHEETS: dict[str, tuple[float, float]] = {
    "A4": (210.0, 297.0),
    "A3": (297.0, 420.0),
    "Letter": (215.9, 279.4),
}

#: Largest sheet side accepted, mm (the largest laser beds and cutting services stay under 3 m).
MAX_SHEET = 5000.0


class Perforate(Enum):
    """Which fold type becomes short through-cuts on the CUT layer."""

    NONE = "none"
    MOUNTAIN = "mountain"
    VALLEY = "valley"


def parse_sheet(spec: str) -> tuple[float, float]:
    """Sheet size in mm from ``A4``, ``A3``, ``Letter`` or ``WxH`` (mm)."""
    for name, size in SHEETS.items():
        if spec.lower() == name.lower():
            return size
    m = re.fullmatch(r"\s*([0-9]*\.?[0-9]+)\s*[xX×]\s*([0-9]*\.?[0-9]+)\s*(mm)?\s*", spec)
    if not m:
        raise InvalidShapeError(f"sheet: expected A4, A3, Letter or WxH in mm, got {spec!r}")
    w, h = float(m.group(1)), float(m.group(2))
    if w <= 0 or h <= 0:
        raise InvalidShapeError(f"sheet: sides must be positive, got {spec!r}")
    if max(w, h) > MAX_SHEET:
        raise InvalidShapeError(f"sheet: expected sides of at most {MAX_SHEET:g} mm, got {spec[:80]!r}")
    return w, h


@dataclasses.dataclass(frozen=True)
class DrawingOptions:
    """How a net is drawn.

    Parameters
    ----------
    pitch : float or None
        Face edge length in mm; ``None`` picks the largest pitch (rounded down to
        0.1 mm, at least ``min_auto_pitch``) that puts the net on one sheet.
    sheet : str
        ``A4``, ``A3``, ``Letter`` or ``WxH`` in mm.
    margin : float
        Empty border of the sheet, mm.
    tab_width : float
        Glue tab height (distance from its fold to its free edge), mm.
    tab_angle : float
        Angle of the tab's slanted sides to its fold, degrees in [15, 75].
    label_height : float
        Largest cap height of edge numbers, mm (they shrink to fit the faces).
    title_height : float
        Cap height of the title, mm.
    grid_lines : bool
        Draw coplanar folds as a faint score on the GRID layer.
    perforate : str
        ``none``, ``mountain`` or ``valley``: that fold type is drawn as short cuts.
    perf_cut, perf_bridge : float
        Perforation cut and bridge lengths, mm.
    dxf_version : str
        ``R12`` or ``R2000``.
    colors : str
        Overrides of the colour map, see :func:`parse_colors`.
    min_auto_pitch : float
        Smallest pitch picked automatically; larger nets are split over sheets.
    numbers : bool
        Print the edge numbers (``False``: an explicit opt-out for faces too small
        to carry them).
    tabs : bool
        Add glue tabs (``False``: every seam is marked for tape instead).
    heading : bool
        Print the title line (name, face size, seed, sheet) in a band at the bottom.
    """

    pitch: float | None = None
    sheet: str = "A4"
    margin: float = 10.0
    tab_width: float = 5.0
    tab_angle: float = 45.0
    label_height: float = 5.0
    title_height: float = 3.0
    grid_lines: bool = False
    perforate: str = "none"
    perf_cut: float = 1.5
    perf_bridge: float = 1.0
    dxf_version: str = "R12"
    colors: str = ""
    min_auto_pitch: float = 5.0
    numbers: bool = True
    tabs: bool = True
    heading: bool = True

    def __post_init__(self) -> None:
        if self.pitch is not None:
            check_positive(self.pitch, name="pitch")
        for name in ("tab_width", "label_height", "title_height", "perf_cut", "perf_bridge", "min_auto_pitch"):
            check_positive(getattr(self, name), name=name.replace("_", "-"))
        if not 0 <= float(self.margin) < 1e4:
            raise InvalidShapeError(f"margin: expected a number >= 0 mm, got {self.margin!r}")
        if not 15.0 <= float(self.tab_angle) <= 75.0:
            raise InvalidShapeError(f"tab-angle: expected 15 to 75 degrees, got {self.tab_angle!r}")
        check_choice(self.perforate, Perforate, name="perforate")
        check_choice(self.dxf_version, DxfVersion, name="dxf-version")
        w, h = self.sheet_size
        if min(w, h) <= 2 * self.margin + self.title_height + 4:
            raise InvalidShapeError(f"sheet: {self.sheet} leaves no room inside a {self.margin} mm margin")
        parse_colors(self.colors)

    @property
    def sheet_size(self) -> tuple[float, float]:
        """Sheet width and height, mm."""
        return parse_sheet(self.sheet)

    @property
    def styles(self) -> dict[str, LayerStyle]:
        """Layer styles after applying ``colors``."""
        return parse_colors(self.colors)
