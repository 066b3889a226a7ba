"""Compile the numba kernels ahead of the first build, each group in its own process.

numba compiles a kernel on its first call and caches the machine code beside the
source (``cache=True``), so the first ``voxfab build`` after an install would
spend most of its time compiling (about 35 s of CPU for a chess piece, against
4 s for the build itself).  :func:`warm_up` runs each group of kernels once on a
small fixed shape through the very pipeline functions a build calls, so the
cached signatures are the ones the build needs.

numba compiles under one global lock and mostly in Python, so threads cannot
compile two kernels at once; the groups are independent, so separate processes
compile them side by side, one per core.  A build that finds the net kernels
not yet compiled does the same on its own (:func:`compile_aside`): a second
process compiles them while the build makes the shape and the print.
"""

from __future__ import annotations

import dataclasses
import os
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from voxfab.errors import InvalidShapeError

__all__ = ["GROUPS", "Aside", "GroupTime", "compile_aside", "is_compiled", "warm_group", "warm_up"]


def _shape_makers(folder: Path) -> None:
    import numpy as np

    from voxfab.digitize import revolution, tube
    from voxfab.generate import growth
    from voxfab.shape import GRID_SIDE

    del folder
    # A drawn generatrix (point-in-polygon), a swept tube (frame transport) and the growth generator.
    revolution("x^2 + y^2 - 1", np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [0.0, 2.0]]), size=9)
    tube(["cos(2*pi*t)", "sin(2*pi*t)", "0"], radius=0.3, size=9)
    growth(0, 2 * GRID_SIDE)


def _groups() -> tuple[dict[str, Callable[[Path], None]], dict[str, tuple[tuple[str, str], ...]]]:
    from voxfab.fabricate import outputs

    runs = {o.warm_group: o.warm for o in outputs().values() if o.warm_group and o.warm}
    kernels = {o.warm_group: o.kernels for o in outputs().values() if o.warm_group}
    # The shape makers are no output but compile kernels of their own.
    runs["makers"] = _shape_makers
    kernels["makers"] = (("voxfab.digitize._kernels", "even_odd"), ("voxfab.digitize._kernels", "transport"),
                         ("voxfab.generate._kernels", "grow"))
    return runs, kernels


#: The kernel groups: name → the pipeline run that compiles them (into a scratch folder); the
#: outputs' groups come from the table of outputs (:func:`voxfab.fabricate.outputs`).
GROUPS: dict[str, Callable[[Path], None]]
#: The kernels of each group that the pipelines call from Python, as (module, function); a
#: group is compiled when numba's cache holds every one of them.
ENTRY_KERNELS: dict[str, tuple[tuple[str, str], ...]]
GROUPS, ENTRY_KERNELS = _groups()


@dataclasses.dataclass(frozen=True)
class GroupTime:
    """How long one group took to compile (or to load from numba's cache)."""

    group: str
    seconds: float


def warm_group(group: str, scratch: Path | None = None) -> GroupTime:
    """Compile the kernels of ``group`` in this process, its pipeline writing into a folder made in ``scratch``
    (default the system's temporary folder) and removed after."""
    if group not in GROUPS:
        raise InvalidShapeError(f"warm-up: unknown kernel group {group!r}; expected one of {', '.join(GROUPS)}")
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="voxfab-warmup-", dir=scratch) as tmp:
        GROUPS[group](Path(tmp))
    return GroupTime(group, round(time.perf_counter() - start, 3))


def warm_up(groups: Sequence[str] | None = None, *, processes: int | None = None,
            scratch: Path | None = None) -> list[GroupTime]:
    """Compile the kernel groups, side by side in up to ``processes`` processes (default: one per core).

    With ``processes=1`` the groups are compiled one after the other in this process,
    their scratch folders made in ``scratch`` (a studio's work folder, removed with
    it however the studio stops).

    Returns
    -------
    list of GroupTime
        In the order of ``groups`` (default: all of :data:`GROUPS`).
    """
    names = list(GROUPS) if groups is None else list(dict.fromkeys(groups))
    for name in names:
        if name not in GROUPS:
            raise InvalidShapeError(f"warm-up: unknown kernel group {name!r}; expected one of {', '.join(GROUPS)}")
    workers = min(len(names), processes or os.cpu_count() or 1)
    if workers <= 1:
        return [warm_group(name, scratch) for name in names]
    import concurrent.futures
    import multiprocessing

    # spawn: each child starts clean rather than forking whatever this process has loaded
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=ctx) as pool:
        return list(pool.map(warm_group, names))


def is_compiled(group: str) -> bool:
    """Whether numba's cache holds fresh machine code of every entry kernel of ``group``.

    Reads numba's cache index through its private ``_cache`` object (the only way
    to ask without compiling); should that change shape, the group counts as
    compiled and nothing is done aside.
    """
    import importlib

    for module, name in ENTRY_KERNELS[group]:
        try:
            kernel = getattr(importlib.import_module(module), name)
            # {} when the index is missing, of another numba or older than the source
            if not kernel._cache._cache_file._load_index():
                return False
        except Exception:  # noqa: BLE001 - a kernel or numba's internals moved: assume compiled
            return True
    return True


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on every platform
        return os.cpu_count() or 1


def _warm_aside(groups: tuple[str, ...]) -> None:
    warm_up(groups, processes=1)


def _idle_core() -> bool:
    """Whether a second process would find a core to itself (on a busy machine it only takes turns)."""
    cores = _cores()
    try:
        busy = os.getloadavg()[0]
    except (AttributeError, OSError):  # no load average on this platform
        busy = 0.0
    return cores >= 2 and busy < cores - 0.5  # the 1-minute load: most of a core free


class Aside:
    """Kernel groups compiling in a side process; :meth:`wait` before the work that calls them.

    As a context manager it waits at the end, or stops the side process when the
    block fails (numba writes each cache file whole, under a temporary name, so
    a stopped compile leaves no broken entry).
    """

    def __init__(self, groups: Sequence[str]) -> None:
        self.groups = tuple(groups)
        self._process = None
        if self.groups:
            import multiprocessing

            # spawn: the child starts clean rather than forking whatever this process has loaded
            self._process = multiprocessing.get_context("spawn").Process(
                target=_warm_aside, args=(self.groups,), name="voxfab-warmup", daemon=True)
            self._process.start()

    def wait(self) -> None:
        """Block until the side compile is over; had it failed, the kernels compile in this process as usual."""
        if self._process is not None:
            self._process.join()
            self._process = None

    def stop(self) -> None:
        """End the side compile now."""
        if self._process is not None:
            self._process.terminate()
            self._process.join()
            self._process = None

    def __enter__(self) -> Aside:
        return self

    def __exit__(self, exc_type: object, exc: object, tb: object) -> None:
        if exc_type is None:
            self.wait()
        else:
            self.stop()


def compile_aside(groups: Sequence[str]) -> Aside:
    """Start compiling those of ``groups`` not yet compiled in a side process.

    Nothing starts without an idle core (on one core, or one whose other cores are
    busy, the side process would only take turns with this one; measured on 2
    busy cores it made the first build slower), inside a daemonic worker, or
    when every group is compiled, so a warm build pays only the cache check.
    """
    import multiprocessing

    # A pool's worker (a batch) is daemonic and may not start processes of its own.
    if not groups or not _idle_core() or multiprocessing.current_process().daemon:
        return Aside(())
    return Aside([g for g in dict.fromkeys(groups) if not is_compiled(g)])
