"""Checks of written slice plates from the files alone: assembly.3mf, the DXF sheets, plates.json.

``assembly.3mf`` is read with trimesh, the sheets with ezdxf, and the plates
are compared with manifold3d against the voxel solid meshed by the print
pipeline.
"""

from __future__ import annotations

import functools
import json

import ezdxf
import manifold3d
import numpy as np
import pytest
import shapely
import trimesh
from _dxf_read import closed_rings

from voxfab.fabricate.mesh import build_mesh
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import VoxelShape, examples


def _overhang() -> np.ndarray:
    """A mushroom: a stem under a cap that overhangs it on every side."""
    g = np.zeros((15, 15, 16), bool)
    g[5:10, 5:10, :10] = True
    g[:, :, 10:16] = True
    g[:4, :4, 10:16] = False
    return g


@functools.lru_cache(maxsize=1)
def construction_shapes() -> dict[str, VoxelShape]:
    """The shapes every construction is checked on, made once per test run."""
    return {
        "ball": VoxelShape(examples.ball(8), 4.0),
        "torus": VoxelShape(examples.torus(8, 3), 4.0),
        "overhang": VoxelShape(_overhang(), 4.0),
        "queen": make_shape(load_recipe("recipes/chess/queen.toml")),
        "vase": make_shape(load_recipe("recipes/vase.toml")),
    }


def manifold_of(mesh: trimesh.Trimesh) -> manifold3d.Manifold:
    m = manifold3d.Mesh(vert_properties=np.asarray(mesh.vertices, np.float32),
                        tri_verts=np.asarray(mesh.faces, np.uint32))
    return manifold3d.Manifold(m)


def voxel_solid(shape: VoxelShape) -> manifold3d.Manifold:
    """The voxel solid exactly (split contacts, no bridges), in the print frame."""
    mesh = build_mesh(shape, contacts="split").mesh
    return manifold3d.Manifold(manifold3d.Mesh(vert_properties=np.asarray(mesh.vertices, np.float32),
                                               tri_verts=np.asarray(mesh.triangles, np.uint32)))


def dxf_parts(path) -> tuple[list[float], np.ndarray]:
    """Areas of the parts cut on one DXF sheet (outer rings minus the rings inside them) and all cut points."""
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    rings = [shapely.Polygon(pts) for pts in closed_rings(doc)]
    points = np.concatenate([np.asarray(r.exterior.coords) for r in rings])
    rings.sort(key=lambda r: -r.area)
    outer: list[shapely.Polygon] = []
    areas: list[float] = []
    for r in rings:
        host = [i for i, o in enumerate(outer) if o.contains(r)]
        depth = len(host)
        if depth % 2 == 0:
            outer.append(r)
            areas.append(r.area)
        else:
            areas[host[-1]] -= r.area
            outer.append(r)
            areas.append(0.0)
    return [a for a in areas if a > 0], points


def check_written(folder, shape: VoxelShape, thickness: float, kerf: float) -> dict:
    """Check a written slotted construction from its files; return its ``plates.json``."""
    report = json.loads((folder / "plates.json").read_text())
    scene = trimesh.load(folder / "assembly.3mf", process=False, force="scene")
    meshes = {name: m for name, m in scene.geometry.items()}
    plates = report["plates_list"]
    labels = [p["label"] for p in plates]
    assert sorted(meshes) == sorted(labels) and len(meshes) == report["plates"] > 1
    # one scale: the assembly fills the print's box (origin at the shape's minimum corner, z up)
    size = np.array(report["size"])
    bounds = np.array([m.bounds for m in meshes.values()])
    assert np.all(bounds[:, 0] >= -1e-4) and np.all(bounds[:, 1] <= size + 1e-4)
    solid = voxel_solid(shape)
    solids = {}
    for p in plates:
        mesh = meshes[p["label"]]
        assert mesh.is_watertight
        # flat and one material thickness thick: every vertex on one of two parallel planes
        normal = np.cross(p["u"], p["v"])
        depth = np.asarray(mesh.vertices) @ normal
        assert np.ptp(depth) == pytest.approx(thickness, abs=1e-4)
        assert np.all(np.isclose(depth, depth.min(), atol=1e-4) | np.isclose(depth, depth.max(), atol=1e-4))
        assert mesh.volume == pytest.approx(p["area"] * thickness, rel=1e-4)
        m = manifold_of(mesh)
        solids[p["label"]] = m
        # inside the voxel solid, within one kerf (and float32 rounding)
        outside = (m - solid).volume()
        assert outside <= max(kerf, 1e-3) * p["area"] * 0.01 + 1e-3, (p["label"], outside)
    # no two plates share volume
    names = sorted(solids)
    boxes = {n: meshes[n].bounds for n in names}
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if np.any(boxes[a][1] < boxes[b][0]) or np.any(boxes[b][1] < boxes[a][0]):
                continue
            assert (solids[a] ^ solids[b]).volume() < 1e-3, (a, b)
    # the crossing graph, from the slots' partner labels, is one piece; partners touch in 3D
    parent = {n: n for n in labels}

    def find(x):
        while parent[x] != x:
            x = parent[x]
        return x

    for p in plates:
        assert p["slots"], p["label"]
        for s in p["slots"]:
            assert s["partner"] in parent
            assert s["depth"] > 0
            # partners meet at the slot's end or, at most, across the fit clearance of the slot's sides
            assert solids[p["label"]].min_gap(solids[s["partner"]], 1.0) <= report["clearance"] + 1e-3
            parent[find(p["label"])] = find(s["partner"])
    assert len({find(n) for n in labels}) == 1
    # the sheets cut the plates of the assembly: same count, same areas
    areas: list[float] = []
    width, height = report["sheet_width"], report["sheet_height"]
    for k in range(1, report["sheets"] + 1):
        a, points = dxf_parts(folder / f"sheet-{k:02d}.dxf")
        areas += a
        assert points.min() >= 0 and points[:, 0].max() <= width and points[:, 1].max() <= height
    assert len(areas) == len(plates)
    if kerf == 0:
        assert sorted(areas) == pytest.approx(sorted(p["area"] for p in plates), rel=0.01)
    return report


#: PrusaSlicer's low-poly bunny, installed with prusa-slicer: ears and a back that the slotted styles lose.
BUNNY_STL = "/usr/share/PrusaSlicer/shapes/bunny.stl"


@functools.lru_cache(maxsize=1)
def bunny() -> VoxelShape:
    """The bunny voxelized as ``voxfab slices bunny.stl`` reads it (25 voxels along its longest side)."""
    from pathlib import Path

    from voxfab.repo import load_shape

    assert Path(BUNNY_STL).is_file(), f"{BUNNY_STL} is installed with prusa-slicer (apt-get install prusa-slicer)"
    return load_shape(BUNNY_STL, None)[0]


def svg_polylines(path) -> list[tuple[np.ndarray, bool]]:
    """Points and closedness of every ``<path>`` of an SVG as voxfab writes them (M, L, Z)."""
    import re
    from xml.etree import ElementTree

    out = []
    for e in ElementTree.parse(path).getroot().iter("{http://www.w3.org/2000/svg}path"):
        d = e.get("d")
        pts = [(float(x), float(y)) for x, y in re.findall(r"[ML]\s*(-?[\d.]+),(-?[\d.]+)", d)]
        out.append((np.array(pts, float).reshape(-1, 2), d.rstrip().endswith("Z")))
    return out


def repeated_vertices(points: np.ndarray, closed: bool) -> int:
    """Zero-length segments of one written polyline: consecutive equal vertices, and the closing one."""
    same = int(np.all(points[1:] == points[:-1], axis=1).sum())
    return same + int(closed and len(points) > 1 and np.all(points[0] == points[-1]))


def pdf_polylines(path) -> list[list[np.ndarray]]:
    """The polylines of each page of a PDF as voxfab writes them (``x y m``, ``x y l`` in deflated streams)."""
    import re
    import zlib

    data = path.read_bytes()
    pages = []
    for m in re.finditer(rb"/Filter /FlateDecode >>\nstream\n", data):
        start = m.end()
        end = data.index(b"\nendstream", start)
        text = zlib.decompress(data[start:end]).decode("latin-1")
        lines: list[list[tuple[float, float]]] = []
        for x, y, op in re.findall(r"(-?[\d.]+) (-?[\d.]+) ([ml])\n", text):
            if op == "m":
                lines.append([])
            lines[-1].append((float(x), float(y)))
        pages.append([np.array(line) for line in lines])
    return pages


def draws_text(lines: list[np.ndarray], text: str) -> bool:
    """Whether consecutive ``lines`` draw ``text`` in voxfab's stroke font, at some size and place, reading right."""
    from voxfab.drawing import text_polylines

    ref = text_polylines([text.replace(" ", "")], [(0.0, 0.0)], [(1.0, 0.0)], 1.0).lines()
    counts = [len(r) for r in ref]
    flat = np.concatenate(ref) - ref[0][0]
    span = np.ptp(flat[:, 0])
    for i in range(len(lines) - len(ref) + 1):
        window = lines[i:i + len(ref)]
        if [len(w) for w in window] != counts:
            continue
        pts = np.concatenate(window) - window[0][0]
        scale = np.ptp(pts[:, 0]) / span
        if scale > 0 and np.allclose(pts, flat * scale, atol=0.01 + 0.01 * scale):
            return True
    return False
