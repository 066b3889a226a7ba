"""Sheet sizes by name: the papers, cutting mats and laser beds that nets and plates are laid out on."""

from __future__ import annotations

import re

from voxfab.errors import InvalidShapeError

#: Paper sizes in mm (portrait), smallest first: a net that does not fit is told the smallest that does.
SHEETS: dict[str, tuple[float, float]] = {
    "A5": (148.0, 210.0),
    "A4": (210.0, 297.0),
    "Letter": (215.9, 279.4),
    "Legal": (215.9, 355.6),
    "A3": (297.0, 420.0),
    "Tabloid": (279.4, 431.8),
    "A2": (420.0, 594.0),
    "A1": (594.0, 841.0),
    "A0": (841.0, 1189.0),
    # Desktop cutters' 12 x 12 inch mat and a small laser cutter's bed.
    "mat12": (305.0, 305.0),
    "laser": (495.0, 279.0),
}

#: Largest sheet side accepted, mm (the largest laser beds and cutting services stay under 3 m).
MAX_SHEET = 5000.0


def parse_sheet(spec: str) -> tuple[float, float]:
    """Sheet size in mm from a name of :data:`SHEETS` (``A4``, ``A3``, ``Letter``, ...) or ``WxH`` (mm)."""
    for name, size in SHEETS.items():
        if spec.lower() == name.lower():
            return size
    m = re.fullmatch(r"\s*([0-9]*\.?[0-9]+)\s*[xX×]\s*([0-9]*\.?[0-9]+)\s*(mm)?\s*", spec)
    if not m:
        raise InvalidShapeError(f"sheet: expected {', '.join(SHEETS)} or WxH in mm, got {spec!r}")
    w, h = float(m.group(1)), float(m.group(2))
    if w <= 0 or h <= 0:
        raise InvalidShapeError(f"sheet: sides must be positive, got {spec!r}")
    if max(w, h) > MAX_SHEET:
        raise InvalidShapeError(f"sheet: expected sides of at most {MAX_SHEET:g} mm, got {spec[:80]!r}")
    return w, h


def sheet_problem(value: str) -> str | None:
    """Why ``value`` is not a usable sheet (the option checks' message), or None."""
    try:
        parse_sheet(value)
    except InvalidShapeError:
        return f"expected {', '.join(SHEETS)} or WxH in mm with sides of at most {MAX_SHEET:g} mm"
    return None
