"""Every recipe shipped in recipes/ builds, and its outputs pass independent checks."""

import hashlib
import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from voxfab.recipe import build, load_recipe
from voxfab.shape import fill_cavities, well_formed_reasons

RECIPES = sorted((Path(__file__).parents[2] / "recipes").rglob("*.toml"))


@pytest.fixture(scope="session")
def built(tmp_path_factory):
    """Build each shipped recipe once per session (outputs shared by the checks below)."""
    root = tmp_path_factory.mktemp("recipes")
    cache: dict[Path, Path] = {}

    def get(path: Path) -> Path:
        if path not in cache:
            cache[path] = build(load_recipe(path), root)
        return cache[path]

    return get


def test_recipes_are_shipped():
    assert len(RECIPES) >= 10


@pytest.mark.parametrize("path", RECIPES, ids=[p.stem for p in RECIPES])
def test_recipe_builds_with_a_true_manifest(built, path):
    folder = built(path)
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["shape"]["well_formed"], manifest["shape"]["reasons"]
    grid = np.load(folder / "shape.npy")
    assert well_formed_reasons(grid) == []
    listed = {f["path"] for f in manifest["files"]}
    on_disk = {str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file()} - {"manifest.json"}
    assert listed == on_disk
    for f in manifest["files"]:
        assert hashlib.sha256((folder / f["path"]).read_bytes()).hexdigest() == f["sha256"]
        assert len(f["purpose"]) > 10


@pytest.mark.parametrize("path", RECIPES, ids=[p.stem for p in RECIPES])
def test_recipe_nets_refold_onto_the_shape(built, path):
    from voxfab.unfold import Net, validate

    nets = sorted(built(path).rglob("*.json"))
    nets = [p for p in nets if p.name != "manifest.json" and '"voxfab-net/1"' in p.read_text()[:200]]
    if not any("net" == s.name for s in load_recipe(path).outputs):
        pytest.skip("this recipe asks for no net")
    assert nets, "the net output wrote no voxfab-net/1 JSON"
    grid = np.load(built(path) / "shape.npy")
    options = dict(next(s for s in load_recipe(path).outputs if s.name == "net").options)
    if options.get("fill"):
        grid = fill_cavities(grid)
    # A net in pieces (net.piece-N.json) refolds as a whole.
    found = [Net.from_json(p.read_text()) for p in nets]
    assert validate(grid, found if len(found) > 1 else found[0]).ok


@pytest.mark.parametrize("path", RECIPES, ids=[p.stem for p in RECIPES])
def test_recipe_3mf_passes_prusa_slicer(built, path, tmp_path):
    slicer = shutil.which("prusa-slicer")
    if slicer is None:
        pytest.skip("prusa-slicer is not installed (.ci/run installs it with apt-get)")
    meshes = sorted(built(path).rglob("*.3mf"))
    if not any("mesh" == s.name for s in load_recipe(path).outputs):
        pytest.skip("this recipe asks for no mesh")
    assert meshes, "the mesh output wrote no 3MF"
    for mesh in meshes:
        info = subprocess.run([slicer, "--info", str(mesh)], capture_output=True, text=True, timeout=300)
        assert info.returncode == 0, info.stderr
        assert re.search(r"^manifold = yes$", info.stdout, re.M), info.stdout
        assert re.search(r"^number_of_parts =\s*1$", info.stdout, re.M), info.stdout
        gcode = tmp_path / (mesh.stem + ".gcode")
        sliced = subprocess.run(
            [slicer, "--export-gcode", str(mesh), "--output", str(gcode)],
            capture_output=True, text=True, timeout=600,
        )
        assert sliced.returncode == 0, sliced.stderr + sliced.stdout
        assert gcode.stat().st_size > 1000 and b"G1 " in gcode.read_bytes()


def test_a_rebuild_is_byte_identical(built, tmp_path):
    path = RECIPES[0]
    first = built(path)
    second = build(load_recipe(path), tmp_path)
    for p in sorted(first.rglob("*")):
        if p.is_file():
            assert p.read_bytes() == (second / p.relative_to(first)).read_bytes(), p.name


def _mesh_size_from_3mf(path: Path) -> np.ndarray:
    """Bounding-box size in mm of the 3MF's vertices, read from its XML (no voxfab code)."""
    import xml.etree.ElementTree as ET
    import zipfile

    with zipfile.ZipFile(path) as z:
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    assert root.get("unit", "millimeter") == "millimeter"
    xyz = np.array([[float(v.get(a)) for a in "xyz"] for v in root.iterfind(".//m:vertex", ns)])
    return xyz.max(axis=0) - xyz.min(axis=0)


def _face_size_from_dxf(path: Path) -> float:
    """The net's face edge in mm, measured from the fold lines of the DXF (no voxfab code).

    Folds lie on the lines of the face lattice: the x of the vertical ones and the y of
    the horizontal ones differ by whole numbers of faces, the smallest gap being one face.
    """
    import ezdxf

    msp = ezdxf.readfile(path).modelspace()
    xs, ys = set(), set()
    for e in msp.query('LINE[layer=="MOUNTAIN" | layer=="VALLEY"]'):
        (x0, y0, _), (x1, y1, _) = e.dxf.start, e.dxf.end
        if abs(x0 - x1) < 1e-9:
            xs.add(round(x0, 6))
        elif abs(y0 - y1) < 1e-9:
            ys.add(round(y0, 6))
    gaps = np.concatenate([np.diff(sorted(xs)), np.diff(sorted(ys))])
    assert len(gaps), "no fold line in the net drawing"
    face = float(gaps.min())
    assert np.allclose(gaps / face, np.round(gaps / face), atol=1e-4), sorted(set(np.round(gaps, 4)))
    return face


def _plates_in_dxf(paths: list[Path]) -> int:
    """Plates cut from the sheets: closed CUT outlines that are not holes of another outline."""
    import ezdxf
    import shapely

    count = 0
    for path in paths:
        rings = []
        for e in ezdxf.readfile(path).modelspace().query('POLYLINE[layer=="CUT"]'):
            pts = [(v.dxf.location.x, v.dxf.location.y) for v in e.vertices]
            if e.is_closed and len(pts) >= 3:
                rings.append(shapely.Polygon(pts))
        for i, ring in enumerate(rings):
            depth = sum(1 for j, other in enumerate(rings) if j != i and other.contains(ring))
            count += depth % 2 == 0  # inside an even number of rings: an outline, not a hole
    return count


@pytest.mark.parametrize("path", RECIPES, ids=[p.stem for p in RECIPES])
def test_recipe_builds_one_consistent_object(built, path):
    """The print, the paper net and the plate stack have one size, measured from the written files."""
    recipe = load_recipe(path)
    outputs = {s.name: s.settings for s in recipe.outputs}
    if not {"mesh", "net", "slices"} <= set(outputs):
        pytest.skip("this recipe does not ask for all three objects")
    folder = built(path)
    cells = np.array(np.nonzero(np.load(folder / "shape.npy")))
    extents = cells.max(axis=1) - cells.min(axis=1) + 1
    print_size = _mesh_size_from_3mf(folder / "mesh.3mf")
    face = _face_size_from_dxf(folder / "net.dxf")
    plates = outputs["slices"]
    axis = "xyz".index(plates.axis)
    report = json.loads((folder / "slices" / "plates.json").read_text())
    # Every listed plate is cut from a sheet; a layer may have several pieces, so the stack's
    # height counts the plate levels (layer and copy), each one plate thickness.
    assert _plates_in_dxf(sorted((folder / "slices").glob("sheet-*.dxf"))) == len(report["plates_list"])
    levels = {(p["layer"], p["copy"]) for p in report["plates_list"]}
    stack = len(levels) * plates.thickness
    tolerance = plates.thickness
    assert np.allclose(print_size, extents * recipe.pitch, atol=1e-6), (print_size, extents)
    assert np.all(np.abs(extents * face - print_size) <= tolerance), (face, recipe.pitch)
    assert abs(stack - print_size[axis]) <= tolerance / 2 + 1e-9, (stack, print_size[axis])
    assert report["stack_height"] == pytest.approx(stack)
