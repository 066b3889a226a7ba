"""The options of a print mesh, declared once (CLI flags, recipe keys, checks, README table)."""

from __future__ import annotations

import dataclasses

from voxfab._shared.options import Options, option

from ._colours import MAX_FILAMENTS

#: Longest print side accepted, mm (a room-sized object is a typo, not a print).
MAX_SIZE = 10_000.0


def _magnet_problem(value: str | None) -> str | None:
    """Why a magnet spec ``"DxH"`` is not usable, or None."""
    if value is None:
        return None
    from ._build import parse_magnet

    try:
        d, h = parse_magnet(value)
    except ValueError:
        return "expected DIAMETERxDEPTH in mm such as 6x3"
    if d > 1000 or h > 1000:
        return "expected a pocket under 1000 mm"
    return None


@dataclasses.dataclass(frozen=True)
class MeshOptions(Options):
    """How a shape becomes a print-ready solid (see :func:`build_mesh`).

    The scale is the shape's pitch (mm per voxel) unless ``size`` is given.
    """

    format: str = option("3mf", help="file format of the recipe output mesh.FORMAT",
                         choices=("3mf", "stl", "obj", "glb", "ply"), cli=False)
    size: float | None = option(None, help="length of the longest side, instead of the shape's pitch",
                                unit="mm", low=0.0, low_open=True, high=MAX_SIZE)
    contacts: str = option("bridge", help="voxels touching only along an edge or at a corner: bridge them, "
                           "keep separate shells, or refuse (error also refuses a print in several parts)",
                           choices=("bridge", "split", "error"))
    bridge_width: float | None = option(None, help="width of contact bridges (default 1 mm, at most 0.6 x pitch)",
                                        unit="mm", low=0.0, low_open=True, high=1000.0)
    solid: bool = option(True, help="fill enclosed cavities (a solid print)", flag="--keep-cavities",
                         negate=True, flag_help="do not fill enclosed cavities")
    hollow: int = option(0, help="hollow with walls N voxels thick and a drain hole per cavity (0: solid)",
                         unit="voxels", low=0, high=128)
    label: str | None = option(None, help="text engraved on the bottom ({name}: the shape's name)")
    engrave_depth: float = option(0.6, help="depth of the label", unit="mm", low=0.0, low_open=True, high=100.0)
    base: float = option(0.0, help="flat base plate under the footprint (0: none)", unit="mm", low=0.0,
                         high=1000.0)
    magnet: str | None = option(None, help="round magnet pocket in the bottom, DIAMETERxDEPTH such as 6x3",
                                unit="mm", check=_magnet_problem, metavar="DxH")
    merge: bool = option(True, help="merge coplanar faces (off: two triangles per voxel face)",
                         flag="--no-merge", negate=True,
                         flag_help="two triangles per voxel face (no coplanar merging)")
    infill: float = option(20.0, help="sparse infill the filament, mass and print-time estimates assume "
                           "(PLA, 0.3 mm layers, 3 perimeters)", unit="%", low=0.0, high=100.0)
    colours: int | None = option(None, help="filaments of a coloured print: merge the shape's colours to N perceptually "
                                 "(CIELAB, weighted by visible area); default one per colour, at most 16 in a 3MF",
                                 unit="filaments", low=1, high=MAX_FILAMENTS, metavar="N")
    spin: bool = option(False, help="check the print as a spinning top: a single tip under the centre of mass, "
                        "wide rather than tall in its mass")

    def check(self) -> None:
        """A label needs some text."""
        if self.label is not None and not self.label.strip():
            from voxfab._shared.options import OptionError

            raise OptionError("label", "expected some text, got an empty string")
