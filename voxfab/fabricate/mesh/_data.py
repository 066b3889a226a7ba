"""The mesh value passed between the builder, the checker and the writers."""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt


@dataclasses.dataclass(frozen=True, eq=False)
class MeshData:
    """An indexed triangle mesh in millimetres, grouped into printable parts.

    Attributes
    ----------
    vertices : (V, 3) float64 ndarray
        Vertex positions in mm.  Two vertices may share a position (a split
        vertex where voxels touch only along an edge or at a corner).
    triangles : (T, 3) int64 ndarray
        Vertex indices, counter-clockwise seen from outside.
    part : (T,) int64 ndarray
        Part of each triangle, ``0..P-1``: one part is one solid (its outer
        shell and the shells of its enclosed cavities).
    colour : (T,) int64 ndarray or None
        For a coloured mesh, the row of ``palette`` of each triangle: the colour
        of the voxel whose face it lies on.
    palette : (K, 4) uint8 ndarray or None
        For a coloured mesh, the RGBA of each colour (for a print, one row per
        filament in extruder order).
    """

    vertices: npt.NDArray[np.float64]
    triangles: npt.NDArray[np.int64]
    part: npt.NDArray[np.int64]
    colour: npt.NDArray[np.int64] | None = None
    palette: npt.NDArray[np.uint8] | None = None

    def __post_init__(self) -> None:
        for name in ("vertices", "triangles", "part", "colour", "palette"):
            if getattr(self, name) is None:
                continue
            a = np.ascontiguousarray(getattr(self, name))
            a.flags.writeable = False
            object.__setattr__(self, name, a)

    @property
    def part_count(self) -> int:
        """Number of parts P."""
        return int(self.part.max()) + 1 if self.part.size else 0

    def part_mesh(self, p: int) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
        """Vertices and triangles of part ``p`` alone, re-indexed from 0 in vertex order."""
        tris = self.triangles[self.part == p]
        used = np.unique(tris)
        return self.vertices[used], np.searchsorted(used, tris)

    @property
    def coloured(self) -> bool:
        """Whether the triangles carry colours."""
        return self.colour is not None and self.palette is not None

    def bounds(self) -> npt.NDArray[np.float64]:
        """``(2, 3)`` minimum and maximum corner in mm."""
        used = self.vertices[np.unique(self.triangles)]
        return np.stack([used.min(axis=0), used.max(axis=0)])


def shell_labels(triangles: npt.NDArray[np.int64], vertex_count: int) -> tuple[npt.NDArray[np.int64], int]:
    """Label the triangles by connected shell (triangles sharing a vertex index).

    Returns
    -------
    labels : (T,) int64 ndarray
        Shell of each triangle, numbered by first appearance.
    n : int
        Number of shells.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    t = triangles.shape[0]
    if t == 0:
        return np.zeros(0, dtype=np.int64), 0
    rows = np.repeat(np.arange(t), 3)
    cols = t + triangles.ravel()
    n_nodes = t + vertex_count
    m = coo_matrix((np.ones(rows.size, dtype=np.int8), (rows, cols)), shape=(n_nodes, n_nodes))
    _, labels = connected_components(m, directed=False)
    tri_labels = labels[:t]
    _, first, inverse = np.unique(tri_labels, return_index=True, return_inverse=True)
    order = np.argsort(np.argsort(first))
    return order[inverse].astype(np.int64), int(first.size)


def signed_volumes(
    vertices: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64], labels: npt.NDArray[np.int64], n: int
) -> npt.NDArray[np.float64]:
    """Signed volume enclosed by each labelled shell (positive when facing outward), mm³."""
    # Relative to a point near the mesh keeps the sums well conditioned far from the origin.
    ref = vertices.mean(axis=0) if vertices.size else np.zeros(3)
    a = vertices[triangles[:, 0]] - ref
    b = vertices[triangles[:, 1]] - ref
    c = vertices[triangles[:, 2]] - ref
    v = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    return np.bincount(labels, weights=v, minlength=n)


def parts_from_shells(vertices: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """Group shells into parts: each outward shell with the inward shells it encloses.

    An inward (cavity) shell joins the smallest outward shell whose bounding
    box contains its own.  Used for meshes that come back from CAD booleans,
    where voxel labels are no longer known.
    """
    labels, n = shell_labels(triangles, vertices.shape[0])
    if n <= 1:
        return np.zeros(triangles.shape[0], dtype=np.int64)
    vol = signed_volumes(vertices, triangles, labels, n)
    lo = np.full((n, 3), np.inf)
    hi = np.full((n, 3), -np.inf)
    pts = vertices[triangles].reshape(-1, 3)
    lab3 = np.repeat(labels, 3)
    for axis in range(3):
        np.minimum.at(lo[:, axis], lab3, pts[:, axis])
        np.maximum.at(hi[:, axis], lab3, pts[:, axis])
    outer = np.flatnonzero(vol > 0)
    owner = np.full(n, -1, dtype=np.int64)
    owner[outer] = outer
    for s in np.flatnonzero(vol <= 0):
        inside = outer[(lo[outer] <= lo[s]).all(axis=1) & (hi[outer] >= hi[s]).all(axis=1)]
        owner[s] = inside[np.argmin(vol[inside])] if inside.size else s
    _, part = np.unique(owner, return_inverse=True)
    # Number parts by first triangle so the order follows the mesh.
    _, first, inv = np.unique(part[labels], return_index=True, return_inverse=True)
    return np.argsort(np.argsort(first))[inv].astype(np.int64)
