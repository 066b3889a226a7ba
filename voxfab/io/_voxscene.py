"""MagicaVoxel's scene graph (``.vox`` version 200): where each model stands in the scene.

The scene is a tree from transform node 0: a transform (``nTRN``: a rotation
``_r``, a translation ``_t``, a layer, maybe ``_hidden``) holds one child, a group
(``nGRP``) holds several transforms, a shape (``nSHP``) names a model, or one model
per animation frame.  A model's voxel ``v`` of a model of size ``S`` has its centre
at ``v + 1/2 - S // 2`` in the model's own frame (the pivot is ``S // 2``, rounded
down, as MagicaVoxel and its reference exporter place it); the transforms from the
root down rotate it and shift it: ``world = R_root (... (R_leaf c + t_leaf) ...) + t_root``.
Hidden transforms and hidden layers (``LAYR`` ``_hidden``) leave their subtree out,
as the editor shows the scene.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np

from voxfab.errors import FormatError

__all__ = ["Placement", "rotation_matrix", "scene_placements"]

#: A scene deeper than this is corrupt (the editor nests groups a few levels deep).
_MAX_DEPTH = 256


@dataclasses.dataclass(frozen=True)
class Placement:
    """One model in the scene: its id, rotation, translation and the name the editor shows."""

    model: int
    rotation: np.ndarray
    translation: np.ndarray
    name: str


def rotation_matrix(code: int) -> np.ndarray:
    """The signed permutation matrix of a ``_r`` byte.

    Bits 0-1: the column of the first row's non-zero entry; bits 2-3: the second
    row's; the third row takes the column left; bits 4, 5, 6: the rows' signs (1 = -).

    Raises
    ------
    ValueError
        When the two columns are equal or out of range (no rotation has that code).
    """
    first, second = code & 3, (code >> 2) & 3
    if first > 2 or second > 2 or first == second or not 0 <= code < 128:
        raise ValueError(f"rotation code {code} names no rotation")
    third = 3 - first - second
    m = np.zeros((3, 3), dtype=np.int64)
    for row, col in enumerate((first, second, third)):
        m[row, col] = -1 if code >> (4 + row) & 1 else 1
    return m


def _translation(text: str | None) -> np.ndarray:
    if text is None:
        return np.zeros(3, dtype=np.int64)
    parts = text.split()
    if len(parts) != 3:
        raise ValueError(f"translation {text!r} is not three numbers")
    return np.array([int(p) for p in parts], dtype=np.int64)


def scene_placements(
    chunks: list[tuple[bytes, int, int]], cursor: Callable[[int, int, str], Any], *, frame: int,
    path: object,
) -> tuple[list[Placement], int]:
    """The visible models of the scene graph, each placed, and the number of animation frames.

    Parameters
    ----------
    chunks : list of (id, start, stop)
        The children of ``MAIN``.
    cursor : callable
        ``cursor(start, stop, name)``: a reader of the chunk's INT32, STRING and DICT values.
    frame : int
        Which model a shape node with several (animation frames) stands for, from 0.
    path : object
        The file, for messages.

    Raises
    ------
    FormatError
        For a node named twice, a child that does not exist, a cycle, a corrupt
        rotation or translation.
    """
    transforms: dict[int, tuple[dict[str, str], int, int, dict[str, str]]] = {}
    groups: dict[int, list[int]] = {}
    shapes: dict[int, list[int]] = {}
    hidden_layers: set[int] = set()
    for cid, start, stop in chunks:
        if cid not in (b"nTRN", b"nGRP", b"nSHP", b"LAYR"):
            continue
        cur = cursor(start, stop, cid.decode())
        node = cur.int32()
        attrs = cur.dict()
        if cid == b"LAYR":
            if attrs.get("_hidden") == "1":
                hidden_layers.add(node)
            continue
        if node in transforms or node in groups or node in shapes:
            raise FormatError(f"{path}: scene node {node} is defined twice")
        if cid == b"nTRN":
            child, _reserved, layer, frames = cur.int32(), cur.int32(), cur.int32(), cur.int32()
            if frames < 0 or frames > (stop - cur.pos) // 4:
                raise FormatError(f"{path}: nTRN node {node} holds a corrupt frame count {frames}")
            first = cur.dict() if frames else {}
            transforms[node] = (attrs, child, layer, first)
        elif cid == b"nGRP":
            count = cur.int32()
            if count < 0 or count > (stop - cur.pos) // 4:
                raise FormatError(f"{path}: nGRP node {node} holds a corrupt child count {count}")
            groups[node] = [cur.int32() for _ in range(count)]
        else:
            count = cur.int32()
            if count < 0 or count > (stop - cur.pos) // 8:
                raise FormatError(f"{path}: nSHP node {node} holds a corrupt model count {count}")
            models = []
            for _ in range(count):
                models.append(cur.int32())
                cur.dict()
            shapes[node] = models
    if 0 not in transforms:
        raise FormatError(f"{path}: the scene graph has no root transform (node 0)")

    frames = max((len(m) for m in shapes.values()), default=1)
    placed: list[Placement] = []
    # (node, rotation, translation, name, depth); a tree walk bounded by its depth.
    stack: list[tuple[int, np.ndarray, np.ndarray, str, int]] = [(0, np.eye(3, dtype=np.int64),
                                                                  np.zeros(3, dtype=np.int64), "", 0)]
    while stack:
        node, rot, shift, name, depth = stack.pop()
        if depth > _MAX_DEPTH:
            raise FormatError(f"{path}: the scene graph is deeper than {_MAX_DEPTH} nodes (a cycle?)")
        if node in transforms:
            attrs, child, layer, first = transforms[node]
            if attrs.get("_hidden") == "1" or layer in hidden_layers:
                continue
            try:
                local_rot = rotation_matrix(int(first.get("_r", "4")))
                local_shift = _translation(first.get("_t"))
            except ValueError as exc:
                raise FormatError(f"{path}: nTRN node {node} holds a corrupt transform ({exc})") from None
            stack.append((child, rot @ local_rot, rot @ local_shift + shift, attrs.get("_name") or name, depth + 1))
        elif node in groups:
            stack.extend((c, rot, shift, name, depth + 1) for c in reversed(groups[node]))
        elif node in shapes:
            models = shapes[node]
            if models:
                model = models[min(frame, len(models) - 1)]
                placed.append(Placement(model, rot, shift, name or f"model {model}"))
        else:
            raise FormatError(f"{path}: the scene graph names node {node}, which the file does not hold")
    return placed, frames


def place_voxels(xyz: np.ndarray, size: tuple[int, int, int], placement: Placement) -> np.ndarray:
    """World voxel coordinates ``(N, 3)`` of a model's voxels ``xyz`` placed by ``placement``.

    Computed on doubled coordinates, so that the half-voxel centres stay integers.
    """
    pivot = np.array(size, dtype=np.int64) // 2
    centre2 = 2 * xyz.astype(np.int64) + 1 - 2 * pivot
    world2 = centre2 @ placement.rotation.T + 2 * placement.translation
    return (world2 - 1) // 2
