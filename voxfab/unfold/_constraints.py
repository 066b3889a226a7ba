"""Edge constraints: surface edges the artist wants cut, or kept folded.

An edge is named by its two faces, a face by ``(x, y, z, n)`` with ``n`` its
outward normal, one of ``"+x" "-x" "+y" "-y" "+z" "-z"``.  The JSON form is
``{"cut": [[[x, y, z, "+z"], [x, y, z, "+x"]], ...], "keep": [...]}``.

Keep edges are always folds, so the faces they join form rigid groups that the
search lays out once (:func:`resolve`) and then moves as one piece.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Iterable
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from voxfab._shared.options import quote
from voxfab.errors import FormatError, InvalidShapeError, UnfoldError
from voxfab.shape import SurfaceGraph

__all__ = ["EdgeConstraints", "Face", "Edge", "check_one_piece"]

#: A face: voxel ``(x, y, z)`` and outward normal.
Face = tuple[int, int, int, str]
#: An edge: its two faces, the smaller first.
Edge = tuple[Face, Face]

#: Normal names in the order of :data:`voxfab.shape.DIRECTIONS`.
NORMALS = ("+x", "-x", "+y", "-y", "+z", "-z")
_NORMAL_INDEX = {n: d for d, n in enumerate(NORMALS)}
#: Most edges one constraint set may name (a 25³ surface has under 40 000 edges).
MAX_EDGES = 100_000
#: Largest voxel coordinate accepted (grids are at most 256 per side).
_MAX_COORD = 4096

#: Half-edge flags in :attr:`Resolved.edge`.
FREE, CUT, KEEP = 0, 1, 2
#: Cell offset across each cell side (bottom, right, top, left), y up.
_SIDE_STEP = ((0, -1), (1, 0), (0, 1), (-1, 0))


def _face(item: Any, where: str) -> Face:
    """A face from its JSON form, every field checked whatever its type (a normal may arrive as a list)."""
    if not isinstance(item, (list, tuple)) or len(item) != 4:
        raise InvalidShapeError(f"{where}: a face is [x, y, z, normal], got {quote(item)}")
    *xyz, n = item
    if not all(isinstance(c, (int, np.integer)) and not isinstance(c, bool) for c in xyz):
        raise InvalidShapeError(f"{where}: face coordinates must be integers, got {quote(item)}")
    if not all(-_MAX_COORD <= int(c) <= _MAX_COORD for c in xyz):
        raise InvalidShapeError(f"{where}: face coordinates must be -{_MAX_COORD} to {_MAX_COORD}, got {quote(item)}")
    # isinstance first: a list or an object is no normal, and cannot even be looked up
    if not isinstance(n, str) or n not in _NORMAL_INDEX:
        raise InvalidShapeError(f"{where}: face normal must be one of {', '.join(NORMALS)}, got {quote(n, 24)}")
    return (int(xyz[0]), int(xyz[1]), int(xyz[2]), n)


def _edge(item: Any, where: str) -> Edge:
    if not isinstance(item, (list, tuple)) or len(item) != 2:
        raise InvalidShapeError(f"{where}: an edge is a pair of faces, got {quote(item)}")
    a, b = _face(item[0], where), _face(item[1], where)
    if a == b:
        raise InvalidShapeError(f"{where}: an edge needs two different faces, got {a} twice")
    return (a, b) if a < b else (b, a)


def _edges(items: Iterable[Any], name: str) -> frozenset[Edge]:
    if not isinstance(items, (list, tuple, set, frozenset)):
        raise InvalidShapeError(f"{name}: expected a list of edges, got {type(items).__name__}")
    out = set()
    for t, item in enumerate(items):
        if t >= MAX_EDGES:
            raise InvalidShapeError(f"{name}: more than {MAX_EDGES} edges")
        out.add(_edge(item, f"{name} edge {t}"))
    return frozenset(out)


@dataclasses.dataclass(frozen=True)
class EdgeConstraints:
    """Edges of a surface to cut, and edges to keep folded.

    Parameters
    ----------
    cut, keep : iterable of edges
        An edge is a pair of faces ``((x, y, z, n), (x, y, z, n))`` with ``n`` in
        ``"+x" "-x" "+y" "-y" "+z" "-z"``; each is stored with its smaller face
        first.  Cut edges are never folds of the net; keep edges always are.

    Raises
    ------
    InvalidShapeError
        A malformed edge, or an edge that is both cut and kept.
    """

    cut: frozenset[Edge] = frozenset()
    keep: frozenset[Edge] = frozenset()

    def __post_init__(self) -> None:
        cut = _edges(self.cut, "cut")
        keep = _edges(self.keep, "keep")
        both = cut & keep
        if both:
            raise InvalidShapeError(f"edge {_name(min(both))} is both cut and kept")
        object.__setattr__(self, "cut", cut)
        object.__setattr__(self, "keep", keep)

    def __bool__(self) -> bool:
        return bool(self.cut or self.keep)

    def to_dict(self) -> dict[str, list]:
        """The JSON object, edges sorted."""
        return {name: [[list(a), list(b)] for a, b in sorted(getattr(self, name))]
                for name in ("cut", "keep")}

    def to_json(self) -> str:
        """Deterministic JSON text, one edge per line."""
        parts = []
        for name, edges in self.to_dict().items():
            lines = ",\n    ".join(json.dumps(e) for e in edges)
            parts.append(f'  "{name}": [' + (f"\n    {lines}\n  ]" if edges else "]"))
        return "{\n" + ",\n".join(parts) + "\n}\n"

    @classmethod
    def from_dict(cls, data: Any) -> EdgeConstraints:
        """Build constraints from their JSON object (``cut`` and ``keep`` both optional)."""
        if not isinstance(data, dict):
            raise FormatError(f"edge constraints: expected a JSON object, got {type(data).__name__}")
        unknown = sorted(set(data) - {"cut", "keep"})
        if unknown:
            raise FormatError(f"edge constraints: unknown key {str(unknown[0])[:40]!r} "
                              "(expected 'cut' and 'keep')")
        return cls(cut=data.get("cut", ()), keep=data.get("keep", ()))

    @classmethod
    def from_json(cls, text: str | bytes) -> EdgeConstraints:
        """Parse the JSON form; raises FormatError or InvalidShapeError when malformed."""
        try:
            data = json.loads(text)
        except (ValueError, RecursionError) as exc:
            raise FormatError(f"edge constraints: not JSON: {str(exc)[:80]}") from None
        return cls.from_dict(data)


def _name(edge: Edge) -> str:
    (ax, ay, az, an), (bx, by, bz, bn) = edge
    return f"[{ax},{ay},{az},{an}]-[{bx},{by},{bz},{bn}]"


class Resolved(NamedTuple):
    """Constraints as arrays over a surface graph's faces (for the search kernels).

    ``edge[f, k]`` is FREE, CUT or KEEP.  Faces joined by keep edges form groups:
    ``group[f]`` is the group of face f (-1 alone), ``gx, gy, grot`` its cell and
    rotation in the group's own flat layout, and the members of group g are
    ``members[start[g]:start[g + 1]]``.
    """

    edge: npt.NDArray[np.int8]
    group: npt.NDArray[np.int64]
    gx: npt.NDArray[np.int64]
    gy: npt.NDArray[np.int64]
    grot: npt.NDArray[np.int64]
    members: npt.NDArray[np.int64]
    start: npt.NDArray[np.int64]


def face_index(sg: SurfaceGraph, faces: list[Face]) -> npt.NDArray[np.int64]:
    """Surface-graph index of each face, -1 for faces not on the surface."""
    if not faces:
        return np.zeros(0, dtype=np.int64)
    q = np.array([f[:3] for f in faces], dtype=np.int64)
    d = np.array([_NORMAL_INDEX[f[3]] for f in faces], dtype=np.int64)
    lo = np.minimum(sg.voxel.min(axis=0), q.min(axis=0))
    span = np.maximum(sg.voxel.max(axis=0), q.max(axis=0)) - lo + 1

    def key(v: npt.NDArray[np.int64], dd: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
        # Faces are sorted by (x, y, z, d), so this key is increasing along them.
        w = v - lo
        return ((w[:, 0] * span[1] + w[:, 1]) * span[2] + w[:, 2]) * 6 + dd

    keys = key(sg.voxel, sg.direction)
    want = key(q, d)
    idx = np.minimum(np.searchsorted(keys, want), keys.size - 1)
    return np.where(keys[idx] == want, idx, -1)


def resolve(constraints: EdgeConstraints | None, sg: SurfaceGraph,
            faces: npt.NDArray[np.int64] | None = None) -> Resolved | None:
    """Check every constrained edge against the surface and lay out the kept groups.

    Parameters
    ----------
    constraints : EdgeConstraints or None
    sg : SurfaceGraph
        The surface being unfolded.
    faces : (P,) int ndarray, optional
        The faces of the piece being unfolded; constrained edges with no face in
        it are ignored (other pieces of the surface).

    Returns
    -------
    Resolved or None
        None when there is no constraint.

    Raises
    ------
    InvalidShapeError
        A named face is not an exposed face, or two faces do not meet along an
        edge of the surface.
    UnfoldError
        Kept edges that cannot all be folds: they close a loop that does not lie
        flat, or their faces would overlap in the plane, or a cut edge joins two
        kept faces that meet in the plane.
    """
    if not constraints:
        return None
    f = sg.face_count
    edge = np.zeros((f, 4), dtype=np.int8)
    for flag, name in ((CUT, "cut"), (KEEP, "keep")):
        edges = sorted(getattr(constraints, name))
        ids = face_index(sg, [face for e in edges for face in e]).reshape(-1, 2)
        for e, (a, b) in zip(edges, ids.tolist()):
            if a < 0 or b < 0:
                missing = e[0] if a < 0 else e[1]
                raise InvalidShapeError(
                    f"{name} edge {_name(e)}: face {list(missing)} is not an exposed face of the shape")
            ks = np.flatnonzero(sg.neighbor[a] == b)
            if ks.size == 0:
                raise InvalidShapeError(
                    f"{name} edge {_name(e)}: the two faces do not meet along an edge of the surface")
            for k in ks.tolist():
                edge[a, k] = flag
                edge[b, sg.neighbor_edge[a, k]] = flag
    if faces is not None:
        inside = np.zeros(f, dtype=bool)
        inside[faces] = True
        edge[~inside] = FREE
        edge[~inside[sg.neighbor]] = FREE
    return _groups(sg, edge)


def _groups(sg: SurfaceGraph, edge: npt.NDArray[np.int8]) -> Resolved:
    """Lay out each group of faces joined by keep edges, flat and rigid."""
    f = sg.face_count
    group = np.full(f, -1, dtype=np.int64)
    gx = np.zeros(f, dtype=np.int64)
    gy = np.zeros(f, dtype=np.int64)
    grot = np.zeros(f, dtype=np.int64)
    members: list[int] = []
    start = [0]
    nb, ne = sg.neighbor, sg.neighbor_edge
    for seed in np.flatnonzero((edge == KEEP).any(axis=1)).tolist():
        if group[seed] >= 0:
            continue
        g = len(start) - 1
        group[seed] = g
        cells = {(0, 0): seed}
        queue = [seed]
        for a in queue:  # breadth first: the queue grows while it is read
            for k in np.flatnonzero(edge[a] == KEEP).tolist():
                b = int(nb[a, k])
                s = (k + grot[a]) % 4
                x, y = gx[a] + _SIDE_STEP[s][0], gy[a] + _SIDE_STEP[s][1]
                r = (s + 2 - ne[a, k]) % 4
                if group[b] >= 0:
                    if (gx[b], gy[b], grot[b]) != (x, y, r):
                        raise UnfoldError(
                            f"the kept edges around face {_face_name(sg, a)} close a loop that "
                            "cannot lie flat (around a corner of the shape), so they cannot all "
                            "be folds; cut one of them")
                    continue
                if (x, y) in cells:
                    raise UnfoldError(
                        f"kept faces {_face_name(sg, cells[(x, y)])} and {_face_name(sg, b)} "
                        "would overlap when laid flat; cut one of the kept edges between them")
                group[b], gx[b], gy[b], grot[b] = g, x, y, r
                cells[(x, y)] = b
                queue.append(b)
        members.extend(sorted(queue))
        start.append(len(members))
    _check_cuts_in_groups(sg, edge, group, gx, gy, grot)
    return Resolved(edge, group, gx, gy, grot, np.array(members, dtype=np.int64),
                    np.array(start, dtype=np.int64))


def _check_cuts_in_groups(sg, edge, group, gx, gy, grot) -> None:
    a, k = np.nonzero(edge == CUT)
    b = sg.neighbor[a, k]
    same = (group[a] >= 0) & (group[a] == group[b])
    for i, kk, j in zip(a[same].tolist(), k[same].tolist(), b[same].tolist()):
        s = (kk + grot[i]) % 4
        meets = (gx[i] + _SIDE_STEP[s][0], gy[i] + _SIDE_STEP[s][1]) == (gx[j], gy[j])
        if meets and grot[j] == (s + 2 - sg.neighbor_edge[i, kk]) % 4:
            raise UnfoldError(
                f"cut edge between kept faces {_face_name(sg, i)} and {_face_name(sg, j)} closes "
                "up in the plane (the kept edges around it hold both sides in place); keep "
                "fewer edges there")


def check_one_piece(sg: SurfaceGraph, resolved: Resolved | None) -> None:
    """Refuse, before any search, cut edges under which no one-piece net exists.

    A net is the surface held together by its folds, so the faces must stay
    connected across the edges that are not cut: a face whose four edges are all
    cut, or a ring of cut edges around a patch, leaves no one-piece net to find.
    (Kept edges that close a loop which cannot lie flat, or whose faces would
    overlap, are refused by :func:`resolve` already.)

    Raises
    ------
    UnfoldError
        Naming a face of the smallest part the cuts separate.
    """
    if resolved is None:
        return
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    f = sg.face_count
    a, k = np.nonzero(resolved.edge != CUT)
    b = sg.neighbor[a, k]
    joined = b >= 0
    graph = coo_matrix((np.ones(int(joined.sum()), dtype=np.int8), (a[joined], b[joined])), shape=(f, f))
    parts, labels = connected_components(graph, directed=False)
    if parts <= 1:
        return
    sizes = np.bincount(labels, minlength=parts)
    small = int(np.argmin(sizes))
    face = _face_name(sg, int(np.flatnonzero(labels == small)[0]))
    where = (f"face {face} is cut off from all its neighbours" if sizes[small] == 1
             else f"the cut edges separate the {int(sizes[small])} faces around face {face} from the rest")
    raise UnfoldError(f"{where}, so no one-piece net exists; cut fewer edges, or allow several pieces "
                      "(--pieces auto)")


def _face_name(sg: SurfaceGraph, i: int) -> str:
    x, y, z = sg.voxel[i].tolist()
    return f"[{x},{y},{z},{NORMALS[int(sg.direction[i])]}]"


def face_of(sg: SurfaceGraph, i: int) -> Face:
    """The ``(x, y, z, n)`` name of surface face ``i``."""
    x, y, z = sg.voxel[i].tolist()
    return (x, y, z, NORMALS[int(sg.direction[i])])
