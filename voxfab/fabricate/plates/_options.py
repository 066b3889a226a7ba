"""The options of slice plates, declared once (CLI flags, recipe keys, checks, README table)."""

from __future__ import annotations

import dataclasses

from voxfab._shared.options import Options, option
from voxfab.drawing import sheet_problem
from voxfab.drawing.dxf import dxf_version_option

#: The options only some styles read (every other one is read by all three).
STYLE_OPTIONS: dict[str, tuple[str, ...]] = {
    "axis": ("stacked",), "dowel": ("stacked",), "dowel_margin": ("stacked",), "dowels_per_joint": ("stacked",),
    "score": ("stacked",), "axes": ("interlocked",), "count": ("interlocked",), "interval": ("interlocked",),
    "radial_plates": ("radial",), "clearance": ("interlocked", "radial"),
}


@dataclasses.dataclass(frozen=True)
class PlateOptions(Options):
    """How a shape becomes laser-cut plates nested on sheets (see :func:`make_plates`, :func:`nest_plates`).

    The stack is as tall as the object (the shape's pitch times its voxel layers);
    a ``thickness`` other than the pitch resamples the layers.
    """

    style: str = option("stacked", help="construction: stacked (glued layers), interlocked (two slotted "
                        "families), radial (plates fanned about the vertical axis)",
                        choices=("stacked", "interlocked", "radial"))
    axis: str = option("z", help="slicing axis of the stacked style; plates stack along it", choices=("x", "y", "z"))
    axes: str = option("xy", help="interlocked: normals of family A and family B (they cross along the third axis)",
                       choices=("xy", "yx", "xz", "zx", "yz", "zy"))
    count: int = option(5, help="interlocked: plates per family (0: one every interval)", low=0, high=64)
    interval: float = option(12.0, help="interlocked: distance between the plates of a family", unit="mm",
                             low=1.0, high=1000.0)
    radial_plates: int = option(4, help="radial: plates fanned at equal angles about the axis", low=2,
                                high=36)
    clearance: float = option(0.1, help="interlocked, radial: slot width beyond the material thickness, for the fit",
                              unit="mm", low=0.0, high=5.0)
    thickness: float = option(3.0, help="measured plate thickness", unit="mm", low=0.1, high=100.0)
    sheet: str = option("600x400", help="sheet (laser bed): a name such as laser, or WxH", unit="mm",
                        check=sheet_problem, metavar="WxH")
    margin: float = option(5.0, help="empty border of the sheet", unit="mm", low=0.0, high=1000.0)
    spacing: float = option(2.0, help="gap between parts on a sheet", unit="mm", low=0.0, high=1000.0)
    by_colour: bool = option(False, help="nest the plates of each main colour on sheets of their own, one colour "
                             "of material per sheet (a coloured shape)")
    kerf: float = option(0.0, help="laser kerf; outlines grow and holes shrink by half of it", unit="mm",
                         low=0.0, high=5.0)
    dowel: float = option(3.0, help="dowel hole diameter (0: no dowels)", unit="mm", low=0.0, high=100.0)
    dowel_margin: float = option(1.0, help="least material between a dowel hole and an edge", unit="mm",
                                 low=0.0, high=100.0)
    dowels_per_joint: int = option(2, help="most dowels between two overlapping pieces (0: none)", low=0, high=16)
    score: bool = option(True, help="score the next layer's outline as a gluing guide")
    min_width: float = option(1.0, help="narrowest cuttable feature; narrower parts are reported", unit="mm",
                              low=0.0, high=1000.0)
    dxf_version: str = dxf_version_option()
    step: bool = option(False, help="also write the plate stack as STEP and STL (needs voxfab[cad])")

    def check(self) -> None:
        """The margins must leave room on the sheet; an option of another style than the chosen one
        (``radial_plates`` of a stacked construction) is refused, not ignored; STEP is for the stacked style."""
        from voxfab._shared.options import OptionError
        from voxfab.drawing import parse_sheet

        defaults = PlateOptions.__dataclass_fields__
        for name, styles in STYLE_OPTIONS.items():
            value = getattr(self, name)
            if self.style not in styles and value != defaults[name].default:
                raise OptionError(name, f"for the {' and '.join(styles)} style{'s' if len(styles) > 1 else ''}, "
                                        f"not {self.style}; it would change nothing (got {value!r})")
        if self.step and self.style != "stacked":
            raise OptionError("step", f"STEP and STL are written for the stacked style only, not {self.style}; "
                                      "assembly.3mf holds the plates of every style")
        w, h = parse_sheet(self.sheet)
        if min(w, h) <= 2 * self.margin:
            raise OptionError("sheet", f"{self.sheet} leaves no room inside a {self.margin:g} mm margin")
