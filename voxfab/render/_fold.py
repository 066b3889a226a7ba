"""Folding a net up: from the flat sheet to the shape, each face hinged on its parent.

Each face of a net has a rigid pose: the map from its place in the sheet
(``corners2d`` at z = 0, seen from outside) to its place on the surface
(``corners3d``).  Along the fold tree, a child's pose is its parent's pose
followed by a turn about their shared edge; :func:`fold_poses` turns every
hinge by the same fraction of its angle, so at 0 the net lies flat in the plane
of the root face and at 1 every face is back on the surface, exactly.  Mountain
and valley folds turn opposite ways because the angles come from the surface
itself, never from a rule.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.errors import InvalidShapeError
from voxfab.shape import VoxelColours
from voxfab.unfold import fold_tree

from ._image import gif_bytes, shared_palette
from ._views import View, camera_for, orbit_camera

__all__ = ["fold_angles", "fold_frames", "draw_fold", "save_fold_animation"]

#: Most frames of a fold animation.
MAX_FOLD_FRAMES = 240


def _poses(net: object) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Each face's rotation (F, 3, 3) and translation (F, 3) from the sheet (z = 0) to the surface."""
    c2 = np.asarray(net.corners2d, dtype=np.float64)  # type: ignore[attr-defined]
    c3 = np.asarray(net.corners3d, dtype=np.float64)  # type: ignore[attr-defined]
    n = np.asarray(net.normal, dtype=np.float64)  # type: ignore[attr-defined]
    f = c2.shape[0]
    src = np.zeros((f, 3, 3))
    src[:, :2, 0] = c2[:, 1] - c2[:, 0]
    src[:, :2, 1] = c2[:, 3] - c2[:, 0]
    src[:, 2, 2] = 1.0  # the sheet's +z, towards the viewer, is the outside
    dst = np.stack([c3[:, 1] - c3[:, 0], c3[:, 3] - c3[:, 0], n], axis=2)
    rot = dst @ np.linalg.inv(src)
    flat0 = np.concatenate([c2[:, 0], np.zeros((f, 1))], axis=1)
    shift = c3[:, 0] - np.einsum("fij,fj->fi", rot, flat0)
    return rot, shift


def _hinge(net: object, a: int, b: int) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """A point on the edge parent ``a`` and child ``b`` share in the sheet, and its unit direction (z = 0).

    The direction has the child on its left, seen from outside: a turn by a positive
    angle then lifts the child towards the viewer, so the angle's sign tells a
    valley fold (positive) from a mountain fold (negative).
    """
    c2 = np.asarray(net.corners2d, dtype=np.int64)  # type: ignore[attr-defined]
    shared = [p for p in c2[a].tolist() if p in c2[b].tolist()]
    if len(shared) != 2:
        raise InvalidShapeError(f"net: faces {a} and {b} are folded together but share no edge in the sheet")
    p, q = (np.array([*s, 0.0]) for s in shared)
    axis = (q - p) / np.linalg.norm(q - p)
    towards_child = np.array([*c2[b].mean(axis=0), 0.0]) - p
    if np.cross(axis, towards_child)[2] < 0:
        p, axis = q, -axis
    return p, axis


def _turn(axis: npt.NDArray[np.float64], angle: float) -> npt.NDArray[np.float64]:
    """Rotation matrix about the unit ``axis`` by ``angle`` radians (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def fold_angles(net: object) -> tuple[int, npt.NDArray[np.int64], list[int], npt.NDArray[np.float64]]:
    """The fold tree and each face's hinge angle on its parent, radians (0 for the root).

    The angle turns the child about the shared edge, directed as :func:`_hinge`
    gives it, from the sheet to the surface: a quarter turn one way for a
    mountain fold, the other way for a valley fold, 0 for a flat one.
    """
    root, parent, order = fold_tree(net)
    rot, _ = _poses(net)
    angles = np.zeros(len(parent))
    for c in order[1:]:
        p = int(parent[c])
        _, axis = _hinge(net, p, c)
        relative = rot[p].T @ rot[c]  # the child's pose in the parent's sheet frame
        skew = np.array([relative[2, 1] - relative[1, 2], relative[0, 2] - relative[2, 0],
                         relative[1, 0] - relative[0, 1]]) / 2.0
        angles[c] = math.atan2(float(skew @ axis), (float(np.trace(relative)) - 1.0) / 2.0)
    return root, parent, order, angles


def fold_frames(net: object, *, steps: int = 24) -> list[npt.NDArray[np.float64]]:
    """The face corners (F, 4, 3) at ``steps`` moments from flat (first) to folded (last).

    The last frame is the net's own ``corners3d``: the folded faces are the surface.
    """
    if isinstance(steps, bool) or not isinstance(steps, int) or not 2 <= steps <= MAX_FOLD_FRAMES:
        raise InvalidShapeError(f"steps: expected a whole number from 2 to {MAX_FOLD_FRAMES}, got {steps!r}")
    root, parent, order, angles = fold_angles(net)
    rot, shift = _poses(net)
    c2 = np.asarray(net.corners2d, dtype=np.float64)  # type: ignore[attr-defined]
    flat = np.concatenate([c2, np.zeros(c2.shape[:2] + (1,))], axis=2)  # (F, 4, 3) in the sheet
    hinges = {c: _hinge(net, int(parent[c]), c) for c in order[1:]}
    frames = []
    for t in np.linspace(0.0, 1.0, steps):
        r = np.empty_like(rot)
        s = np.empty_like(shift)
        # The root stays where it lies on the surface; the sheet unrolls around it.
        r[root], s[root] = rot[root], shift[root]
        for c in order[1:]:
            p = int(parent[c])
            point, axis = hinges[c]
            turn = _turn(axis, float(t) * angles[c])
            # pose_c = pose_p ∘ (turn about the hinge line through `point`), in the sheet's frame.
            r[c] = r[p] @ turn
            s[c] = r[p] @ (point - turn @ point) + s[p]
        frames.append(np.einsum("fij,fkj->fki", r, flat) + s[:, None, :])
    return frames


def draw_fold(corners: npt.NDArray[np.float64], *, view: str = "iso", size: int = 400,
              scale: tuple[npt.NDArray[np.float64], float] | None = None,
              face_rgb: npt.NDArray[np.uint8] | None = None) -> object:
    """One picture of faces in space: the painter's algorithm, the outside shaded, the back paper-grey.

    ``scale`` (centre, half-width) fixes the framing so the frames of one animation line up;
    ``face_rgb`` (F, 3) colours each face's outside (default: card).
    """
    from PIL import Image, ImageDraw

    camera = camera_for(view) if view != "iso" else orbit_camera(-55.0, 30.0)
    m = camera.matrix
    pts = corners @ m.T  # (F, 4, 3): right, up, toward
    if scale is None:
        flat = pts.reshape(-1, 3)
        centre = (flat.min(axis=0) + flat.max(axis=0)) / 2
        half = float(max(np.ptp(flat[:, 0]), np.ptp(flat[:, 1]))) / 2 or 1.0
    else:
        centre, half = scale[0] @ m.T, scale[1]
    px = (pts[..., :2] - centre[:2]) / (2.05 * half) * size + size / 2
    px[..., 1] = size - px[..., 1]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 3] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    facing = normals @ camera.toward
    light = np.abs(normals @ np.array([0.36, 0.48, 0.8]))
    image = Image.new("RGB", (size, size), "white")
    draw = ImageDraw.Draw(image)
    # Face edges only where faces are large enough to show them; else they would turn the picture dark.
    edge = float(np.linalg.norm(px[:, 1] - px[:, 0], axis=1).mean()) if len(px) else 0.0
    outline = (60, 45, 30) if edge >= 6 else None
    for f in np.argsort(pts[..., 2].mean(axis=1)):  # far faces first
        shade = 0.55 + 0.45 * float(light[f])
        outside = (225, 190, 140) if face_rgb is None else face_rgb[f].tolist()
        colour = (int(outside[0] * shade), int(outside[1] * shade), int(outside[2] * shade)) if facing[f] > 0 \
            else (int(200 * shade), int(200 * shade), int(200 * shade))
        draw.polygon([tuple(p) for p in px[f].tolist()], fill=colour, outline=outline)
    return image


def _face_colours(net: object, colours: VoxelColours) -> npt.NDArray[np.uint8]:
    """The RGB of each face's voxel; refused when a face's voxel is not a coloured voxel (another shape's net)."""
    v = np.asarray(net.voxel, dtype=np.int64).reshape(-1, 3)  # type: ignore[attr-defined]
    inside = np.all((v >= 0) & (v < colours.index.shape), axis=1)
    if not inside.all() or not colours.index[v[:, 0], v[:, 1], v[:, 2]].all():
        raise InvalidShapeError("colours: the net's faces do not lie on the shape's voxels; give the shape "
                                "the net was made of")
    return colours.at(v)[:, :3]


def save_fold_animation(net: object, path: PathLike, *, steps: int = 36, view: str = "iso", size: int = 400,
                        duration_ms: int = 80, hold: int = 8, colours: VoxelColours | None = None) -> int:
    """Write a GIF of ``net`` folding up from flat to the shape; return its frame count (``steps``).

    The folded shape is held for ``hold`` more frame times at the end (one frame of the GIF).
    With ``colours`` (of the grid the net unfolds) each face shows its voxel's colour, and all
    frames share one palette made for them (:func:`~._image.shared_palette`).
    """
    if view not in tuple(v.value for v in View):
        raise InvalidShapeError(f"view: expected one of {', '.join(v.value for v in View)}, got {view!r}")
    frames = fold_frames(net, steps=steps)
    every = np.concatenate([f.reshape(-1, 3) for f in frames])
    centre = (every.min(axis=0) + every.max(axis=0)) / 2
    # One framing for the whole animation: the widest moment sets it.
    half = float(np.linalg.norm(every - centre, axis=1).max())
    face_rgb = None if colours is None else _face_colours(net, colours)
    pictures = [draw_fold(f, view=view, size=size, scale=(centre, half), face_rgb=face_rgb) for f in frames]
    if face_rgb is not None:
        pictures = shared_palette(pictures, face_rgb)
    pictures += [pictures[-1]] * hold
    write_bytes(path, gif_bytes(pictures, duration_ms=duration_ms))  # type: ignore[arg-type]
    return len(frames)
