"""Every reader turns corrupt input into a FormatError naming the file, never a traceback."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh
from PIL import Image

from voxfab import io
from voxfab.errors import FormatError
from voxfab.shape import examples

WRITABLE = [".npy", ".npz", ".txt", ".vox", ".binvox"]
MESHES = [".stl", ".obj", ".ply", ".3mf", ".glb"]
READERS = [*WRITABLE, ".png", "/", *MESHES]

TEXT = b"Shopping list:\n- eggs\n- flour\n- 25 little cubes\n" * 4


def test_every_reader_is_covered():
    assert sorted(READERS) == io.readable_formats()


def valid_bytes(ext: str, tmp: Path) -> bytes:
    """The bytes of a valid file of the format (for "/": of its first slice)."""
    path = tmp / f"valid{'.png' if ext == '/' else ext}"
    if ext in WRITABLE:
        io.write(examples.ball(3), path)
    elif ext in (".png", "/"):
        Image.fromarray(np.where(examples.ball(3)[:, :, 3], 0, 255).astype(np.uint8), "L").save(path)
    else:
        trimesh.creation.icosphere(subdivisions=1, radius=2.0).export(path)
    io.read(path.parent if ext == "/" else path)  # the valid file does read
    return path.read_bytes()


def put(ext: str, tmp: Path, data: bytes, name: str) -> tuple[Path, Path]:
    """Store ``data`` as a file of the format; return (path to read, file holding the data)."""
    if ext == "/":
        folder = tmp / name
        folder.mkdir()
        (folder / "z0.png").write_bytes(data)
        return folder, folder / "z0.png"
    path = tmp / f"{name}{ext}"
    path.write_bytes(data)
    return path, path


def check_format_error(path: Path, culprit: Path) -> str:
    with pytest.raises(FormatError) as info:
        io.read(path)
    message = str(info.value)
    assert str(culprit) in message and "\n" not in message
    return message


@pytest.fixture
def tmp(tmp_path):
    (tmp_path / "valid").mkdir()
    return tmp_path


@pytest.mark.parametrize("ext", READERS)
def test_truncated(tmp, ext):
    data = valid_bytes(ext, tmp / "valid")
    cuts = sorted({1, len(data) // 4, len(data) // 2, 3 * len(data) // 4, len(data) - 2})
    for cut in cuts:
        path, culprit = put(ext, tmp, data[:cut], f"cut{cut}")
        if ext == ".obj" and cut > len(data) // 4:
            # OBJ declares no counts and no end: a cut file is often a smaller valid
            # mesh (usually an open one, which the notes then report).  It must read
            # or fail with a FormatError, nothing else.
            try:
                result = io.read(path)
            except FormatError:
                continue
            assert result.grid.any() and result.notes[0].startswith("mesh of ")
            continue
        check_format_error(path, culprit)


@pytest.mark.parametrize("ext", READERS)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_garbage(tmp, ext, seed):
    data = np.random.default_rng(seed).integers(0, 256, 600 + 37 * seed, dtype=np.uint8).tobytes()
    check_format_error(*put(ext, tmp, data, "garbage"))


@pytest.mark.parametrize("ext", READERS)
def test_text_file_renamed(tmp, ext):
    check_format_error(*put(ext, tmp, TEXT, "renamed"))


@pytest.mark.parametrize("ext", READERS)
def test_empty_file(tmp, ext):
    check_format_error(*put(ext, tmp, b"", "empty"))


@pytest.mark.parametrize("ext", READERS)
def test_wrong_magic(tmp, ext):
    if ext == ".stl":
        # binary STL has a free 80-byte header: the ASCII keyword is its only magic
        valid = trimesh.creation.icosphere(subdivisions=1).export(file_type="stl_ascii").encode()
        assert valid.startswith(b"solid")
        data = b"xolid" + valid[5:]
    elif ext == ".obj":
        data = valid_bytes(ext, tmp / "valid").replace(b"\nv ", b"\nw ").replace(b"\nf ", b"\ng ")
    else:
        data = valid_bytes(ext, tmp / "valid")
        magic = {".txt": 3, ".npz": 2, ".ply": 3}.get(ext, 4)
        data = b"X" * magic + data[magic:]
    check_format_error(*put(ext, tmp, data, "magic"))


def test_missing_files(tmp):
    for name in ("nothing.vox", "nothing.stl", "nothing"):
        with pytest.raises(FormatError, match="no such file"):
            io.read(tmp / name)


def test_a_folder_named_like_a_file_is_a_slice_stack(tmp):
    (tmp / "odd.vox").mkdir()
    with pytest.raises(FormatError, match="odd.vox: the folder holds no .png slice"):
        io.read(tmp / "odd.vox")
