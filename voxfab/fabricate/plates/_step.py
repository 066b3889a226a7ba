"""3D plates with build123d: STEP (exact B-rep, true circles) and STL.

build123d takes seconds to import, so it is imported only here, inside the
functions.  Plates sit in the stack frame: ``(u, v)`` as on the sheets, the
stack axis up, plate 1 on ``z = 0``.
"""

from __future__ import annotations

import itertools
import os
import re
import tempfile
from pathlib import Path

from voxfab._shared.atomic import write_bytes
from voxfab._shared.progress import progress
from voxfab._shared.typing import PathLike
from voxfab.errors import FabricationError

from ._stack import Plate, PlateStack

_NAUO = re.compile(r"(NEXT_ASSEMBLY_USAGE_OCCURRENCE\()'\d+'")

#: Fixed STEP header time stamp, so equal stacks give equal files.
STEP_TIMESTAMP = "2000-01-01T00:00:00"


def _bd():
    from voxfab._shared.deps import require_extra

    require_extra("cad", "STEP and STL plates (--step)")
    import build123d

    return build123d


def plate_solid(plate: Plate) -> object:
    """One plate as a build123d Solid (mm, in the stack frame)."""
    bd = _bd()
    z = plate.z

    def wire(coords) -> object:
        return bd.Wire.make_polygon([bd.Vector(float(x), float(y), z) for x, y in list(coords)[:-1]], close=True)

    outer = wire(plate.outline.exterior.coords)
    inner = [wire(r.coords) for r in plate.outline.interiors]
    r = plate.hole_diameter / 2.0
    for x, y in plate.holes:
        inner.append(bd.Wire.make_circle(r, bd.Plane(origin=(float(x), float(y), z))))
    face = bd.Face(outer, inner)
    solid = bd.extrude(face, amount=plate.thickness)
    solid.label = f"plate {plate.number} ({plate.label.text})"
    return solid


def stack_compound(stack: PlateStack) -> object:
    """All plates as one build123d Compound."""
    bd = _bd()
    return bd.Compound(children=[plate_solid(p) for p in progress(stack.plates, desc="3D plates")])


def step_bytes(stack: PlateStack, *, compound: object | None = None) -> bytes:
    """The plate stack as STEP (AP214, mm) bytes.

    ``compound`` may pass the result of :func:`stack_compound` to reuse it.
    """
    import io

    bd = _bd()
    buf = io.BytesIO()
    if not bd.export_step(compound if compound is not None else stack_compound(stack), buf, timestamp=STEP_TIMESTAMP):
        raise FabricationError("STEP export of the plate stack failed")
    # OCC numbers assembly usages with a process-wide counter: renumber from 1
    counter = itertools.count(1)
    return _NAUO.sub(lambda m: f"{m.group(1)}'{next(counter)}'", buf.getvalue().decode("latin-1")).encode("latin-1")


def write_step(stack: PlateStack, path: PathLike, *, compound: object | None = None) -> None:
    """Write the plate stack as STEP to ``path`` (atomically)."""
    write_bytes(path, step_bytes(stack, compound=compound))


def write_stl(stack: PlateStack, path: PathLike, *, tolerance: float = 0.01, compound: object | None = None) -> None:
    """Write the plate stack as binary STL to ``path`` (atomically).

    ``tolerance`` is the chord error in mm of the tessellated dowel holes;
    ``compound`` may pass the result of :func:`stack_compound` to reuse it.
    """
    bd = _bd()
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=".stl", dir=target.parent)
    os.close(fd)
    try:
        if not bd.export_stl(compound if compound is not None else stack_compound(stack), tmp, tolerance=tolerance):
            raise FabricationError("STL export of the plate stack failed")
        data = Path(tmp).read_bytes()
    finally:
        os.unlink(tmp)
    write_bytes(target, data)
