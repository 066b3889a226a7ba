import dataclasses
import hashlib
import json
import shutil
import textwrap
from pathlib import Path

import numpy as np
import pytest

from voxfab._shared.options import Options, option
from voxfab.errors import RecipeError
from voxfab.recipe import build, build_recipe, load_recipe, make_shape
from voxfab.shape import examples


@pytest.fixture
def shape_file(tmp_path):
    path = tmp_path / "blob.npy"
    np.save(path, examples.random_shape(3))
    return path


def write(tmp_path, text, name="r.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def test_file_source_with_operations(tmp_path, shape_file):
    other = tmp_path / "bar.npy"
    bar = np.zeros((25, 25, 25), bool)
    bar[:, 0, 0] = True
    np.save(other, bar)
    r = load_recipe(write(tmp_path, f"""
        name = "blob"
        seed = 4
        pitch = 2.5
        [source]
        file = "{shape_file.name}"
        [[operations]]
        op = "rotate"
        axis = "x"
        turns = 1
        [[operations]]
        op = "union"
        source = {{ file = "bar.npy" }}
        [[operations]]
        op = "largest"
    """))
    assert (r.name, r.seed, r.pitch) == ("blob", 4, 2.5)
    s = make_shape(r)
    assert s.pitch == 2.5
    from voxfab.shape import largest_component, rotate, union

    expected = largest_component(union(rotate(examples.random_shape(3), "x", 1), bar))
    assert (s.grid == expected).all()


def test_shift_moves_the_shape_by_whole_voxels_and_refuses_to_push_it_out(tmp_path):
    cube = np.zeros((25, 25, 25), bool)
    cube[10:15, 10:15, 10:15] = True
    np.save(tmp_path / "cube.npy", cube)
    r = load_recipe(write(tmp_path, '[source]\nfile = "cube.npy"\n[[operations]]\nop = "shift"\nby = [1, -2, -10]\n'))
    moved = make_shape(r).grid
    assert np.argwhere(moved).min(axis=0).tolist() == [11, 8, 0] and moved.sum() == 125
    out = load_recipe(write(tmp_path, '[source]\nfile = "cube.npy"\n[[operations]]\nop = "shift"\nby = [0, 0, 11]\n'))
    with pytest.raises(RecipeError, match=r"operations\[0\] \(shift\): offset: \(0, 0, 11\) moves filled voxels out"):
        make_shape(out)


def test_build_writes_shape_and_manifest_and_is_reproducible(tmp_path, shape_file):
    recipe = load_recipe(write(tmp_path, f'[source]\nfile = "{shape_file.name}"\n'))
    a = build(recipe, tmp_path / "a")
    b = build(recipe, tmp_path / "b")
    manifest = json.loads((a / "manifest.json").read_text())
    assert manifest["recipe"] == "r" and manifest["seed"] == 0
    paths = {f["path"] for f in manifest["files"]}
    assert {"shape.npy"} <= paths
    for f in manifest["files"]:
        assert (a / f["path"]).read_bytes() == (b / f["path"]).read_bytes()
        assert f["purpose"]
    assert (a / "manifest.json").read_bytes() == (b / "manifest.json").read_bytes()
    assert np.array_equal(np.load(a / "shape.npy"), examples.random_shape(3))


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ('colour = 1\n[source]\nfile = "x.npy"\n', r"r\.toml:1: colour: unknown key"),
        ('seed = "one"\n[source]\nfile = "x.npy"\n', r"r\.toml:1: seed: expected an integer"),
        ('[source]\nfile = "x.npy"\n[[operations]]\nop = "melt"\n', r"r\.toml:4: operations\[0\]\.op: unknown operation"),
        ('[source]\nfile = "x.npy"\n[[operations]]\nop = "rotate"\nturns = "2"\n', r"r\.toml:5: operations\[0\]\.turns: expected int"),
        ('[source]\nfile = "x.npy"\n[outputs.laser]\n', r"r\.toml:3: outputs\.laser: unknown output"),
        ('[source]\nfile = "x.npy"\n[[operations]]\nop = "shift"\nby = [1, 2]\n', r"r\.toml:5: operations\[0\]\.by: expected list of int"),
        ('[source]\nfile = "x.npy"\n[[operations]]\nop = "shift"\n', r"operations\[0\]: op 'shift' needs 'by"),
        ('[source]\nmaker = "no-such-maker"\n', r"r\.toml:2: source\.maker: unknown maker"),
        ('[source]\nmaker = "focal"\nfoci = [[0, 0, 0]]\nradius = 1.0\nk = 7\n',
         r"r\.toml:5: source\.k: expected an integer in 0\.\.2, got 7"),
        ('[source]\nmaker = "tube"\nspine = ["t", "0", "t"]\nsamples = 1\n',
         r"r\.toml:4: source\.samples: expected an integer in 2\.\.100000, got 1"),
        ('[source]\nmaker = "implicit"\nexpression = "x"\nmode = "hollow"\n', r"source\.mode: expected 'solid' or 'surface'"),
        ('[source]\nmaker = "focal"\nradius = 1.0\n', r"source\.foci: missing required key"),
        ('seed = -1\n[source]\nfile = "x.npy"\n', r"r\.toml:1: seed: expected an integer from 0 to"),
        ('[source]\nfile = "x.npy"\nmaker = "x"\n', r"source: expected exactly one"),
        ('name = "a/b"\n[source]\nfile = "x.npy"\n', r"name: expected a folder-safe name"),
        ("[source\n", r"invalid TOML"),
        ('pitch = 2.0\n', r"missing the \[source\] table"),
    ],
)
def test_errors_name_the_file_line_and_key(tmp_path, body, message):
    with pytest.raises(RecipeError, match=message):
        load_recipe(write(tmp_path, body))


@dataclasses.dataclass(frozen=True)
class _DemoOptions(Options):
    size: float = option(1.0, help="a size", unit="mm", low=0.0, low_open=True, high=10.0)
    mode: str = option("a", help="a mode", choices=("a", "b"))
    views: tuple[str, ...] = option(("iso",), help="views", choices=("iso", "x"))


def _demo_kind(run):
    from voxfab._shared.options import from_mapping
    from voxfab.fabricate import OptionTable, Output

    return Output("demo", (OptionTable(_DemoOptions, "demo"),), "tests.recipe:run", ("x.txt",), run,
                  parse=lambda t: from_mapping(_DemoOptions, t))


def test_output_options_are_checked_against_the_options_dataclass(tmp_path, monkeypatch):
    from voxfab import fabricate
    from voxfab.fabricate import Artefact, OutputFile

    def run(shape, o, outdir, *, name, seed, context):
        (outdir / "x.txt").write_text(f"{name} {seed} {o.size} {o.mode} {list(o.views)}")
        return Artefact((OutputFile("x.txt", "a test file"),), ("demo warning",))

    monkeypatch.setitem(fabricate.outputs(), "demo", _demo_kind(run))
    np.save(tmp_path / "x.npy", examples.random_shape(1))
    ok = load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\nsize = 3\nmode = "b"\nviews = ["iso"]\n'))
    folder = build(ok, tmp_path / "out")
    assert (folder / "x.txt").read_text() == "r 0 3.0 b ['iso']"
    assert json.loads((folder / "manifest.json").read_text())["warnings"] == ["demo: demo warning"]
    with pytest.raises(RecipeError, match=r"r\.toml:4: outputs\.demo\.mode: unknown choice 'c'; expected one of a, b"):
        load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\nmode = "c"\n'))
    with pytest.raises(RecipeError, match=r"outputs\.demo\.colour: unknown key; outputs\.demo accepts: mode, size, views"):
        load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\ncolour = 1\n'))
    with pytest.raises(RecipeError, match=r"r\.toml:4: outputs\.demo\.size: expected a positive number of mm up to 10, got 1e\+300"):
        load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\nsize = 1e300\n'))


def test_failed_build_leaves_no_partial_folder(tmp_path, monkeypatch):
    from voxfab import fabricate

    def failing(shape, o, outdir, *, name, seed, context):
        (outdir / "half.bin").write_bytes(b"x")
        raise RecipeError("boom")

    monkeypatch.setitem(fabricate.outputs(), "demo", _demo_kind(failing))
    np.save(tmp_path / "x.npy", examples.random_shape(1))
    r = load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\n'))
    with pytest.raises(RecipeError):
        build(r, tmp_path / "out")
    assert not (tmp_path / "out" / "r").exists()
    assert list((tmp_path / "out").iterdir()) == []


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ('[outputs.net]\nsheet = "1x1"', r"outputs\.net\.sheet: 1x1 leaves no room"),
        ('[outputs.net]\nsheet = "1e9x1e9"', r"outputs\.net\.sheet: expected .*at most 5000 mm"),
        ('[outputs.net]\ntab_width = -3', r"outputs\.net\.tab_width: expected a positive number"),
        ('[outputs.net]\ntimeout = 0', r"outputs\.net\.timeout: expected a positive number of s"),
        ('[outputs.slices]\nsheet = "1x1"', r"outputs\.slices\.sheet: 1x1 leaves no room"),
        ('[outputs.slices]\nthickness = 0.0001', r"outputs\.slices\.thickness: expected a number of mm from 0\.1"),
        ('[outputs.slices]\ndowel = 1000', r"outputs\.slices\.dowel: expected a number of mm from 0 to 100, got 1000"),
        ('[outputs.mesh]\nsize = 1e300', r"outputs\.mesh\.size: expected a positive number of mm up to 10000, got 1e\+300"),
        ('[outputs.mesh]\nsize = nan', r"outputs\.mesh\.size: expected a positive number of mm .*got nan"),
        ('[outputs.mesh]\nmagnet = "big"', r"outputs\.mesh\.magnet: expected DIAMETERxDEPTH"),
        ('[outputs.pictures]\nsize = 0', r"outputs\.pictures\.size: expected an integer number of px from 16"),
        ('[outputs.pictures]\nviews = ["top"]', r"outputs\.pictures\.views: unknown choice 'top'"),
        ('[outputs.pictures]\ncolor = "' + "x" * 500 + '"', r"outputs\.pictures\.color: expected a colour name .*502 characters"),
        ('pitch = 1e300\n', r"pitch: expected a positive number of mm up to 1000"),
    ],
)
def test_check_catches_what_the_build_would_reject(tmp_path, table, message):
    """`voxfab build --check` (load_recipe) refuses every value the build would refuse."""
    np.save(tmp_path / "x.npy", examples.random_shape(1))
    top, _, rest = table.partition("[")
    body = (top if not rest else "") + '[source]\nfile = "x.npy"\n' + ("[" + rest if rest else "") + "\n"
    with pytest.raises(RecipeError, match=message):
        load_recipe(write(tmp_path, body))


def test_another_scale_by_its_name_is_warned_about(tmp_path):
    """A print of another size and a paper model at its own scale: the build says both."""
    np.save(tmp_path / "box.npy", examples.box(2, 3, 4))
    r = load_recipe(write(tmp_path, 'pitch = 4.0\n[source]\nfile = "box.npy"\n[outputs.net]\nformats = ["dxf"]\n'
                                    'sheet = "A3"\nface_size = 8.0\n[outputs.mesh]\nsize = 20.0\n'))
    folder = build(r, tmp_path / "out")
    warnings = json.loads((folder / "manifest.json").read_text())["warnings"]
    assert "mesh: printed at size = 20 mm (5 mm per voxel), 1.25 x the recipe's pitch of 4 mm" in warnings
    assert "net: the paper model is at face_size = 8 mm, 2 x the recipe's pitch of 4 mm" in warnings
    assert json.loads((folder / "mesh.json").read_text())["size_mm"] == [10.0, 15.0, 20.0]


def test_net_faces_default_to_the_shape_pitch(tmp_path):
    """One scale: without face_size, the paper faces are the print's voxels."""
    import ezdxf

    np.save(tmp_path / "box.npy", examples.box(2, 3, 4))
    # 8 mm: the smallest whole face size with 3 mm glue tabs (7.5 mm)
    r = load_recipe(write(tmp_path, 'pitch = 8.0\n[source]\nfile = "box.npy"\n[outputs.net]\nformats = ["dxf"]\n'
                                    'sheet = "A3"\n[outputs.mesh]\n'))
    folder = build(r, tmp_path / "out")
    folds = ezdxf.readfile(folder / "net.dxf").modelspace().query('LINE[layer=="MOUNTAIN" | layer=="VALLEY"]')
    xs = sorted({round(e.dxf.start.x, 6) for e in folds if abs(e.dxf.end.x - e.dxf.start.x) < 1e-9})
    assert min(np.diff(xs)) == pytest.approx(8.0)  # folds lie on the face lattice
    assert json.loads((folder / "mesh.json").read_text())["size_mm"] == [16.0, 24.0, 32.0]


def test_a_net_split_into_pieces_is_a_warning(tmp_path):
    np.save(tmp_path / "box.npy", examples.box(3, 3, 3))
    r = load_recipe(write(tmp_path, '[source]\nfile = "box.npy"\n[outputs.net]\nformats = ["svg"]\nface_size = 40.0\n'
                                    'sheet = "A5"\npieces = "auto"\ntimeout = 10.0\n'))
    manifest = json.loads((build(r, tmp_path / "out") / "manifest.json").read_text())
    assert any(w.startswith("net: net split into") for w in manifest["warnings"]), manifest["warnings"]
    assert any(f["path"] == "net.sheet-2.svg" for f in manifest["files"])


CHESS = Path(__file__).resolve().parents[2] / "recipes" / "chess"


def test_the_pictures_draw_the_net_written_whatever_the_order_of_outputs(tmp_path):
    """The net output hands its net to the pictures: listed before or after the net (in the recipe's text, or in
    a Recipe made in code), they draw the very net of net.json, and the build is the same file for file."""
    from voxfab.render import PictureOptions, png_bytes
    from voxfab.render._net import net_picture
    from voxfab.render._triptych import make_net
    from voxfab.shape import fill_cavities
    from voxfab.unfold import Net, validate

    head = (CHESS / "queen.toml").read_text().split("[outputs.")[0]
    net = '[outputs.net]\nface_size = 8.6\nsheet = "900x600"\nlabel_height = 2.0\nformats = ["svg"]\n'
    pictures = "[outputs.pictures]\nsize = 200\nnet_picture = true\n"
    recipes = {}
    for order, outputs in (("pictures-first", pictures + net), ("net-first", net + pictures)):
        (tmp_path / order).mkdir()
        shutil.copy(CHESS / "queen_generatrix.svg", tmp_path / order)
        (tmp_path / order / "queen.toml").write_text(head + outputs)
        recipes[order] = load_recipe(tmp_path / order / "queen.toml")
    by_name = {spec.name: spec for spec in recipes["pictures-first"].outputs}
    recipes["pictures-first in code"] = dataclasses.replace(
        recipes["pictures-first"], outputs=(by_name["pictures"], by_name["net"]))
    built, gives = {}, {}
    for order, recipe in recipes.items():
        (tmp_path / "out" / order).mkdir(parents=True)
        made = build_recipe(recipe, tmp_path / "out" / order)
        built[order], gives[order] = made.folder, made.gives

    folder = built["pictures-first in code"]
    grid = np.load(folder / "shape.npy")
    written = Net.from_json((folder / "net.json").read_text())
    assert validate(fill_cavities(grid) if written.filled else grid, written).ok
    # The build hands its caller the very net written.
    assert [n.to_json() for n in gives["pictures-first in code"]["net"]] == [written.to_json()]
    background = PictureOptions().background

    def picture(of: Net) -> bytes:
        return png_bytes(net_picture(of, fill_cavities(grid) if of.filled else grid, size=200, background=background))

    drawn = (folder / "net_picture.png").read_bytes()
    assert drawn == picture(written)
    # Not the net the pictures would unfold on their own: they were given the one written.
    assert drawn != picture(make_net(grid, rng=recipes["net-first"].seed))

    manifest = {order: (f / "manifest.json").read_bytes() for order, f in built.items()}
    assert manifest["pictures-first in code"] == manifest["pictures-first"]
    # The texts differ in their order of outputs, so in recipe_sha256 only.
    first, second = (json.loads(manifest[order]) for order in ("pictures-first", "net-first"))
    for order, data in (("pictures-first", first), ("net-first", second)):
        assert data.pop("recipe_sha256") == hashlib.sha256((tmp_path / order / "queen.toml").read_bytes()).hexdigest()
    assert first == second and first["outputs"] == ["net", "pictures"]
