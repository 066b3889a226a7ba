"""Coloured prints on random shapes and palettes, and hostile coloured mesh files read back.

Every random coloured shape either prints or fails with a voxfab error; a print is
closed edge by edge, holds no more filaments than asked, and every triangle of its
3MF is in the colour of the voxel it lies on (checked by the independent reader of
``_colourcheck``).  Mutated coloured files read back as a mesh or a FormatError.
"""

from __future__ import annotations

import json
import zipfile

import numpy as np
import pytest
from _colourcheck import check_triangle_colours, edges_closed, printed_as_map, read_3mf, voxel_colours
from _fuzz import mutated
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab.errors import FormatError, VoxfabError
from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh, read_mesh
from voxfab.shape import VoxelColours, VoxelShape


@st.composite
def coloured_shapes(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """A random grid up to 7³ and an RGBA per voxel from a palette of 1 to 40 colours."""
    size = tuple(draw(st.integers(1, 7)) for _ in range(3))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    grid = rng.random(size) < draw(st.floats(0.2, 0.9))
    grid.flat[rng.integers(grid.size)] = True
    palette = rng.integers(0, 256, (draw(st.integers(1, 40)), 3))
    rgba = np.zeros((*size, 4), np.uint8)
    rgba[..., :3] = palette[rng.integers(0, len(palette), size)]
    rgba[..., 3] = np.where(grid, 255, 0)
    return grid, rgba


@settings(max_examples=30, deadline=None, database=None, derandomize=True)
@given(shape=coloured_shapes(), colours=st.one_of(st.none(), st.integers(1, 16)),
       contacts=st.sampled_from(["bridge", "split"]), merge=st.booleans())
def test_random_coloured_prints_are_closed_and_in_their_voxels_colours(tmp_path_factory, shape, colours, contacts,
                                                                      merge):
    grid, rgba = shape
    folder = tmp_path_factory.mktemp("print")
    s = VoxelShape(grid, 2.0, VoxelColours.from_rgba(grid, rgba))
    try:
        made = fabricate_mesh(s, MeshOptions(colours=colours, contacts=contacts, merge=merge), folder / "m.3mf",
                              name="r", report_path=folder / "m.json")
    except VoxfabError:
        return
    report = json.loads((folder / "m.json").read_text())
    filaments = report["colours"]["filaments"]
    assert 1 <= len(filaments) <= (colours or 16)
    filled, hexes = voxel_colours(rgba)
    printed_as = printed_as_map(report)
    for v, t, colour, _, _ in read_3mf(folder / "m.3mf"):
        assert edges_closed(t)
        _, off = check_triangle_colours(v, t, colour, hexes, filled, 2.0, printed_as)
        assert off == 0 or (contacts == "bridge" and made.report["bridges"] > 0)


@pytest.fixture(scope="module")
def coloured_files(tmp_path_factory):
    from _voxart import character

    folder = tmp_path_factory.mktemp("files")
    files = {}
    for ext in ("3mf", "obj", "glb", "ply"):
        fabricate_mesh(character(), MeshOptions(colours=5), folder / f"c.{ext}", name="c")
        files[ext] = folder / f"c.{ext}"
    with zipfile.ZipFile(files["3mf"]) as z:
        model = z.read("3D/3dmodel.model")
    return folder, files, model


@pytest.mark.parametrize("ext", ["3mf", "obj", "glb", "ply"])
def test_mutated_coloured_files_read_or_fail_cleanly(coloured_files, ext):
    folder, files, model = coloured_files
    valid = model if ext == "3mf" else files[ext].read_bytes()
    outcomes = []

    @settings(max_examples=40, database=None, derandomize=True)
    @given(data=mutated(valid))
    def fuzz(data):
        path = folder / "fuzz" / f"m.{ext}"
        path.parent.mkdir(exist_ok=True)
        if ext == "3mf":  # mutate the model inside a valid package
            with zipfile.ZipFile(files["3mf"]) as src, zipfile.ZipFile(path, "w") as z:
                for name in src.namelist():
                    z.writestr(name, data if name == "3D/3dmodel.model" else src.read(name))
        else:
            path.write_bytes(data)
        if ext == "obj":
            (path.parent / "c.mtl").write_bytes((folder / "c.mtl").read_bytes())
        try:
            mesh = read_mesh(path)
        except FormatError:
            outcomes.append(False)
            return
        outcomes.append(True)
        if mesh.coloured:
            assert len(mesh.colour) == len(mesh.triangles)
            assert mesh.colour.min() >= 0 and mesh.colour.max() < len(mesh.palette)

    fuzz()
    assert not all(outcomes)


@pytest.mark.parametrize("ext, old, new", [
    ("3mf", b' z="', b' w="'),  # a vertex without its z
    ("3mf", b' p1="1"', b' p1="99"'),  # a colour the file does not hold
    ("obj", b"\nv ", b"\nv 1\nv "),  # a vertex of one coordinate
    ("obj", b"usemtl colour_1", b"usemtl colour_9"),  # a material the library does not hold
    ("glb", b'"material":1', b'"material":7'),
    ("glb", b'"indices":1', b'"indices":99'),
])
def test_broken_coloured_files_are_format_errors(coloured_files, ext, old, new):
    folder, files, model = coloured_files
    path = folder / "broken" / f"m.{ext}"
    path.parent.mkdir(exist_ok=True)
    if ext == "3mf":
        assert old in model
        with zipfile.ZipFile(files["3mf"]) as src, zipfile.ZipFile(path, "w") as z:
            for name in src.namelist():
                z.writestr(name, model.replace(old, new, 1) if name == "3D/3dmodel.model" else src.read(name))
    else:
        data = files[ext].read_bytes()
        assert old in data
        path.write_bytes(data.replace(old, new, 1))
        if ext == "obj":
            (path.parent / "c.mtl").write_bytes((folder / "c.mtl").read_bytes())
    with pytest.raises(FormatError):
        read_mesh(path)
