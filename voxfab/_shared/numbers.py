"""Numbers read from text (command lines, query strings, file headers): ASCII digits only, one way everywhere.

``int()`` and ``float()`` take any script's digits (``'３'``, ``'٣'``), and
``str.isdigit`` is true of some that ``int`` then refuses (``'²'``, ``'①'``):
checking with one and converting with the other turns a typo into a crash.
Every number voxfab reads from text goes through :func:`parse_int` or
:func:`parse_float`, which take what a keyboard in any locale types for a
number: ASCII digits, a sign, a point and an exponent.
"""

from __future__ import annotations

import re

__all__ = ["is_digits", "parse_int", "parse_float"]

_DIGITS = re.compile(r"[0-9]+")
_INT = re.compile(r"[+-]?[0-9]+")
_FLOAT = re.compile(r"[+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|nan|inf|infinity)", re.IGNORECASE)


def is_digits(text: str) -> bool:
    """Whether ``text`` is one or more ASCII digits, nothing else (no sign, no space)."""
    return _DIGITS.fullmatch(text) is not None


def parse_int(text: str, *, max_digits: int | None = None) -> int:
    """``text`` as an integer: an optional sign and ASCII digits, at most ``max_digits`` of them.

    Raises
    ------
    ValueError
        For anything else (as :func:`int` would, so callers catch one error).
    """
    if not isinstance(text, str) or _INT.fullmatch(text) is None:
        raise ValueError(f"not a whole number in ASCII digits: {text!r:.80}")
    if max_digits is not None and len(text.lstrip("+-")) > max_digits:
        raise ValueError(f"a whole number of more than {max_digits} digits")
    return int(text)


def parse_float(text: str) -> float:
    """``text`` as a float: ASCII digits with an optional sign, point and exponent; ``nan`` and ``inf`` pass.

    Raises
    ------
    ValueError
        For anything else (as :func:`float` would).
    """
    if not isinstance(text, str) or _FLOAT.fullmatch(text) is None:
        raise ValueError(f"not a number in ASCII digits: {text!r:.80}")
    return float(text)
