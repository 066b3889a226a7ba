"""3MF, STL, OBJ, GLB and PLY: valid files that read back to the same mesh, byte for byte stable."""

import zipfile

import numpy as np
import pytest

from voxfab.errors import FabricationError, FormatError, UnknownFormatError
from voxfab.fabricate.mesh import MeshData, build_mesh, format_for, read_mesh, write_mesh
from voxfab.shape import examples


@pytest.fixture(scope="module")
def split_pair() -> MeshData:
    # Three parts touching along edges, split vertices there: the hardest case for writers.
    g = np.zeros((3, 3, 2), bool)
    g[0, 0, :] = True
    g[1, 1, :] = True
    g[2, 2, 0] = True
    return build_mesh(g, pitch=2.5, contacts="split").mesh


def _same_mesh(a: MeshData, b: MeshData, *, atol: float) -> None:
    assert a.part_count == b.part_count
    for p in range(a.part_count):
        va, ta = a.part_mesh(p)
        vb, tb = b.part_mesh(p)
        assert np.array_equal(ta, tb)
        assert np.allclose(va, vb, atol=atol)


@pytest.mark.parametrize("ext", [".3mf", ".obj", ".glb", ".ply"])
def test_indexed_formats_round_trip(tmp_path, split_pair, ext):
    path = tmp_path / f"m{ext}"
    write_mesh(path, split_pair, name="pair")
    back = read_mesh(path)
    _same_mesh(split_pair, back, atol=1e-6)
    first = path.read_bytes()
    write_mesh(path, split_pair, name="pair")
    assert path.read_bytes() == first


def test_stl_round_trip_keeps_every_triangle(tmp_path, split_pair):
    path = tmp_path / "m.stl"
    write_mesh(path, split_pair, name="pair")
    assert path.stat().st_size == 84 + 50 * len(split_pair.triangles)
    assert not path.read_bytes().startswith(b"solid")
    back = read_mesh(path)
    assert np.allclose(back.vertices.reshape(-1, 3, 3), split_pair.vertices[split_pair.triangles], atol=1e-5)


def test_3mf_package_and_model(tmp_path, split_pair):
    path = tmp_path / "m.3mf"
    write_mesh(path, split_pair, name="a <pair> & more")
    with zipfile.ZipFile(path) as z:
        assert sorted(z.namelist()) == ["3D/3dmodel.model", "[Content_Types].xml", "_rels/.rels"]
        assert all(i.date_time == (1980, 1, 1, 0, 0, 0) for i in z.infolist())
        model = z.read("3D/3dmodel.model").decode()
    from lxml import etree

    root = etree.fromstring(model.encode())
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    assert root.get("unit") == "millimeter"
    assert root.find("m:metadata[@name='Title']", ns).text == "a <pair> & more"
    assert split_pair.part_count == 3
    assert len(root.findall("m:resources/m:object", ns)) == 3
    assert len(root.findall("m:build/m:item", ns)) == 3


@pytest.mark.parametrize("ext", [".3mf", ".obj", ".glb", ".ply"])
def test_trimesh_reads_the_same_split_mesh(tmp_path, split_pair, ext):
    trimesh = pytest.importorskip("trimesh")
    path = tmp_path / f"m{ext}"
    write_mesh(path, split_pair, name="pair")
    loaded = trimesh.load(path, process=False, force="scene" if ext != ".obj" else None)
    geoms = list(loaded.geometry.values()) if hasattr(loaded, "geometry") else [loaded]
    n_tri = sum(len(g.faces) for g in geoms)
    n_vert = sum(len(g.vertices) for g in geoms)
    assert n_tri == len(split_pair.triangles)
    assert n_vert == len(split_pair.vertices)  # split vertices were not merged


def test_glb_scene_is_in_metres_and_y_up(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    m = build_mesh(examples.box(2, 3, 4), pitch=10.0).mesh
    path = tmp_path / "box.glb"
    write_mesh(path, m, name="box")
    scene = trimesh.load(path, process=False, force="scene")
    # glTF is Y-up: the 40 mm height is along +Y, the 30 mm depth along -Z (towards the back)
    assert np.allclose(scene.bounds, [[0, 0, -0.03], [0.02, 0.04, 0]])
    mesh = scene.to_geometry() if hasattr(scene, "to_geometry") else scene.dump(concatenate=True)
    assert mesh.is_watertight and mesh.volume == pytest.approx(0.02 * 0.03 * 0.04)  # winding kept: outward


def test_unknown_extension_and_bad_files(tmp_path, split_pair):
    with pytest.raises(UnknownFormatError, match=r"\.step"):
        format_for(tmp_path / "m.step")
    bad = tmp_path / "bad.3mf"
    bad.write_bytes(b"not a zip")
    with pytest.raises(FormatError):
        read_mesh(bad)
    short = tmp_path / "bad.stl"
    short.write_bytes(b"\0" * 90)
    with pytest.raises(FormatError):
        read_mesh(short)


def test_nothing_is_written_when_the_check_fails(tmp_path, split_pair):
    broken = MeshData(vertices=split_pair.vertices, triangles=split_pair.triangles[1:], part=split_pair.part[1:])
    with pytest.raises(FabricationError):
        write_mesh(tmp_path / "x.3mf", broken, name="x")
    assert list(tmp_path.iterdir()) == []
