"""Polylines: many 2D polylines in one ragged array, the geometry of every drawing.

Lengths are millimetres.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

#: Decimals of the coarsest writer (SVG): vertices printed alike at this rounding are one vertex.
WRITTEN_DECIMALS = 3


@dataclasses.dataclass(frozen=True, eq=False)
class Polylines:
    """Many polylines in one ragged array.

    Attributes
    ----------
    points : (P, 2) float ndarray
        All vertices, mm.
    offsets : (S + 1,) int ndarray
        Polyline ``i`` is ``points[offsets[i]:offsets[i + 1]]``.
    closed : (S,) bool ndarray
        Whether polyline ``i`` returns to its first point.
    """

    points: npt.NDArray[np.float64]
    offsets: npt.NDArray[np.int64]
    closed: npt.NDArray[np.bool_]

    @classmethod
    def empty(cls) -> Polylines:
        """No polyline."""
        return cls(np.zeros((0, 2)), np.zeros(1, dtype=np.int64), np.zeros(0, dtype=bool))

    @classmethod
    def from_segments(cls, a: npt.ArrayLike, b: npt.ArrayLike) -> Polylines:
        """Open two-point polylines from ``(N, 2)`` start and end points."""
        a = np.asarray(a, dtype=np.float64).reshape(-1, 2)
        b = np.asarray(b, dtype=np.float64).reshape(-1, 2)
        n = a.shape[0]
        pts = np.stack([a, b], axis=1).reshape(-1, 2)
        return cls(pts, np.arange(0, 2 * n + 1, 2, dtype=np.int64), np.zeros(n, dtype=bool))

    @classmethod
    def from_list(cls, lines: list[npt.NDArray[np.float64]], closed: list[bool]) -> Polylines:
        """Polylines from a list of ``(n_i, 2)`` arrays."""
        if not lines:
            return cls.empty()
        lengths = np.array([len(x) for x in lines], dtype=np.int64)
        return cls(
            np.concatenate(lines).astype(np.float64),
            np.concatenate([[0], np.cumsum(lengths)]),
            np.array(closed, dtype=bool),
        )

    @classmethod
    def concat(cls, parts: list[Polylines]) -> Polylines:
        """All polylines of ``parts``, in order."""
        parts = [p for p in parts if len(p)]
        if not parts:
            return cls.empty()
        pts = np.concatenate([p.points for p in parts])
        shift = np.cumsum([0] + [p.points.shape[0] for p in parts[:-1]])
        offs = np.concatenate([[0]] + [p.offsets[1:] + s for p, s in zip(parts, shift)])
        return cls(pts, offs, np.concatenate([p.closed for p in parts]))

    def select(self, keep: npt.ArrayLike) -> Polylines:
        """The polylines where ``keep`` (S,) bool is True, in order."""
        keep = np.asarray(keep, dtype=bool)
        counts = np.diff(self.offsets)
        return Polylines(self.points[np.repeat(keep, counts)], np.concatenate([[0], np.cumsum(counts[keep])]),
                         self.closed[keep])

    def __len__(self) -> int:
        return int(self.closed.shape[0])

    def lines(self) -> list[npt.NDArray[np.float64]]:
        """Each polyline as an ``(n, 2)`` array."""
        return [self.points[a:b] for a, b in zip(self.offsets[:-1], self.offsets[1:])]

    def segments(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """Every straight piece as ``(N, 2)`` start and end arrays (closing pieces included)."""
        if not len(self):
            return np.zeros((0, 2)), np.zeros((0, 2))
        p = self.points
        nxt = np.arange(1, p.shape[0] + 1)
        last = self.offsets[1:] - 1
        keep = np.ones(p.shape[0], dtype=bool)
        keep[last] = False
        nxt[last] = self.offsets[:-1]
        keep[last[self.closed]] = True
        return p[keep], p[nxt[keep]]

    def length(self) -> float:
        """Total length, mm."""
        a, b = self.segments()
        return float(np.linalg.norm(b - a, axis=1).sum())

    def without_repeats(self, decimals: int = WRITTEN_DECIMALS) -> Polylines:
        """The same polylines without the zero-length segments a writer would print (cutters stall on them).

        A vertex equal to the one before it at ``decimals`` is dropped, and so is the last
        vertex of a closed polyline equal to its first; a polyline left with one vertex
        (a point) is dropped.
        """
        if not len(self):
            return self
        if not self.points.shape[0]:
            return Polylines.empty()
        q = np.round(self.points, decimals)
        counts = np.diff(self.offsets)
        owner = np.repeat(np.arange(len(self)), counts)
        keep = np.ones(q.shape[0], dtype=bool)
        keep[1:] = ~(np.all(q[1:] == q[:-1], axis=1) & (owner[1:] == owner[:-1]))
        # a closed polyline's last kept vertex is the first of its run: compare it with the first vertex
        kept_idx = np.flatnonzero(keep)
        last = kept_idx[np.searchsorted(kept_idx, self.offsets[1:], side="left") - 1]
        first = self.offsets[:-1]
        wrap = self.closed & (counts > 1) & (last != first)
        wrap[wrap] = np.all(q[last[wrap]] == q[first[wrap]], axis=1)
        keep[last[wrap]] = False
        kept = np.bincount(owner[keep], minlength=len(self))
        if keep.all() and np.all(kept >= 2):
            return self
        keep &= (kept >= 2)[owner]
        lines = kept[kept >= 2]
        return Polylines(self.points[keep], np.concatenate([[0], np.cumsum(lines)]).astype(np.int64),
                         self.closed[kept >= 2])

    def translated(self, shift: npt.ArrayLike) -> Polylines:
        """The same polylines moved by ``shift`` (2,)."""
        return Polylines(self.points + np.asarray(shift, dtype=np.float64), self.offsets, self.closed)
