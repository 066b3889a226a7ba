"""Batch builds of repository shapes on Dask distributed, with an index of the results.

This package sits beside :mod:`voxfab.cli`: it uses the library (the repository,
recipes, pictures) and the library never imports it.  The client sends each
worker a small task (a shape's name, its packed bits and the outputs text); the
worker writes ``DIR/<name>/`` atomically, the same files as ``voxfab build`` of a
recipe with that shape and those outputs.  See :func:`run_batch`.
"""

from ._index import HuntSummary, hunt_summary, write_index
from ._run import BATCH_FORMAT, BatchReport, load_outputs, parse_name_range, run_batch, select_names
from ._task import BatchTask, Outcome, build_task, recipe_text

__all__ = [
    "BATCH_FORMAT",
    "BatchReport",
    "BatchTask",
    "HuntSummary",
    "Outcome",
    "build_task",
    "hunt_summary",
    "load_outputs",
    "parse_name_range",
    "recipe_text",
    "run_batch",
    "select_names",
    "write_index",
]
