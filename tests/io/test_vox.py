"""MagicaVoxel .vox: bytes checked against the spec, files written and read back."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from voxfab import io
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.io.vox import read_vox, vox_bytes
from voxfab.shape import examples

# -- an independent builder, straight from the spec ---------------------------------

def chunk(cid: bytes, content: bytes = b"", children: bytes = b"") -> bytes:
    return cid + struct.pack("<ii", len(content), len(children)) + content + children


def vstring(s: str) -> bytes:
    return struct.pack("<i", len(s)) + s.encode()


def vdict(d: dict[str, str]) -> bytes:
    return struct.pack("<i", len(d)) + b"".join(vstring(k) + vstring(v) for k, v in d.items())


def model(size: tuple[int, int, int], voxels: list[tuple[int, int, int, int]]) -> bytes:
    return chunk(b"SIZE", struct.pack("<3i", *size)) + chunk(
        b"XYZI", struct.pack("<i", len(voxels)) + b"".join(bytes(v) for v in voxels)
    )


def ntrn(node: int, child: int, frame: dict[str, str], attrs: dict[str, str] | None = None) -> bytes:
    return chunk(b"nTRN", struct.pack("<i", node) + vdict(attrs or {}) + struct.pack("<iiii", child, -1, 0, 1)
                 + vdict(frame))


def ngrp(node: int, children: list[int]) -> bytes:
    return chunk(b"nGRP", struct.pack("<i", node) + vdict({}) + struct.pack("<i", len(children))
                 + b"".join(struct.pack("<i", c) for c in children))


def nshp(node: int, model_id: int) -> bytes:
    return chunk(b"nSHP", struct.pack("<i", node) + vdict({}) + struct.pack("<ii", 1, model_id) + vdict({}))


def vox_file(children: bytes, version: int = 150) -> bytes:
    return b"VOX " + struct.pack("<i", version) + chunk(b"MAIN", b"", children)


def parse(data: bytes) -> list[tuple[bytes, bytes]]:
    """Children of MAIN as (id, content), parsed by hand."""
    assert data[:4] == b"VOX "
    assert data[8:12] == b"MAIN"
    n, m = struct.unpack_from("<ii", data, 12)
    assert n == 0 and 20 + m == len(data)
    out, pos = [], 20
    while pos < len(data):
        cid = data[pos : pos + 4]
        n, m = struct.unpack_from("<ii", data, pos + 4)
        out.append((cid, data[pos + 12 : pos + 12 + n]))
        pos += 12 + n + m
    return out


# -- writing -----------------------------------------------------------------------

def test_written_bytes_follow_the_spec(tmp_path):
    grid = np.zeros((3, 4, 5), dtype=bool)
    grid[1, 2, 3] = grid[0, 0, 0] = grid[2, 3, 4] = True
    path = tmp_path / "a.vox"
    io.write(grid, path)
    data = path.read_bytes()
    assert struct.unpack_from("<i", data, 4)[0] == 150
    chunks = parse(data)
    assert [c for c, _ in chunks] == [b"SIZE", b"XYZI", b"RGBA"]
    assert struct.unpack("<3i", chunks[0][1]) == (3, 4, 5)
    xyzi = chunks[1][1]
    assert struct.unpack_from("<i", xyzi)[0] == 3
    entries = [tuple(xyzi[4 + 4 * k : 8 + 4 * k]) for k in range(3)]
    # x, y, z stored as they are in the grid (both z up), all in colour index 1
    assert entries == [(0, 0, 0, 1), (1, 2, 3, 1), (2, 3, 4, 1)]
    rgba = chunks[2][1]
    assert len(rgba) == 1024
    assert rgba[3] == 255 and sum(rgba[:3]) > 0  # colour index 1 is an opaque colour


def test_write_is_deterministic_and_atomic(tmp_path):
    grid = examples.vase()
    io.write(grid, tmp_path / "a.vox")
    io.write(grid.copy(), tmp_path / "b.vox")
    assert (tmp_path / "a.vox").read_bytes() == (tmp_path / "b.vox").read_bytes() == vox_bytes(grid)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.vox", "b.vox"]  # no temporary left


@pytest.mark.parametrize("make", [examples.vase, lambda: examples.ball(6), lambda: examples.tunnel_cube(9)])
def test_written_then_read_back(tmp_path, make):
    grid = make()
    io.write(grid, tmp_path / "s.vox")
    result = io.read(tmp_path / "s.vox")
    assert result.grid.shape == grid.shape
    assert np.array_equal(result.grid, grid)
    assert result.notes == ()


def test_full_256_side_round_trips_and_257_is_refused(tmp_path):
    grid = np.zeros((256, 2, 3), dtype=bool)
    grid[255, 1, 2] = grid[0, 0, 0] = True
    io.write(grid, tmp_path / "big.vox")
    assert np.array_equal(io.read(tmp_path / "big.vox").grid, grid)
    with pytest.raises(InvalidShapeError, match="256"):
        io.write(np.ones((257, 1, 1), dtype=bool), tmp_path / "huge.vox")
    assert not (tmp_path / "huge.vox").exists()


# -- reading files of other writers ---------------------------------------------------

def test_scene_graph_places_each_model_by_its_transform(tmp_path):
    scene = (
        ntrn(0, 1, {}) + ngrp(1, [2, 4])
        + ntrn(2, 3, {"_t": "10 0 0"}) + nshp(3, 0)
        + ntrn(4, 5, {"_t": "-10 0 0"}) + nshp(5, 1)
    )
    children = (
        model((2, 3, 4), [(0, 0, 0, 5), (1, 2, 3, 200)])
        + model((5, 5, 5), [(4, 4, 4, 1)])
        + scene
        + chunk(b"LAYR", struct.pack("<i", 0) + vdict({"_name": "a"}) + struct.pack("<i", -1))
        + chunk(b"RGBA", bytes(range(256)) * 4)
        + chunk(b"MATL", struct.pack("<i", 1) + vdict({"_type": "_diffuse"}))
    )
    path = tmp_path / "scene.vox"
    path.write_bytes(vox_file(children, version=200))
    result = io.read(path)
    # By hand: a model's voxel v has its centre at v + 1/2 - size // 2, then the translation.
    # Model 0 (pivot 1, 1, 2): (0,0,0) -> (9,-1,-2), (1,2,3) -> (10,1,1); model 1 (pivot 2,2,2): (4,4,4) -> (-8,2,2).
    assert result.grid.shape == (19, 4, 5) and result.grid.sum() == 3
    index = result.colours.index
    assert index[17, 0, 0] == 5 and index[18, 2, 3] == 200 and index[0, 3, 4] == 1
    # The file's RGBA entry i is the colour of index i + 1.
    assert list(result.colours.palette[5]) == [16, 17, 18, 19]
    assert result.notes == ()


def test_scene_rotations_compose_and_hidden_models_are_left_out(tmp_path):
    # _r = 17: the first row picks -y, the second +x: a quarter turn about z, the x axis onto y.
    line = model((3, 1, 1), [(0, 0, 0, 1), (2, 0, 0, 2)])
    hidden = model((1, 1, 1), [(0, 0, 0, 3)])
    children = (line + hidden + ntrn(0, 1, {}) + ngrp(1, [2, 4, 6])
                + ntrn(2, 3, {"_r": "17"}) + nshp(3, 0)
                + chunk(b"nTRN", struct.pack("<i", 4) + vdict({"_hidden": "1"}) + struct.pack("<iiii", 5, -1, 0, 1)
                        + vdict({"_t": "5 5 5"})) + nshp(5, 1)
                + chunk(b"nTRN", struct.pack("<i", 6) + vdict({}) + struct.pack("<iiii", 7, -1, 1, 1)
                        + vdict({"_t": "0 9 0"})) + nshp(7, 1)
                + chunk(b"LAYR", struct.pack("<i", 1) + vdict({"_hidden": "1"}) + struct.pack("<i", -1)))
    path = tmp_path / "rot.vox"
    path.write_bytes(vox_file(children, version=200))
    result = read_vox(path)
    assert result.grid.shape == (1, 3, 1)
    assert result.colours.index[0, 0, 0] == 1 and result.colours.index[0, 2, 0] == 2


def test_scene_of_a_characters_parts_gives_the_character(tmp_path):
    from _voxart import character

    from voxfab.shape import label_components

    shape = character()
    labels, count = label_components(shape.grid)
    models, nodes, children = b"", b"", []
    for part in range(1, count + 1):
        mask = labels == part
        lo, hi = np.argwhere(mask).min(axis=0), np.argwhere(mask).max(axis=0) + 1
        size = tuple(int(v) for v in hi - lo)
        xyz = np.argwhere(mask) - lo
        models += model(size, [(*map(int, v), int(shape.colours.index[tuple(v + lo)])) for v in xyz])
        t = lo + np.array(size) // 2  # the translation that puts the model's pivot back in place
        node = 2 * part
        nodes += ntrn(node, node + 1, {"_t": " ".join(map(str, t))}, {"_name": f"part{part}"}) + nshp(node + 1, part - 1)
        children.append(node)
    palette = chunk(b"RGBA", np.roll(shape.colours.palette, -1, axis=0).tobytes())
    path = tmp_path / "char.vox"
    path.write_bytes(vox_file(models + ntrn(0, 1, {}) + ngrp(1, children) + nodes + palette, version=200))
    assert io.read(path).shape(shape.pitch) == shape.crop()


def test_scene_over_the_grid_names_its_models(tmp_path):
    children = (model((4, 4, 4), [(0, 0, 0, 1)]) + model((2, 2, 30), [(0, 0, 29, 1)])
                + ntrn(0, 1, {}) + ngrp(1, [2, 4])
                + ntrn(2, 3, {}, {"_name": "body"}) + nshp(3, 0) + ntrn(4, 5, {"_t": "0 0 20"}, {"_name": "pole"})
                + nshp(5, 1))
    path = tmp_path / "big.vox"
    path.write_bytes(vox_file(children, version=200))
    with pytest.raises(InvalidShapeError, match=r"the scene is 2x2x37 voxels, over the 25-voxel grid: body \(4x4x4\) at \(-2, -2, -2\); pole \(2x2x30\)"):
        io.read(path)


def test_animation_frames(tmp_path):
    frames = [model((2, 1, 1), [(k % 2, 0, 0, k + 1)]) for k in range(3)]
    path = tmp_path / "anim.vox"
    path.write_bytes(vox_file(chunk(b"PACK", struct.pack("<i", 3)) + b"".join(frames)))
    first = io.read(path)
    assert first.colours.index[0, 0, 0] == 1
    assert first.notes == ("file holds 3 animation frames; read the first (--frame K reads frame K)",)
    second = io.read(path, frame=2)
    assert second.colours.index[1, 0, 0] == 2 and second.notes == ()
    with pytest.raises(InvalidShapeError, match="frame 4: the file holds 3 frames"):
        io.read(path, frame=4)
    with pytest.raises(InvalidShapeError, match="option frame does not apply to .npy"):
        np.save(tmp_path / "a.npy", np.ones((1, 1, 1), bool))
        io.read(tmp_path / "a.npy", frame=1)


def test_single_model_without_scene_has_no_note(tmp_path):
    path = tmp_path / "one.vox"
    path.write_bytes(vox_file(model((1, 1, 1), [(0, 0, 0, 1)])))
    result = io.read(path)
    assert result.grid.shape == (1, 1, 1) and result.grid.all()
    assert result.notes == ()


@pytest.mark.parametrize(
    ("children", "message"),
    [
        (model((2, 2, 2), [(2, 0, 0, 1)]), "outside the model size"),
        (model((2, 2, 2), [(0, 0, 0, 1)]) + model((2, 2, 2), [(0, 5, 0, 1)]), r"voxel \(0, 5, 0\) lies outside"),
        (chunk(b"XYZI", struct.pack("<i", 0)), "XYZI chunk without a SIZE"),
        (chunk(b"SIZE", struct.pack("<3i", 1, 1, 1)), "no XYZI chunk"),
        (chunk(b"RGBA", bytes(1024)), "no model"),
        (model((0, 2, 2), []), "a side below 1"),
        (chunk(b"SIZE", struct.pack("<2i", 1, 1)) + chunk(b"XYZI", struct.pack("<i", 0)), "SIZE chunk holds 8 bytes"),
        (chunk(b"SIZE", struct.pack("<3i", 2, 2, 2)) + chunk(b"XYZI", struct.pack("<i", 5) + bytes(8)), "truncated"),
        (chunk(b"SIZE", struct.pack("<3i", 2, 2, 2)) + chunk(b"XYZI", struct.pack("<i", -1)), "truncated"),
        (model((2, 2, 2), [(0, 0, 0, 1)]) + chunk(b"RGBA", bytes(100)), "RGBA chunk holds 100"),
        (model((2, 2, 2), [(0, 0, 0, 1)]) + b"\x00\x01\x02\x03" + struct.pack("<ii", 0, 0), "corrupt chunk id"),
        (model((2, 2, 2), [(0, 0, 0, 1)]) + b"nTRN" + struct.pack("<ii", -5, 0), "negative size"),
        (model((2, 2, 2), [(0, 0, 0, 1)]) + chunk(b"nTRN", struct.pack("<i", 0) + struct.pack("<i", 99)), "corrupt DICT"),
        (model((2, 2, 2), [(0, 0, 0, 1)]) + ntrn(0, 1, {"_r": "abc"}), "corrupt transform"),
    ],
)
def test_corrupt_chunks_give_format_error_naming_the_file(tmp_path, children, message):
    path = tmp_path / "bad.vox"
    path.write_bytes(vox_file(children))
    with pytest.raises(FormatError, match=message) as info:
        io.read(path)
    assert str(path) in str(info.value)


def test_main_chunk_layout_errors(tmp_path):
    good = vox_file(model((1, 1, 1), [(0, 0, 0, 1)]))
    cases = {
        "wrong magic": (b"VOX!" + good[4:], "not a MagicaVoxel file"),
        "bad first chunk": (good[:8] + b"MAIX" + good[12:], "expected MAIN"),
        "trailing bytes": (good + b"\x00" * 12, "unexpected bytes after MAIN"),
        "bad version": (b"VOX " + struct.pack("<i", -3) + good[8:], "version"),
    }
    for name, (data, message) in cases.items():
        path = tmp_path / f"{name.replace(' ', '_')}.vox"
        path.write_bytes(data)
        with pytest.raises(FormatError, match=message):
            io.read(path)


def test_model_over_256_is_invalid_shape(tmp_path):
    path = tmp_path / "big.vox"
    path.write_bytes(vox_file(model((300, 2, 2), [(0, 0, 0, 1)])))
    with pytest.raises(InvalidShapeError, match="big.vox: grid 300x2x2 is over the limit of 256"):
        io.read(path)


def test_empty_model_is_an_empty_grid_error(tmp_path):
    path = tmp_path / "empty.vox"
    path.write_bytes(vox_file(model((3, 3, 3), [])))
    with pytest.raises(InvalidShapeError, match="empty"):
        io.read(path)


def test_frame_on_the_command_line(tmp_path, capsys):
    import json

    from voxfab.cli import main

    frames = [model((3, 1, 1), [(0, 0, 0, 1)] + [(1, 0, 0, 2)] * k) for k in range(2)]
    path = tmp_path / "anim.vox"
    path.write_bytes(vox_file(chunk(b"PACK", struct.pack("<i", 2)) + b"".join(frames)))
    assert main(["info", str(path), "--frame", "2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["volume"] == 2
    assert main(["info", str(path), "--frame", "3"]) != 0
    assert "frame 3: the file holds 2 frames" in capsys.readouterr().err


def test_a_palette_of_alpha_0_reads_opaque_and_survives_png_slices(tmp_path):
    # Some editors leave the palette's alpha at 0; MagicaVoxel draws those voxels all the same.
    from _voxart import character

    shape = character()
    io.write(shape, tmp_path / "c.vox")
    data = bytearray((tmp_path / "c.vox").read_bytes())
    at = data.index(b"RGBA") + 12
    data[at + 3:at + 1024:4] = bytes(256)
    (tmp_path / "clear.vox").write_bytes(bytes(data))
    read = io.read(tmp_path / "clear.vox").shape()
    assert np.array_equal(read.grid, shape.grid)
    assert np.array_equal(read.colours.rgba, shape.colours.rgba)  # the character's colours, all opaque
    io.write(read, f"{tmp_path}/slices/")
    back = io.read(tmp_path / "slices")
    assert np.array_equal(back.grid, shape.grid)
