"""Recipe makers and the shipped recipes."""

from __future__ import annotations

import dataclasses
import inspect
import tomllib
import typing
from pathlib import Path

import numpy as np
import pytest

from voxfab.digitize import (
    MAKERS,
    available_makers,
    get_maker,
    get_random_params,
    maker_params,
    random_makers,
)
from voxfab.errors import InvalidShapeError, UnknownFormatError
from voxfab.shape import well_formed_reasons

RECIPES = Path(__file__).resolve().parents[2] / "recipes"
SHIPPED = sorted(RECIPES.rglob("*.toml"))
OUTPUTS = {"mesh", "net", "slices", "pictures"}


def test_registry():
    assert {"revolution", "tube", "focal", "implicit"} <= set(MAKERS)
    assert available_makers() == sorted(MAKERS)
    with pytest.raises(UnknownFormatError, match="unknown maker 'nope'"):
        get_maker("nope")


@pytest.mark.parametrize("name", sorted(MAKERS))
def test_every_keyword_has_a_row(name):
    """The table describes exactly the maker's keywords, each with words; type and default come from the code."""
    sig = inspect.signature(get_maker(name))
    keywords = {p for p in sig.parameters if p != "base_dir"}
    params = maker_params(name)
    assert set(params) == keywords
    for key, param in params.items():
        assert param.help and param.hint is not None, key
        assert param.required == (sig.parameters[key].default is inspect.Parameter.empty)
        if not param.required:
            assert param.default == sig.parameters[key].default


def test_a_row_that_drifts_from_its_function_is_refused(monkeypatch):
    row = MAKERS["focal"]
    monkeypatch.setitem(MAKERS, "focal", dataclasses.replace(row, params=row.params[:-1]))
    maker_params.cache_clear()
    try:
        with pytest.raises(TypeError, match="its row describes"):
            maker_params("focal")
    finally:
        maker_params.cache_clear()


def test_params_check_type_and_range():
    k = maker_params("revolution")["k"]
    assert k.problem(2) is None
    assert k.problem(3) == "expected an integer in 0..2, got 3"
    assert k.problem(-1) == "expected an integer in 0..2, got -1"
    assert maker_params("tube")["samples"].problem(1) == "expected an integer in 2..100000, got 1"
    assert maker_params("tube")["radius"].problem(float("nan")) == "expected a finite number, got nan"
    assert k.problem(True).startswith("expected int, got bool")
    mode = maker_params("revolution")["mode"]
    assert mode.problem("surface") is None and "'solid' or 'surface'" in mode.problem("hollow")
    assert mode.is_scalar and maker_params("revolution")["axis"].is_scalar
    assert maker_params("tube")["radius"].is_scalar and not maker_params("tube")["spine"].is_scalar


def test_params_say_what_kind_of_value_they_take():
    tube = maker_params("tube")
    kinds = {name: tube[name].kind for name in ("spine", "profile", "radius", "samples", "cap", "closed", "center")}
    assert kinds == {"spine": None, "profile": None, "radius": "number", "samples": "integer", "cap": "word",
                     "closed": "flag", "center": "numbers"}
    assert tube["cap"].choices == ("flat", "round") and tube["radius"].choices == ()
    assert tube["closed"].type_words == "bool" and tube["cap"].type_words == '"flat" or "round"'
    bounds = maker_params("implicit")["bounds"]
    assert bounds.problem([-1, 1, -1, 1, -1, 1]) is None and bounds.normal([-1, 1]) == [-1.0, 1.0]
    assert bounds.problem([0, float("inf")]) == "expected finite numbers, got inf at [1]"
    assert bounds.problem([0, 10**400]).startswith("expected finite numbers, got 1000")


def test_random_makers_come_from_the_table():
    assert random_makers() == tuple(n for n, row in MAKERS.items() if row.random)
    assert "implicit" not in random_makers()
    with pytest.raises(UnknownFormatError, match="no random parameters"):
        get_random_params("implicit")


@pytest.mark.parametrize("name", sorted(MAKERS))
def test_maker_interface(name):
    maker = get_maker(name)
    sig = inspect.signature(maker)
    hints = typing.get_type_hints(maker)
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in sig.parameters.values())
    assert "base_dir" in sig.parameters
    assert all(p in hints for p in sig.parameters)


def test_the_shipped_set_is_complete():
    names = {p.stem for p in SHIPPED}
    assert {"queen", "king", "rook", "bishop", "pawn", "spinning_top", "interlaced", "egg", "torus4d_slice", "vase"} <= names
    queen = tomllib.loads((RECIPES / "chess" / "queen.toml").read_text())["source"]
    assert queen["curve"].startswith("x^2 + y^2") and queen["generatrix"].endswith(".svg")


MADE = [p for p in SHIPPED if "maker" in tomllib.loads(p.read_text(encoding="utf-8"))["source"]]


@pytest.mark.parametrize("path", MADE, ids=[p.stem for p in MADE])
def test_shipped_recipe_makes_a_well_formed_solid(path):
    """Every shipped recipe whose source is a maker (the swordsman is drawn in a file)."""
    recipe = tomllib.loads(path.read_text(encoding="utf-8"))
    assert set(recipe["outputs"]) == OUTPUTS
    params = dict(recipe["source"])
    maker = get_maker(params.pop("maker"))
    for value in params.values():
        if isinstance(value, str) and Path(value).suffix in (".svg", ".png", ".json", ".csv"):
            assert (path.parent / value).is_file(), value
            assert (path.parent / value).stat().st_size < 20_000
    grid = maker(base_dir=path.parent, **params)
    side = params.get("size", 25)  # a body the operations complete (the king's cross) may take fewer voxels
    assert grid.dtype == bool and grid.shape == (side, side, side)
    assert params.get("mode", "solid") == "solid"
    # deterministic
    assert np.array_equal(grid, maker(base_dir=path.parent, **params))
    if recipe.get("operations"):
        # A union of makers (the knight): the shape is the source after its operations.
        from voxfab.recipe import load_recipe
        from voxfab.recipe._build import make_shape

        grid = make_shape(load_recipe(path)).grid
    assert well_formed_reasons(grid) == []


def test_makers_report_bad_parameters(tmp_path):
    with pytest.raises(InvalidShapeError, match="^generatrix"):
        get_maker("revolution")(base_dir=tmp_path, generatrix="missing.svg")
    with pytest.raises(InvalidShapeError, match="^spine"):
        get_maker("tube")(base_dir=tmp_path, spine=["t", "0"])
    with pytest.raises(InvalidShapeError, match="^radius"):
        get_maker("focal")(base_dir=tmp_path, foci=[[0, 0, 0], [3, 0, 0]], radius=1.0)
    with pytest.raises(InvalidShapeError, match="^expression"):
        get_maker("implicit")(base_dir=tmp_path, expression="x^2 + y^2 + z^2 + 1")
