"""Dense pages: pieces packed several to a sheet, checked from the written files only.

For each shape the test reads the pieces' JSON and the DXF sheets and checks,
by its own measures: every face once, the pieces refold, no piece meets
another or leaves the margin, the sheets against ``ceil(1.25 A / U)`` (A the
paper inside the cut outlines, U a sheet less its margins and title band), and
the glue tabs against the seams.  The goal is that bound and a tab at every
seam; each case says how many sheets over the bound the packing was measured
at (so a worse packing fails), and seams without a tab stay under 1 % of the
faces.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from _net_sheets import pieces_of, queen, read_pieces

from voxfab.shape import examples, fill_cavities


def _entities(path: Path):
    import ezdxf

    rings, segments = [], []
    for e in ezdxf.readfile(path).modelspace():
        kind = e.dxftype()
        if kind in ("POLYLINE", "LWPOLYLINE"):
            pts = [tuple(v.dxf.location)[:2] for v in e.vertices] if kind == "POLYLINE" else \
                [tuple(p)[:2] for p in e.get_points()]
            if e.dxf.layer == "CUT" and e.is_closed:
                rings.append(np.array(pts))
            elif e.dxf.layer in ("MOUNTAIN", "VALLEY"):
                segments += [(np.array(a), np.array(b)) for a, b in zip(pts[:-1], pts[1:])]
        elif kind == "LINE" and e.dxf.layer in ("MOUNTAIN", "VALLEY"):
            segments.append((np.array(tuple(e.dxf.start)[:2]), np.array(tuple(e.dxf.end)[:2])))
    return rings, segments


#: name, shape, face size, sheet, and sheets over ceil(1.25 A / U) as measured.
CASES = [
    ("ball r=6", lambda: examples.ball(6), 10.0, "A4", 1),
    ("torus", lambda: examples.torus(7.0, 3.0), 10.0, "mat12", 1),
    ("tunnel cube", lambda: examples.tunnel_cube(9), 10.0, "A4", 2),
    ("queen", queen, 8.6, "mat12", 1),
]


@pytest.mark.parametrize(("name", "make", "face", "sheet", "over"), CASES, ids=[c[0] for c in CASES])
def test_dense_pages_read_back_from_the_files(sheet_net, name, make, face, sheet, over) -> None:

    grid = fill_cavities(make())
    folder, made, drawing = sheet_net(name, grid, face, sheet)
    pieces = read_pieces(folder, grid)
    faces = sum(p.face_count for p in pieces)
    sheets = sorted(folder.glob("net.sheet-*.dxf"))
    assert len(sheets) == made.report["sheets"]
    w, h = drawing.sheet_size
    m = drawing.margin
    paper = 0.0
    outer = 0
    tabs = 0
    inset = min(0.5, 0.05 * face)
    for path in sheets:
        rings, segments = _entities(path)
        shells = pieces_of(rings)
        outer += len(shells)
        for i, a in enumerate(shells):
            x0, y0, x1, y1 = a.bounds
            assert x0 >= m - 1e-6 and y0 >= m - 1e-6 and x1 <= w - m + 1e-6 and y1 <= h - m + 1e-6
            for b in shells[i + 1:]:
                assert a.intersection(b).area < 1e-6
            paper += a.area
        # A tab's fold is a face edge less the inset at both ends; folds between faces are whole edges.
        lengths = np.array([np.linalg.norm(b - a) for a, b in segments])
        tabs += int(np.count_nonzero(np.abs(lengths - (face - 2 * inset)) < 1e-3))
    assert outer == len(pieces)
    # Seams: surface edges (2 per face) less the folds of every piece (which include edges closed in the plane).
    seams = 2 * faces - sum(int(p.folds.shape[0]) for p in pieces)
    assert tabs <= seams
    assert seams - tabs <= 0.01 * faces, f"{seams - tabs} seams without a tab"
    usable = (w - 2 * m) * (h - 2 * m - (drawing.title_height + 2.0))
    assert len(sheets) <= math.ceil(1.25 * paper / usable) + over, (len(sheets), paper / usable)
