"""Drawing writers found by file extension; multi-sheet drawings get numbered files."""

from __future__ import annotations

import importlib
from pathlib import Path

from voxfab.errors import UnknownFormatError

from ._drawing import Drawing
from ._options import DrawingOptions

#: Extension → ``"module:function"`` of the writer.  Each writer takes
#: ``(drawing, paths, options)`` and returns the paths it wrote.
WRITERS: dict[str, str] = {
    ".svg": "voxfab.fabricate.netdraw._writers:_svg",
    ".dxf": "voxfab.fabricate.netdraw._writers:_dxf",
    ".pdf": "voxfab.fabricate.netdraw._writers:_pdf",
}


def drawing_formats() -> list[str]:
    """Extensions a drawing can be written to."""
    return sorted(WRITERS)


def sheet_paths(path: Path, count: int) -> list[Path]:
    """``path`` itself for one sheet, else ``name-1.ext``, ``name-2.ext``, ..."""
    if count == 1:
        return [path]
    return [path.with_name(f"{path.stem}-{i + 1}{path.suffix}") for i in range(count)]


def _svg(drawing: Drawing, path: Path, options: DrawingOptions) -> list[str]:
    from .svg import write_svg

    return write_svg(drawing, sheet_paths(path, len(drawing.sheets)), options.styles, title=drawing.title)


def _dxf(drawing: Drawing, path: Path, options: DrawingOptions) -> list[str]:
    from .dxf import write_dxf

    return write_dxf(drawing, sheet_paths(path, len(drawing.sheets)), options.styles,
                     version=options.dxf_version)


def _pdf(drawing: Drawing, path: Path, options: DrawingOptions) -> list[str]:
    from .pdf import write_pdf

    # One PDF holds every sheet as a page, ready to print in one go.
    return write_pdf(drawing, path, options.styles, title=drawing.title)


def write(drawing: Drawing, path: Path, options: DrawingOptions) -> list[str]:
    """Write ``drawing`` in the format named by the extension of ``path``."""
    ext = path.suffix.lower()
    if ext not in WRITERS:
        raise UnknownFormatError(
            f"{path}: unknown drawing format {ext or '(none)'!r}; expected one of {', '.join(drawing_formats())}"
        )
    module, func = WRITERS[ext].split(":")
    return getattr(importlib.import_module(module), func)(drawing, path, options)
