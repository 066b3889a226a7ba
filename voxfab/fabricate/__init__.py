"""Fabrication outputs: print meshes (:mod:`.mesh`), paper nets (:mod:`.netdraw`), slice plates (:mod:`.plates`).

Each artefact has one options dataclass and one pipeline function that the CLI,
recipes, the studio and batch runs all call; a pipeline returns an
:class:`Artefact` (the files written, the warnings a maker must read, figures).
"""

from ._outputs import Artefact, OutputFile

__all__ = ["Artefact", "OutputFile"]
