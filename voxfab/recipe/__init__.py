"""TOML recipes: a shape source, operations and the outputs to make.

See the README's "Recipe format" section for the keys.
"""

from ._build import (
    MANIFEST_FORMAT,
    SHAPE_FILES,
    BuiltRecipe,
    apply_operation,
    build,
    build_recipe,
    built_shape_name,
    make_shape,
    make_source,
)
from ._schema import OperationSpec, OutputSpec, Recipe, SourceSpec, load_recipe

__all__ = [
    "MANIFEST_FORMAT",
    "SHAPE_FILES",
    "BuiltRecipe",
    "OperationSpec",
    "OutputSpec",
    "Recipe",
    "SourceSpec",
    "apply_operation",
    "build",
    "build_recipe",
    "built_shape_name",
    "load_recipe",
    "make_shape",
    "make_source",
]
