"""Coloured voxel art of realistic complexity for the colour tests, and a ``.vox`` reader of their own.

``character()`` is a MagicaVoxel-style figure, 19 x 7 x 20 voxels in a 20 x 21 x 20
grid, in 12 colours and 5 parts: the body (legs, torso, neck, head, buttons) is one
6-connected piece, the raised arms touch the shoulders along edges only, the sword
touches a hand at one corner, and the feather touches the head at one corner, as
voxel art usually is.  Single-voxel details (eyes, buttons) are in colours of their own.

``read_vox_independently`` parses a ``.vox`` with ``struct`` alone, sharing no code
with voxfab, so that a test can check what voxfab wrote.
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

from voxfab.shape import VoxelColours, VoxelShape

#: The character's colours by part: RGBA.
CHARACTER_COLOURS = {
    "trousers": (40, 60, 150, 255),
    "shoes": (90, 50, 20, 255),
    "shirt": (200, 40, 40, 255),
    "belt": (20, 20, 20, 255),
    "buttons": (240, 200, 30, 255),
    "skin": (240, 190, 150, 255),
    "eyes": (255, 255, 255, 255),
    "mouth": (120, 10, 30, 255),
    "hair": (70, 40, 10, 255),
    "feather": (30, 160, 60, 255),
    "blade": (170, 175, 185, 255),
    "hilt": (200, 150, 20, 255),
}


def character_rgba() -> np.ndarray:
    """The character as an RGBA grid ``(20, 21, 20, 4)``: alpha 0 where empty."""
    rgba = np.zeros((20, 21, 20, 4), dtype=np.uint8)

    def put(part: str, xs: slice | int, ys: slice | int, zs: slice | int) -> None:
        rgba[xs, ys, zs] = CHARACTER_COLOURS[part]

    put("trousers", slice(5, 8), slice(8, 11), slice(1, 5))
    put("trousers", slice(12, 15), slice(8, 11), slice(1, 5))
    put("shoes", slice(5, 8), slice(7, 11), 0)
    put("shoes", slice(12, 15), slice(7, 11), 0)
    put("shirt", slice(4, 16), slice(7, 12), slice(6, 12))
    put("belt", slice(4, 16), slice(7, 12), 5)
    put("trousers", slice(8, 12), slice(8, 11), 4)  # the crotch joins the legs to the belt
    put("buttons", slice(9, 11), 6, 7)
    put("buttons", slice(9, 11), 6, 9)
    # Raised arms: each touches the torso's top edge along an edge only.
    put("skin", slice(1, 4), slice(8, 11), slice(12, 15))
    put("skin", slice(16, 19), slice(8, 11), slice(12, 15))
    put("skin", slice(9, 11), 9, 12)  # neck
    put("skin", slice(7, 13), slice(7, 12), slice(13, 18))  # head
    put("hair", slice(7, 13), slice(7, 12), 18)
    put("eyes", 8, 7, 16)
    put("eyes", 11, 7, 16)
    put("mouth", slice(9, 11), 7, 14)
    put("feather", 13, 12, 19)  # touches the hair at one corner
    put("blade", 0, 7, slice(15, 20))  # touches the left hand at one corner
    put("hilt", 0, 7, 15)
    return rgba


def character(pitch: float = 2.0) -> VoxelShape:
    """The character as a coloured shape."""
    rgba = character_rgba()
    grid = rgba[..., 3] > 0
    return VoxelShape(grid, pitch, VoxelColours.from_rgba(grid, rgba))


def read_vox_independently(path: str | Path) -> tuple[tuple[int, int, int], dict[tuple[int, int, int], tuple]]:
    """``(size, {(x, y, z): (r, g, b, a)})`` of the first model of a ``.vox``, by the spec alone."""
    data = Path(path).read_bytes()
    assert data[:4] == b"VOX "
    pos = 8 + 12  # header, then MAIN's own header: its children follow
    size, voxels, palette = None, None, None
    while pos < len(data):
        cid = data[pos:pos + 4]
        n, m = struct.unpack_from("<ii", data, pos + 4)
        body = data[pos + 12:pos + 12 + n]
        if cid == b"SIZE" and size is None:
            size = struct.unpack_from("<3i", body)
        elif cid == b"XYZI" and voxels is None:
            (count,) = struct.unpack_from("<i", body)
            voxels = [tuple(body[4 + 4 * i:8 + 4 * i]) for i in range(count)]
        elif cid == b"RGBA":
            palette = [tuple(body[4 * i:4 * i + 4]) for i in range(256)]
        pos += 12 + n + m
    assert size is not None and voxels is not None and palette is not None
    # The file's RGBA entry i is the colour of index i + 1.
    return size, {(x, y, z): palette[c - 1] for x, y, z, c in voxels}


def write_animated_character(path: Path) -> None:
    """A two-frame .vox (a PACK of models): the character, then the character mirrored left to right."""
    from voxfab import io

    chunks = []
    for k, shape in enumerate((character(), character().mirror("x"))):
        io.write(shape, path.with_name(f"f{k}.vox"))
        data = path.with_name(f"f{k}.vox").read_bytes()
        found, at = {}, 20
        while at < len(data):
            cid, n, m = data[at:at + 4], *struct.unpack("<ii", data[at + 4:at + 12])
            found[cid] = data[at:at + 12 + n + m]
            at += 12 + n + m
        chunks.append(found)
    assert chunks[0][b"RGBA"] == chunks[1][b"RGBA"]  # one palette serves both frames
    body = (b"PACK" + struct.pack("<iii", 4, 0, 2) + b"".join(c[b"SIZE"] + c[b"XYZI"] for c in chunks)
            + chunks[0][b"RGBA"])
    path.write_bytes(b"VOX " + struct.pack("<i", 150) + b"MAIN" + struct.pack("<ii", 0, len(body)) + body)

