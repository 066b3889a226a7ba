"""A numpy z-buffer rasterizer for voxel faces under an orthographic camera.

Every exposed voxel face that looks at the camera is a parallelogram on screen.
Each one is sampled at the pixel centres of its bounding box (whole arrays, in
chunks of faces), the nearest sample per pixel wins through a packed
``(depth, face)`` key and ``np.minimum.at``, and the winning face's local
coordinates give its distance to the voxel edges, which are drawn dark.

Colour is one scalar *shade* per pixel times the base colour, so a picture of an
uncoloured shape uses at most 256 colours (background + shade levels) and GIF
frames share one fixed palette exactly.  The raster also keeps the voxel each pixel
shows, so a coloured shape is drawn with each voxel's own colour times its shade.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid, check_positive
from voxfab.errors import InvalidShapeError
from voxfab.shape import DIRECTIONS, VoxelColours

from ._views import Camera

__all__ = ["Raster", "rasterize", "fit_frame", "Frame", "parse_color", "to_rgb", "to_indexed",
           "DEFAULT_COLOR", "EDGE_SHADE"]

#: Base colour of the cubes (a light card tone).
DEFAULT_COLOR = (236, 204, 150)
#: Shade multiplier of voxel edge lines.
EDGE_SHADE = 0.28
#: Ambient and diffuse parts of the flat shading (they sum to 1: a face facing the light is the base colour).
_AMBIENT, _DIFFUSE = 0.38, 0.62
#: How much darker the farthest visible point is than the nearest (depth cue for axis views).
_DEPTH_CUE = 0.30
_FACE_BITS = 28
_DEPTH_QUANTUM = 4096.0
#: Samples handled per chunk: bounds peak memory near 100 MB.
_CHUNK_SAMPLES = 1 << 21


def parse_color(value: str | tuple[int, int, int] | list[int], *, name: str) -> tuple[int, int, int]:
    """Return an ``(r, g, b)`` tuple for a colour name, ``#rrggbb`` text or a triple."""
    if isinstance(value, str):
        from PIL import ImageColor

        try:
            rgb = ImageColor.getrgb(value)
        except ValueError:
            raise InvalidShapeError(f"{name}: unknown colour {value!r}; use a name or #rrggbb") from None
        return (int(rgb[0]), int(rgb[1]), int(rgb[2]))
    t = tuple(int(c) for c in value)
    if len(t) != 3 or not all(0 <= c <= 255 for c in t):
        raise InvalidShapeError(f"{name}: expected 3 integers in 0..255, got {value!r}")
    return (t[0], t[1], t[2])


@dataclasses.dataclass(frozen=True)
class Frame:
    """Where world points land in the picture: ``col = ox + s·x_cam``, ``row = oy − s·y_cam``.

    Attributes
    ----------
    width, height : int
        Picture size in pixels.
    scale : float
        Pixels per voxel.
    ox, oy : float
        Pixel position of the world origin.
    """

    width: int
    height: int
    scale: float
    ox: float
    oy: float


@dataclasses.dataclass(frozen=True, eq=False)
class Raster:
    """The rasterized picture before colouring.

    Attributes
    ----------
    shade : (H, W) float32 ndarray
        Brightness in [0, 1] of covered pixels (0 elsewhere).
    coverage : (H, W) bool ndarray
        Pixels covered by the shape.
    edge : (H, W) bool ndarray
        Covered pixels that belong to a voxel edge line.
    frame : Frame
        The projection used.
    voxel : (H, W) int64 ndarray
        The flat index (C order, in the grid rasterized) of the voxel each covered
        pixel shows; -1 elsewhere.
    """

    shade: npt.NDArray[np.float32]
    coverage: npt.NDArray[np.bool_]
    edge: npt.NDArray[np.bool_]
    frame: Frame
    voxel: npt.NDArray[np.int64]


def _box_corners(lo: npt.NDArray[np.int64], hi: npt.NDArray[np.int64]) -> npt.NDArray[np.float64]:
    idx = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    return np.where(idx == 0, lo, hi).astype(np.float64)


def fit_frame(
    lo: npt.ArrayLike,
    hi: npt.ArrayLike,
    camera: Camera,
    *,
    width: int,
    height: int,
    margin: float = 0.04,
    scale: float | None = None,
) -> Frame:
    """Frame the world box ``[lo, hi]`` (voxel-corner coordinates) in a picture.

    The box is centred; without ``scale`` it is as large as the margin allows.
    For axis-aligned cameras the scale is rounded down to whole pixels per voxel
    (when at least 1) and the origin to a whole pixel, so every voxel face covers
    exactly ``scale × scale`` pixels.
    """
    corners = _box_corners(np.asarray(lo, dtype=np.int64), np.asarray(hi, dtype=np.int64))
    xs = corners @ camera.right
    ys = corners @ camera.up
    span_x = max(float(xs.max() - xs.min()), 1e-9)
    span_y = max(float(ys.max() - ys.min()), 1e-9)
    if scale is None:
        s = (1.0 - 2.0 * margin) * min(width / span_x, height / span_y)
        if camera.axis_aligned and s >= 1.0:
            s = float(math.floor(s))
    else:
        s = check_positive(scale, name="scale")
    ox = width / 2.0 - s * (float(xs.max()) + float(xs.min())) / 2.0
    oy = height / 2.0 + s * (float(ys.max()) + float(ys.min())) / 2.0
    if camera.axis_aligned:
        ox, oy = float(round(ox)), float(round(oy))
    return Frame(width=int(width), height=int(height), scale=s, ox=ox, oy=oy)


def _visible_faces(
    grid: npt.NDArray[np.bool_], camera: Camera
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """Origin corners ``(F, 3)``, directions ``(F,)`` and voxels (flat indices) of exposed faces facing the camera."""
    p = np.pad(grid, 1)
    origins, dirs, voxels = [], [], []
    for d, n in enumerate(DIRECTIONS):
        if float(n @ camera.toward) <= 1e-9:
            continue  # back faces are hidden by the front ones of a closed surface
        exposed = p & ~np.roll(p, tuple(-n), axis=(0, 1, 2))
        v = np.argwhere(exposed[1:-1, 1:-1, 1:-1])
        o = v.astype(np.float64)
        if d % 2 == 0:
            o[:, d // 2] += 1.0
        origins.append(o)
        dirs.append(np.full(len(v), d, dtype=np.int64))
        voxels.append(np.ravel_multi_index(tuple(v.T), grid.shape) if len(v) else np.zeros(0, np.int64))
    if not origins:
        return np.zeros((0, 3)), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(origins), np.concatenate(dirs), np.concatenate(voxels).astype(np.int64)


def _face_axes(d: int) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    a = d // 2
    e1 = np.zeros(3)
    e2 = np.zeros(3)
    e1[(a + 1) % 3] = 1.0
    e2[(a + 2) % 3] = 1.0
    return e1, e2


def rasterize(
    grid: npt.ArrayLike,
    camera: Camera,
    frame: Frame,
    *,
    edge_width: float | None = None,
    light: tuple[float, float, float] = (-0.35, 0.6, 0.75),
) -> Raster:
    """Rasterize the visible voxel faces of ``grid``.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape, indexed ``[x, y, z]``; voxel ``(x, y, z)`` spans ``[x, x+1]×[y, y+1]×[z, z+1]``.
    camera : Camera
        Orthographic view.
    frame : Frame
        Picture size and placement (see :func:`fit_frame`).
    edge_width : float or None
        Half width of the voxel edge lines in pixels (default ``0.05·scale`` within [0.5, 1.6]).
    light : (3,) float
        Light direction in camera coordinates (right, up, toward).

    Returns
    -------
    Raster
        Shade, coverage and edge masks of shape ``(height, width)``.
    """
    g = as_grid(grid, name="shape", allow_empty=True)
    w, h, s = frame.width, frame.height, frame.scale
    ew = min(max(0.5, 0.05 * s), 1.6) if edge_width is None else float(edge_width)
    origins, dirs, face_voxel = _visible_faces(g, camera)
    nf = len(dirs)
    if nf >= 1 << _FACE_BITS:
        raise InvalidShapeError(f"shape: {nf} visible faces is too many to render")
    cam = camera.matrix
    lvec = np.asarray(light, dtype=np.float64) @ cam  # camera → world
    lvec /= np.linalg.norm(lvec)

    # Screen position (pixels) of each face's origin corner and its depth (smaller = nearer).
    oc = origins @ cam.T
    sx = frame.ox + s * oc[:, 0]
    sy = frame.oy - s * oc[:, 1]
    depth = -oc[:, 2]
    dmin = float(depth.min() - 2.0) if nf else 0.0

    inv = np.zeros((6, 2, 2))
    dz = np.zeros((6, 2))
    heights = np.ones((6, 2))
    face_shade = np.zeros(6)
    for d in range(6):
        e1, e2 = _face_axes(d)
        a = np.array([s * (e1 @ camera.right), -s * (e1 @ camera.up)])
        b = np.array([s * (e2 @ camera.right), -s * (e2 @ camera.up)])
        m = np.stack([a, b], axis=1)
        det = float(np.linalg.det(m))
        if abs(det) < 1e-12:
            continue  # edge-on: never visible
        inv[d] = np.linalg.inv(m)
        dz[d] = [-(e1 @ camera.toward), -(e2 @ camera.toward)]
        heights[d] = [abs(det) / np.linalg.norm(b), abs(det) / np.linalg.norm(a)]
        face_shade[d] = _AMBIENT + _DIFFUSE * max(0.0, float(DIRECTIONS[d] @ lvec))

    zbuf = np.full(w * h, np.iinfo(np.int64).max, dtype=np.int64)
    for d in np.unique(dirs):
        sel = np.flatnonzero(dirs == d)
        quad = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=np.float64)
        m = np.linalg.inv(inv[d])
        offs = quad @ m.T  # pixel offsets of the 4 corners from the origin corner
        k = int(math.ceil(offs[:, 0].max() - offs[:, 0].min())) + 2
        kk = int(math.ceil(offs[:, 1].max() - offs[:, 1].min())) + 2
        jj, ii = np.meshgrid(np.arange(k), np.arange(kk))
        jj, ii = jj.ravel(), ii.ravel()
        # u, v of a sample = per-face part + per-offset part, so the big arrays cost one add each.
        m00, m01, m10, m11 = inv[d, 0, 0], inv[d, 0, 1], inv[d, 1, 0], inv[d, 1, 1]
        u_off = m00 * (jj + 0.5) + m01 * (ii + 0.5)
        v_off = m10 * (jj + 0.5) + m11 * (ii + 0.5)
        per_chunk = max(1, _CHUNK_SAMPLES // (k * kk))
        for start in range(0, len(sel), per_chunk):
            f = sel[start : start + per_chunk]
            bx = np.floor(sx[f] + offs[:, 0].min()).astype(np.int64)
            by = np.floor(sy[f] + offs[:, 1].min()).astype(np.int64)
            fx, fy = bx - sx[f], by - sy[f]
            u = (m00 * fx + m01 * fy)[:, None] + u_off[None, :]
            v = (m10 * fx + m11 * fy)[:, None] + v_off[None, :]
            inside = (u >= 0) & (u < 1) & (v >= 0) & (v < 1)
            row, col = np.nonzero(inside)
            px = bx[row] + jj[col]
            py = by[row] + ii[col]
            ok = (px >= 0) & (px < w) & (py >= 0) & (py < h)
            row, col, px, py = row[ok], col[ok], px[ok], py[ok]
            fi = f[row]
            z = depth[fi] + u[row, col] * dz[d, 0] + v[row, col] * dz[d, 1]
            key = (np.rint((z - dmin) * _DEPTH_QUANTUM).astype(np.int64) << _FACE_BITS) | fi
            np.minimum.at(zbuf, py * w + px, key)

    covered = zbuf != np.iinfo(np.int64).max
    pix = np.flatnonzero(covered)
    win = zbuf[pix] & ((1 << _FACE_BITS) - 1)
    wd = dirs[win]
    rx = (pix % w) + 0.5 - sx[win]
    ry = (pix // w) + 0.5 - sy[win]
    u = inv[wd, 0, 0] * rx + inv[wd, 0, 1] * ry
    v = inv[wd, 1, 0] * rx + inv[wd, 1, 1] * ry
    du = np.minimum(u, 1 - u) * heights[wd, 0]
    dv = np.minimum(v, 1 - v) * heights[wd, 1]
    on_edge = (du < ew) | (dv < ew)
    zq = (zbuf[pix] >> _FACE_BITS).astype(np.float64) / _DEPTH_QUANTUM
    zlo = float(zq.min()) if len(zq) else 0.0
    span = float(zq.max()) - zlo if len(zq) else 0.0
    cue = 1.0 - _DEPTH_CUE * ((zq - zlo) / span if span > 0 else 0.0)
    val = face_shade[wd] * cue * np.where(on_edge, EDGE_SHADE, 1.0)

    shade = np.zeros(w * h, dtype=np.float32)
    shade[pix] = val
    edge = np.zeros(w * h, dtype=bool)
    edge[pix] = on_edge
    voxel = np.full(w * h, -1, dtype=np.int64)
    voxel[pix] = face_voxel[win]
    return Raster(
        shade=shade.reshape(h, w),
        coverage=covered.reshape(h, w),
        edge=edge.reshape(h, w),
        frame=frame,
        voxel=voxel.reshape(h, w),
    )


#: Number of shade levels in indexed pictures (palette index 0 is the background).
SHADE_LEVELS = 255


def palette_for(color: tuple[int, int, int], background: tuple[int, int, int]) -> list[int]:
    """The fixed 256-colour palette: background, then ``color × i/254`` for i = 0..254."""
    levels = np.arange(SHADE_LEVELS, dtype=np.float64) / (SHADE_LEVELS - 1)
    rgb = np.rint(levels[:, None] * np.asarray(color, dtype=np.float64)[None, :]).astype(np.int64)
    return [*background, *rgb.ravel().tolist()]


def to_indexed(raster: Raster) -> npt.NDArray[np.uint8]:
    """``(H, W)`` palette indices for :func:`palette_for` (0 = background)."""
    idx = 1 + np.rint(np.clip(raster.shade, 0.0, 1.0) * (SHADE_LEVELS - 1)).astype(np.int64)
    return np.where(raster.coverage, idx, 0).astype(np.uint8)


def to_rgb(
    raster: Raster, color: tuple[int, int, int], background: tuple[int, int, int],
    colours: VoxelColours | None = None,
) -> npt.NDArray[np.uint8]:
    """``(H, W, 3)`` uint8 picture: the palette of :func:`palette_for` applied to :func:`to_indexed`, or,
    with ``colours`` (of the grid rasterized), each pixel its voxel's colour times its shade."""
    pal = np.asarray(palette_for(color, background), dtype=np.uint8).reshape(-1, 3)
    if colours is None:
        return pal[to_indexed(raster)]
    base = colours.rgba[..., :3].reshape(-1, 3)[np.maximum(raster.voxel, 0)].astype(np.float64)
    shaded = np.rint(base * np.clip(raster.shade, 0.0, 1.0)[..., None]).astype(np.uint8)
    return np.where(raster.coverage[..., None], shaded, np.asarray(background, dtype=np.uint8))
