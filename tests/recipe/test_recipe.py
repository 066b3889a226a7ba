import json
import textwrap

import numpy as np
import pytest

from voxfab.errors import RecipeError
from voxfab.recipe import build, load_recipe, make_shape
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
        ('[source]\nmaker = "no-such-maker"\n', r"r\.toml:2: source\.maker: unknown maker"),
        ('[source]\nfile = "x.npy"\nmaker = "x"\n', r"source: expected exactly one"),
        ('name = "a/b"\n[source]\nfile = "x.npy"\n', r"name: expected a folder-safe name"),
        ("[source\n", r"invalid TOML"),
        ('pitch = 2.0\n', r"missing the \[source\] table"),
    ],
)
def test_errors_name_the_file_line_and_key(tmp_path, body, message):
    with pytest.raises(RecipeError, match=message):
        load_recipe(write(tmp_path, body))


def test_output_options_are_checked_against_the_output_signature(tmp_path, monkeypatch):
    from pathlib import Path
    from typing import Literal

    import voxfab.fabricate._registry as reg

    def fake_output(shape, outdir: Path, *, name: str, seed: int, size: float = 1.0,
                    mode: Literal["a", "b"] = "a", views: list[str] | None = None):
        (outdir / "x.txt").write_text(f"{name} {seed} {size} {mode} {views}")
        return [reg.OutputFile("x.txt", "a test file")]

    import types

    module = types.ModuleType("voxfab_test_output")
    module.out = fake_output
    monkeypatch.setitem(__import__("sys").modules, "voxfab_test_output", module)
    monkeypatch.setitem(reg.OUTPUTS, "demo", "voxfab_test_output:out")
    np.save(tmp_path / "x.npy", examples.random_shape(1))
    ok = load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\nsize = 3\nmode = "b"\nviews = ["iso"]\n'))
    folder = build(ok, tmp_path / "out")
    assert (folder / "x.txt").read_text() == "r 0 3 b ['iso']"
    with pytest.raises(RecipeError, match=r"r\.toml:4: outputs\.demo\.mode: expected 'a' or 'b'"):
        load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\nmode = "c"\n'))
    with pytest.raises(RecipeError, match=r"outputs\.demo\.colour: unknown key; outputs\.demo accepts: mode, size, views"):
        load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.demo]\ncolour = 1\n'))


def test_failed_build_leaves_no_partial_folder(tmp_path, monkeypatch):
    import voxfab.fabricate._registry as reg

    def failing(shape, outdir, *, name: str, seed: int):
        (outdir / "half.bin").write_bytes(b"x")
        raise RecipeError("boom")

    import sys
    import types

    module = types.ModuleType("voxfab_test_failing")
    module.out = failing
    monkeypatch.setitem(sys.modules, "voxfab_test_failing", module)
    monkeypatch.setitem(reg.OUTPUTS, "failing", "voxfab_test_failing:out")
    np.save(tmp_path / "x.npy", examples.random_shape(1))
    r = load_recipe(write(tmp_path, '[source]\nfile = "x.npy"\n[outputs.failing]\n'))
    with pytest.raises(RecipeError):
        build(r, tmp_path / "out")
    assert not (tmp_path / "out" / "r").exists()
    assert list((tmp_path / "out").iterdir()) == []
