"""Fuzz recipes: random TOML trees over the real schema keys, checked and built."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from _fuzz import check_outcome, hostile_recipe_folder, recipe_trees, run_cli, toml_text
from hypothesis import given, settings
from hypothesis import strategies as st


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    root = tmp_path_factory.mktemp("recipes")
    hostile_recipe_folder(root / "r")
    return root / "r"


def test_random_recipes_are_checked_cleanly(folder):
    @settings(max_examples=120, database=None, derandomize=True)
    @given(tree=recipe_trees())
    def fuzz(tree):
        path = folder / "fuzz.toml"
        path.write_text(toml_text(tree))
        o = check_outcome(run_cli(["build", path, "--check"]))
        if o.code == 0:
            assert o.out.startswith(f"{path}: ok")

    fuzz()


def test_random_recipes_build_or_fail_cleanly(folder):
    out = folder.parent / "out"
    built = []

    @settings(max_examples=25, database=None, derandomize=True)
    @given(tree=recipe_trees(with_outputs=False, strict=True))
    def fuzz(tree):
        tree["name"] = "fuzz"
        path = folder / "fuzz.toml"
        path.write_text(toml_text(tree))
        o = check_outcome(run_cli(["build", path, "-o", out]))
        if o.code == 0:
            built.append(tree)
            manifest = json.loads((out / "fuzz" / "manifest.json").read_text())
            assert all((out / "fuzz" / f["path"]).is_file() for f in manifest["files"])
        # Nothing half-made is ever left beside the outputs.
        assert not [p for p in out.glob(".*")] if out.exists() else True

    fuzz()
    assert built  # some random recipes reach the end of a build, not only its refusals


def test_random_text_as_a_recipe(folder):
    @settings(max_examples=60, database=None, derandomize=True)
    @given(text=st.one_of(st.text(max_size=200), st.binary(max_size=200).map(lambda b: b.decode("latin-1"))))
    def fuzz(text):
        path = folder / "text.toml"
        path.write_bytes(text.encode("utf-8", "surrogatepass"))
        check_outcome(run_cli(["build", path, "--check"]))

    fuzz()


def test_trees_cover_the_schema():
    """The strategy reaches makers, file sources, operations and outputs (it is not vacuous)."""
    seen: set[str] = set()

    @settings(max_examples=150, database=None, derandomize=True)
    @given(tree=recipe_trees())
    def collect(tree):
        source = tree.get("source", {})
        seen.update(k for k in ("maker", "file") if k in source)
        seen.update(k for k in ("operations", "outputs") if tree.get(k))

    collect()
    assert seen == {"maker", "file", "operations", "outputs"}
    assert Path(__file__).exists()
