"""Net drawings to files through the drawing backends, chosen by file extension."""

from __future__ import annotations

from pathlib import Path

from voxfab.drawing import FORMATS, Legend, Lines, WriteOptions, write_drawing

from ._drawing import NetDrawing
from ._options import DrawingOptions


def drawing_formats() -> list[str]:
    """Extensions a net drawing can be written to."""
    return sorted(FORMATS)


def write(drawing: NetDrawing, path: Path, options: DrawingOptions) -> list[str]:
    """Write ``drawing`` in the format named by the extension of ``path``.

    SVG and DXF pages are laser files (hairlines; SVG with visible lines when
    ``options.svg_lines`` is ``preview``); PDF and PNG are for people, with
    visible lines, shaded tabs and a legend.
    """
    opts = WriteOptions(styles=options.styles, lines=Lines(options.svg_lines), dxf_version=options.dxf_version,
                        legend=Legend(y=float(options.margin) + 1.0), creator="voxfab net")
    # A printed net of several pieces opens with its assembly page; laser files hold sheets only.
    assembly = path.suffix.lower() == ".pdf"
    return write_drawing(drawing.document(assembly=assembly), path, opts)
