"""The one table of drawing layers: names, colours, dash styles and line widths.

Every drawing voxfab writes (paper nets, slice plates, the net picture) uses
these layers, so a laser operator meets the same names and colours in every
file.  Colours are pure RGB (laser drivers map them exactly) with the common
fab-lab meaning: cut red, score blue, engrave black.  The mountain/valley
folds of a paper net are two scores with their own dash styles, so printed
sheets read like an origami diagram, and colours of their own (magenta, green):
every layer has a colour, and an AutoCAD Color Index, no other layer has, so a
laser program that maps its jobs by colour never merges two kinds of line.
"""

from __future__ import annotations

import dataclasses
import re
from enum import Enum

from voxfab._shared.validate import check_choice
from voxfab.errors import InvalidShapeError


class LineStyle(Enum):
    """Dash styles; the patterns are in mm (:data:`DASH_PATTERNS`)."""

    SOLID = "solid"
    DASHED = "dashed"
    DASHDOT = "dashdot"
    DOTTED = "dotted"


#: Dash pattern (on, off, ...) in mm of each style.
DASH_PATTERNS: dict[LineStyle, tuple[float, ...]] = {
    LineStyle.SOLID: (),
    LineStyle.DASHED: (2.0, 1.0),
    LineStyle.DASHDOT: (3.0, 1.0, 0.5, 1.0),
    LineStyle.DOTTED: (0.5, 1.0),
}


class Lines(Enum):
    """Line widths of a file: hairlines for a laser, visible lines for people.

    Laser drivers treat only very thin strokes as vector cuts (0.01 mm here);
    such lines vanish on a screen, so previews and prints use visible widths.
    """

    LASER = "laser"
    PREVIEW = "preview"


@dataclasses.dataclass(frozen=True)
class LayerStyle:
    """How one layer is drawn.

    Parameters
    ----------
    color : str
        ``#rrggbb``.
    style : LineStyle
        Dash style.
    width : float
        Visible line width for previews and prints, mm (lasers get hairlines).
    """

    color: str
    style: LineStyle
    width: float = 0.2

    @property
    def rgb(self) -> tuple[int, int, int]:
        """The colour as 0..255 integers."""
        c = self.color
        return int(c[1:3], 16), int(c[3:5], 16), int(c[5:7], 16)

    def line_width(self, lines: Lines) -> float:
        """Stroke width in mm for a laser file or a preview."""
        return HAIRLINE if lines is Lines.LASER else self.width


#: Stroke width of every laser line, mm: thin enough to count as a vector "hairline".
HAIRLINE = 0.01

#: The layers in drawing order: engraving and scoring first, the cut last, so
#: parts do not move before the laser has marked them.
LAYERS: dict[str, LayerStyle] = {
    "LABEL": LayerStyle("#000000", LineStyle.SOLID, 0.15),
    "GRID": LayerStyle("#b0b0b0", LineStyle.DOTTED, 0.15),
    "SCORE": LayerStyle("#0000ff", LineStyle.SOLID, 0.2),
    "VALLEY": LayerStyle("#00ff00", LineStyle.DASHDOT, 0.2),
    "MOUNTAIN": LayerStyle("#ff00ff", LineStyle.DASHED, 0.2),
    "CUT": LayerStyle("#ff0000", LineStyle.SOLID, 0.2),
}

#: What each layer holds, for file descriptions and legends.
LAYER_PURPOSES: dict[str, str] = {
    "LABEL": "single-stroke seam labels, plate numbers and titles (engrave or print)",
    "GRID": "coplanar folds, a faint score",
    "SCORE": "score lines (outline of the next plate)",
    "VALLEY": "valley folds (fold towards you)",
    "MOUNTAIN": "mountain folds (fold away from you)",
    "CUT": "cut lines",
}

_NAMED_COLORS = {
    "red": "#ff0000", "green": "#00ff00", "blue": "#0000ff", "black": "#000000",
    "cyan": "#00ffff", "magenta": "#ff00ff", "yellow": "#ffff00", "grey": "#808080",
    "gray": "#808080", "white": "#ffffff",
}


def parse_colors(spec: str) -> dict[str, LayerStyle]:
    """Layer styles from ``"cut=#ff0000,mountain=blue:dashed,..."`` over :data:`LAYERS`.

    Each item is ``layer=colour[:style]`` with a layer of :data:`LAYERS` (any
    case), a colour ``#rrggbb`` or a basic name, and a style among solid,
    dashed, dashdot, dotted.

    Raises
    ------
    InvalidShapeError
        On an unknown layer, colour or style; the message lists the valid ones.
    """
    styles = dict(LAYERS)
    for item in (s.strip() for s in spec.split(",")):
        if not item:
            continue
        if "=" not in item:
            raise InvalidShapeError(f"colors: expected layer=colour[:style], got {item!r}")
        layer, value = (s.strip() for s in item.split("=", 1))
        layer = layer.upper()
        if layer not in styles:
            raise InvalidShapeError(f"colors: unknown layer {layer!r}; expected one of {', '.join(LAYERS)}")
        color, _, style = value.partition(":")
        color = _NAMED_COLORS.get(color.lower(), color.lower())
        if not re.fullmatch(r"#[0-9a-f]{6}", color):
            raise InvalidShapeError(f"colors: {layer}: expected #rrggbb or a colour name, got {value!r}")
        ls = check_choice(style.lower(), LineStyle, name=f"colors: {layer} style") if style else styles[layer].style
        styles[layer] = dataclasses.replace(styles[layer], color=color, style=ls)
    return styles


# AutoCAD Color Index entries an RGB colour is matched against (7 prints black on white).
_ACI = {1: (255, 0, 0), 2: (255, 255, 0), 3: (0, 255, 0), 4: (0, 255, 255), 5: (0, 0, 255),
        6: (255, 0, 255), 7: (0, 0, 0), 8: (128, 128, 128), 9: (192, 192, 192)}


def aci(rgb: tuple[int, int, int]) -> int:
    """Nearest AutoCAD Color Index for an RGB colour (white maps to 7 as well)."""
    if rgb == (255, 255, 255):
        return 7
    return min(_ACI, key=lambda k: (sum((a - b) ** 2 for a, b in zip(_ACI[k], rgb)), k))
