"""What a fabrication pipeline hands back: the files it wrote, its warnings and its figures."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any


@dataclasses.dataclass(frozen=True)
class OutputFile:
    """A file written by a pipeline, relative to the folder it was asked to write into."""

    path: str
    purpose: str


@dataclasses.dataclass(frozen=True, eq=False)
class Artefact:
    """The outcome of one artefact pipeline (print, net, plates, pictures).

    Attributes
    ----------
    files : tuple of OutputFile
        Every file written, relative to the output folder.
    warnings : tuple of str
        What a maker must know before building the object, one line each
        (plates without dowels, a print in several parts, ...).
    report : mapping
        The pipeline's figures as plain JSON values.
    gives : mapping
        What the pipeline made for the outputs built after it, by the names its
        row of the table declares (:attr:`voxfab.fabricate.Output.gives`): the net
        pipeline gives ``"net"``, the pieces of the net it wrote.
    """

    files: tuple[OutputFile, ...]
    warnings: tuple[str, ...] = ()
    report: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    gives: Mapping[str, Any] = dataclasses.field(default_factory=dict)
