"""Fabrication outputs: print meshes (:mod:`.mesh`), paper nets (:mod:`.netdraw`), slice plates (:mod:`.plates`).

Each artefact has one options dataclass and one pipeline function that the CLI,
recipes, the studio and batch runs all call; a pipeline returns an
:class:`Artefact` (the files written, the warnings a maker must read, figures).
:func:`outputs` is the one table of them (:mod:`._table`).
"""

from ._outputs import Artefact, OutputFile
from ._table import BuildContext, OptionTable, Output, build_order, output_for_download, outputs

__all__ = ["Artefact", "OutputFile", "BuildContext", "Output", "OptionTable", "build_order", "output_for_download",
           "outputs"]
