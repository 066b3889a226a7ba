"""Seam labels: short codes of a fixed length over characters that cannot be taken for one another.

Every seam carries one label, printed on both of its edges, so the maker glues
the edge labelled ``3K7`` to the other edge labelled ``3K7``.  Decimal numbers
need four digits for the 1000-9999 seams of a 25-voxel shape, and the face
must be long enough for the whole label; a base-25 code needs three characters
for up to 15 625 seams and two for up to 625, so the same 2 mm labels fit on
faces a fifth smaller (8.6 mm instead of 10.9 mm).

The alphabet leaves out every character that a pen, a laser or a glance could
confuse with another one: O and Q (0), I (1), Z (2), S (5), B (8), G (6), V (U)
and those that read as another one turned half a turn: 9 (6), W (M) and T (1).  A
label always stands on its edge (its baseline runs along the cut line), so its
way up is never in doubt; with no character the turned twin of another, a
label seen upside down cannot pass for a valid one character by character.
"""

from __future__ import annotations

from collections.abc import Iterable

#: The characters of seam labels, in the order of their values.
LABEL_ALPHABET = "012345678ACDEFHJKLMNPRUXY"
_BASE = len(LABEL_ALPHABET)
_VALUE = {c: i for i, c in enumerate(LABEL_ALPHABET)}


def label_length(seams: int) -> int:
    """Characters of every label when seam numbers run up to ``seams`` (at least one)."""
    length, capacity = 1, _BASE
    while capacity < seams:
        length += 1
        capacity *= _BASE
    return length


def seam_label(number: int, length: int) -> str:
    """The label of seam ``number`` (1-based), ``length`` characters long."""
    value = int(number) - 1
    if value < 0 or value >= _BASE**length:
        raise ValueError(f"seam {number} has no {length}-character label")
    chars = []
    for _ in range(length):
        value, digit = divmod(value, _BASE)
        chars.append(LABEL_ALPHABET[digit])
    return "".join(reversed(chars))


def seam_labels(numbers: Iterable[int], length: int) -> list[str]:
    """Labels of many seams at once."""
    return [seam_label(n, length) for n in numbers]


def label_number(label: str) -> int:
    """The seam number (1-based) a label stands for; the inverse of :func:`seam_label`."""
    value = 0
    for c in label.upper():
        if c not in _VALUE:
            raise ValueError(f"{label!r} is not a seam label: {c!r} is not one of {LABEL_ALPHABET}")
        value = value * _BASE + _VALUE[c]
    return value + 1
