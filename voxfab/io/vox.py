"""MagicaVoxel ``.vox``: RIFF-like chunks ``MAIN`` / ``SIZE`` / ``XYZI`` / ``RGBA``.

Layout (ephtracy/voxel-model, ``MagicaVoxel-file-format-vox.txt``)::

    "VOX " int32 version (150; newer editors write 200)
    chunk := id[4] int32 content_bytes int32 children_bytes content children
    MAIN  children: [PACK] (SIZE XYZI)+ [RGBA] [MATT/MATL/nTRN/nGRP/nSHP/LAYR/...]
    SIZE  int32 x, y, z                         (z is up)
    XYZI  int32 n, then n × uint8 (x, y, z, colour index 1..255)
    RGBA  256 × uint8 (r, g, b, a); entry i is the colour of index i + 1

Axes: MagicaVoxel is right-handed with z up, as voxfab is, so ``x, y, z`` in the
file are ``x, y, z`` of the grid ``[x, y, z]`` without any swap.

Reading keeps every voxel with its colour: the index of each voxel and the palette
(the file's ``RGBA``, else MagicaVoxel's default palette), so that writing it back
gives the same RGBA everywhere.  A voxel stored with colour index 0, which
MagicaVoxel never writes, takes index 255.  A version 200 file's scene graph is
read as the editor shows it: every visible model placed by its transforms
(:mod:`voxfab.io._voxscene`).  An animation (a ``PACK`` of models, or shape nodes
with a model per frame) gives its first frame, with a note, or the ``frame`` asked.
Writing gives one model (``SIZE`` + ``XYZI``) with each voxel's colour index and the
shape's palette (an uncoloured shape: index 1, a light grey), as
version 150, which every MagicaVoxel since 0.98 opens.
"""

from __future__ import annotations

import struct

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import as_grid
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.shape._colour import VoxelColours, default_palette

from ._registry import ReadResult, register

__all__ = ["read_vox", "vox_bytes", "write_vox", "VOX_VERSION", "MAX_VOX_SIDE"]

#: Version number written in the header.
VOX_VERSION = 150
#: Coordinates are one byte each, so a model has at most 256 voxels per side.
MAX_VOX_SIDE = 256

_MAGIC = b"VOX "
_SCENE_CHUNKS = frozenset({b"nTRN", b"nGRP", b"nSHP"})
_HEADER = struct.Struct("<4sii")


def _palette() -> bytes:
    """The palette written with every file: index 1 a warm light grey, then a grey ramp."""
    pal = np.zeros((256, 4), dtype=np.uint8)
    pal[:, 3] = 255
    pal[0, :3] = (214, 206, 190)
    ramp = np.linspace(250, 20, 254).round().astype(np.uint8)
    pal[1:255, :3] = ramp[:, None]
    pal[255] = 0  # entry 255 would be colour index 256, which does not exist
    return pal.tobytes()


_PALETTE = _palette()


def _chunk(chunk_id: bytes, content: bytes, children: bytes = b"") -> bytes:
    return _HEADER.pack(chunk_id, len(content), len(children)) + content + children


def vox_bytes(grid: BoolGrid, colours: VoxelColours | None = None) -> bytes:
    """Return the ``.vox`` file content of a grid (deterministic).

    Parameters
    ----------
    grid : (X, Y, Z) bool ndarray
        At most 256 voxels per side.
    colours : VoxelColours, optional
        Each voxel's colour index and the palette; default index 1, a light grey.

    Returns
    -------
    bytes
        ``VOX `` header, then ``MAIN`` holding ``SIZE``, ``XYZI`` and ``RGBA``.
    """
    g = as_grid(grid, name="shape", max_side=MAX_VOX_SIDE, allow_empty=True)
    xyz = np.argwhere(g)  # C order: sorted by x, then y, then z
    xyzi = np.empty((len(xyz), 4), dtype=np.uint8)
    xyzi[:, :3] = xyz
    xyzi[:, 3] = 1 if colours is None else colours.index[g]
    size = _chunk(b"SIZE", struct.pack("<3i", *g.shape))
    voxels = _chunk(b"XYZI", struct.pack("<i", len(xyz)) + xyzi.tobytes())
    # The file's RGBA entry i is colour index i + 1.
    palette = _PALETTE if colours is None else np.roll(colours.palette, -1, axis=0).tobytes()
    rgba = _chunk(b"RGBA", palette)
    main = _chunk(b"MAIN", b"", size + voxels + rgba)
    return _MAGIC + struct.pack("<i", VOX_VERSION) + main


def write_vox(grid: BoolGrid, path: PathLike, *, colours: VoxelColours | None = None) -> None:
    """Write a grid, in its colours when given, as a one-model MagicaVoxel file, atomically."""
    write_bytes(path, vox_bytes(grid, colours))


def _chunks(data: bytes, start: int, end: int, path: PathLike, where: str) -> list[tuple[bytes, int, int]]:
    """Split ``data[start:end]`` into chunks ``(id, content_start, content_end)``.

    Children of the chunks are skipped (only ``MAIN`` has children in the spec).
    """
    out = []
    pos = start
    while pos < end:
        if end - pos < _HEADER.size:
            raise FormatError(f"{path}: truncated chunk header at byte {pos} in {where}")
        cid, n_content, n_children = _HEADER.unpack_from(data, pos)
        if not all(32 <= c < 127 for c in cid):
            raise FormatError(f"{path}: corrupt chunk id {cid!r} at byte {pos} in {where}")
        name = cid.decode("ascii")
        if n_content < 0 or n_children < 0:
            raise FormatError(f"{path}: chunk {name} at byte {pos} has a negative size")
        body = pos + _HEADER.size
        if body + n_content + n_children > end:
            raise FormatError(
                f"{path}: chunk {name} at byte {pos} is truncated "
                f"(needs {n_content + n_children} bytes, {end - body} left in {where})"
            )
        out.append((cid, body, body + n_content))
        pos = body + n_content + n_children
    return out


def _model(data: bytes, size: tuple[int, int], xyzi: tuple[int, int], path: PathLike) -> np.ndarray:
    """Check one model's SIZE and XYZI chunks; return its colour index grid (0 = empty)."""
    s0, s1 = size
    if s1 - s0 < 12:
        raise FormatError(f"{path}: SIZE chunk holds {s1 - s0} bytes, expected 12")
    dims = struct.unpack_from("<3i", data, s0)
    if min(dims) < 1:
        raise FormatError(f"{path}: corrupt model size {dims} (a side below 1)")
    if max(dims) > MAX_VOX_SIDE:
        raise InvalidShapeError(
            f"{path}: grid {'x'.join(map(str, dims))} is over the limit of {MAX_VOX_SIDE} voxels per side"
        )
    x0, x1 = xyzi
    if x1 - x0 < 4:
        raise FormatError(f"{path}: XYZI chunk holds {x1 - x0} bytes, expected at least 4")
    (count,) = struct.unpack_from("<i", data, x0)
    if count < 0 or 4 + 4 * count > x1 - x0:
        raise FormatError(
            f"{path}: XYZI chunk is truncated: {count} voxels need {4 + 4 * count} bytes, "
            f"it holds {x1 - x0}"
        )
    xyzi = np.frombuffer(data, dtype=np.uint8, count=4 * count, offset=x0 + 4).reshape(count, 4)
    xyz = xyzi[:, :3]
    outside = (xyz >= np.array(dims)).any(axis=1)
    if outside.any():
        bad = tuple(int(v) for v in xyz[np.argmax(outside)])
        raise FormatError(f"{path}: voxel {bad} lies outside the model size {dims}")
    index = np.zeros(dims, dtype=np.uint8)
    # Index 0 is no colour in MagicaVoxel; such a voxel keeps the place of index 255,
    # the palette's last, unused, entry.
    index[xyz[:, 0], xyz[:, 1], xyz[:, 2]] = np.where(xyzi[:, 3] == 0, 255, xyzi[:, 3])
    return index


class _Cursor:
    """Reads the STRING and DICT values of the scene-graph chunks, bounds-checked."""

    def __init__(self, data: bytes, start: int, stop: int, path: PathLike, name: str) -> None:
        self.data, self.pos, self.stop, self.path, self.name = data, start, stop, path, name

    def int32(self) -> int:
        if self.pos + 4 > self.stop:
            raise FormatError(f"{self.path}: {self.name} chunk at byte {self.pos} is truncated")
        (value,) = struct.unpack_from("<i", self.data, self.pos)
        self.pos += 4
        return int(value)

    def string(self) -> str:
        n = self.int32()
        if n < 0 or self.pos + n > self.stop:
            raise FormatError(f"{self.path}: {self.name} chunk holds a corrupt string at byte {self.pos}")
        raw = self.data[self.pos : self.pos + n]
        self.pos += n
        return raw.decode("latin-1")

    def dict(self) -> dict[str, str]:
        n = self.int32()
        # Each pair takes at least 8 bytes: a bad count must not loop for long.
        if n < 0 or self.pos + 8 * n > self.stop:
            raise FormatError(f"{self.path}: {self.name} chunk holds a corrupt DICT at byte {self.pos}")
        return {self.string(): self.string() for _ in range(n)}


def read_vox(path: PathLike, *, frame: int | None = None) -> ReadResult:
    """Read a MagicaVoxel ``.vox`` file in its colours, as the editor shows it.

    Parameters
    ----------
    path : path
    frame : int, optional
        The animation frame to read, from 1 (default the first, with a note when
        the file holds several): a ``PACK`` file's models, or a scene's shape nodes'.

    Returns
    -------
    ReadResult
        ``grid`` (X, Y, Z) bool and ``colours``: a file without a scene graph gives
        its model with its ``SIZE``; a scene graph (version 200) gives every visible
        model placed by its transforms, cut to the scene's bounding box.

    Raises
    ------
    FormatError
        On a wrong magic, a truncated or corrupt chunk, a voxel outside its model,
        a corrupt scene graph.
    InvalidShapeError
        For a model over 256 voxels on a side, a scene that does not fit the
        25-voxel grid (naming its models and their sizes), a frame that does not exist.
    """
    with open(path, "rb") as fh:
        data = fh.read()
    if len(data) < 8 or data[:4] != _MAGIC:
        raise FormatError(f"{path}: not a MagicaVoxel file (the header 'VOX ' is missing)")
    (version,) = struct.unpack_from("<i", data, 4)
    if version <= 0:
        raise FormatError(f"{path}: corrupt .vox version {version}")
    if len(data) < 8 + _HEADER.size:
        raise FormatError(f"{path}: truncated .vox file ({len(data)} bytes)")
    cid, n_content, n_children = _HEADER.unpack_from(data, 8)
    if cid != b"MAIN":
        raise FormatError(f"{path}: the first chunk is {cid!r}, expected MAIN")
    start = 8 + _HEADER.size + n_content
    if n_content < 0 or n_children < 0 or start + n_children > len(data):
        raise FormatError(
            f"{path}: truncated MAIN chunk (needs {n_content + n_children} bytes, "
            f"the file holds {len(data) - 8 - _HEADER.size})"
        )
    if start + n_children < len(data):
        raise FormatError(f"{path}: {len(data) - start - n_children} unexpected bytes after MAIN")
    children = _chunks(data, start, start + n_children, path, "MAIN")

    sizes: list[tuple[int, int]] = []
    xyzis: list[tuple[int, int]] = []
    rgba: int | None = None
    scene = sorted({c.decode() for c, _, _ in children if c in _SCENE_CHUNKS})
    for cid, start, stop in children:
        if cid == b"SIZE":
            if len(sizes) != len(xyzis):
                raise FormatError(f"{path}: SIZE chunk without its XYZI chunk")
            sizes.append((start, stop))
        elif cid == b"XYZI":
            if len(xyzis) != len(sizes) - 1:
                raise FormatError(f"{path}: XYZI chunk without a SIZE chunk before it")
            xyzis.append((start, stop))
        elif cid == b"RGBA":
            if stop - start < 1024:
                raise FormatError(f"{path}: RGBA chunk holds {stop - start} bytes, expected 1024")
            rgba = start
    if not sizes:
        raise FormatError(f"{path}: no model (SIZE and XYZI chunks) in the file")
    if len(xyzis) != len(sizes):
        raise FormatError(f"{path}: the last SIZE chunk has no XYZI chunk")
    if rgba is None:
        palette = default_palette()
    else:
        # The file's entry i is colour index i + 1; entry 255 (index 256) does not exist.
        palette = np.roll(np.frombuffer(data, dtype=np.uint8, count=1024, offset=rgba).reshape(256, 4), 1, axis=0)
        # MagicaVoxel draws every voxel whatever its entry's alpha, and alpha 0 marks an empty voxel in
        # voxfab's RGBA grids and files: a voxel of an alpha-0 entry is read opaque, not lost on the way.
        palette[1:, 3] = np.where(palette[1:, 3] == 0, 255, palette[1:, 3])
    # Every model is checked, so that corruption anywhere is reported.
    models = [_model(data, s, x, path) for s, x in zip(sizes, xyzis)]
    if frame is not None and frame < 1:
        raise InvalidShapeError(f"{path}: frame {frame}: frames count from 1")
    notes: list[str] = []
    if scene:
        index, frames = _scene(data, children, models, path, frame=(frame or 1) - 1)
    else:
        frames = len(models) if any(c == b"PACK" for c, _, _ in children) else 1
        index = models[min((frame or 1) - 1, len(models) - 1)]
        if frames == 1 and len(models) > 1:
            notes.append(f"file has {len(models)} models and no scene graph; read the first")
    if frame is not None and frame > frames:
        raise InvalidShapeError(f"{path}: frame {frame}: the file holds {frames} frame{'s' * (frames > 1)}")
    if frame is None and frames > 1:
        notes.append(f"file holds {frames} animation frames; read the first (--frame K reads frame K)")
    return ReadResult(index != 0, None, tuple(notes), VoxelColours(index, palette))


def _scene(data: bytes, children: list[tuple[bytes, int, int]], models: list[np.ndarray], path: PathLike,
           *, frame: int) -> tuple[np.ndarray, int]:
    """The colour index grid of the scene as the editor shows it, and its number of frames."""
    from voxfab.shape import GRID_SIDE

    from ._voxscene import place_voxels, scene_placements

    placements, frames = scene_placements(
        children, lambda start, stop, name: _Cursor(data, start, stop, path, name), frame=frame, path=path)
    coords, colours, boxes = [], [], []
    for p in placements:
        if not 0 <= p.model < len(models):
            raise FormatError(f"{path}: the scene places model {p.model}; the file holds {len(models)}")
        model = models[p.model]
        xyz = np.argwhere(model)
        world = place_voxels(xyz, model.shape, p)
        coords.append(world)
        colours.append(model[tuple(xyz.T)])
        if len(world):
            # The model's own box as the scene turns it, and where its voxels land.
            boxes.append((p.name, np.abs(p.rotation) @ np.array(model.shape), world.min(axis=0)))
    if not boxes:
        raise InvalidShapeError(f"{path}: the scene shows no voxel (every model is hidden or empty)")
    every = np.concatenate(coords)
    lo, hi = every.min(axis=0), every.max(axis=0)
    size = hi - lo + 1
    if size.max() > GRID_SIDE:
        parts = "; ".join(f"{name} ({'x'.join(map(str, box))}) at ({', '.join(map(str, at))})"
                          for name, box, at in boxes)
        raise InvalidShapeError(f"{path}: the scene is {'x'.join(map(str, size))} voxels, over the "
                                f"{GRID_SIDE}-voxel grid: {parts}")
    index = np.zeros(tuple(size), dtype=np.uint8)
    # Models later in the scene cover earlier ones where they overlap.
    for world, colour in zip(coords, colours):
        local = world - lo
        index[local[:, 0], local[:, 1], local[:, 2]] = colour
    return index, frames


register(".vox", reader=read_vox, writer=write_vox)
