"""The hunt of one shape: a one-piece net by the random engine, else by the exact strategy, and a zipper net.

This is the per-shape step of a hunt over the Library (``[outputs.hunt]`` in a
batch): the random engine (ruin-and-recreate growth, no box) usually finds a
net in milliseconds; a shape it fails on goes to the exact strategy, which
finds a net or proves that none exists; then the exact zipper search
(:mod:`._zipper`) looks for a net whose cut edges form one path.  Each search
has its own time limit, and a limit that runs out is recorded as
``undecided``, never as an answer.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy.typing as npt

from voxfab.errors import InvalidShapeError, NoNetExistsError, UnfoldError

from ._net import Net

__all__ = ["HUNT_NET", "HUNT_ZIPPER", "HuntOutcome", "hunt_shape"]

#: What a hunt found about a one-piece net: by the random engine, only by the exact strategy,
#: proved to be none, or not decided within the time limits.
HUNT_NET = ("random", "exact", "none", "undecided")
#: What it found about a zipper net; ``skipped`` when it was not looked for.
HUNT_ZIPPER = ("found", "none", "undecided", "skipped")


@dataclasses.dataclass(frozen=True, eq=False)
class HuntOutcome:
    """What the hunt of one shape found.

    Attributes
    ----------
    faces : int
        Faces of the unfolded surface (the outer one: cavities are filled).
    net : str
        One of :data:`HUNT_NET`.
    zipper : str
        One of :data:`HUNT_ZIPPER`.
    one_piece, zipper_net : Net or None
        The nets found (``net`` in ``random`` or ``exact``; ``zipper`` is ``found``).
    why : tuple of str
        The searches' own words for ``none`` and ``undecided`` outcomes.
    seconds : (float, float, float)
        Time spent by the random engine, the exact one-piece search and the zipper search.
    """

    faces: int
    net: str
    zipper: str
    one_piece: Net | None
    zipper_net: Net | None
    why: tuple[str, ...]
    seconds: tuple[float, float, float]

    def to_dict(self) -> dict[str, object]:
        """The outcome as plain JSON values, without the nets and the times (which vary run to run)."""
        data: dict[str, object] = {"faces": self.faces, "net": self.net, "zipper": self.zipper}
        for key, net in (("net_box", self.one_piece), ("zipper_box", self.zipper_net)):
            if net is not None:
                x0, y0, x1, y1 = net.bounds()
                data[key] = sorted((x1 - x0, y1 - y0))
        if self.why:
            data["why"] = list(self.why)
        return data


def _check_limit(value: object, name: str) -> float:
    try:
        seconds = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InvalidShapeError(f"{name}: expected a number of seconds, got {str(value)[:40]!r}") from None
    if not seconds > 0 or seconds == float("inf"):
        raise InvalidShapeError(f"{name}: expected a positive number of seconds, got {str(value)[:40]}")
    return seconds


def hunt_shape(grid: npt.ArrayLike, *, seed: int = 0, timeout: float = 10.0, exact_timeout: float = 10.0,
               zipper_timeout: float = 2.0, zipper: bool = True) -> HuntOutcome:
    """Hunt one shape: a one-piece net (random engine, then exact), and a zipper net.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        A 6-connected shape; enclosed cavities are filled (only the outer surface unfolds).
    seed : int
        The random engine's seed (the exact searches take none).
    timeout : float
        Seconds for the random engine.
    exact_timeout : float
        Seconds for the exact one-piece search, run only when the random engine failed.
    zipper_timeout : float
        Seconds for the exact zipper search.
    zipper : bool
        Look for a zipper net at all.

    Returns
    -------
    HuntOutcome

    Raises
    ------
    InvalidShapeError
        A bad grid or time limit, or a shape of several components.
    """
    from voxfab._shared.validate import as_grid
    from voxfab.shape import component_count, fill_cavities, surface_graph

    from ._search import unfold

    limits = [_check_limit(v, n) for v, n in ((timeout, "timeout"), (exact_timeout, "exact_timeout"),
                                               (zipper_timeout, "zipper_timeout"))]

    g = fill_cavities(as_grid(grid))
    if component_count(g) != 1:
        raise InvalidShapeError(f"the shape has {component_count(g)} separate components: a hunt unfolds one piece")
    faces = surface_graph(g).face_count
    why: list[str] = []
    seconds = [0.0, 0.0, 0.0]

    t = time.perf_counter()
    one_piece: Net | None = None
    try:
        one_piece = unfold(g, rng=seed, timeout=limits[0], tab_aware=False)  # type: ignore[assignment]
        found = "random"
    except UnfoldError:
        found = ""
    seconds[0] = time.perf_counter() - t
    if not found:
        found, one_piece, seconds[1] = _exact(lambda: unfold(g, rng=0, strategy="exact", timeout=limits[1]),
                                                "exact", why)
    zipped, zipper_net = "skipped", None
    if zipper:
        zipped, zipper_net, seconds[2] = _exact(lambda: unfold(g, rng=0, strategy="exact", zipper=True,
                                                              timeout=limits[2]), "found", why)
    return HuntOutcome(faces, found, zipped, one_piece, zipper_net, tuple(why), tuple(seconds))  # type: ignore[arg-type]


def _exact(search: Callable[[], Net], found: str, why: list[str]) -> tuple[str, Net | None, float]:
    """Run one exact search: ``found`` with its net, ``"none"`` (proved) or ``"undecided"``, and its seconds;
    the reason of a "none" or "undecided" goes into ``why``."""
    from ._exact import Undecided

    t = time.perf_counter()
    try:
        return found, search(), time.perf_counter() - t
    except NoNetExistsError as exc:
        outcome = "none"
        why.append(" ".join(str(exc).split()))
    except Undecided as exc:
        outcome = "undecided"
        why.append(" ".join(str(exc).split()))
    return outcome, None, time.perf_counter() - t
