"""Independent checks of coloured mesh files, for the colour tests: no code shared with voxfab.

A 3MF is read with zipfile and xml.etree; the voxel under a triangle is found from
its points and normal by plain arithmetic; PrusaSlicer's painting codes are derived
from their bit layout.
"""

from __future__ import annotations

import zipfile
from xml.etree import ElementTree as ET

import numpy as np

CORE = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
SLIC3RPE = "{http://schemas.slic3r.org/3mf/2017/06}"
#: Points of each triangle tested, barycentric: its centroid and one near each corner.
SAMPLES = np.array([[1 / 3, 1 / 3, 1 / 3], [0.8, 0.1, 0.1], [0.1, 0.8, 0.1], [0.1, 0.1, 0.8]])


def hexed(rgb) -> str:
    return "#" + "".join(f"{int(c):02x}" for c in rgb[:3])


def painting_code(extruder: int) -> str:
    """PrusaSlicer's code of a whole triangle painted with ``extruder``, from its bit layout: two bits of
    split sides (none), then the state in two bits when below 3, else 0b11 and the state minus 3 in
    four bits; the bits fill hex digits from the lowest, and the digits are written last first."""
    bits = [0, 0]
    if extruder < 3:
        bits += [extruder & 1, extruder >> 1]
    else:
        bits += [1, 1] + [((extruder - 3) >> i) & 1 for i in range(4)]
    digits = [sum(b << i for i, b in enumerate(bits[k:k + 4])) for k in range(0, len(bits), 4)]
    return "".join(f"{d:X}" for d in reversed(digits))


def read_3mf(path):
    """Per object: vertices, triangles, each triangle's displaycolor, mmu_segmentation and paint_color."""
    with zipfile.ZipFile(path) as z:
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    groups = {g.get("id"): [b.get("displaycolor").lower() for b in g.findall(f"{CORE}base")]
              for g in root.iter(f"{CORE}basematerials")}
    objects = []
    for obj in root.iter(f"{CORE}object"):
        v = np.array([[float(e.get(k)) for k in "xyz"] for e in obj.iter(f"{CORE}vertex")])
        tris = list(obj.iter(f"{CORE}triangle"))
        t = np.array([[int(e.get(k)) for k in ("v1", "v2", "v3")] for e in tris])
        assert obj.get("pid") in groups and int(obj.get("pindex")) < len(groups[obj.get("pid")])
        colour = [groups[e.get("pid", obj.get("pid"))][int(e.get("p1", obj.get("pindex")))] for e in tris]
        mmu = [e.get(f"{SLIC3RPE}mmu_segmentation") for e in tris]
        bambu = [e.get("paint_color") for e in tris]
        objects.append((v, t, colour, mmu, bambu))
    return objects


def edges_closed(t: np.ndarray) -> bool:
    """Each directed edge once, and its reverse once: a closed, consistently wound surface."""
    directed = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    keys = {tuple(e) for e in directed.tolist()}
    return len(keys) == len(directed) and all((b, a) in keys for a, b in keys)


def voxel_colours(rgba: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The filled voxels cropped to their box (the mesh's frame) and each voxel's ``#rrggbb``."""
    filled = rgba[..., 3] > 0
    nz = np.nonzero(filled)
    box = tuple(slice(a.min(), a.max() + 1) for a in nz)
    crop = rgba[box]
    hexes = np.full(crop.shape[:3], "", dtype=object)
    for idx in zip(*np.nonzero(crop[..., 3] > 0)):
        hexes[idx] = hexed(crop[idx])
    return crop[..., 3] > 0, hexes


def check_triangle_colours(v, t, colour, hexes, filled, pitch, printed_as, *, z0=0.0):
    """Every sampled point of each triangle, pushed just inside along the normal, lies in a voxel printed
    in the triangle's colour; a point over an empty voxel (a bridge) in a colour of a voxel beside it.

    ``printed_as`` maps each voxel colour to the filament colour it is printed with.  Returns the number
    of triangles found on voxel faces and off them.
    """
    on_voxels = off = 0
    shape = np.array(filled.shape)
    voxels = np.argwhere(filled)
    for tri, got in zip(v[t], colour):
        n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
        n /= np.linalg.norm(n)
        points = SAMPLES @ tri - n * 1e-3 * pitch - np.array([0, 0, z0])
        cells = np.floor(points / pitch).astype(int)
        all_filled = True
        for c in cells:
            if (c >= 0).all() and (c < shape).all() and filled[tuple(c)]:
                assert printed_as[hexes[tuple(c)]] == got, (tri, c, hexes[tuple(c)], got)
                continue
            all_filled = False
            lo, hi = np.clip(c - 1, 0, shape - 1), np.clip(c + 1, 0, shape - 1) + 1
            near = {printed_as[h] for h in hexes[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].ravel() if h}
            # Off the voxels and their neighbours (a base plate): the nearest filled voxel's colours.
            d = np.linalg.norm(voxels - np.clip(c, 0, shape - 1), axis=1)
            near |= {printed_as[hexes[tuple(x)]] for x in voxels[d <= d.min() + 1e-9]}
            assert got in near, (tri, c, got, near)
        on_voxels += all_filled
        off += not all_filled
    return on_voxels, off


def printed_as_map(report) -> dict[str, str]:
    """mesh.json's filaments as voxel colour -> filament colour."""
    out = {}
    for f in report["colours"]["filaments"]:
        out[f["colour"]] = f["colour"]
        out.update({m: f["colour"] for m in f["merged"]})
    return out
