"""Meshes ``.stl``, ``.obj``, ``.ply``, ``.3mf`` (read): a shape extracted from reality.

A mesh is voxelized so that its longest side spans ``resolution`` voxels:

1. the voxel grid covers the mesh's bounding box, centred on it;
2. a voxel is filled when its centre is inside the mesh.  The inside test counts
   the crossings of rays along +x, +y and +z (ray parity) and takes the majority of
   the three answers, so a hole in a mesh that is not watertight, or a ray grazing
   an edge, spoils at most one of three votes;
3. enclosed cavities are filled (the shape is solid) and only the largest
   6-connected piece is kept; the notes say what was dropped and filled;
4. when stray pieces were dropped, the mesh parts of the kept piece are
   voxelized again, so that the kept piece spans ``resolution`` voxels.

``pitch`` is the voxel size in the mesh's units (millimetres for STL and 3MF as
usually written; a glTF's metres and y-up are turned into millimetres and z-up).  trimesh is imported only when a mesh is read.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab._shared.limits import MAX_MESH_BYTES, MAX_RAY_TESTS, MAX_TRIANGLES, check_regular_file
from voxfab._shared.progress import Meter, meter
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError, LimitError, VoxfabError

from ._registry import ReadResult, register

__all__ = ["read_mesh_shape", "voxelize", "mesh_grid", "from_y_up", "to_y_up", "MESH_EXTENSIONS",
           "DEFAULT_RESOLUTION"]

#: Extensions read as triangle meshes.
MESH_EXTENSIONS = (".stl", ".obj", ".ply", ".3mf", ".glb")
#: Voxels along the longest side of the mesh, as the artist's 25³ grid.
DEFAULT_RESOLUTION = 25

# Every query point is moved off the voxel centre by this tiny amount (in voxels):
# meshes are often aligned with the grid (a box's diagonal passes through centres),
# and a ray through a shared edge would count one crossing twice.
_JITTER = np.array([1.3e-5, 2.9e-5, 2.3e-5])
# Triangle-column pairs processed at once, to bound memory on big meshes.
_PAIRS_PER_BATCH = 1 << 19


def _check_resolution(resolution: int) -> int:
    ok = isinstance(resolution, (int, np.integer)) and not isinstance(resolution, bool)
    if not ok or not 1 <= resolution <= MAX_SIDE:
        raise InvalidShapeError(f"resolution: expected an integer in 1..{MAX_SIDE}, got {resolution!r}")
    return int(resolution)


def _crossings(
    tri: npt.NDArray[np.float64], axis: int, shape: tuple[int, int, int], bar: Meter
) -> npt.NDArray[np.uint8]:
    """Ray parity along ``axis``: 1 where a query point has an odd number of crossings below it.

    ``tri`` (F, 3, 3) holds the triangles in grid units (voxel centre ``i`` at ``i``);
    the query points are the voxel centres plus ``_JITTER``.  ``bar`` counts the
    triangles done.  Returns an (X, Y, Z) uint8 array.
    """
    u, v = (a for a in range(3) if a != axis)
    nu, nv, nw = shape[u], shape[v], shape[axis]
    ju, jv, jw = _JITTER[u], _JITTER[v], _JITTER[axis]
    P = tri[:, :, (u, v)]
    W = tri[:, :, axis]
    i0 = np.maximum(np.ceil(P[:, :, 0].min(axis=1) - ju), 0).astype(np.int64)
    i1 = np.minimum(np.floor(P[:, :, 0].max(axis=1) - ju), nu - 1).astype(np.int64)
    j0 = np.maximum(np.ceil(P[:, :, 1].min(axis=1) - jv), 0).astype(np.int64)
    j1 = np.minimum(np.floor(P[:, :, 1].max(axis=1) - jv), nv - 1).astype(np.int64)
    ci = np.maximum(i1 - i0 + 1, 0)
    cj = np.maximum(j1 - j0 + 1, 0)
    pairs = ci * cj
    # Flat index (i, j, k) of each crossing: column (i, j), just below query point k.
    crossings: list[np.ndarray] = []
    ends = np.cumsum(pairs)
    first = 0
    while first < len(tri):
        # Triangles first..last-1 give at most _PAIRS_PER_BATCH pairs (at least one triangle).
        base = ends[first - 1] if first else 0
        last = max(int(np.searchsorted(ends, base + _PAIRS_PER_BATCH, side="right")), first + 1)
        f = np.arange(first, last)
        n = pairs[f]
        t = np.repeat(f, n)
        local = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        ii = i0[t] + local // np.maximum(cj[t], 1)
        jj = j0[t] + local % np.maximum(cj[t], 1)
        pu, pv = ii + ju, jj + jv
        a, b, c = P[t, 0], P[t, 1], P[t, 2]
        d = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            lb = ((pu - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (pv - a[:, 1])) / d
            lc = ((b[:, 0] - a[:, 0]) * (pv - a[:, 1]) - (pu - a[:, 0]) * (b[:, 1] - a[:, 1])) / d
            la = 1.0 - lb - lc
        # Triangles seen edge-on (d == 0) give NaN weights and drop out here.
        hit = (la >= 0) & (lb >= 0) & (lc >= 0)
        w = la[hit] * W[t[hit], 0] + lb[hit] * W[t[hit], 1] + lc[hit] * W[t[hit], 2]
        # The crossing is below query points k > w - jw, i.e. from k = floor(w - jw) + 1.
        k = np.clip(np.floor(w - jw) + 1, 0, nw).astype(np.int64)
        crossings.append((ii[hit] * nv + jj[hit]) * (nw + 1) + k)
        bar.update(last - first)
        first = last
    # Only the parity of the count in each slot matters: mark slots crossed an odd
    # number of times, then a running sum mod 2 (uint8 wraps at 256, an even number)
    # gives the parity of the crossings below each query point.
    slots, times = np.unique(np.concatenate(crossings), return_counts=True)
    marks = np.zeros(nu * nv * (nw + 1), dtype=np.uint8)
    marks[slots[(times & 1) == 1]] = 1
    parity = np.cumsum(marks.reshape(nu, nv, nw + 1)[:, :, :nw], axis=2, dtype=np.uint8) & 1
    return np.transpose(parity, np.argsort((u, v, axis)))


def voxelize(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, resolution: int = DEFAULT_RESOLUTION
) -> tuple[BoolGrid, float, npt.NDArray[np.float64]]:
    """Fill the voxels whose centre is inside a triangle mesh.

    Parameters
    ----------
    vertices : (V, 3) float array
        Vertex positions, in the mesh's units.
    faces : (F, 3) int array
        Triangles as vertex indices.
    resolution : int
        Voxels along the longest side of the mesh's bounding box (1..256).

    Returns
    -------
    grid : (X, Y, Z) bool ndarray
        Voxels whose centre is inside by a majority of the x, y and z ray tests.
    pitch : float
        Voxel size, in the mesh's units.
    origin : (3,) float ndarray
        Position of the grid's corner (the low corner of voxel ``[0, 0, 0]``).

    Raises
    ------
    InvalidShapeError
        For a bad ``resolution`` or a mesh with no extent.
    """
    n = _check_resolution(resolution)
    vert = np.asarray(vertices, dtype=np.float64)
    tri_idx = np.asarray(faces, dtype=np.int64)
    if tri_idx.ndim != 2 or tri_idx.shape[1] != 3 or len(tri_idx) == 0:
        raise InvalidShapeError(f"mesh: expected (F, 3) triangles with F >= 1, got shape {tri_idx.shape}")
    tri = vert[tri_idx]
    lo, hi = tri.reshape(-1, 3).min(axis=0), tri.reshape(-1, 3).max(axis=0)
    size = hi - lo
    longest = float(size.max())
    if not longest > 0:
        raise InvalidShapeError("mesh: it has no extent (all vertices at one point)")
    pitch = longest / n
    shape = tuple(int(max(1, min(n, math.ceil(s / pitch - 1e-9)))) for s in size)
    origin = lo + (size - np.array(shape) * pitch) / 2
    grid_tri = (tri - origin) / pitch - 0.5
    with meter(3 * len(tri), desc="voxelizing: triangles x 3 rays") as bar:
        votes = _crossings(grid_tri, 0, shape, bar)
        votes += _crossings(grid_tri, 1, shape, bar)
        votes += _crossings(grid_tri, 2, shape, bar)
    return votes >= 2, pitch, origin


def mesh_grid(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, resolution: int = DEFAULT_RESOLUTION, name: str = "mesh"
) -> tuple[BoolGrid, float, list[str]]:
    """Voxelize a mesh, fill it solid and keep its largest 6-connected piece (see :func:`placed_mesh_grid`)."""
    grid, pitch, notes, _ = placed_mesh_grid(vertices, faces, resolution=resolution, name=name)
    return grid, pitch, notes


def placed_mesh_grid(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, resolution: int = DEFAULT_RESOLUTION, name: str = "mesh"
) -> tuple[BoolGrid, float, list[str], npt.NDArray[np.float64]]:
    """Voxelize a mesh, fill it solid and keep its largest 6-connected piece.

    Returns
    -------
    grid : (X, Y, Z) bool ndarray
        Cropped to its content.
    pitch : float
        Voxel size in the mesh's units.
    notes : list of str
        The resolution used and what was filled or dropped.
    origin : (3,) float ndarray
        Where the low corner of the cropped grid's voxel ``[0, 0, 0]`` is, in the mesh's units.

    Raises
    ------
    InvalidShapeError
        When no voxel centre lies inside the mesh.
    """
    raw, pitch, origin = voxelize(vertices, faces, resolution=resolution)
    if not raw.any():
        raise InvalidShapeError(
            f"{name}: no voxel centre lies inside the mesh at resolution {resolution} "
            "(is it a closed solid? try a higher --resolution)"
        )
    notes = [f"voxelized at {resolution} voxels along the longest side ({pitch:.6g} mesh units per voxel)"]
    solid, kept = _solid_piece(raw, notes)
    if kept is not None and max(kept[1] - kept[0]) < resolution:
        # Stray pieces set the scale of the first pass; voxelize the kept piece's own mesh
        # parts again, so it spans the requested resolution as a whole mesh would.
        lo_mm, hi_mm = origin + kept[0] * pitch, origin + kept[1] * pitch
        part = _faces_within(vertices, faces, lo_mm, hi_mm)
        if part is not None:
            raw, pitch, origin = voxelize(vertices, part, resolution=resolution)
            notes.append(
                f"voxelized the kept piece again at {resolution} voxels along its longest side "
                f"({pitch:.6g} mesh units per voxel)"
            )
            solid, _ = _solid_piece(raw, notes)
    from voxfab.shape import bounding_box

    lo, hi = bounding_box(solid)
    cropped = solid[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].copy()
    return cropped, pitch, notes, origin + np.array(lo) * pitch


def _solid_piece(raw: BoolGrid, notes: list[str]) -> tuple[BoolGrid, tuple[np.ndarray, np.ndarray] | None]:
    """Fill cavities and keep the largest 6-connected piece, noting what changed.

    Returns
    -------
    solid : bool ndarray
    kept : (lo, hi) voxel index bounds of the kept piece (hi exclusive), or None when nothing was dropped
    """
    from voxfab.shape import cavity_count, fill_cavities, label_components

    solid = fill_cavities(raw)
    added = int(np.count_nonzero(solid)) - int(np.count_nonzero(raw))
    if added:
        cavities = cavity_count(raw)
        notes.append(f"filled {cavities} enclosed cavit{'y' if cavities == 1 else 'ies'} ({added} voxels)")
    labels, count = label_components(solid)
    if count <= 1:
        return solid, None
    sizes = np.bincount(labels.ravel())[1:]
    keep = int(np.argmax(sizes))
    dropped = int(sizes.sum() - sizes[keep])
    solid = labels == keep + 1
    notes.append(
        f"kept the largest 6-connected piece ({int(sizes[keep])} voxels); dropped "
        f"{count - 1} other piece{'s' if count > 2 else ''} ({dropped} voxels)"
    )
    idx = np.argwhere(solid)
    return solid, (idx.min(axis=0), idx.max(axis=0) + 1)


def _faces_within(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, lo: npt.NDArray[np.float64], hi: npt.NDArray[np.float64]
) -> npt.NDArray[np.int64] | None:
    """The triangles of the mesh parts whose bounding box meets the box ``lo..hi``.

    Mesh parts are the triangles connected through shared vertex positions.  Returns
    None when that is every triangle (nothing to leave out).
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    vert = np.asarray(vertices, dtype=np.float64)
    tri = np.asarray(faces, dtype=np.int64)
    # STL stores each corner apart: weld by position before following the connections.
    _, welded = np.unique(vert, axis=0, return_inverse=True)
    t = welded.reshape(-1)[tri]
    n = int(t.max()) + 1
    edges = coo_matrix((np.ones(2 * len(t)), (np.r_[t[:, 0], t[:, 1]], np.r_[t[:, 1], t[:, 2]])), shape=(n, n))
    _, comp = connected_components(edges, directed=False)
    face_comp = comp[t[:, 0]]
    corners = vert[tri]
    n_comp = int(face_comp.max()) + 1
    cmin = np.full((n_comp, 3), np.inf)
    cmax = np.full((n_comp, 3), -np.inf)
    np.minimum.at(cmin, face_comp, corners.min(axis=1))
    np.maximum.at(cmax, face_comp, corners.max(axis=1))
    meets = np.all((cmin <= hi) & (cmax >= lo), axis=1)
    chosen = meets[face_comp]
    if chosen.all() or not chosen.any():
        return None
    return tri[chosen]


def check_mesh_size(path: PathLike, file_type: str) -> None:
    """Refuse, before parsing, a mesh file over the size limits of :mod:`voxfab._shared.limits`.

    A binary STL states its triangle count in its header; a 3MF package is a zip
    whose parts are checked for their unpacked size; any mesh file is at most
    ``MAX_MESH_BYTES``.  Parsing and voxelizing take time and memory in
    proportion to these sizes.

    Raises
    ------
    LimitError
        A file over ``MAX_MESH_BYTES`` bytes (64 MiB), a 3MF unpacking to more,
        or a binary STL of more than ``MAX_TRIANGLES`` triangles (1,000,000).
    """
    size = check_regular_file(path, what="a mesh").st_size
    if size > MAX_MESH_BYTES:
        raise LimitError(f"{path}: {size:,} bytes is over the limit of {MAX_MESH_BYTES:,} bytes for a mesh file")
    with open(path, "rb") as fh:
        head = fh.read(84)
    if file_type == "stl" and len(head) == 84 and not head.lstrip().lower().startswith(b"solid"):
        count = int.from_bytes(head[80:84], "little")
        # A header whose count does not match the size is corrupt: the parser says so.
        if count > MAX_TRIANGLES and size == 84 + 50 * count:
            raise LimitError(
                f"{path}: the STL header states {count:,} triangles, over the limit of {MAX_TRIANGLES:,}"
            )
    if file_type == "ply":
        faces = ply_face_count(path)
        if faces is not None and faces > MAX_TRIANGLES:
            raise LimitError(f"{path}: the PLY header states {faces:,} faces, over the limit of {MAX_TRIANGLES:,}")
    if file_type == "3mf":
        import zipfile

        try:
            with zipfile.ZipFile(path) as zf:
                unpacked = sum(info.file_size for info in zf.infolist())
        except (zipfile.BadZipFile, OSError, ValueError, EOFError) as exc:
            raise FormatError(f"{path}: not a 3MF package (a zip archive): {exc}") from None
        if unpacked > MAX_MESH_BYTES:
            raise LimitError(
                f"{path}: the 3MF package unpacks to {unpacked:,} bytes, over the limit of {MAX_MESH_BYTES:,}"
            )


def ply_face_count(path: PathLike) -> int | None:
    """The face count a PLY file's header states, or None when its header gives none.

    The header is text up to ``end_header``; only its first 64 KiB are read.
    """
    with open(path, "rb") as fh:
        head = fh.read(65536)
    end = head.find(b"end_header")
    if not head.startswith(b"ply") or end < 0:
        return None
    for line in head[:end].decode("latin-1").splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == "element" and words[1] == "face":
            try:
                return int(words[2])
            except ValueError:
                raise FormatError(f"{path}: the PLY header's face count {words[2][:20]!r} is not a number") from None
    return None


def ray_tests(vertices: npt.ArrayLike, faces: npt.ArrayLike, *, resolution: int) -> int:
    """Number of (triangle, voxel column) pairs :func:`voxelize` tests, over its three ray directions.

    Each triangle is tested against every column its bounding box covers, so long
    thin triangles lying across the grid cost far more than their count suggests.
    """
    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces, dtype=np.int64)]
    lo, hi = tri.reshape(-1, 3).min(axis=0), tri.reshape(-1, 3).max(axis=0)
    longest = float((hi - lo).max())
    if not longest > 0:
        return 0
    g = (tri - lo) * (resolution / longest)
    span = np.floor(g.max(axis=1)) - np.ceil(g.min(axis=1)) + 1  # (F, 3) columns per axis
    span = np.clip(span, 0, resolution + 1)
    total = span[:, 0] * span[:, 1] + span[:, 1] * span[:, 2] + span[:, 0] * span[:, 2]
    return int(total.sum())


def to_y_up(v: np.ndarray) -> np.ndarray:
    """``(x, y, z)`` z-up → glTF's ``(x, z, -y)`` y-up (a quarter turn about x)."""
    return np.column_stack([v[:, 0], v[:, 2], -v[:, 1]])


def from_y_up(v: np.ndarray) -> np.ndarray:
    """glTF's ``(X, Y, Z)`` y-up → ``(X, -Z, Y)`` z-up, the inverse of :func:`to_y_up`."""
    return np.column_stack([v[:, 0], -v[:, 2], v[:, 1]])


def _load(path: PathLike, file_type: str) -> tuple[np.ndarray, np.ndarray, bool, Any]:
    """Load vertices, faces, watertightness and the loaded mesh (its colours) with trimesh; any parser
    failure is a FormatError."""
    try:
        import trimesh
    except ImportError:  # pragma: no cover - trimesh is a dependency
        from voxfab.errors import MissingDependencyError

        raise MissingDependencyError("trimesh", "reading meshes") from None
    try:
        # Unprocessed first: trimesh's cleanup would silently drop non-finite
        # vertices, which only a corrupt file has.
        with open(path, "rb") as fh, warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            # An OBJ names its materials and textures by file names beside it.
            resolver = trimesh.resolvers.FilePathResolver(str(path)) if file_type == "obj" else None
            loaded = trimesh.load(fh, file_type=file_type, force="mesh", process=False, resolver=resolver)
        vertices = np.asarray(loaded.vertices, dtype=np.float64)
        if file_type == "glb" and vertices.ndim == 2 and vertices.shape[1:] == (3,):
            # glTF is y-up in metres; a shape is z-up and its pitch in mm, as STL and 3MF give it.
            vertices = from_y_up(vertices) * 1000.0
        faces = np.asarray(loaded.faces, dtype=np.int64)
    except VoxfabError:
        raise
    except Exception as exc:  # noqa: BLE001
        # trimesh's parsers fail on corrupt input with whatever the underlying library
        # raises (zip, XML, struct, numpy, Unicode errors...): all mean "unreadable".
        if isinstance(exc, StopIteration) and file_type == "3mf":
            # trimesh looks for the package's model part with next(): none there.
            raise FormatError(f"{path}: the 3MF package holds no 3D model (no 3D/*.model part)") from None
        why = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
        raise FormatError(f"{path}: cannot read as a .{file_type} mesh ({why})") from None
    if faces.ndim != 2 or faces.shape[1] != 3 or len(faces) == 0:
        raise FormatError(f"{path}: the file holds no triangle (empty, truncated or not a .{file_type} mesh)")
    stated = ply_face_count(path) if file_type == "ply" else None
    if stated is not None and len(faces) < stated:
        # Each PLY face gives at least one triangle: fewer means a truncated file or a lying header.
        raise FormatError(f"{path}: the PLY header states {stated:,} faces but the file holds {len(faces):,}")
    if len(faces) > MAX_TRIANGLES:
        raise LimitError(f"{path}: {len(faces):,} triangles is over the limit of {MAX_TRIANGLES:,}")
    if vertices.ndim != 2 or vertices.shape[1] != 3 or not np.isfinite(vertices).all():
        raise FormatError(f"{path}: the mesh has missing or non-finite vertex coordinates (corrupt file)")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise FormatError(f"{path}: a face refers to a vertex that does not exist")
    # Watertightness needs shared vertices: STL stores each triangle's corners apart.
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        watertight = bool(trimesh.Trimesh(vertices, faces, process=True, validate=False).is_watertight)
    return vertices, faces, watertight, loaded


def read_mesh_shape(path: PathLike, *, resolution: int = DEFAULT_RESOLUTION) -> ReadResult:
    """Read a triangle mesh and voxelize it (see the module description).

    Parameters
    ----------
    path : path
        An ``.stl``, ``.obj``, ``.ply`` or ``.3mf`` file.
    resolution : int
        Voxels along the longest side of the mesh (default 25, at most 256).

    Returns
    -------
    ReadResult
        The solid grid, its pitch in mesh units, and notes on the mesh and on
        what was filled or dropped.

    Raises
    ------
    FormatError
        When the file is not a readable mesh or holds no triangle.
    InvalidShapeError
        For a bad ``resolution``, a flat mesh, or one with nothing inside.
    LimitError
        For a file over 64 MiB, a mesh of more than 1,000,000 triangles (see
        :func:`check_mesh_size`), or one whose voxelizing takes more than
        ``MAX_RAY_TESTS`` (60 million) triangle-column tests (see :func:`ray_tests`).
    """
    n = _check_resolution(resolution)
    file_type = Path(path).suffix.lower().lstrip(".")
    check_mesh_size(path, file_type)
    vertices, faces, watertight, loaded = _load(path, file_type)
    work = ray_tests(vertices, faces, resolution=n)
    if work > MAX_RAY_TESTS:
        raise LimitError(
            f"{path}: voxelizing at resolution {n} takes {work:,} triangle-column tests, over the limit of "
            f"{MAX_RAY_TESTS:,} (long thin triangles across the grid; try a lower --resolution)"
        )
    try:
        grid, pitch, notes, origin = placed_mesh_grid(vertices, faces, resolution=n, name=str(path))
    except InvalidShapeError as exc:
        msg = str(exc)
        raise InvalidShapeError(msg if msg.startswith(str(path)) else f"{path}: {msg}") from None
    notes.insert(0, f"mesh of {len(faces)} triangles, {'watertight' if watertight else 'NOT watertight'}")
    if not watertight:
        notes.append("the mesh has open or non-manifold edges: inside voxels are those most rays along x, y, z see inside")
    colours = None
    if getattr(getattr(loaded, "visual", None), "defined", False):
        from ._meshcolour import surface_samples, voxel_colours

        samples = surface_samples(loaded, vertices, faces, pitch / 2)
        if samples is not None:
            colours, colour_notes = voxel_colours(grid, origin, pitch, *samples)
            notes += colour_notes + [f"{colours.count} colours from the mesh's surface, each voxel the nearest's"]
    return ReadResult(grid, pitch, tuple(notes), colours)


for _ext in MESH_EXTENSIONS:
    register(_ext, reader=read_mesh_shape)
