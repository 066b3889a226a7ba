"""A maker added to the makers table, and nothing else, is a maker of recipes, ``explore`` and the studio.

The row below points at a superellipsoid defined in this module; the test adds it to
``voxfab.digitize.MAKERS`` for its own run and edits nothing else.
"""

from __future__ import annotations

import io
import math
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from voxfab.digitize import MAKERS, Maker, Param, maker_params
from voxfab.studio._grid import centred, unpack


def make_superellipsoid(*, base_dir: Path, p: float = 2.0, size: int = 25) -> np.ndarray:
    """``|x|^p + |y|^p + |z|^p <= 1`` at the voxel centres of a ``size``³ grid spanning [-1, 1]³."""
    c = (np.arange(size) + 0.5) / size * 2 - 1
    x, y, z = np.meshgrid(c, c, c, indexing="ij")
    return np.abs(x) ** p + np.abs(y) ** p + np.abs(z) ** p <= 1


def random_superellipsoid(rng: np.random.Generator) -> dict[str, Any]:
    """A rounder or squarer superellipsoid on the studio's grid."""
    return {"p": round(float(rng.uniform(1.5, 6.0)), 3), "size": 25}


ROW = Maker(
    "superellipsoid", f"{__name__}:make_superellipsoid", "the superellipsoid |x|^p + |y|^p + |z|^p <= 1",
    (Param("p", "the exponent: 1 an octahedron, 2 a ball, large a cube", 0.5, 8),
     Param("size", "side of the voxel grid", 2, 256)),
    random=f"{__name__}:random_superellipsoid",
)


def grid_of(answer: dict[str, Any]) -> np.ndarray:
    return unpack(answer["grid"])


def analytic_voxels(p: float, size: int) -> float:
    """The superellipsoid's volume, 8 Γ(1 + 1/p)³ / Γ(1 + 3/p) in [-1, 1]³ units, in voxels of a ``size`` grid."""
    return 8 * math.gamma(1 + 1 / p) ** 3 / math.gamma(1 + 3 / p) * (size / 2) ** 3


@pytest.fixture
def superellipsoid(monkeypatch):
    """The row in the table for one test; the table's cache of keys is cleared on both sides."""
    maker_params.cache_clear()
    monkeypatch.setitem(MAKERS, ROW.name, ROW)
    yield ROW
    monkeypatch.undo()
    maker_params.cache_clear()


def test_a_recipe_with_the_new_maker_builds_and_checks_its_keys(superellipsoid, tmp_path):
    from voxfab.errors import RecipeError
    from voxfab.recipe import load_recipe, make_shape

    recipe = tmp_path / "blob.toml"
    recipe.write_text('name = "blob"\n\n[source]\nmaker = "superellipsoid"\np = 3\nsize = 21\n')
    grid = make_shape(load_recipe(recipe)).grid
    assert grid.shape == (21, 21, 21)
    assert abs(int(grid.sum()) - analytic_voxels(3, 21)) < 0.04 * analytic_voxels(3, 21)
    recipe.write_text('name = "blob"\n\n[source]\nmaker = "superellipsoid"\np = 9\n')
    with pytest.raises(RecipeError, match=r"source\.p: expected a number in 0\.5\.\.8, got 9"):
        load_recipe(recipe)


def test_explore_knows_the_new_maker(superellipsoid, tmp_path, capsys):
    from voxfab.cli import main
    from voxfab.generate import candidate, generators
    from voxfab.repo import Repository

    assert "superellipsoid" in generators()
    made = candidate("superellipsoid", 3, 0)
    assert made.generator == "superellipsoid" and made.grid.shape == (25, 25, 25)
    assert np.array_equal(made.grid, make_superellipsoid(base_dir=tmp_path, **made.params))
    repo = tmp_path / "r.sqlite"
    assert main(["explore", "--count", "2", "--seed", "1", "--generator", "superellipsoid", "--repo", str(repo)]) == 0
    assert capsys.readouterr().out.startswith("2 new shapes")
    with Repository(repo, create=False) as opened:
        assert len(opened.list()) == 2


def test_the_studio_lists_the_new_maker_with_its_keys(superellipsoid, client):
    makers = {m["name"]: m for m in client.get("/api/info").json()["makers"]}
    assert list(makers)[:4] == ["revolution", "tube", "focal", "implicit"]
    row = makers["superellipsoid"]
    assert row["help"] == ROW.help
    assert row["params"] == [
        {"name": "p", "label": "p", "help": ROW.params[0].help, "type": "float", "low": 0.5, "high": 8, "default": 2.0,
         "required": False, "kind": "number", "choices": [], "input": "form"},
        {"name": "size", "label": "size", "help": "side of the voxel grid", "type": "int", "low": 2, "high": 256, "default": 25,
         "required": False, "kind": "integer", "choices": [], "input": "form"},
    ]


def test_the_studio_makes_the_new_maker_from_its_form_and_refuses_a_bad_key(superellipsoid, client, tmp_path):
    r = client.post("/api/preview", json={"maker": "superellipsoid", "p": 4, "size": 21})
    assert r.status_code == 200, r.text
    shown = grid_of(r.json())
    assert np.array_equal(shown, centred(make_superellipsoid(base_dir=tmp_path, p=4.0, size=21)))
    assert r.json()["facts"]["extents"] == [21, 21, 21]
    assert abs(r.json()["facts"]["volume"] - analytic_voxels(4, 21)) < 0.04 * analytic_voxels(4, 21)
    # the row's words for a key out of its range, and for one the maker does not take
    for body, words in (({"p": 9}, "shape.p: expected a number in 0.5..8, got 9"),
                        ({"size": 2.5}, "shape.size: expected int, got float 2.5"),
                        ({"twist": 3}, "unknown key 'twist'; expected maker, p, size")):
        r = client.post("/api/preview", json={"maker": "superellipsoid", **body})
        assert r.status_code == 400 and words in r.json()["error"] and "\n" not in r.json()["error"], r.text
    # the recipe the page downloads builds the same shape from the command line's path
    r = client.post("/api/recipe", json={"shape": {"maker": "superellipsoid", "p": 4, "size": 21}, "name": "blob"})
    assert r.status_code == 200, r.text
    assert 'maker = "superellipsoid"\np = 4.0\nsize = 21\n' in r.content.decode()
    from voxfab.recipe import load_recipe, make_shape

    (tmp_path / "blob.toml").write_bytes(r.content)
    assert np.array_equal(make_shape(load_recipe(tmp_path / "blob.toml")).grid,
                          make_superellipsoid(base_dir=tmp_path, p=4.0, size=21))


def test_the_drawn_makers_take_their_other_keys_from_the_form(client):
    """The page's four drawn makers: a key the page has no field of its own for (size, bounds) comes from the form."""
    info = {m["name"]: {p["name"]: p for p in m["params"]} for m in client.get("/api/info").json()["makers"]}
    assert info["implicit"]["expression"]["input"] == "drawn" and info["implicit"]["bounds"]["kind"] == "numbers"
    assert info["tube"]["spine"]["input"] == "drawn" and info["tube"]["t_min"]["input"] == "drawn"
    assert info["tube"]["cap"]["choices"] == ["flat", "round"] and info["tube"]["closed"]["kind"] == "flag"
    ball = {"maker": "implicit", "expression": "x^2 + y^2 + z^2 - 1"}
    assert grid_of(client.post("/api/preview", json=ball).json()).sum() > 0
    small = client.post("/api/preview", json={**ball, "size": 15}).json()
    assert small["facts"]["extents"] == [15, 15, 15]
    # 6 voxels per unit and a box of the list form: a ball of diameter 2 × 6 = 12 voxels (13 with its flake)
    keys = {"scale": 6, "bounds": [-2, 2, -2, 2, -2, 2]}
    placed = client.post("/api/preview", json={**ball, **keys}).json()
    assert placed["facts"]["extents"] == [13, 13, 13]
    from voxfab.digitize import get_maker

    direct = get_maker("implicit")(base_dir=Path("."), expression=ball["expression"], scale=6.0,
                                   bounds=[-2.0, 2.0, -2.0, 2.0, -2.0, 2.0])
    assert np.array_equal(grid_of(placed), centred(direct))
    r = client.post("/api/preview", json={**ball, "bounds": [-2, 2, -2, 2, -2, 10**400]})
    assert r.status_code == 400 and "shape.bounds: expected finite numbers" in r.json()["error"], r.text
    r = client.post("/api/preview", json={**ball, "bounds": list(range(100))})
    assert r.status_code == 400 and "at most 64 numbers" in r.json()["error"], r.text
    # a recipe from the page names the form's keys
    r = client.post("/api/recipe", json={"shape": {**ball, "size": 15}, "name": "ball"})
    assert "size = 15" in r.content.decode()
    assert not zipfile.is_zipfile(io.BytesIO(r.content))
