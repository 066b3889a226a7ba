"""Fabrication outputs (print meshes, paper nets, slice plates, pictures), found by name.

Each output is a function ``recipe_output(shape, outdir, *, name, seed, **options)``
returning the files it wrote as :class:`OutputFile` records.  Its keyword-only
parameters, with their type hints, are the recipe keys it accepts.
"""

from ._registry import OUTPUTS, OutputFile, available_outputs, get_output

__all__ = ["OUTPUTS", "OutputFile", "available_outputs", "get_output"]
