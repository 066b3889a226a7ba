"""The artist's words for the library's messages: the page shows these, with the technical line as a tooltip.

The library and the CLI speak to programmers ("6-connected", "pass draft=True",
"--pieces auto"); the studio passes each message it shows through :func:`plain`
and keeps the original beside it (``"detail"``), so nothing is lost and the
words on screen name the page's own controls.
"""

from __future__ import annotations

import re
from typing import Any

#: (pattern, replacement) in order; each names what the artist sees on the page.
_PLAIN: tuple[tuple[re.Pattern[str], str], ...] = (
    (re.compile(r"\s*\(pass draft=True to store it as a draft\)"),
     " (tick \u201cas a draft if not well formed\u201d to keep it anyway)"),
    (re.compile(r"\b(\d+) 6-connected pieces, expected 1"),
     r"\1 separate pieces: a shape must be one piece, its voxels joined face to face"),
    (re.compile(r"\bnot 6-connected\b"), "not one piece (voxels joined face to face)"),
    (re.compile(r"\bextents \((\d+), (\d+), (\d+)\): none is (\d+), so the shape touches no two opposite sides"),
     "\\1\u00d7\\2\u00d7\\3 voxels: it must reach right across the \\4-voxel box in at least one direction"),
    (re.compile(r"\bextents \((\d+), (\d+), (\d+)\) do not fit in (\d+)x\d+x\d+"),
     "\\1\u00d7\\2\u00d7\\3 voxels: larger than the \\4\u00b3 box"),
    # CLI options in parentheses, e.g. "(--pieces auto)", "(--sheet)": the page's choice of that name
    (re.compile(r"\(--([a-z][a-z-]*)(?: ([^()\s]+))?\)"),
     lambda m: f"(choose {m.group(1).replace('-', ' ')}{': ' + m.group(2) if m.group(2) else ''})"),  # type: ignore[list-item]
    (re.compile(r"\bk-flake\b"), "wall"),
)


def plain(message: str) -> str:
    """``message`` in the artist's words (unchanged when it has no technical term)."""
    for pattern, replacement in _PLAIN:
        message = pattern.sub(replacement, message)
    return message


def explained(message: str) -> dict[str, Any]:
    """``{"text": plain words, "detail": the original}`` (no ``detail`` when they are the same)."""
    text = plain(message)
    return {"text": text} if text == message else {"text": text, "detail": message}
