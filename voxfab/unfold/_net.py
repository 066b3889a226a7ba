"""Net: a single-piece edge unfolding of a voxel surface, and its JSON form."""

from __future__ import annotations

import dataclasses
import json
from collections import deque
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.errors import FormatError, InvalidShapeError

NET_FORMAT = "voxfab-net/1"


def _frozen(a: npt.ArrayLike, dtype: type, shape_tail: tuple[int, ...]) -> np.ndarray:
    arr = np.array(a, dtype=dtype).reshape((-1,) + shape_tail)
    arr.flags.writeable = False
    return arr


@dataclasses.dataclass(frozen=True, eq=False)
class Net:
    """An unfolded voxel surface.

    Faces are listed in the order of :func:`voxfab.shape.surface_graph` (sorted by
    voxel then direction), so face ``i`` of a net of a shape is face ``i`` of that
    shape's surface graph.  The net is seen from outside: each face's 2D corners
    keep the counter-clockwise order its 3D corners have seen from outside.

    Attributes
    ----------
    voxel : (F, 3) int ndarray
    normal : (F, 3) int ndarray
        Outward unit normals.
    corners3d : (F, 4, 3) int ndarray
        Face corners in voxel-corner coordinates, counter-clockwise from outside.
    corners2d : (F, 4, 2) int ndarray
        The same corners' positions in the net, in the same order.
    folds : (M, 2) int ndarray
        Face index pairs joined by a fold (the other shared edges are cut): a
        spanning tree of the faces, plus every edge whose two sides meet in the
        plane anyway (cutting it would leave a slit that closes up).
    seed : int
    strategy : str
    mountain, valley, flat : int
        Counts of folds by type.
    seams_without_tab_room : int
        Cut edge pairs where neither side has a free cell for a glue tab.
    filled : bool
        The net unfolds the outer surface of the shape with its enclosed
        cavities filled (``unfold(..., fill=True)``), so its faces are those of
        ``surface_graph(fill_cavities(shape))``.
    """

    voxel: np.ndarray
    normal: np.ndarray
    corners3d: np.ndarray
    corners2d: np.ndarray
    folds: np.ndarray
    seed: int
    strategy: str
    mountain: int = 0
    valley: int = 0
    flat: int = 0
    seams_without_tab_room: int = 0
    filled: bool = False

    def __post_init__(self) -> None:
        for name, dtype, tail in (
            ("voxel", np.int64, (3,)),
            ("normal", np.int64, (3,)),
            ("corners3d", np.int64, (4, 3)),
            ("corners2d", np.int64, (4, 2)),
            ("folds", np.int64, (2,)),
        ):
            object.__setattr__(self, name, _frozen(getattr(self, name), dtype, tail))

    @property
    def face_count(self) -> int:
        """Number of faces F."""
        return int(self.voxel.shape[0])

    def bounds(self) -> tuple[int, int, int, int]:
        """``(xmin, ymin, xmax, ymax)`` of the net in face units."""
        c = self.corners2d.reshape(-1, 2)
        return (int(c[:, 0].min()), int(c[:, 1].min()), int(c[:, 0].max()), int(c[:, 1].max()))

    def to_dict(self, colours: Any = None) -> dict[str, Any]:
        """The ``voxfab-net/1`` JSON object; with the shape's ``colours`` (a
        :class:`~voxfab.shape.VoxelColours`), each face says its voxel's ``"colour": "#rrggbb"``."""
        d = self._dict()
        if colours is not None:
            from voxfab.shape import hex_colour

            for face, rgba in zip(d["faces"], colours.at(self.voxel)):
                face["colour"] = hex_colour(rgba)
        return d

    def _dict(self) -> dict[str, Any]:
        return {
            "format": NET_FORMAT,
            "seed": int(self.seed),
            "strategy": self.strategy,
            "face_count": self.face_count,
            "mountain": int(self.mountain),
            "valley": int(self.valley),
            "flat": int(self.flat),
            "seams_without_tab_room": int(self.seams_without_tab_room),
            "filled": bool(self.filled),
            "faces": [
                {
                    "voxel": v.tolist(),
                    "normal": n.tolist(),
                    "corners3d": c3.tolist(),
                    "corners2d": c2.tolist(),
                }
                for v, n, c3, c2 in zip(self.voxel, self.normal, self.corners3d, self.corners2d)
            ],
            "folds": self.folds.tolist(),
        }

    def to_json(self, colours: Any = None) -> str:
        """Deterministic JSON text (one face per line keeps diffs readable); ``colours`` as in :meth:`to_dict`."""
        d = self.to_dict(colours)
        faces = d.pop("faces")
        folds = d.pop("folds")
        head = json.dumps(d, sort_keys=True)[:-1]
        face_lines = ",\n    ".join(json.dumps(f, sort_keys=True) for f in faces)
        return f'{head}, "faces": [\n    {face_lines}\n  ], "folds": {json.dumps(folds)}}}\n'

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Net:
        """Build a net from its JSON object; raises FormatError when malformed."""
        if not isinstance(data, dict) or data.get("format") != NET_FORMAT:
            raise FormatError(f"not a {NET_FORMAT} object")
        try:
            faces = data["faces"]
            return cls(
                voxel=[f["voxel"] for f in faces],
                normal=[f["normal"] for f in faces],
                corners3d=[f["corners3d"] for f in faces],
                corners2d=[f["corners2d"] for f in faces],
                folds=data["folds"] if data["folds"] else np.zeros((0, 2)),
                seed=int(data.get("seed", 0)),
                strategy=str(data.get("strategy", "")),
                mountain=int(data.get("mountain", 0)),
                valley=int(data.get("valley", 0)),
                flat=int(data.get("flat", 0)),
                seams_without_tab_room=int(data.get("seams_without_tab_room", 0)),
                filled=bool(data.get("filled", False)),
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise FormatError(f"malformed {NET_FORMAT} data: {exc}") from None

    @classmethod
    def from_json(cls, text: str) -> Net:
        """Parse ``voxfab-net/1`` JSON text."""
        from voxfab._shared.limits import parse_json

        return cls.from_dict(parse_json(text, name="net JSON"))


def fold_tree(net: Net) -> tuple[int, npt.NDArray[np.int64], list[int]]:
    """The fold tree from the face nearest the middle of the sheet: root, parent of each face, order.

    The net's folds are a spanning tree plus edges that meet in the plane anyway;
    a breadth-first walk keeps one parent per face, so the pieces hinge on the
    faces nearer the middle (the sheet stays put around its centre).
    """
    c2 = np.asarray(net.corners2d, dtype=np.float64).mean(axis=1)
    f = c2.shape[0]
    root = int(np.argmin(((c2 - c2.mean(axis=0)) ** 2).sum(axis=1)))
    neighbours: list[list[int]] = [[] for _ in range(f)]
    for a, b in np.asarray(net.folds, dtype=np.int64).tolist():
        neighbours[a].append(b)
        neighbours[b].append(a)
    parent = np.full(f, -1, dtype=np.int64)
    seen = np.zeros(f, dtype=bool)
    seen[root] = True
    order = [root]
    queue = deque([root])
    while queue:
        a = queue.popleft()
        for b in sorted(neighbours[a]):
            if not seen[b]:
                seen[b] = True
                parent[b] = a
                order.append(b)
                queue.append(b)
    if not seen.all():
        raise InvalidShapeError(f"net: its folds leave {int((~seen).sum())} faces unconnected; not a one-piece net")
    return root, parent, order
