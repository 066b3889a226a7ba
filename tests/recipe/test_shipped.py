"""Every recipe shipped in recipes/ builds, and its outputs pass independent checks."""

import functools
import hashlib
import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from _dxf_read import closed_rings, polylines

from voxfab.recipe import build, load_recipe
from voxfab.shape import fill_cavities, well_formed_reasons

RECIPES = sorted((Path(__file__).parents[2] / "recipes").rglob("*.toml"))
#: Build volume the recipes' comments ask for, mm (a common 220 x 220 x 250 mm printer).
PRINT_VOLUME = (220.0, 220.0, 250.0)
#: How close voxfab's filament and time estimates come to PrusaSlicer's, as a fraction.
ESTIMATE_TOLERANCE = 0.30


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
    meshes = sorted(built(path).rglob("mesh.3mf"))  # the print, not the plates' assembly.3mf
    if not any("mesh" == s.name for s in load_recipe(path).outputs):
        pytest.skip("this recipe asks for no mesh")
    assert meshes, "the mesh output wrote no 3MF"
    for mesh in meshes:
        info = subprocess.run([slicer, "--info", str(mesh)], capture_output=True, text=True, timeout=300)
        assert info.returncode == 0, info.stderr
        assert re.search(r"^manifold = yes$", info.stdout, re.M), info.stdout
        assert re.search(r"^number_of_parts =\s*1$", info.stdout, re.M), info.stdout
        gcode = tmp_path / (mesh.stem + ".gcode")
        # Sliced for a common printer with PrusaSlicer's default print profile, in PLA.
        assert (_mesh_size_from_3mf(mesh) <= np.array(PRINT_VOLUME)).all()
        (w, d, h), report = PRINT_VOLUME, json.loads((mesh.parent / "mesh.json").read_text())
        sliced = subprocess.run(
            [slicer, "--export-gcode", str(mesh), "--bed-shape", f"0x0,{w:g}x0,{w:g}x{d:g},0x{d:g}",
             "--max-print-height", f"{h:g}", "--filament-density", "1.24",
             "--fill-density", f"{report['infill_percent']:g}%", "--output", str(gcode)],
            capture_output=True, text=True, timeout=600,
        )
        assert sliced.returncode == 0, sliced.stderr + sliced.stdout
        text = gcode.read_text()
        assert len(text) > 1000 and "G1 " in text
        grams, seconds = _slicer_estimates(text)
        assert abs(report["mass_g"] / grams - 1) <= ESTIMATE_TOLERANCE, (report["mass_g"], grams)
        assert abs(report["print_time_s"] / seconds - 1) <= ESTIMATE_TOLERANCE, (report["print_time_s"], seconds)


def _slicer_estimates(gcode: str) -> tuple[float, float]:
    """PrusaSlicer's filament mass (g) and print time (s), from the comments of its G-code."""
    grams = float(re.search(r"^; filament used \[g\] = ([0-9.]+)", gcode, re.M).group(1))
    spent = re.search(r"^; estimated printing time \(normal mode\) = (.+)$", gcode, re.M).group(1)
    units = {"d": 86400, "h": 3600, "m": 60, "s": 1}
    seconds = sum(int(n) * units[u] for n, u in re.findall(r"(\d+)([dhms])", spent))
    return grams, float(seconds)


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
    layers = _dxf_layers(path)
    xs, ys = set(), set()
    for (x0, y0), (x1, y1) in (line for k in ("MOUNTAIN", "VALLEY") for line in layers.get(k, []) if len(line) == 2):
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
        for pts in closed_rings(ezdxf.readfile(path)):
            rings.append(shapely.Polygon(pts))
        for i, ring in enumerate(rings):
            depth = sum(1 for j, other in enumerate(rings) if j != i and other.contains(ring))
            count += depth % 2 == 0  # inside an even number of rings: an outline, not a hole
    return count


#: ISO sheets a recipe may name, mm (portrait); laser beds are given as WxH.
_ISO_SHEETS = {"A0": (841.0, 1189.0), "A1": (594.0, 841.0), "A2": (420.0, 594.0), "A3": (297.0, 420.0),
               "A4": (210.0, 297.0)}


def _sheet_mm(spec: str) -> tuple[float, float]:
    if spec.upper() in _ISO_SHEETS:
        return _ISO_SHEETS[spec.upper()]
    w, h = re.fullmatch(r"\s*([0-9.]+)\s*[xX]\s*([0-9.]+)\s*", spec).groups()
    return float(w), float(h)


@functools.cache
def _dxf_layers(path: Path) -> dict[str, list[np.ndarray]]:
    """The polylines of each layer of a DXF (lines and polylines, closed ones closed), read with ezdxf.

    Read once per file: ezdxf takes seconds over a net of a few thousand faces.
    """
    import ezdxf

    out: dict[str, list[np.ndarray]] = {}
    for layer, pts, closed in polylines(ezdxf.readfile(path)):
        out.setdefault(layer, []).append(np.vstack([pts, pts[:1]]) if closed else pts)
    return out


def _paper(cut: list[np.ndarray]):
    """The paper the CUT lines outline, polygonized with shapely: inside an odd number of closed rings."""
    import shapely

    rings = shapely.polygonize([shapely.union_all([shapely.LineString(x) for x in cut])]).geoms
    return functools.reduce(shapely.symmetric_difference, [shapely.Polygon(r.exterior) for r in rings])


def _net_on_sheet(net: dict, layers: dict[str, list[np.ndarray]], face: float, paper) -> np.ndarray:
    """Where the faces of ``net.json`` lie on the sheet, ``(F, 4, 2)`` mm, matched to the drawn lattice.

    The faces' bounding box is that of the drawn straight lines that lie on the face lattice (folds,
    tab folds, slits and outline; tab tops and sides are off it); the net is drawn as is or turned a
    quarter turn, whichever puts every face inside the paper.
    """
    import shapely

    def on_axes(kinds: tuple[str, ...]) -> tuple[np.ndarray, np.ndarray]:
        segs = np.concatenate([np.stack([x[:-1], x[1:]], axis=1) for k in kinds for x in layers.get(k, [])])
        vertical = np.abs(segs[:, 0, 0] - segs[:, 1, 0]) < 1e-6
        horizontal = np.abs(segs[:, 0, 1] - segs[:, 1, 1]) < 1e-6
        return segs[vertical][:, 0, 0], segs[horizontal][:, 0, 1]

    def on_lattice(values: np.ndarray, origin: float) -> np.ndarray:
        units = (values - origin) / face
        return values[np.abs(units - np.round(units)) < 1e-4]

    # Fold lines (tab folds too) lie on the lattice; they fix its offset.
    fx, fy = on_axes(("MOUNTAIN", "VALLEY"))
    xs, ys = on_axes(("CUT", "MOUNTAIN", "VALLEY"))
    ox, oy = on_lattice(xs, fx[0]), on_lattice(ys, fy[0])
    cells = np.array([f["corners2d"] for f in net["faces"]], dtype=float)
    for turned in (False, True):
        c = np.stack([-cells[..., 1], cells[..., 0]], axis=-1) if turned else cells
        c = c - c.reshape(-1, 2).min(axis=0)
        pos = np.array([ox.min(), oy.min()]) + c * face
        centres = pos.mean(axis=1)
        if np.allclose(pos.reshape(-1, 2).max(axis=0), [ox.max(), oy.max()], atol=1e-4) and \
                shapely.contains_xy(paper.buffer(1e-6), centres[:, 0], centres[:, 1]).all():
            return pos
    raise AssertionError("the faces of net.json do not match the drawn net")


def _edge_labels(pos: np.ndarray, label: list[np.ndarray], face: float, band: float) -> dict:
    """The LABEL strokes standing on each face edge, in the edge's frame: ``(face, edge) → (n, 2, 2)``.

    A label stands on its edge inside its face, reading along it with the face on its left; the
    stroke segments within ``band`` mm of the edge and more than ``band`` from its start belong to
    it (the label of the previous edge keeps within ``band`` of that corner).
    """
    import shapely

    segs = np.concatenate([np.stack([x[:-1], x[1:]], axis=1) for x in label])
    mid = segs.mean(axis=1)
    hit_seg, hit_face = shapely.STRtree(shapely.polygons(pos)).query(shapely.points(mid), predicate="within")
    out: dict[tuple[int, int], np.ndarray] = {}
    for f in np.unique(hit_face).tolist():
        mine = segs[hit_seg[hit_face == f]]
        for k in range(4):
            p0, p1 = pos[f, k], pos[f, (k + 1) % 4]
            d = (p1 - p0) / face
            local = (mine - p0) @ np.stack([d, [-d[1], d[0]]], axis=1)
            keep = ((local[..., 1] < band) & (local[..., 0] > band)).all(axis=1)
            if keep.any():
                out[(f, k)] = local[keep]
    return out


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
    # Another scale only by its name: the print's `size`, the paper's `face_size`.
    size = outputs["mesh"].size
    print_pitch = recipe.pitch if size is None else size / extents.max()
    paper_pitch = outputs["net"].net.face_size or recipe.pitch
    assert np.allclose(print_size, extents * print_pitch, atol=1e-6), (print_size, extents)
    assert face == pytest.approx(paper_pitch, abs=1e-6), (face, paper_pitch)
    manifest = json.loads((folder / "manifest.json").read_text())
    named = [w for w in manifest["warnings"] if "face_size =" in w or "size =" in w]
    assert len(named) == (size is not None) + (abs(paper_pitch - recipe.pitch) > 1e-9), manifest["warnings"]
    # The plates stand at the recipe's pitch, the print's scale unless the print names a size.
    assert abs(stack - extents[axis] * recipe.pitch) <= tolerance / 2 + 1e-9, (stack, extents[axis])
    assert report["stack_height"] == pytest.approx(stack)


@pytest.mark.parametrize("path", RECIPES, ids=[p.stem for p in RECIPES])
def test_recipe_net_is_legible_on_its_sheet(built, path):
    """From net.dxf alone: the paper lies on the recipe's sheet, tabs are 3 mm deep, labels 2 mm tall and paired.

    Each seam's two edges (found from the 3D corners in net.json) carry the same label, drawn alike
    in the frame of the edge, and no two seams share a label.
    """
    import shapely

    recipe = load_recipe(path)
    spec = next((s for s in recipe.outputs if s.name == "net"), None)
    if spec is None:
        pytest.skip("this recipe asks for no net")
    written = dict(spec.options)
    assert "numbers" not in written and "tabs" not in written and "min_tab_depth" not in written, \
        "a bundled recipe draws legible labels and tabs"
    folder = built(path)
    layers = _dxf_layers(folder / "net.dxf")
    face = _face_size_from_dxf(folder / "net.dxf")
    paper = _paper(layers["CUT"])
    w, h = _sheet_mm(written.get("sheet", "A4"))
    assert paper.within(shapely.box(0, 0, w, h)), (paper.bounds, w, h)
    net = json.loads((folder / "net.json").read_text())
    pos = _net_on_sheet(net, layers, face, paper)
    # Tabs: the paper outside the faces (grown by a hair so tabs part at their folds), each a
    # trapezoid whose depth is its short side.
    faces = shapely.union_all(shapely.polygons(pos)).buffer(1e-4, join_style="mitre")
    tabs = [t for t in getattr(paper.difference(faces), "geoms", []) if t.area > 1e-3]
    depths = [min(t.bounds[2] - t.bounds[0], t.bounds[3] - t.bounds[1]) + 1e-4 for t in tabs]
    assert min(depths) >= 3.0 - 1e-6, min(depths)
    # Seams: face edges that are no fold, paired by their 3D corners; those meeting in the plane are uncut.
    c3 = np.array([f["corners3d"] for f in net["faces"]])
    folds = {tuple(sorted(x)) for x in net["folds"]}
    ends = {}
    for f in range(len(c3)):
        for k in range(4):
            ends.setdefault(frozenset((tuple(c3[f, k]), tuple(c3[f, (k + 1) % 4]))), []).append((f, k))
    labels = _edge_labels(pos, layers["LABEL"], face, band=0.08 * face + 2.0)
    signatures: dict[tuple, int] = {}
    heights = []
    four = 0  # edges where four faces meet: up to two seams each, left to the validator
    for pair in ends.values():
        assert len(pair) in (2, 4)
        if len(pair) == 4:
            four += 1
            # Two voxels touching along an edge (voxel art joined into one piece): four faces meet
            # there, and which of them a seam pairs is the surface graph's 6-connectivity rule, which
            # the validator checks as the net is refolded (test_recipe_nets_refold_onto_the_shape).
            continue
        (f, k), (g, j) = pair
        if tuple(sorted((f, g))) in folds:
            continue
        a0, a1 = pos[f, k], pos[f, (k + 1) % 4]
        if np.allclose(a0, pos[g, (j + 1) % 4]) and np.allclose(a1, pos[g, j]):
            continue
        sides = [labels.get((f, k)), labels.get((g, j))]
        assert sides[0] is not None and sides[1] is not None, ("seam without a label", pair)
        # The strokes as a set of segments, each with its ends in order: the label as drawn.
        one, two = (frozenset(tuple(sorted(map(tuple, seg))) for seg in np.round(x, 3).tolist()) for x in sides)
        assert one == two, ("the two edges of a seam carry different labels", pair)
        signatures[one] = signatures.get(one, 0) + 1
        # Cap height: the depth the glyphs span above the tape bar of a seam without a tab.
        depth = sides[0][..., 1]
        depth = depth[depth > 0.03 * face]
        heights.append(depth.max() - depth.min())
    assert signatures and set(signatures.values()) == {1}, "two seams share a label"
    assert min(heights) >= 2.0 - 1e-6, min(heights)
    # One tab per seam, but for the few without room (marked for tape and warned about).
    assert len(signatures) - 10 <= len(tabs) <= len(signatures) + 2 * four


#: Heights of the pieces, mm, from FIDE's Standards of Chess Equipment (2022), tallest first; each may differ
#: by up to 10 %, the order kept, and the base is 40-50 % of the height across.
CHESS_HEIGHTS = {"king": 95.0, "queen": 85.0, "bishop": 70.0, "knight": 60.0, "rook": 55.0, "pawn": 50.0}
CHESS = [p for p in RECIPES if p.parent.name == "chess"]


def _objects_in_3mf(path: Path) -> list[np.ndarray]:
    """Each 3MF object's triangle corners, ``(T, 3, 3)`` mm, read from its XML (no voxfab code)."""
    import xml.etree.ElementTree as ET
    import zipfile

    with zipfile.ZipFile(path) as z:
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    out = []
    for obj in root.iterfind(".//m:object", ns):
        xyz = np.array([[float(v.get(a)) for a in "xyz"] for v in obj.iterfind(".//m:vertex", ns)])
        tri = np.array([[int(t.get(k)) for k in ("v1", "v2", "v3")] for t in obj.iterfind(".//m:triangle", ns)])
        out.append(xyz[tri])
    return out


def _centroid(corners: np.ndarray) -> np.ndarray:
    """Centre of the solid a closed mesh bounds, by signed tetrahedra from the origin."""
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    vol = np.einsum("ij,ij->i", np.cross(a, b), c) / 6.0
    return (vol[:, None] * (a + b + c) / 4.0).sum(axis=0) / vol.sum()


def _footprint(corners: np.ndarray) -> np.ndarray:
    """``(2, 2)`` min and max xy corner of the triangles lying on the lowest plane, mm."""
    z0 = corners[..., 2].min()
    low = corners[(np.abs(corners[..., 2] - z0) < 1e-6).all(axis=1)].reshape(-1, 3)[:, :2]
    return np.stack([low.min(axis=0), low.max(axis=0)])


def test_the_chess_set_has_six_kinds_of_piece():
    assert {p.stem for p in CHESS} == set(CHESS_HEIGHTS)


@pytest.mark.parametrize("path", CHESS, ids=[p.stem for p in CHESS])
def test_chess_piece_is_one_part_at_playing_size_on_a_base_it_stands_on(built, path):
    folder = built(path)
    objects = _objects_in_3mf(folder / "mesh.3mf")
    assert len(objects) == 1, "one part"
    corners = objects[0]
    size = corners.reshape(-1, 3).max(axis=0) - corners.reshape(-1, 3).min(axis=0)
    assert size[2] == pytest.approx(CHESS_HEIGHTS[path.stem], rel=0.03), size
    assert (size <= np.array(PRINT_VOLUME)).all()
    # The base: at least 40 % of the height across, and the centre of mass over its middle.
    foot = _footprint(corners)
    across = foot[1] - foot[0]
    assert across.min() >= 0.4 * size[2], (across, size)
    centre = _centroid(corners)
    assert (np.abs(centre[:2] - foot.mean(axis=0)) <= across / 4).all(), (centre, foot)
    assert json.loads((folder / "mesh.json").read_text())["center_of_mass_mm"] == pytest.approx(centre, abs=1e-4)


def _sections(corners: np.ndarray, step: float) -> list[tuple[float, np.ndarray]]:
    """(height, x and y extent in mm) of horizontal sections of a closed mesh, every ``step`` mm from the bottom."""
    import trimesh

    mesh = trimesh.Trimesh(corners.reshape(-1, 3), np.arange(corners.shape[0] * 3).reshape(-1, 3), process=True)
    z0, z1 = mesh.bounds[:, 2]
    out = []
    for z in np.arange(z0 + step / 2, z1, step):
        section = mesh.section(plane_origin=(0, 0, z), plane_normal=(0, 0, 1))
        if section is not None:
            out.append((float(z - z0), np.ptp(section.vertices[:, :2], axis=0)))
    return out


def test_the_chess_set_keeps_fide_proportions(built):
    """Heights and bases read from the built 3MFs: FIDE heights within 10 % in their order, bases 40-50 % of the
    height and never wider on a smaller piece, and a king whose top (a cross) is clearly not the queen's."""
    heights, bases = [], []
    tops = {}
    for name in CHESS_HEIGHTS:
        (corners,) = _objects_in_3mf(built(next(p for p in CHESS if p.stem == name)) / "mesh.3mf")
        height = float(np.ptp(corners[..., 2]))
        across = np.diff(_footprint(corners), axis=0)[0]
        assert abs(height - CHESS_HEIGHTS[name]) <= 0.1 * CHESS_HEIGHTS[name], (name, height)
        assert 0.40 * height <= across.min() <= across.max() <= 0.50 * height, (name, across, height)
        heights.append(height)
        bases.append(float(across.max()))
        if name in ("king", "queen"):
            tops[name] = [ext for z, ext in _sections(corners, height / 50) if z > 0.8 * height]
    assert heights == sorted(heights, reverse=True) and len(set(heights)) == len(heights), heights
    assert bases == sorted(bases, reverse=True), bases
    # The king's cross: a section near its top three times wider one way than the other; the queen's are round.
    assert max(ext.max() / ext.min() for ext in tops["king"]) >= 3.0
    assert max(ext.max() / ext.min() for ext in tops["queen"]) < 1.2


PICTURES = Path(__file__).parents[2] / "output" / "test-pictures"


def _widest_step(grid: np.ndarray) -> int:
    """The most voxels any layer reaches beyond the layer under it (1: a 45 degree staircase at worst)."""
    from scipy import ndimage

    z = np.flatnonzero(grid.any(axis=(0, 1)))
    steps = [int(ndimage.distance_transform_cdt(~grid[:, :, k - 1], metric="chessboard")[grid[:, :, k]].max())
             for k in range(z.min() + 1, z.max() + 1)]
    return max(steps)


@pytest.mark.parametrize("name", ["knight", "spinning_top"])
def test_the_designed_pieces_step_at_most_one_voxel_a_layer(built, name):
    """Each layer stands on the one below, reaching at most one voxel further (a 45 degree staircase; its
    ledges still take a slicer's supports, which mesh.json reports)."""
    path = next(p for p in RECIPES if p.stem == name)
    assert _widest_step(np.load(built(path) / "shape.npy")) == 1


def test_the_knight_is_a_horse_on_a_base_not_a_surface_of_revolution(built):
    from PIL import Image

    from voxfab.render import render

    knight = next(p for p in CHESS if p.stem == "knight")
    grid = np.load(built(knight) / "shape.npy")
    assert well_formed_reasons(grid) == []
    assert not np.array_equal(grid, np.rot90(grid, axes=(0, 1))), "unchanged by a quarter turn about z"
    # Seen from the side (along x), the head reaches further forward than the neck under it, and the
    # outline is far from a mirror image of itself; from the front (along y) the head is narrow.
    side, front = grid.any(axis=0), grid.any(axis=1)
    head = np.flatnonzero(side[:, 15:].any(axis=1))
    neck = np.flatnonzero(side[:, 7:12].any(axis=1))
    assert head.max() >= neck.max() + 3, (head, neck)
    assert (side != side[::-1]).sum() > 0.2 * side.sum()
    assert np.flatnonzero(front[:, 15:].any(axis=1)).size <= 0.5 * head.size
    # A side view for a person to look at; read back, it is no mirror image of itself.
    PICTURES.mkdir(parents=True, exist_ok=True)
    picture = PICTURES / "knight-side.png"
    tmp = picture.with_suffix(".part.png")
    render(grid, view="x", size=400).save(tmp)
    tmp.replace(picture)
    ink = np.asarray(Image.open(picture).convert("L")) < 200
    assert ink.mean() > 0.1
    assert (ink != ink[:, ::-1]).mean() > 0.05


def test_the_spinning_top_spins_and_fits_a_hand(built):
    top = next(p for p in RECIPES if p.stem == "spinning_top")
    folder = built(top)
    report = json.loads((folder / "mesh.json").read_text())
    spin = report["spin"]
    assert spin["spins"], report["warnings"]
    manifest = json.loads((folder / "manifest.json").read_text())
    assert not [w for w in manifest["warnings"] if "spin:" in w]
    (corners,) = _objects_in_3mf(folder / "mesh.3mf")
    size = corners.reshape(-1, 3).max(axis=0) - corners.reshape(-1, 3).min(axis=0)
    assert size[:2] == pytest.approx([60.0, 60.0], abs=1.0) and size[2] < size[0]
    # The tip is one voxel face; the centre of mass stands within 0.5 mm of the vertical through it.
    foot = _footprint(corners)
    assert (foot[1] - foot[0]) == pytest.approx([report["pitch_mm"]] * 2)
    offset = float(np.hypot(*(_centroid(corners)[:2] - foot.mean(axis=0))))
    assert offset <= 0.5 and spin["axis_offset_mm"] == pytest.approx(offset, abs=1e-5)
