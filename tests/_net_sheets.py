"""Reading a net in pieces back from its written files: the pieces' JSON and the sheets' DXF outlines."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from voxfab.shape import surface_graph
from voxfab.unfold import Net, validate


def queen() -> np.ndarray:
    """The bundled queen's grid."""
    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape

    return make_shape(load_recipe(Path(__file__).parents[1] / "recipes/chess/queen.toml")).grid


def read_pieces(folder: Path, grid: np.ndarray) -> list[Net]:
    """The ``net.piece-N.json`` files of ``folder``, checked: every face of ``grid`` once, and they refold."""
    pieces = [Net.from_json(p.read_text()) for p in sorted(folder.glob("net.piece-*.json"))]
    assert len(pieces) > 1, "the surface is larger than the sheet"
    keys = [(tuple(v), tuple(n)) for p in pieces for v, n in zip(p.voxel.tolist(), p.normal.tolist())]
    assert len(keys) == len(set(keys)) == surface_graph(grid).face_count
    assert validate(grid, pieces).ok
    return pieces


def pieces_of(rings: list[np.ndarray]) -> list:
    """Polygons of the pieces on a sheet from its closed CUT rings: outer rings run counter-clockwise,
    holes clockwise, and each hole belongs to the smallest outer ring round all of it (a piece may lie in
    a hole of another, and a point of the hole may then lie in that piece)."""
    import shapely

    outers = [shapely.Polygon(r) for r in rings if shapely.LinearRing(r).is_ccw]
    holes: list[list[np.ndarray]] = [[] for _ in outers]
    for r in rings:
        if shapely.LinearRing(r).is_ccw:
            continue
        hole = shapely.Polygon(r)
        around = [i for i, o in enumerate(outers) if o.covers(hole)]
        holes[min(around, key=lambda i: outers[i].area)].append(r)
    return [shapely.Polygon(o.exterior.coords, h) for o, h in zip(outers, holes)]
