"""The colour of a mesh's surface, given to the voxels made from it: each voxel takes the nearest surface's colour.

A mesh carries colour three ways, all read through trimesh's visuals: a colour per
face, a colour per vertex (blended across each triangle), or a texture image with a
UV per vertex (sampled where each point of a triangle falls in the image).  The
surface is sampled on a lattice of points per triangle, finer than half a voxel, and
every filled voxel takes the colour of the sample nearest its centre (a k-d tree), so
a voxel under a painted stripe takes the stripe's colour whatever the triangle sizes.
Voxel art is limited to a palette of 255 colours: more distinct colours (a texture)
are merged in CIELAB to the 255 that cover the surface best.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.shape import VoxelColours

__all__ = ["surface_samples", "voxel_colours"]

#: Samples per triangle at most: a few long triangles must not make millions of points.
_MAX_SAMPLES_PER_TRIANGLE = 2_000
#: Samples per mesh at most.
_MAX_SAMPLES = 2_000_000


def _lattice(k: int) -> npt.NDArray[np.float64]:
    """Barycentric coordinates of a triangular lattice of ``k`` steps per side (centres of its cells)."""
    i, j = np.meshgrid(np.arange(k), np.arange(k), indexing="ij")
    keep = i + j < k
    a = (i[keep] + 1 / 3) / k
    b = (j[keep] + 1 / 3) / k
    return np.stack([1 - a - b, a, b], axis=1)


def surface_samples(loaded: Any, vertices: np.ndarray, faces: np.ndarray, spacing: float
                    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.uint8]] | None:
    """Points on the surface and their RGBA, or None for a mesh without colours.

    Parameters
    ----------
    loaded : trimesh.Trimesh
        The mesh as loaded (its ``visual`` holds the colours).
    vertices, faces : arrays
        Its vertices and triangles.
    spacing : float
        The largest distance between samples on a triangle (half a voxel).
    """
    visual = getattr(loaded, "visual", None)
    kind = getattr(visual, "kind", None)
    if kind is None:
        return None
    tri = vertices[faces]
    longest = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)
    steps = np.clip(np.ceil(longest / spacing), 1, int(math.isqrt(2 * _MAX_SAMPLES_PER_TRIANGLE))).astype(int)
    while (steps * (steps + 1) // 2).sum() > _MAX_SAMPLES and steps.max() > 1:
        steps = np.maximum(1, steps // 2)
    points, colours = [], []
    for k in np.unique(steps):
        which = np.flatnonzero(steps == k)
        bary = _lattice(int(k))
        points.append(np.einsum("pc,fcd->fpd", bary, tri[which]).reshape(-1, 3))
        colours.append(_colour_at(visual, kind, faces, which, bary).reshape(-1, 4))
    return np.concatenate(points), np.concatenate(colours)


def _colour_at(visual: Any, kind: str, all_faces: np.ndarray, rows: np.ndarray, bary: np.ndarray) -> np.ndarray:
    """RGBA ``(F, P, 4)`` at barycentric points ``bary`` of the triangles ``all_faces[rows]``."""
    faces = all_faces[rows]
    if kind == "texture":
        uv = getattr(visual, "uv", None)
        image = getattr(getattr(visual, "material", None), "image", None)
        if image is None:
            image = getattr(getattr(visual, "material", None), "baseColorTexture", None)
        if uv is not None and image is not None:
            pixels = np.asarray(image.convert("RGBA"))
            h, w = pixels.shape[:2]
            at = np.einsum("pc,fcd->fpd", bary, np.asarray(uv, dtype=np.float64)[faces])
            # UVs wrap around, and v runs up the image.
            col = np.floor((at[..., 0] % 1.0) * w).astype(int).clip(0, w - 1)
            row = np.floor((1.0 - at[..., 1] % 1.0) * h).astype(int).clip(0, h - 1)
            return pixels[row, col]
        visual = visual.to_color()
        kind = "vertex"
    if kind == "vertex":
        per_vertex = np.asarray(visual.vertex_colors, dtype=np.float64)[faces]
        return np.einsum("pc,fcd->fpd", bary, per_vertex).round().astype(np.uint8)
    per_face = np.asarray(visual.face_colors, dtype=np.uint8)[rows]
    return np.repeat(per_face[:, None, :], len(bary), axis=1)


def voxel_colours(grid: np.ndarray, origin: np.ndarray, pitch: float,
                  points: np.ndarray, rgba: np.ndarray) -> tuple[VoxelColours, list[str]]:
    """Each filled voxel's colour: the colour of the surface sample nearest its centre.

    ``origin`` is the position of the low corner of voxel ``[0, 0, 0]`` and ``pitch`` the
    voxel size, in the mesh's units.  Returns the colours and notes (colours merged).
    """
    from scipy.spatial import cKDTree

    filled = np.argwhere(grid)
    centres = origin + (filled + 0.5) * pitch
    _, nearest = cKDTree(points).query(centres)
    voxel_rgba = np.asarray(rgba, dtype=np.uint8)[nearest]
    voxel_rgba[:, 3] = 255  # a print, a net and a picture are opaque
    notes: list[str] = []
    distinct = np.unique(voxel_rgba, axis=0)
    if len(distinct) > 255:
        voxel_rgba = _merged(voxel_rgba, 255)
        notes.append(f"{len(distinct)} surface colours merged to the 255 a voxel palette holds")
    full = np.zeros((*grid.shape, 4), dtype=np.uint8)
    full[tuple(filled.T)] = voxel_rgba
    return VoxelColours.from_rgba(grid, full), notes


def _merged(rgba: np.ndarray, count: int) -> np.ndarray:
    """``rgba`` with its colours replaced by ``count`` representatives, by k-means in CIELAB (seeded)."""
    from scipy.cluster.vq import kmeans2

    from voxfab.shape import srgb_to_lab

    colours, inverse, weight = np.unique(rgba, axis=0, return_inverse=True, return_counts=True)
    lab = srgb_to_lab(colours)
    # The most common colours start the clusters, so the result never depends on chance.
    start = lab[np.argsort(-weight, kind="stable")[:count]]
    _, label = kmeans2(np.repeat(lab, weight, axis=0), start, minit="matrix", iter=10)
    # Each cluster is drawn in the most common colour it holds.
    first = np.cumsum(weight) - weight
    cluster_of = label[first]
    best = {}
    for c, (w, colour) in zip(cluster_of, zip(weight, colours)):
        if c not in best or w > best[c][0]:
            best[c] = (w, colour)
    representative = np.array([best[c][1] for c in cluster_of], dtype=np.uint8)
    return representative[inverse.reshape(-1)]
