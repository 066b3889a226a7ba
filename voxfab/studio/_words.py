"""The artist's words for the library's messages: the page shows these, with the technical line as a tooltip.

The library and the CLI speak to programmers ("6-connected", "pass draft=True",
"--pieces auto"); the studio passes each message it shows through :func:`plain`
and keeps the original beside it (``"detail"``), so nothing is lost and the
words on screen name the page's own controls.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any


def _choose(name: str, value: str) -> str:
    """``(choose fill: on)`` for the option ``fill=True``: the page's control and its setting, in its words."""
    words = PAGE_CHOICES.get((name, value), ON_OFF.get(value, value))
    return f"(choose {name.replace('_', ' ')}: {words})"


ON_OFF = {"True": "on", "False": "off"}

#: The page's own words for option values its menus show otherwise ("pieces: auto" is a CLI setting).
PAGE_CHOICES = {("pieces", "auto"): "split into pieces if needed", ("pieces", "one"): "one piece"}

#: (pattern, replacement) in order; each names what the artist sees on the page.
_PLAIN: tuple[tuple[re.Pattern[str], str | Callable[[re.Match[str]], str]], ...] = (
    (re.compile(r"\s*\(pass draft=True to store it as a draft\)"),
     " (tick \u201cas a draft if not well formed\u201d to keep it anyway)"),
    (re.compile(r"\b(\d+) 6-connected pieces, expected 1"),
     r"\1 separate pieces: a shape must be one piece, its voxels joined face to face"),
    (re.compile(r"\bnot 6-connected\b"), "not one piece (voxels joined face to face)"),
    (re.compile(r"\bextents \((\d+), (\d+), (\d+)\): none is (\d+), so the shape touches no two opposite sides"),
     "\\1\u00d7\\2\u00d7\\3 voxels: it must reach right across the \\4-voxel box in at least one direction"),
    (re.compile(r"\bextents \((\d+), (\d+), (\d+)\) do not fit in (\d+)x\d+x\d+"),
     "\\1\u00d7\\2\u00d7\\3 voxels: larger than the \\4\u00b3 box"),
    # the library's "Python name and CLI option" notes: "(pieces='auto', CLI --pieces auto)", "(CLI --fill)"
    (re.compile(r"\(([a-z_]+)=(?:'([^']*)'|(\w+)), CLI --[a-z-]+(?: [^()\s]+)?\)"),
     lambda m: _choose(m.group(1), m.group(2) or m.group(3))),
    (re.compile(r"\s*\(CLI --[a-z-]+(?: [^()\s]+)?\)"), ""),
    (re.compile(r"\bpieces='auto'"), "pieces: split into pieces if needed"),
    # CLI options in parentheses, e.g. "(--pieces auto)", "(--sheet)": the page's choice of that name
    (re.compile(r"\(--([a-z][a-z-]*)(?: ([^()\s]+))?\)"),
     lambda m: _choose(m.group(1).replace("-", "_"), m.group(2)) if m.group(2) else f"(choose {m.group(1).replace('-', ' ')})"),
    (re.compile(r"\bk-flake\b"), "wall"),
    # a refused edit in the pieces' numbers, its technical line (the edge's faces) kept for the tooltip
    (re.compile(r" \(no room to join edge \[[^()]*\)$"), ""),
    # the marks' names on the page: the checkbox says "seam labels"
    (re.compile(r"\bedge labels\b"), "seam labels"),
    # "exact search": the search that tries every net in a box until one fits or none can
    (re.compile(r"\b(?:the )?exact search\b"), "the complete search"),
    # a failure of the server itself: its exception's name and text stay in the tooltip
    (re.compile(r"^internal error \([A-Za-z_.]+\)(?::.*)?$"),
     "the server could not finish this (the technical line is in the tooltip)"),
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
