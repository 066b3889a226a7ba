"""Net drawings to files through the drawing backends, chosen by file extension."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from voxfab.drawing import FORMATS, Cutter, Legend, Lines, WriteOptions, write_drawing

from ._drawing import NetDrawing
from ._options import DrawingOptions


def drawing_formats() -> list[str]:
    """Extensions a net drawing can be written to."""
    return sorted(FORMATS)


def write(drawing: NetDrawing, path: Path, options: DrawingOptions) -> list[str]:
    """Write ``drawing`` in the format named by the extension of ``path``.

    SVG and DXF pages are laser files (hairlines; SVG with visible lines when
    ``options.svg_lines`` is ``preview``); PDF and PNG are for people, with
    visible lines, shaded tabs and a legend.  A coloured net's faces are
    filled in SVG, PDF and PNG.  With a ``cutter``, SVG, PDF and PNG are the
    print (registration marks, no cut lines) and ``NAME.cut.svg`` the cut
    (beside a PDF or PNG print too: a print without its cut file cannot be cut).
    """
    ext = path.suffix.lower()
    styles = options.styles
    if ext in (".pdf", ".png") and drawing.coloured:
        # The folds print in black or white over the colours: the legend shows them black.
        styles = {k: dataclasses.replace(v, color="#000000") if k in ("MOUNTAIN", "VALLEY") else v
                  for k, v in styles.items()}
    opts = WriteOptions(styles=styles, lines=Lines(options.svg_lines), dxf_version=options.dxf_version,
                        legend=Legend(y=options.edge + 1.0), creator="voxfab net")
    # A printed net of several pieces opens with its assembly page; laser files hold sheets only.
    assembly = ext == ".pdf"
    if Cutter(options.cutter) is Cutter.NONE or ext == ".dxf":
        return write_drawing(drawing.document(assembly=assembly), path, opts)
    # Print then cut: the print without the cut lines, and the cut lines alone in an SVG of their own
    # (the file the cutter's program imports), both with the cutter's registration marks at the same place.
    written = write_drawing(drawing.document(assembly=assembly, part="print"), path, opts)
    return written + write_drawing(drawing.document(part="cut"), cut_path(path), opts)


def cut_path(path: Path) -> Path:
    """The cut file beside a print file: ``NAME.cut.svg`` for ``NAME.svg``, ``NAME.pdf`` or ``NAME.png``."""
    return path.with_name(f"{path.stem}.cut.svg")
