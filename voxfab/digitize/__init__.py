"""Shape makers: k-flake digitization, surfaces of revolution, swept tubes, focal shapes.

Heavy helpers (scipy, numba, svgelements, pillow) are imported only when used.
"""

from ._curves import (
    Curve2D,
    OpenCurve,
    bitmap_curve,
    implicit_curve,
    load_curve,
    open_star_curve,
    polyline_curve,
)
from ._expr import Expression, compile_expression
from ._fit import Field, Mode, fit
from ._flake import digitize, flake_vertices, solid, surface
from ._focal import fermat_weber, focal, focal_field
from ._implicit import implicit, implicit_field
from ._makers import (
    MAKERS,
    Maker,
    Param,
    available_makers,
    get_maker,
    get_random_params,
    maker_markdown,
    maker_params,
    random_makers,
)
from ._recipes import rounded_param
from ._revolution import (
    RevolutionCurve,
    Run,
    load_revolution_curve,
    revolution,
    revolution_field,
    slices,
    split_runs,
)
from ._tube import Cap, Frame, Spine, load_spine, spine_frames, tube, tube_field, tube_rotations

__all__ = [
    "MAKERS",
    "Maker",
    "Param",
    "available_makers",
    "get_maker",
    "get_random_params",
    "maker_markdown",
    "maker_params",
    "random_makers",
    "rounded_param",
    "surface",
    "solid",
    "digitize",
    "flake_vertices",
    "Expression",
    "compile_expression",
    "Curve2D",
    "OpenCurve",
    "open_star_curve",
    "load_curve",
    "implicit_curve",
    "polyline_curve",
    "bitmap_curve",
    "Field",
    "Mode",
    "fit",
    "RevolutionCurve",
    "Run",
    "load_revolution_curve",
    "split_runs",
    "revolution_field",
    "revolution",
    "slices",
    "Frame",
    "Cap",
    "Spine",
    "load_spine",
    "spine_frames",
    "tube_field",
    "tube",
    "tube_rotations",
    "focal_field",
    "focal",
    "fermat_weber",
    "implicit_field",
    "implicit",
]
