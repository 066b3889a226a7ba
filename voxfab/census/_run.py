"""``census.json``: every polycube of 1..N cubes unfolded and unzipped, serially or on Dask, resumable.

The client enumerates the polycubes (:mod:`._enumerate`, a fixed order), sends
chunks of them to the workers (:func:`._task.census_task`), which write the nets
under ``DIR/nets/`` and send back small records, and writes ``DIR/census.json``
(under a temporary name, then renamed) every few seconds and at the end, with
the page ``DIR/census.html``.  A run started again on the same DIR with the
same settings keeps every record whose net files check out (:mod:`._resume`)
and censuses only the rest, so an interrupted run resumes, ``census 8`` after
``census 6`` censuses only the polycubes of 7 and 8 cubes, and ``census 6``
after ``census 8`` keeps the census of 8.

Everything that can be refused is refused before anything is made: N, the
settings, the scheduler's address (``tcp://HOST:PORT``) and the scheduler
itself, the output folder, an earlier ``census.json`` that is no census.  A
serial run stops within a fraction of a second on Ctrl-C (SIGINT sets the
searches' cancel event, :func:`_interrupts`), saves the records done and raises
KeyboardInterrupt; an interrupted search is never recorded.  A run whose every
search failed raises :class:`~voxfab.errors.UnfoldError` after saving.

Everything in ``census.json`` but the times and the workers (``rows[].seconds``
and ``rows[].cpu_seconds``, this run's search time per n, and ``run``) depends
only on N and the settings: a serial run and a Dask run write the same file
apart from those.
"""

from __future__ import annotations

import contextlib
import dataclasses
import ipaddress
import json
import os
import re
import select
import signal
import tempfile
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from voxfab.errors import CancelledError, InvalidShapeError, OutputError, RepositoryError, UnfoldError

from ._resume import CENSUS_FORMAT
from ._task import NETS, CensusSettings, CensusTask, census_task

__all__ = ["CENSUS_FORMAT", "CensusInterrupted", "CensusReport", "check_census_size", "check_scheduler", "run_census", "shape_id"]
#: Shapes sent to a worker at once: a polycube takes tens of milliseconds, a Dask task a few.
_CHUNK = 24
#: Shapes listed per n as the first without an unzipping (or undecided), with their proofs.
_LISTED = 10
#: Seconds between two saves of the partial census, at the least.
_SAVE_EVERY = 15.0
#: ... and at least this many times the last save's own time: the client shares the workers' cores,
#: and rewriting a census of 50,000 shapes takes seconds, so saving stays under 5 % of one core.
_SAVE_SHARE = 20.0


def shape_id(n: int, index: int) -> str:
    """The census name of the ``index``-th polycube (from 0) of ``n`` cubes in the fixed order: ``08-000001``."""
    return f"{n:02d}-{index + 1:06d}"


def check_census_size(n: object) -> int:
    """Return N as an int of 1 to :data:`MAX_CUBES`, or refuse it in one line."""
    from ._enumerate import MAX_CUBES

    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_CUBES:
        raise InvalidShapeError(f"census N: expected a whole number of cubes from 1 to {MAX_CUBES}, got {n!r}")
    return n


#: A host name (RFC 1123 labels) or an IPv4 address's digits; IPv6 comes in brackets.
_HOST = re.compile(r"^(?=.{1,253}$)[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}[A-Za-z0-9])?(?:\.[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}"
                   r"[A-Za-z0-9])?)*$")


def check_scheduler(address: object) -> str:
    """Return a scheduler address ``tcp://HOST:PORT`` (or ``HOST:PORT``), or refuse it in one line.

    The census talks to a scheduler over plain TCP only: ``tls://`` needs
    certificates it has no option for, ``ucx://`` and ``inproc://`` are no
    address of a scheduler another process runs.
    """
    text = str(address)
    refuse = RepositoryError(f"--scheduler: expected tcp://HOST:PORT with a port of 1 to 65535, got {text[:80]!r}")
    if not isinstance(address, str):
        raise refuse
    protocol, sep, rest = address.partition("://")
    if not sep:
        protocol, rest = "tcp", address
    if protocol != "tcp":
        raise RepositoryError(f"--scheduler: the census reaches a scheduler over tcp:// only, got {text[:80]!r}")
    host, sep, port = rest.rpartition(":")
    if not sep or not port.isdigit() or not 1 <= int(port) <= 65535:
        raise refuse
    if host.startswith("[") and host.endswith("]"):
        try:
            ipaddress.IPv6Address(host[1:-1])
        except ValueError:
            raise refuse from None
    elif re.fullmatch(r"[0-9.]+", host):
        try:
            ipaddress.IPv4Address(host)
        except ValueError:
            raise refuse from None
    elif not _HOST.match(host):
        raise refuse
    return address


def _check_folder(out: Path, path: Path) -> None:
    """Refuse DIR, DIR/nets or DIR/census.json where they are not what the census makes, before anything is made."""
    from voxfab._shared.atomic import check_output

    check_output(path, parents=True)
    nets = out / NETS
    if nets.exists() and not nets.is_dir():
        raise OutputError(f"{nets}: exists and is not a folder; the census keeps its nets there")
    # A folder is tried by making and removing a hidden one in it: permissions alone do not tell a read-only
    # mount or a virtual file system (/proc), nor anything to root; the scheduler is reached only after.
    where = out if out.is_dir() else out.parent
    try:
        os.rmdir(tempfile.mkdtemp(prefix=f".{out.name}.{os.getpid()}-", suffix=".tmp", dir=where))
    except OSError as exc:
        raise OutputError(f"{out}: cannot write in {where}: {exc.strerror or exc}") from None


def _make_folder(out: Path) -> None:
    """Make DIR and DIR/nets; a folder that cannot hold them (read-only, virtual) is refused in one line."""
    for folder in (out, out / NETS):
        try:
            folder.mkdir(exist_ok=True)
        except OSError as exc:
            raise OutputError(f"{folder}: cannot create the folder: {exc.strerror or exc}") from None


class CensusInterrupted(KeyboardInterrupt):
    """A census stopped by Ctrl-C after it saved the records done (``path``, ``saved`` of them)."""

    def __init__(self, path: Path, saved: int) -> None:
        super().__init__(f"stopped; {saved} polycubes saved in {path}")
        self.path = path
        self.saved = saved


@dataclasses.dataclass(frozen=True)
class CensusReport:
    """What a census run did: its rows, the shapes censused now and kept from an earlier run, time, workers."""

    rows: tuple[dict[str, Any], ...]
    censused: int
    kept: int
    seconds: float
    workers: int
    path: Path
    page: Path


def _rows(n_max: int, counts: dict[int, tuple[int, int]], shapes: dict[str, dict[str, Any]],
          wall: dict[int, float], cpu: dict[int, float]) -> list[dict[str, Any]]:
    """One row per n: the counts, the outcomes, the surfaces, the shapes to show, and this run's search time."""
    rows = []
    for n in range(1, n_max + 1):
        mine = [r for k, r in sorted(shapes.items()) if r.get("n") == n]
        row: dict[str, Any] = {"n": n, "one_sided": counts[n][0], "free": counts[n][1], "censused": len(mine)}
        for key in ("unfold", "unzip"):
            for outcome in ("found", "none", "undecided"):
                row[f"{key}_{outcome}"] = sum(1 for r in mine if r.get(key) == outcome)
        for kind in ("manifold", "edge touching", "vertex touching", "handle"):
            row[kind.replace(" ", "_")] = sum(1 for r in mine if r.get("surface") == kind)
        row["square_zipper_found"] = sum(1 for r in mine if r.get("square_zipper") == "found")
        row["square_zipper_none"] = sum(1 for r in mine if r.get("square_zipper") == "none")
        row["errors"] = sum(1 for r in mine if "error" in r)
        row["first_no_unzip"] = [r["id"] for r in mine if r.get("unzip") == "none"][:_LISTED]
        row["first_undecided"] = [r["id"] for r in mine if "undecided" in (r.get("unzip"), r.get("unfold"))][:_LISTED]
        row["seconds"] = round(wall.get(n, 0.0), 1)
        row["cpu_seconds"] = round(cpu.get(n, 0.0), 1)
        rows.append(row)
    return rows


def _write(path: Path, data: dict[str, Any]) -> None:
    from voxfab._shared.atomic import write_text

    # One row and one shape per line: a diff of two runs shows the shapes that differ.
    head = [f" {json.dumps(k)}: {json.dumps(v, sort_keys=True)}" for k, v in sorted(data.items())
            if k not in ("rows", "shapes")]
    for key in ("rows", "shapes"):
        items = ",\n  ".join(json.dumps(s, sort_keys=True) for s in data[key])
        head.append(f' "{key}": [\n  {items}\n ]')
    write_text(path, "{\n" + ",\n".join(head) + "\n}\n")


def run_census(
    n_max: int,
    outdir: str | Path,
    *,
    settings: CensusSettings | None = None,
    scheduler: str | None = None,
    workers: int = 2,
    connect_timeout: float = 30.0,
    on_progress: Callable[[int, int], None] | None = None,
    store: str | None = None,
    repository: str | Path | None = None,
) -> CensusReport:
    """Census every polycube of 1..``n_max`` cubes into ``outdir``.

    Parameters
    ----------
    n_max : int
        The largest number of cubes, 1 to :data:`MAX_CUBES`.
    outdir : path
        ``DIR``: made when missing (its parent must exist); an earlier census there is resumed.
    settings : CensusSettings, optional
        Seed and time limit of each search (default: seed 0, 10 s).
    scheduler : str, optional
        A running Dask scheduler's address; otherwise ``workers`` local Dask
        processes, or this process alone when ``workers`` is 0.
    connect_timeout : float
        Seconds to wait for the scheduler and its first worker.
    on_progress : callable, optional
        Called with (shapes done, shapes to do) as records arrive.
    store : str, optional
        Also store every polycube in the repository as the named range
        ``store`` (members named by census id: ``polycubes-8:08-000001``), before
        the searches; a range stored by a smaller census grows.
    repository : path, optional
        The repository file for ``store`` (default ``output/repository.sqlite``, made when missing).

    Raises
    ------
    InvalidShapeError
        A bad N.
    RepositoryError
        A bad scheduler or worker count (as for ``voxfab batch``).
    OutputError
        ``outdir`` cannot be made.
    """
    from voxfab.batch._cluster import check_wait, check_workers

    from ._enumerate import _decode as decode_forms
    from ._enumerate import count_polycubes, polycube_levels
    from ._resume import census_size, kept_records, read_earlier
    from ._topology import grid_of

    n_max = check_census_size(n_max)
    if store is not None:
        _check_store(store, repository)
    settings = settings if settings is not None else CensusSettings()
    connect_timeout = check_wait(connect_timeout)
    if scheduler is not None:
        scheduler = check_scheduler(scheduler)
    elif workers != 0:
        workers = check_workers(workers)
    out = Path(outdir)
    path = out / "census.json"
    _check_folder(out, path)
    earlier = read_earlier(path)
    n_max = census_size(earlier, n_max, settings.to_dict(), path)
    if earlier is not None and earlier.settings != settings.to_dict():
        earlier = None
    with _runner(scheduler, workers, connect_timeout) as (run, nworkers):
        counts: dict[int, tuple[int, int]] = {}
        todo: list[tuple[str, int, tuple[tuple[int, int, int], ...]]] = []
        members: list[tuple[str, Any]] = []  # the range to store, when asked
        earlier_cells: dict[str, list[list[int]]] = {}  # the polycubes the earlier records name
        for n, forms in polycube_levels(n_max):
            counts[n] = count_polycubes(n, forms)
            for i, cells in enumerate(decode_forms(forms, n).tolist()):
                sid = shape_id(n, i)
                if store is not None:
                    members.append((sid, grid_of(cells)))
                if earlier is not None and sid in earlier.records:
                    earlier_cells[sid] = cells
                todo.append((sid, n, tuple(tuple(c) for c in cells)))
        records = kept_records(earlier, earlier_cells, out, settings.square_zipper)
        kept = len(records)
        todo = [t for t in todo if t[0] not in records]
        if store is not None:
            from voxfab.repo import DEFAULT_PATH, Repository

            with Repository(repository or DEFAULT_PATH, create=True) as repo:
                repo.add_range(store, members, meta={"source": f"polycube census of 1..{n_max} cubes"})
            members.clear()
        # The first thing made, once the range is stored: every refusal before left nothing behind.
        _make_folder(out)
        wall: dict[int, float] = {}  # search seconds per n, this run's, added over the shapes
        cpu: dict[int, float] = {}
        start = time.perf_counter()
        last, wait = time.monotonic(), _SAVE_EVERY
        done = 0
        failed: list[dict[str, Any]] = []
        per_worker: dict[str, int] = {}

        def save(complete: bool) -> None:
            data = {
                "format": CENSUS_FORMAT, "n": n_max, "settings": settings.to_dict(), "complete": complete,
                "rows": _rows(n_max, counts, records, wall, cpu),
                "run": {"seconds": round(time.perf_counter() - start, 1), "workers": nworkers,
                        "where": scheduler or ("serial" if workers == 0 else "local Dask cluster"),
                        "censused": done, "kept": kept, "shapes_per_worker": dict(sorted(per_worker.items()))},
                "shapes": [{k: v for k, v in r.items() if k not in ("seconds", "cpu_seconds")}
                           for _, r in sorted(records.items())],
            }
            _write(path, data)

        where = str(out.resolve())  # workers elsewhere see the shared folder by its full path, not the client's cwd
        # The largest polycubes first: they cost the most, so the last chunks, which leave a worker idle
        # while the other finishes, are the cheapest (the order of the records in the file does not change).
        todo.sort(key=lambda item: -item[1])
        # One shape at a time in this process: an interrupt loses only the search under way.
        size = 1 if run is _serial else _CHUNK
        chunks = (CensusTask(tuple(todo[i:i + size]), where, settings) for i in range(0, len(todo), size))
        try:
            with contextlib.closing(run(chunks)) as results:
                for recs, worker in results:
                    per_worker[worker] = per_worker.get(worker, 0) + len(recs)
                    for r in recs:
                        wall[r["n"]] = wall.get(r["n"], 0.0) + float(r.get("seconds", 0.0))
                        cpu[r["n"]] = cpu.get(r["n"], 0.0) + float(r.get("cpu_seconds", 0.0))
                        records[r["id"]] = r
                        if "error" in r:
                            failed.append(r)
                    done += len(recs)
                    if on_progress is not None:
                        on_progress(done, len(todo))
                    if time.monotonic() - last > wait:
                        began = time.thread_time()  # the save's own CPU: a client starved by other work is not slow
                        save(False)
                        last = time.monotonic()
                        wait = max(_SAVE_EVERY, _SAVE_SHARE * (time.thread_time() - began))
        except BaseException as exc:
            save(False)  # what is done is kept for the next run, whatever stopped this one
            if type(exc) is KeyboardInterrupt:  # not a subclass the caller gave its own meaning (SIGTERM)
                raise CensusInterrupted(path, len(records)) from None
            raise
    save(True)
    from ._report import write_page

    page = write_page(out, json.loads(path.read_text()))
    rows = tuple(_rows(n_max, counts, records, wall, cpu))
    if failed:
        one = min(failed, key=lambda r: r["id"])  # the first in the file, whichever finished first
        first = f"{one['id']}: {one['error']}"
        if len(failed) == done:
            raise UnfoldError(f"every search of the census failed ({done} polycubes; {first}); see {path}")
        import warnings

        from voxfab.errors import VoxfabWarning

        warnings.warn(f"{len(failed)} of {done} polycubes failed ({first}); they are censused again by the next run",
                      VoxfabWarning, stacklevel=2)
    return CensusReport(rows, done, kept, time.perf_counter() - start, nworkers, path, page)


def _check_store(store: str, repository: str | Path | None) -> None:
    """Refuse a bad range name, or a repository whose range tables are damaged, before anything is made."""
    from voxfab.repo import DEFAULT_PATH, Repository
    from voxfab.repo._records import check_range_name

    check_range_name(store)
    where = Path(repository or DEFAULT_PATH)
    if not where.exists():
        return  # made when the range is stored
    with Repository(where, create=False) as repo:
        problems = repo.check(rows=False)
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        raise RepositoryError(f"{where}: {problems[0]}{more}; 'voxfab repo check' lists every problem")


@contextlib.contextmanager
def _interrupts() -> Iterator[threading.Event]:
    """An event that SIGINT sets while the block runs (main thread), heard even inside a native solver.

    Python runs a signal handler only between bytecodes of the main thread, which a
    solver in native code holds for seconds; so the signal's byte also goes to a
    wakeup pipe that a thread watches.  The event stops every search of the block
    (:func:`voxfab._shared.progress.check_cancelled`, CP-SAT's cancel watcher), and
    the handler raises KeyboardInterrupt as soon as Python runs it.  (CP-SAT's own
    SIGINT handler, which ends a search as if out of time, is off in a cancel scope.)
    """
    event = threading.Event()
    if threading.current_thread() is not threading.main_thread():
        yield event
        return
    r, w = os.pipe()
    os.set_blocking(w, False)
    stop = threading.Event()

    again = threading.Event()

    def on_sigint(signum: int, frame: Any) -> None:
        event.set()  # for a solver in native code, were this handler late
        if _in_exec_of_text(frame):
            again.set()  # not here: the watcher sends SIGINT again in a moment
            return
        raise KeyboardInterrupt  # at once in Python code (an import of seconds, a search's own loop)

    def watch() -> None:
        while not stop.is_set():
            if select.select([r], [], [], 0.1)[0] and signal.SIGINT in os.read(r, 256):
                event.set()
            if again.is_set() and not stop.is_set():
                again.clear()
                os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, on_sigint)
    try:
        old_fd = signal.set_wakeup_fd(w, warn_on_full_buffer=False)
    except ValueError:  # a wakeup fd of the caller's (an event loop) stays: the handler alone sets the event
        old_fd = None
    watcher = threading.Thread(target=watch, name="census-sigint", daemon=True)
    watcher.start()
    try:
        yield event
    finally:
        stop.set()
        watcher.join()
        if old_fd is not None:
            signal.set_wakeup_fd(old_fd)
        signal.signal(signal.SIGINT, previous)
        os.close(r)
        os.close(w)


def _in_exec_of_text(frame: Any) -> bool:
    """Whether Python runs source text given to ``exec`` or ``eval`` (a dataclass's methods being made, at import).

    A KeyboardInterrupt that leaves such source marks the interpreter, which then ends by
    SIGINT whatever the program does with the exception (exit status -2, not 130); there the
    handler waits for the signal sent again a moment later.
    """
    while frame is not None:
        if frame.f_code.co_filename == "<string>" and frame.f_code.co_name == "<module>":
            return True
        frame = frame.f_back
    return False


def _serial(tasks: Iterator[CensusTask]) -> Iterator[tuple[list[dict[str, Any]], str]]:
    """Run tasks in this process; Ctrl-C stops the search under way and raises KeyboardInterrupt, recording nothing."""
    from voxfab._shared.progress import cancel_scope

    with _interrupts() as event:
        for t in tasks:
            try:
                with cancel_scope(event):  # the searches only: the caller's meter, between them, runs outside it
                    result = census_task(t)
            except CancelledError:
                if event.is_set():
                    raise KeyboardInterrupt from None
                raise
            if event.is_set():  # heard between two searches: the chunk is whole, stop after it
                yield result
                raise KeyboardInterrupt
            yield result


@contextlib.contextmanager
def _runner(scheduler: str | None, workers: int, timeout: float) -> Iterator[tuple[Callable, int]]:
    """A function running census tasks (yielding each one's result as it comes), and the worker count."""
    if scheduler is None and workers == 0:
        yield _serial, 1
        return
    from voxfab.batch._cluster import connect

    cl = connect(scheduler, workers, None, timeout)
    try:
        yield (lambda tasks: _on_dask(cl, tasks, 4 * max(1, cl.workers))), cl.workers
    finally:
        cl.close()


def _on_dask(cl: Any, tasks: Iterator[CensusTask], window: int) -> Iterator[tuple[list[dict[str, Any]], str]]:
    """Run tasks through a sliding window of futures; yield each result as it arrives, cancel the rest on exit."""
    from distributed import as_completed

    run_id = uuid.uuid4().hex[:12]
    in_flight: dict[str, Any] = {}
    count = 0

    def submit(t: CensusTask) -> Any:
        nonlocal count
        key = f"voxfab-census-{run_id}-{count}"
        count += 1
        in_flight[key] = cl.client.submit(census_task, t, key=key, pure=False)
        return in_flight[key]

    pending = as_completed([submit(t) for _, t in zip(range(window), tasks)])
    try:
        for future in pending:
            try:
                result = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker fails its chunk, named in the error
                raise RepositoryError(f"a census worker failed: {type(exc).__name__}: {' '.join(str(exc).split())}") \
                    from None
            in_flight.pop(future.key, None)
            future.release()
            yield result
            nxt = next(tasks, None)
            if nxt is not None:
                pending.add(submit(nxt))
    finally:
        for f in in_flight.values():
            f.cancel()
