"""Ways out for the sections a slotted construction leaves out: other options, each one run, offered when it keeps them.

A section is left out when it crosses no plate of the construction (the bunny's ears
between two interlocked plates).  Plates closer together (a finer pitch: more plates
per family, or more radial plates) cross more of the shape, and thinner plates have
larger exact sections and narrower slots.  Each way is checked by making the
construction with it: only the ways that leave no section out are offered.
"""

from __future__ import annotations

import dataclasses
import math

import numpy.typing as npt

from voxfab.errors import VoxfabError

from ._options import PlateOptions

#: Fractions of the thickness tried for thinner plates, thickest first (a plate no thicker than a
#: voxel has the same section at any thickness: one more step would only cost time).
_THINNER = (2 / 3,)
#: Factors of the plate count tried for a finer pitch, fewest plates first.
_DENSER = (1.5, 2.0)


@dataclasses.dataclass(frozen=True)
class Way:
    """Options that keep every section, checked by making the construction with them.

    Attributes
    ----------
    words : str
        What changes, as the options of ``voxfab slices``.
    plates : int
        Plates of the construction made with them (none left out).
    """

    words: str
    plates: int

    def __str__(self) -> str:
        return f"{self.words} (checked: {self.plates} plates, none left out)"


def _thinner(thickness: float) -> list[float]:
    """Thinner plates to try, rounded down to 0.1 mm."""
    out: list[float] = []
    for f in _THINNER:
        t = math.floor(thickness * f * 10 + 1e-9) / 10
        if 0.1 <= t < thickness and t not in out:
            out.append(t)
    return out


def _finer(options: PlateOptions) -> list[tuple[str, dict]]:
    """Closer plates to try: the words and the options changed."""
    out: list[tuple[str, dict]] = []
    if options.style == "radial":
        for f in _DENSER:
            n = min(36, math.ceil(options.radial_plates * f))
            if n > options.radial_plates and all(c["radial_plates"] != n for _, c in out):
                out.append((f"--radial-plates {n}", {"radial_plates": n}))
    elif options.count > 0:
        for f in _DENSER:
            n = min(64, math.ceil(options.count * f))
            if n > options.count and all(c["count"] != n for _, c in out):
                out.append((f"--count {n}", {"count": n}))
    else:
        for f in _DENSER:
            v = max(1.0, math.floor(options.interval / f * 10) / 10)
            if v < options.interval and all(c["interval"] != v for _, c in out):
                out.append((f"--interval {v:g}", {"interval": v}))
    return out


def ways_to_keep(grid: npt.ArrayLike, pitch: float, options: PlateOptions) -> tuple[tuple[Way, ...], tuple[str, ...]]:
    """The ways out that keep every section of a slotted construction, each checked by making it; and all tried.

    A finer pitch alone (the fewest plates that keeps them), thinner plates alone, and when
    neither does, both.
    """
    from . import make_construction

    tried: list[str] = []

    def made(words: str, changes: dict) -> int | None:
        """Plates of the construction with ``changes``, or None when it leaves a section out (or fails)."""
        tried.append(words)
        o = dataclasses.replace(options, **changes)
        try:
            c = make_construction(grid, pitch=pitch, style=o.style, thickness=o.thickness, axes=o.axes,
                                  count=o.count, interval=o.interval, radial_plates=o.radial_plates,
                                  clearance=o.clearance, min_width=o.min_width, kerf=o.kerf)
        except VoxfabError:
            return None
        return None if c.left_out else len(c.plates)

    ways = []
    finer = _finer(options)
    thinner = [(f"--thickness {t:g}", {"thickness": t}) for t in _thinner(options.thickness)]
    for kind, candidates in (("a finer pitch", finer), ("thinner plates", thinner)):
        for words, changes in candidates:
            if (n := made(words, changes)) is not None:
                ways.append(Way(f"{kind} ({words})", n))
                break
    if not ways and thinner:
        for words, changes in finer:
            both = f"{words} {thinner[0][0]}"
            if (n := made(both, {**changes, **thinner[0][1]})) is not None:
                ways.append(Way(f"a finer pitch and thinner plates ({both})", n))
                break
    return tuple(ways), tuple(tried)
