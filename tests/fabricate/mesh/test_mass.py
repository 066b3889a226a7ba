"""mesh.json's mass figures and spin report, checked against the written 3MF and against voxel sums."""

import json
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pytest

from voxfab.fabricate.mesh import PLA_DENSITY, MeshOptions, fabricate_mesh
from voxfab.shape import VoxelShape

_NS = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}


def _make(grid, tmp_path: Path, pitch: float, **options) -> tuple[dict, Path]:
    mesh = tmp_path / "mesh.3mf"
    fabricate_mesh(VoxelShape(grid, pitch), MeshOptions(**options), mesh, name="t", report_path=tmp_path / "mesh.json")
    return json.loads((tmp_path / "mesh.json").read_text()), mesh


def _triangles_from_3mf(path: Path) -> np.ndarray:
    """``(T, 3, 3)`` triangle corners in mm, read from the 3MF's XML (no voxfab code)."""
    with zipfile.ZipFile(path) as z:
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    out = []
    for obj in root.iterfind(".//m:object", _NS):
        xyz = np.array([[float(v.get(a)) for a in "xyz"] for v in obj.iterfind(".//m:vertex", _NS)])
        tri = np.array([[int(t.get(k)) for k in ("v1", "v2", "v3")] for t in obj.iterfind(".//m:triangle", _NS)])
        out.append(xyz[tri])
    return np.concatenate(out)


def _tetrahedra(corners: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """Volume, centroid and inertia tensor (unit density, about the centroid) by signed tetrahedra from the origin.

    Each tetrahedron (0, a, b, c) is integrated through its own centroid and the covariance of
    its four corners: ∫ x xᵀ = V/20 (Σ pᵢ pᵢᵀ + (Σ pᵢ)(Σ pᵢ)ᵀ) over the corners 0, a, b, c.
    """
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    vol = np.einsum("ij,ij->i", np.cross(a, b), c) / 6.0
    total = vol.sum()
    centroid = (vol[:, None] * (a + b + c) / 4.0).sum(axis=0) / total
    s = a + b + c
    cov = sum(vol[:, None, None] * (p[:, :, None] * p[:, None, :]) for p in (a, b, c, s)) / 20.0
    second = cov.sum(axis=0) - total * np.outer(centroid, centroid)
    return float(total), centroid, np.trace(second) * np.eye(3) - second


def _voxel_sums(grid: np.ndarray, pitch: float) -> tuple[float, np.ndarray, np.ndarray]:
    """Volume, centroid and inertia (unit density) of the voxel cubes: point masses plus each cube's own a²/6.

    The print's frame has the shape's minimum corner at the origin.
    """
    cells = np.argwhere(grid)
    idx = (cells - cells.min(axis=0) + 0.5) * pitch
    cube = pitch**3
    total = len(idx) * cube
    centroid = idx.mean(axis=0)
    r = idx - centroid
    second = cube * (r.T @ r) + total * pitch**2 / 12.0 * np.eye(3)
    return total, centroid, np.trace(second) * np.eye(3) - second


def _check_against_mesh_and_voxels(report: dict, mesh: Path, grid: np.ndarray, pitch: float) -> None:
    density = report["mass_g"] / report["volume_mm3"]
    for volume, centroid, inertia in (_tetrahedra(_triangles_from_3mf(mesh)), _voxel_sums(grid, pitch)):
        assert report["volume_mm3"] == pytest.approx(volume, rel=1e-9)
        assert np.allclose(report["center_of_mass_mm"], centroid, atol=1e-6)
        assert np.allclose(report["inertia_tensor_g_mm2"], inertia * density, rtol=1e-6, atol=1e-2)
        assert np.allclose(report["principal_moments"], np.linalg.eigvalsh(inertia * density), rtol=1e-6)


def test_a_cube_has_its_centre_in_the_middle_and_m_a2_over_6(tmp_path):
    grid = np.zeros((25, 25, 25), bool)
    grid[:10, :10, :10] = True
    report, mesh = _make(grid, tmp_path, 2.0)
    assert report["center_of_mass_mm"] == pytest.approx([10.0, 10.0, 10.0])
    m = report["mass_g"]
    assert report["principal_moments"] == pytest.approx([m * 20.0**2 / 6.0] * 3, rel=1e-8)
    _check_against_mesh_and_voxels(report, mesh, grid, 2.0)


def test_a_cylinder_matches_signed_tetrahedra_and_voxel_sums(tmp_path):
    x, y, z = np.ogrid[:25, :25, :25]
    grid = ((x - 12) ** 2 + (y - 12) ** 2 <= 10**2) & (z < 8)
    report, mesh = _make(grid, tmp_path, 2.4)
    _check_against_mesh_and_voxels(report, mesh, grid, 2.4)
    # Flat and wide: the axis moment is the largest, near m r²/2 against m(3r² + h²)/12 across.
    lo, mid, hi = report["principal_moments"]
    assert lo == pytest.approx(mid) and hi > 1.5 * lo


def test_mass_lies_between_the_walls_alone_and_the_solid(tmp_path):
    x, y, z = np.ogrid[:25, :25, :25]
    grid = ((x - 12) ** 2 + (y - 12) ** 2 <= 10**2) & (z < 20)
    solid = grid.sum() * 2.0**3 * PLA_DENSITY / 1000.0
    sparse, _ = _make(grid, tmp_path, 2.0, infill=0.0)
    (tmp_path / "b").mkdir()
    dense, _ = _make(grid, tmp_path / "b", 2.0, infill=100.0)
    assert 0.1 * solid < sparse["mass_g"] < dense["mass_g"]
    assert dense["mass_g"] == pytest.approx(solid, rel=1e-3)
    assert sparse["print_time_s"] < dense["print_time_s"]


def _top(offset: int = 0) -> np.ndarray:
    """A disc on a cone down to a one-voxel tip; ``offset`` voxels of extra rim on one side."""
    x, y, z = np.ogrid[:25, :25, :25]
    r = np.hypot(x - 12, y - 12)
    grid = (r <= z + 0.5) & (z < 11) | (r <= 11.5) & (z >= 11) & (z < 15) | (r <= 2) & (z >= 15) & (z < 21)
    if offset:
        grid |= (x >= 12) & (r <= 11.5 + offset) & (z >= 11) & (z < 13)
    return grid


def test_a_symmetric_top_spins(tmp_path):
    report, mesh = _make(_top(), tmp_path, 2.4, spin=True)
    spin = report["spin"]
    assert spin["spins"] and spin["tip_patches"] == 1 and spin["tip_width_mm"] == pytest.approx(2.4)
    assert spin["tip_mm"] == pytest.approx([report["size_mm"][0] / 2, report["size_mm"][1] / 2, 0.0])
    assert spin["axis_offset_mm"] < 1e-6 and spin["center_moment_ratio"] > 1
    assert not [w for w in report["warnings"] if w.startswith("spin")]
    # The ratio about the tip from the independent tetrahedra and the parallel-axis theorem.
    volume, centroid, inertia = _tetrahedra(_triangles_from_3mf(mesh))
    r = centroid - np.array(spin["tip_mm"])
    at_tip = inertia + volume * (r @ r * np.eye(3) - np.outer(r, r))
    assert spin["moment_ratio"] == pytest.approx(at_tip[2, 2] / at_tip[0, 0], abs=1e-6)
    assert spin["center_height_mm"] == pytest.approx(centroid[2], abs=1e-6)
    assert spin["center_moment_ratio"] == pytest.approx(inertia[2, 2] / inertia[0, 0], abs=1e-6)
    # Sleeping top: ω² = 4 m g h I_t / I_s² (the density cancels).
    omega = np.sqrt(4 * volume * 9806.65 * centroid[2] * at_tip[0, 0] / at_tip[2, 2] ** 2)
    assert spin["sleep_rpm"] == pytest.approx(omega * 60 / (2 * np.pi), abs=0.1)


def test_an_off_centre_top_warns_that_it_wobbles(tmp_path):
    report, mesh = _make(_top(offset=3), tmp_path, 2.4, spin=True)
    _, centroid, _ = _tetrahedra(_triangles_from_3mf(mesh))
    offset = float(np.hypot(*(centroid[:2] - np.array(report["spin"]["tip_mm"][:2]))))
    assert offset > 0.5
    assert report["spin"]["axis_offset_mm"] == pytest.approx(offset, rel=1e-6)
    assert not report["spin"]["spins"]
    assert any("off the axis through the tip" in w for w in report["warnings"])


def test_a_flat_bottom_is_no_tip_and_a_tall_column_falls(tmp_path):
    grid = np.zeros((25, 25, 25), bool)
    grid[10:15, 10:15, :] = True
    report, _ = _make(grid, tmp_path, 2.0, spin=True)
    assert report["spin"]["tip_width_mm"] == pytest.approx(10.0)
    joined = "\n".join(report["warnings"])
    assert "not a single tip" in joined and "taller than wide in its mass" in joined


def test_a_print_without_spin_has_no_spin_report(tmp_path):
    report, _ = _make(_top(), tmp_path, 2.4)
    assert "spin" not in report and report["mass_g"] > 0 and report["print_time"].endswith("min")
