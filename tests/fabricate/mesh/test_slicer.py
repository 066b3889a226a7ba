"""A real slicer and a real STL checker accept the meshes without repair.

PrusaSlicer's ``--info`` must say ``manifold = yes`` and ``number_of_parts = 1``
and the model must slice to G-code; admesh must find no disconnected facet.
Skipped only when the programs are not installed.
"""

import re
import shutil
import subprocess

import numpy as np
import pytest

from voxfab.fabricate.mesh import build_mesh, write_mesh
from voxfab.shape import examples

PRUSA = shutil.which("prusa-slicer")
ADMESH = shutil.which("admesh")
needs_prusa = pytest.mark.skipif(PRUSA is None, reason="prusa-slicer is not installed (apt-get install prusa-slicer)")
needs_admesh = pytest.mark.skipif(ADMESH is None, reason="admesh is not installed (apt-get install admesh)")


def chess_piece() -> np.ndarray:
    """A pawn-like solid of revolution: base, waist, collar and a ball on top."""
    z = np.arange(24)
    radius = np.select(
        [z < 3, z < 5, z < 14, z < 16, z < 17],
        [7.5, 6.0, 5.0 - 2.5 * (z - 5) / 9, 4.5, 2.0],
        default=np.sqrt(np.clip(16 - (z - 20.5) ** 2, 0, None)) + 0.3,
    )
    c = np.arange(-8, 9)
    rho = np.sqrt(c[:, None] ** 2 + c[None, :] ** 2)
    return rho[:, :, None] <= radius[None, None, :]


SHAPES = {
    "chess": (chess_piece, 1.5),
    "blob": (lambda: examples.random_shape(5, side=12, fill=0.3), 2.0),
    "tunnel": (lambda: examples.tunnel_cube(5), 3.0),
    "ball": (lambda: examples.ball(6), 2.0),
}


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    out = tmp_path_factory.mktemp("slicer")
    made = {}
    for name, (make, pitch) in SHAPES.items():
        r = build_mesh(make(), pitch=pitch, name=name)
        write_mesh(out / f"{name}.3mf", r.mesh, name=name)
        write_mesh(out / f"{name}.stl", r.mesh, name=name)
        made[name] = (out, r)
    return made


def _info(path) -> dict[str, str]:
    run = subprocess.run([PRUSA, "--info", str(path)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    return dict(re.findall(r"^(\w+) = +(.*)$", run.stdout, flags=re.M))


def test_the_blob_has_contacts_to_bridge(meshes):
    assert meshes["blob"][1].bridges > 0


@needs_prusa
@pytest.mark.parametrize("name", sorted(SHAPES))
def test_prusa_slicer_info_says_manifold_single_part(meshes, name):
    out, r = meshes[name]
    info = _info(out / f"{name}.3mf")
    assert info["manifold"] == "yes"
    assert info["number_of_parts"] == "1"
    assert float(info["volume"]) == pytest.approx(r.report.volume, rel=1e-4)
    assert int(info["number_of_facets"]) == r.report.triangles


@needs_prusa
@pytest.mark.parametrize("name", ["tunnel", "blob"])
def test_prusa_slicer_slices_to_gcode(meshes, name):
    out, _ = meshes[name]
    gcode = out / f"{name}.gcode"
    run = subprocess.run(
        [PRUSA, "--export-gcode", str(out / f"{name}.3mf"), "--layer-height", "0.3", "-o", str(gcode)],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    text = gcode.read_text()
    assert text.count("\nG1 ") > 100
    assert ";LAYER_CHANGE" in text


@needs_admesh
@pytest.mark.parametrize("name", sorted(SHAPES))
def test_admesh_finds_a_closed_single_part(meshes, name):
    out, r = meshes[name]
    run = subprocess.run([ADMESH, str(out / f"{name}.stl")], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    text = run.stdout
    assert re.search(r"Total disconnected facets\s*:\s*0\s+0", text)
    assert re.search(r"Number of parts\s*:\s*1\b", text)
    assert re.search(r"Degenerate facets\s*:\s*0\b", text)
    assert re.search(r"Backwards edges\s*:\s*0\b", text)
    vol = float(re.search(r"Volume\s*:\s*([\d.]+)", text).group(1))
    assert vol == pytest.approx(r.report.volume, rel=1e-4)


RECIPES = sorted((__import__("pathlib").Path(__file__).resolve().parents[3] / "recipes").rglob("*.toml"))


@needs_prusa
@pytest.mark.parametrize("recipe", RECIPES, ids=[p.stem for p in RECIPES])
def test_every_shipped_recipe_mesh_passes_prusa_slicer(tmp_path, recipe):
    from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh
    from voxfab.recipe import load_recipe, make_shape

    r = load_recipe(recipe)
    shape = make_shape(r)
    options = MeshOptions()
    for out in r.outputs:
        if out.name == "mesh":
            options = out.settings
    made = fabricate_mesh(shape, options, tmp_path / f"mesh.{options.format}", name=r.name)
    mesh_file = tmp_path / made.files[0].path
    info = _info(mesh_file)
    assert info["manifold"] == "yes"
    assert info["number_of_parts"] == "1"


def _ziggurat() -> np.ndarray:
    """Square layers, each one voxel in from the layer below: no voxel stands over air."""
    g = np.zeros((11, 11, 6), bool)
    for k in range(6):
        g[k:11 - k, k:11 - k, k] = True
    return g


@needs_prusa
@pytest.mark.parametrize("name", ["spinning_top", "chess/queen", "chess/knight", "ziggurat"])
def test_mesh_json_says_what_prusa_slicer_supports(tmp_path, name):
    """mesh.json's support figures against PrusaSlicer with automatic supports: the top, the queen and the
    knight get support under their voxel ledges, as mesh.json says; a ziggurat gets none, as it says too."""
    import json
    from pathlib import Path

    from voxfab.fabricate.mesh import MeshOptions, estimate_line, fabricate_mesh
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.shape import VoxelShape

    if name == "ziggurat":
        shape = VoxelShape(_ziggurat(), 4.0)
    else:
        shape = make_shape(load_recipe(Path(__file__).resolve().parents[3] / "recipes" / f"{name}.toml"))
    made = fabricate_mesh(shape, MeshOptions(), tmp_path / "mesh.3mf", name="x", report_path=tmp_path / "mesh.json")
    report = json.loads((tmp_path / "mesh.json").read_text())
    grams = {}
    for supports in (False, True):
        gcode = tmp_path / f"s{supports}.gcode"
        args = [PRUSA, "--export-gcode", str(tmp_path / made.files[0].path), "--bed-shape", "0x0,220x0,220x220,0x220",
                "--max-print-height", "250", "--filament-density", "1.24", "--output", str(gcode)]
        run = subprocess.run(args + (["--support-material", "--support-material-auto"] if supports else []),
                             capture_output=True, text=True, timeout=600)
        assert run.returncode == 0, run.stderr[-2000:]
        text = gcode.read_text()
        grams[supports] = float(re.search(r"^; filament used \[g\] = ([0-9.]+)", text, re.M).group(1))
        if supports:
            supported = ";TYPE:Support material" in text
    needs = report["support_lowest_mm"] is not None
    assert needs == (name != "ziggurat") == supported, (report["support_area_mm2"], supported)
    assert (grams[True] > grams[False] + 0.5) == needs, grams
    assert ("needs support under" in estimate_line(report)) == needs
    if needs:
        assert report["support_area_mm2"] > 0 and report["support_lowest_mm"] >= shape.pitch - 1e-6
    else:
        assert report["support_area_mm2"] == 0


def _slice_with_extruders(path, gcode, extruders: int, *, wipe_tower: bool = True) -> str:
    """PrusaSlicer's G-code of a 3MF for a printer of ``extruders`` extruders (colour.md's command line)."""
    many = lambda value: ",".join([value] * extruders)  # noqa: E731
    args = [PRUSA, "--export-gcode", "--nozzle-diameter", many("0.4"), "--temperature", many("210"),
            "--filament-diameter", many("1.75"), *(["--wipe-tower"] if wipe_tower else []),
            "--use-relative-e-distances", "-o", str(gcode), str(path)]
    run = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-2000:]
    return gcode.read_text()


@needs_prusa
def test_prusa_slicer_prints_a_coloured_character_with_three_tools(tmp_path):
    """A --colours 3 print of the coloured character slices with 3 extruders and changes between the 3
    tools; the same character uncoloured, sliced the same way, never changes tool."""
    from _voxart import character

    from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh

    coloured = fabricate_mesh(character(), MeshOptions(colours=3), tmp_path / "c.3mf", name="c")
    assert len(coloured.report["colours"]["filaments"]) == 3
    info = _info(tmp_path / "c.3mf")
    assert info["manifold"] == "yes" and int(info["number_of_facets"]) == coloured.report["triangles"]
    text = _slice_with_extruders(tmp_path / "c.3mf", tmp_path / "c.gcode", 3)
    assert set(re.findall(r"^T(\d+)\s*$", text, re.M)) == {"0", "1", "2"}
    fabricate_mesh(character().with_colours(None), MeshOptions(), tmp_path / "p.3mf", name="p")
    plain = _slice_with_extruders(tmp_path / "p.3mf", tmp_path / "p.gcode", 3)
    assert not re.findall(r"^T\d+", plain, re.M) and plain.count("\nG1 ") > 100


def _tools_by_layer(text: str) -> dict[float, set[int]]:
    """The tools that extrude on each layer (by its ``;Z:`` height) of PrusaSlicer's G-code."""
    tool, z, layers = None, None, {}
    for line in text.splitlines():
        if m := re.match(r"T(\d+)\s*$", line):
            tool = int(m.group(1))
        elif line.startswith(";Z:"):
            z = float(line[3:])
        elif line.startswith("G1 ") and re.search(r" X", line) and (e := re.search(r" E([0-9.]+)", line)):
            if float(e.group(1)) > 0 and z is not None:
                layers.setdefault(z, set()).add(tool if tool is not None else 0)
    return layers


@needs_prusa
def test_prusa_slicer_prints_each_painted_colour_with_its_extruder(tmp_path):
    """Five slabs in five colours: every layer inside a slab is printed by the extruder mesh.json gives
    its colour, so the painting code of each extruder (4, 8, 0C, 1C, 2C) reaches the right tool."""
    import json

    from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh
    from voxfab.shape import VoxelColours, VoxelShape

    colours = [(230, 230, 230), (200, 30, 30), (30, 60, 200), (40, 170, 60), (240, 200, 30)]
    g = np.ones((5, 5, 5), bool)
    rgba = np.zeros((5, 5, 5, 4), np.uint8)
    for k, c in enumerate(colours):
        rgba[:, :, k] = (*c, 255)
    shape = VoxelShape(g, 3.0, VoxelColours.from_rgba(g, rgba))
    fabricate_mesh(shape, MeshOptions(), tmp_path / "s.3mf", name="s", report_path=tmp_path / "s.json")
    extruder = {f["colour"]: f["extruder"] for f in json.loads((tmp_path / "s.json").read_text())["colours"]["filaments"]}
    assert sorted(extruder.values()) == [1, 2, 3, 4, 5]
    layers = _tools_by_layer(_slice_with_extruders(tmp_path / "s.3mf", tmp_path / "s.gcode", 5, wipe_tower=False))
    checked = 0
    for k, c in enumerate(colours):
        want = extruder["#" + "".join(f"{v:02x}" for v in c)] - 1
        for z, tools in layers.items():
            if 3.0 * k + 0.7 < z < 3.0 * (k + 1) - 0.7:  # well inside slab k
                assert tools == {want}, (k, z, tools, want)
                checked += 1
    assert checked >= 5 * 5
