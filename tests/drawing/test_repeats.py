"""No written polyline has a zero-length segment: cutters stall on repeated vertices."""

from __future__ import annotations

import ezdxf
import numpy as np
import shapely
from _dxf_read import polylines
from _plate_checks import bunny, repeated_vertices, svg_polylines
from hypothesis import given
from hypothesis import strategies as st

from voxfab.drawing import Page, Polylines, write_drawing
from voxfab.drawing._model import Drawing


def _written(folder) -> list[tuple[np.ndarray, bool]]:
    """Every polyline of the DXF and SVG files under ``folder``, as re-read."""
    out = []
    for f in sorted(folder.rglob("*.dxf")):
        out += [(pts, closed) for _, pts, closed in polylines(ezdxf.readfile(f))]
    for f in sorted(folder.rglob("*.svg")):
        out += svg_polylines(f)
    return out


def test_repeated_vertices_are_dropped_from_every_written_format(tmp_path) -> None:
    square = np.array([[0, 0], [0, 0], [10, 0], [10, 10.00001], [10, 10], [0, 10], [0, 0]], float)
    dot = np.array([[5, 5], [5, 5]], float)
    page = Page(50.0, 50.0, layers={"CUT": Polylines.from_list([square], [True]),
                                    "LABEL": Polylines.from_list([dot, square[:3]], [False, False])})
    write_drawing(Drawing((page,)), tmp_path / "p.dxf")
    write_drawing(Drawing((page,)), tmp_path / "p.svg")
    lines = _written(tmp_path)
    assert len(lines) == 4  # the ring and the open stroke, in each file; the point is gone
    for pts, closed in lines:
        assert repeated_vertices(np.round(pts, 3), closed) == 0
        if closed:
            assert shapely.Polygon(pts).area == abs(shapely.Polygon(square).area)


def test_no_written_outline_of_plates_or_nets_repeats_a_vertex(tmp_path) -> None:
    from voxfab.fabricate.plates import PlateOptions, fabricate_plates
    from voxfab.shape import examples
    from voxfab.unfold import unfold

    shape = bunny()  # the radial bunny's R2 and R4 repeated vertices
    for style in ("radial", "stacked"):
        fabricate_plates(shape, PlateOptions(style=style), tmp_path / style, name="bunny")
    from voxfab.fabricate.netdraw import DrawingOptions, write_net_drawing

    ball = examples.ball(3)
    net = unfold(ball, rng=2, timeout=30.0)
    for ext in ("svg", "dxf"):
        write_net_drawing(ball, net, tmp_path / "net" / f"ball.{ext}", DrawingOptions(),
                          title="ball")
    lines = _written(tmp_path)
    assert len(lines) > 100
    # as re-read (ezdxf gives the 4 decimals written, the SVG 3)
    assert [repeated_vertices(pts, closed) for pts, closed in lines if repeated_vertices(pts, closed)] == []


@given(st.lists(st.tuples(st.lists(st.tuples(st.integers(0, 3), st.integers(0, 3)), max_size=8), st.booleans()),
                max_size=6))
def test_without_repeats_keeps_every_other_vertex_in_order(lines) -> None:
    """Any polylines, empty and one-point ones among them: no two consecutive vertices (nor a closed polyline's
    last and first) are equal afterwards, and the distinct runs of vertices are kept, in order."""
    arrays = [np.array(pts, float).reshape(-1, 2) / 1000.0 for pts, _ in lines]  # 1 µm steps: some print alike
    before = Polylines.from_list(arrays, [c for _, c in lines]) if lines else Polylines.empty()
    after = before.without_repeats()
    expected = []
    for a, (_, closed) in zip(arrays, lines):
        q = np.round(a, 3)
        runs = [p for i, p in enumerate(q.tolist()) if i == 0 or p != q[i - 1].tolist()]
        if closed and len(runs) > 1 and runs[-1] == runs[0]:
            runs.pop()
        if len(runs) >= 2:
            expected.append((runs, closed))
    got = [(np.round(x, 3).tolist(), bool(c)) for x, c in zip(after.lines(), after.closed)]
    assert got == expected
