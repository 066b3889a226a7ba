"""A corpus of hostile files made by the tests: bombs, huge headers, truncations, FIFOs, links.

Each is read through ``voxfab info`` (and drawings through a recipe): every one
must fail with one clean line, or read, within the time bound.
"""

from __future__ import annotations

import io as _io
import os
import struct
import zipfile
import zlib
from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, png_claiming, run_cli, valid_files

from voxfab._shared.limits import MAX_MESH_BYTES

EXTENSIONS = [".npy", ".npz", ".txt", ".vox", ".binvox", ".png", ".stl", ".obj", ".ply", ".3mf"]


def deflated_zeros(size: int, byte: bytes = b"\0") -> tuple[bytes, int]:
    """Raw deflate of ``size`` repeated bytes, streamed (small in memory); returns (data, crc)."""
    comp = zlib.compressobj(9, zlib.DEFLATED, -15)
    chunk = byte * (1 << 20)
    out, crc = [], 0
    for _ in range(size // len(chunk)):
        out.append(comp.compress(chunk))
        crc = zlib.crc32(chunk, crc)
    out.append(comp.flush())
    return b"".join(out), crc


def zip_bomb(member: str, prefix: bytes, size: int) -> bytes:
    """A zip whose one member unpacks to ``prefix`` + ``size`` zero bytes (a few hundred KB on disk)."""
    buf = _io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        with zf.open(member, "w", force_zip64=True) as fh:
            fh.write(prefix)
            block = b"\0" * (1 << 20)
            for _ in range(size // len(block)):
                fh.write(block)
    return buf.getvalue()


LAUGHS = (
    '<?xml version="1.0"?>\n<!DOCTYPE lolz [<!ENTITY lol "lololololololololololol">'
    + "".join(f'<!ENTITY lol{i} "{("&lol" + (str(i - 1) if i > 1 else "") + ";") * 10}">' for i in range(1, 10))
    + "]>\n"
)


def corpus(folder: Path) -> dict[str, Path]:
    """Make the hostile files; return name -> path to read."""
    folder.mkdir(parents=True, exist_ok=True)
    made: dict[str, Path] = {}

    def put(name: str, data: bytes) -> None:
        (folder / name).write_bytes(data)
        made[name] = folder / name

    header = "{'descr': '|b1', 'fortran_order': False, 'shape': (100000, 100000, 100000), }"
    npy = b"\x93NUMPY\x01\x00" + struct.pack("<H", 118) + header.ljust(117).encode() + b"\n"
    put("huge-header.npy", npy)
    put("long-header.npy", b"\x93NUMPY\x02\x00" + struct.pack("<I", 2**31) + b"{")
    put("bomb.npz", zip_bomb("shape.npy", b"\x93NUMPY\x01\x00" + struct.pack("<H", 118)
                              + "{'descr': '|b1', 'fortran_order': False, 'shape': (1, 1, 300000000), }"
                              .ljust(117).encode() + b"\n", 300 << 20))
    put("huge-size.vox", b"VOX " + struct.pack("<i", 150) + b"MAIN" + struct.pack("<ii", 0, 40)
        + b"SIZE" + struct.pack("<ii", 12, 0) + struct.pack("<iii", 2**31 - 1, 2**31 - 1, 2**31 - 1)
        + b"XYZI" + struct.pack("<ii", 8, 0) + struct.pack("<I", 2**31))
    put("huge-dims.binvox", b"#binvox 1\ndim 100000 100000 100000\ntranslate 0 0 0\nscale 1\ndata\n\x00\xff")
    put("huge.png", png_claiming(60000, 60000))
    put("wide.png", png_claiming(2**31 - 1, 1))
    stl = b"\0" * 80 + struct.pack("<I", 2**32 - 1) + b"\0" * 100
    put("huge-count.stl", stl)
    put("huge-count.ply", b"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
        b"property float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n")
    put("huge-index.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n")
    put("nan.obj", b"v nan 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n")
    put("bomb.3mf", zip_bomb("3D/3dmodel.model", b"<model>", MAX_MESH_BYTES + (1 << 20)))
    laughs3mf = _io.BytesIO()
    with zipfile.ZipFile(laughs3mf, "w") as zf:
        zf.writestr("3D/3dmodel.model", LAUGHS + '<model xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
                    "<resources><object id=\"1\"><mesh><vertices><vertex x=\"&lol9;\" y=\"0\" z=\"0\"/></vertices>"
                    "</mesh></object></resources></model>")
    put("laughs.3mf", laughs3mf.getvalue())
    put("lines.txt", b"#" * 5_000_000 + b"\n")
    put("huge-grid.txt", b"z=0\n" + b"#" * 100000 + b"\n")
    for ext in EXTENSIONS:
        put(f"empty{ext}", b"")
        fifo = folder / f"fifo{ext}"
        os.mkfifo(fifo)
        made[f"fifo{ext}"] = fifo
    (folder / "dir.npy").mkdir()
    made["dir.npy"] = folder / "dir.npy"
    for name, target in {"zero.npy": "/dev/zero", "null.stl": "/dev/null", "tofifo.vox": str(folder / "fifo.vox"),
                         "dangling.npy": str(folder / "nowhere.npy")}.items():
        (folder / name).symlink_to(target)
        made[name] = folder / name
    (folder / "loop.npy").symlink_to(folder / "loop.npy")
    made["loop.npy"] = folder / "loop.npy"
    stack = folder / "stack"
    stack.mkdir()
    (stack / "z0.png").write_bytes(png_claiming(60000, 60000))
    os.mkfifo(stack / "z1.png")
    made["stack"] = stack
    return made


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    return corpus(tmp_path_factory.mktemp("hostile"))


def test_hostile_files_fail_cleanly_and_fast(hostile):
    results = {}
    for name, path in sorted(hostile.items()):
        o = check_outcome(run_cli(["info", path]), seconds=20)
        results[name] = o
        assert o.code != 0 or name == "stack", (name, o.out)
    assert "over the limit" in results["bomb.3mf"].error_lines[0]
    assert "is a FIFO" in results["fifo.npy"].error_lines[0]
    assert "is a device" in results["zero.npy"].error_lines[0]


def test_truncated_files_fail_cleanly(tmp_path):
    valid = valid_files(tmp_path / "valid")
    for ext in EXTENSIONS:
        data = valid[ext]
        for cut in sorted({1, 4, 8, 12, 40, 84, len(data) // 3, len(data) // 2, len(data) - 1}):
            if 0 < cut < len(data):
                path = tmp_path / f"cut-{cut}{ext}"
                path.write_bytes(data[:cut])
                check_outcome(run_cli(["info", path]), seconds=20)


def test_hostile_drawings_in_recipes(tmp_path):
    drawings = {
        "laughs.svg": (LAUGHS + '<svg xmlns="http://www.w3.org/2000/svg"><text>&lol9;</text>'
                       '<path d="M0 0 L1 0 L1 1 Z"/></svg>').encode(),
        "huge.svg": b'<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L1e308 0 L1e308 1e308 Z"/></svg>',
        "nan.json": b"[[0, 0], [NaN, 1], [1, Infinity]]",
        "strings.json": b'{"polylines": [{"points": "abc"}]}',
        "bomb.png": png_claiming(60000, 60000),
        "deep.csv": b"0,0\n" * 10 + b"[" * 100000,
        "binary.json": bytes(range(256)),
        "wide.json": ("[" + ",".join(["[0, 0]"] * 200000) + "]").encode(),
    }
    for name, data in drawings.items():
        (tmp_path / name).write_bytes(data)
        r = tmp_path / f"{name}.toml"
        r.write_text(f'[source]\nmaker = "revolution"\ncurve = "x^2 + y^2 - 1"\ngeneratrix = "{name}"\nsize = 8\n')
        o = check_outcome(run_cli(["build", r, "-o", tmp_path / "out"]), seconds=30)
        assert o.code != 0 or name in ("huge.svg", "wide.json"), (name, o.err)


def test_no_output_written_through_a_hostile_target(tmp_path):
    """Outputs refuse folders that do not exist and names that are folders; they never follow a FIFO."""
    grid = np.zeros((3, 3, 3), bool)
    grid[1, 1, 1] = True
    np.save(tmp_path / "s.npy", grid)
    os.mkfifo(tmp_path / "fifo.npy")
    o = check_outcome(run_cli(["convert", tmp_path / "s.npy", tmp_path / "fifo.npy"]), seconds=10)
    # The FIFO is replaced by a regular file, atomically, without ever being opened.
    assert o.code == 0 and (tmp_path / "fifo.npy").is_file()
    (tmp_path / "d.npy").mkdir()
    assert "is a folder" in check_outcome(run_cli(["convert", tmp_path / "s.npy", tmp_path / "d.npy"])).err
