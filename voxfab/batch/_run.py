"""A batch run: select shapes, send small tasks to Dask workers, record outcomes, write the index."""

from __future__ import annotations

import contextlib
import dataclasses
import json
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from voxfab._shared.typing import PathLike
from voxfab.errors import RecipeError, RepositoryError, VoxfabError

from ._cluster import Cluster, check_dashboard, check_wait, check_workers, connect
from ._index import THUMBS, HuntSummary, hunt_summary
from ._task import RECIPES, BatchTask, Outcome, build_task, folder_problem, outputs_sha256, shape_file_recipe

__all__ = ["BatchReport", "load_outputs", "parse_name_range", "select_names", "run_batch", "BATCH_FORMAT"]

BATCH_FORMAT = "voxfab-batch/1"
#: Top-level keys an outputs file may hold: what a recipe says about outputs, no source.
_OUTPUT_KEYS = {"outputs", "pitch", "seed", "description"}
#: Seconds between two saves of ``batch.json`` while tasks finish.
_SAVE_EVERY_S = 2.0


@dataclasses.dataclass(frozen=True)
class BatchReport:
    """What :func:`run_batch` did: counts, run time, where the index is, and the hunt's outcomes.

    ``seconds`` runs from the cluster's start to the last file written (``batch.json``, the index).
    ``hunt`` sorts the built shapes by what their ``hunt.json`` says (``[outputs.hunt]``);
    None when no shape has one.
    """

    built: int
    failed: int
    skipped: int
    seconds: float
    workers: int
    index: Path
    failures: tuple[tuple[str, str], ...]
    hunt: HuntSummary | None = None

    @property
    def rate(self) -> float:
        """Shapes built per minute in this run."""
        return 60.0 * self.built / self.seconds if self.seconds > 0 else 0.0


def load_outputs(path: PathLike) -> str:
    """Read and validate an outputs file: ``[outputs.*]`` tables as in a recipe, ``pitch``, ``seed``.

    The file is validated exactly as a recipe is (same messages, same lines), by
    loading the recipe it makes for a placeholder shape.

    Returns
    -------
    str
        The file's text.

    Raises
    ------
    RecipeError
        A file that cannot be read, is not TOML, holds other keys, or whose
        outputs a recipe would refuse.
    """
    import tempfile

    import numpy as np

    from voxfab import io
    from voxfab._shared.limits import parse_toml, read_input_bytes
    from voxfab.recipe import load_recipe

    p = Path(path)
    # The reader build uses: a FIFO, a device or a huge file is refused before reading.
    try:
        text = read_input_bytes(p, what="an outputs file").decode("utf-8")
        data = parse_toml(text, name=str(p))
    except UnicodeDecodeError:
        raise RecipeError(f"{p}: not UTF-8 text") from None
    except VoxfabError as exc:  # the reader's FormatError and LimitError, as a recipe's
        raise RecipeError(str(exc)) from None
    extra = sorted(set(data) - _OUTPUT_KEYS)
    if extra:
        raise RecipeError(f"{p}: {extra[0]}: unknown key; an outputs file accepts: {', '.join(sorted(_OUTPUT_KEYS))}")
    if not data.get("outputs"):
        raise RecipeError(f"{p}: no [outputs.*] table: nothing to build")
    with tempfile.TemporaryDirectory() as tmp:
        probe = Path(tmp) / "probe.toml"
        io.write(np.ones((1, 1, 1), dtype=bool), Path(tmp) / "probe.npy")
        probe.write_text(shape_file_recipe(text, "probe"), encoding="utf-8")
        try:
            load_recipe(probe)
        except RecipeError as exc:
            raise RecipeError(str(exc).replace(str(probe), str(p))) from None
    return text


def parse_name_range(text: str) -> tuple[tuple[int, int], tuple[int, int]]:
    """Parse ``A:B`` (names, inclusive; either side may be empty) into ``(volume, rank)`` bounds."""
    from voxfab.repo import NAME_PATTERN

    lo_text, sep, hi_text = text.partition(":")
    if not sep:
        lo_text = hi_text = text
    bounds = []
    for part, default in ((lo_text, (0, 0)), (hi_text, (10**9, 10**9))):
        part = part.strip()
        if not part:
            bounds.append(default)
            continue
        m = NAME_PATTERN.fullmatch(part)
        if not m:
            raise RepositoryError(f"--names: {part!r} is not a shape name (expected A:B such as 00100.001:00200.999)")
        bounds.append((int(m.group(1)), int(m.group(2))))
    if bounds[0] > bounds[1]:
        raise RepositoryError(f"--names: the range {text!r} is empty (A comes after B)")
    return bounds[0], bounds[1]


def select_names(repo: Any, *, names: str | None = None, limit: int | None = None) -> list[str]:
    """The named shapes (no drafts) in the name range ``A:B`` and/or the first ``limit``, in name order."""
    if limit is not None and limit < 1:
        raise RepositoryError(f"--limit: expected at least 1, got {limit}")
    if names is None:
        return [e.name for e in repo.list(drafts=False, limit=limit)]
    lo, hi = parse_name_range(names)
    picked = []
    # The volume range narrows the query on the index; ranks are compared here.
    for e in repo.list(volume=(max(1, lo[0]), max(1, hi[0])), drafts=False):
        v, r = (int(x) for x in e.name.split("."))
        if lo <= (v, r) <= hi:
            picked.append(e.name)
            if limit is not None and len(picked) == limit:
                break
    return picked


def _read_previous(path: Path, sha: str) -> dict[str, dict[str, Any]]:
    """The outcomes an earlier run recorded in ``batch.json`` (checked), or none."""
    from voxfab._shared.limits import parse_json, read_input_bytes
    from voxfab.errors import VoxfabError

    if not path.exists():
        return {}
    refuse = RepositoryError(f"{path}: not a voxfab batch record; use another output folder")
    try:
        data = parse_json(read_input_bytes(path, what="a batch record").decode("utf-8"), name=str(path))
    except (VoxfabError, UnicodeDecodeError):
        raise refuse from None
    if not isinstance(data, dict) or data.get("format") != BATCH_FORMAT or not isinstance(data.get("shapes"), dict):
        raise refuse
    shapes = data["shapes"]
    if not all(isinstance(k, str) and isinstance(v, dict) for k, v in shapes.items()):
        raise refuse
    if data.get("outputs_sha256") != sha:
        raise RepositoryError(
            f"{path}: this folder was built with other outputs; use another output folder to build these"
        )
    return dict(shapes)


def _save(path: Path, outputs_file: str, sha: str, shapes: dict[str, dict[str, Any]]) -> None:
    from voxfab._shared.atomic import write_text

    data = {"format": BATCH_FORMAT, "outputs_file": outputs_file, "outputs_sha256": sha, "shapes": shapes}
    write_text(path, json.dumps(data, indent=1, sort_keys=True) + "\n")


def _check_folder(outdir: PathLike) -> None:
    """Refuse ``-o DIR`` before any work: one level below an existing folder, and ours if it holds files."""
    from voxfab._shared.atomic import check_output
    from voxfab.errors import OutputError

    if not str(outdir).strip():  # Path("") would be the current folder
        raise OutputError("-o: expected a folder name, got ''")
    out = Path(outdir)
    check_output(out, folder=True, parents=True, marker="batch.json")
    for sub in (RECIPES, THUMBS):
        if (out / sub).exists() and not (out / sub).is_dir():
            raise OutputError(f"{out / sub}: exists and is not a folder")


def _make_folder(out: Path) -> None:
    from voxfab.errors import OutputError

    try:
        out.mkdir(exist_ok=True)
        (out / RECIPES).mkdir(exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{out}: cannot create the batch folder: {exc.strerror or exc}") from None
    probe = out / f".voxfab-write-test-{uuid.uuid4().hex[:8]}"
    try:
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as exc:
        raise OutputError(f"{out}: cannot write in the batch folder: {exc.strerror or exc}") from None


def _sweep(out: Path) -> None:
    """Remove the temporaries of builds that were stopped (Ctrl-C, a killed worker)."""
    from voxfab._shared.atomic import sweep

    for folder in (out, out / RECIPES, out / THUMBS):
        sweep(folder)


def run_batch(
    repo_path: PathLike,
    outputs_path: PathLike,
    outdir: PathLike,
    *,
    names: str | None = None,
    limit: int | None = None,
    scheduler: str | None = None,
    workers: int = 2,
    dashboard: str | None = None,
    thumbnails: bool = True,
    window: int | None = None,
    timeout: float = 30.0,
    on_start: Callable[[int, int, str | None], None] | None = None,
    on_outcome: Callable[[Outcome], None] | None = None,
) -> BatchReport:
    """Build the outputs of the selected shapes on a Dask cluster.

    Everything is checked before a folder is made or a cluster started: the
    outputs file, the options, ``DIR`` and its ``batch.json``, and each selected
    shape's repository row.  A shape whose row is corrupt fails with the reason
    and is never built.  A folder of an earlier run counts as built only when
    every file matches its manifest's sha256 (:func:`folder_problem`); any other
    is built again, and ``batch.json`` is brought in line with the folders.

    Parameters
    ----------
    repo_path, outputs_path, outdir
        The repository, the outputs file (see :func:`load_outputs`) and ``DIR``.
    names, limit
        Selection: a name range ``A:B`` (inclusive) and/or the first ``limit`` shapes.
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:8786``), probed before Dask
        connects; otherwise a local cluster of ``workers`` processes is started
        and stopped.
    dashboard : str, optional
        Dashboard address of the local cluster (``":8787"``, ``":0"`` for a free
        port); None turns it off.  It needs bokeh.
    thumbnails : bool
        Draw the index thumbnails on the workers, then write the index.
    window : int, optional
        Tasks in flight at once (default 4 per worker): the scheduler holds only
        these, however many shapes are selected.
    timeout : float
        Seconds to wait for the scheduler and a first worker, and at most without
        any worker during the run.
    on_start, on_outcome : callable, optional
        Called with (shapes to build, shapes skipped, dashboard link), and with each outcome as it arrives.

    Returns
    -------
    BatchReport

    Raises
    ------
    RepositoryError
        A bad option, repository, selection or scheduler, or no worker for
        ``timeout`` seconds during the run.
    """
    from voxfab.repo import Repository, decode_bits

    outputs = load_outputs(outputs_path)
    timeout = check_wait(timeout)
    if scheduler is None:
        check_workers(workers)
        check_dashboard(dashboard)
    sha = outputs_sha256(outputs)
    _check_folder(outdir)
    out = Path(outdir)
    record_path = out / "batch.json"
    shapes = _read_previous(record_path, sha)
    with Repository(repo_path, create=False) as repo:
        selected = select_names(repo, names=names, limit=limit)
        if not selected:
            raise RepositoryError(f"{repo_path}: no shape matches the selection")
        packed: dict[str, tuple[bytes, tuple[int, int, int]]] = {}
        corrupt: list[Outcome] = []
        for name in selected:
            try:
                packed[name] = repo.packed(name)  # the row is checked here, before any worker sees it
            except RepositoryError as exc:
                corrupt.append(Outcome(name, "failed", 0.0, "client", " ".join(str(exc).split())))
    todo, skipped = [], 0
    for name, (bits, extents) in packed.items():
        if out.is_dir() and folder_problem(out, name, outputs, decode_bits(bits, extents)) is None:
            skipped += 1
            if shapes.get(name, {}).get("status") != "built":
                shapes[name] = {"status": "built", "seconds": 0.0, "worker": "earlier run"}
        else:
            todo.append(name)
    # Largest shapes first (names run by rising volume): the last round then holds small shapes, so
    # no worker idles for long while another finishes a large one.
    todo.sort(key=lambda n: -_voxel_count(packed[n][0]))
    start = time.perf_counter()
    failures: list[tuple[str, str]] = [(o.name, o.error or "") for o in corrupt]
    for o in corrupt:
        shapes[o.name] = o.to_json()
    built = n_workers = 0
    closing: threading.Thread | None = None
    if todo:
        cl = connect(scheduler, workers, dashboard, timeout)  # before DIR exists: a refusal leaves nothing
        n_workers = cl.workers
        try:
            _make_folder(out)
            if on_start is not None:
                link = cl.client.dashboard_link if dashboard is not None or scheduler is not None else None
                on_start(len(todo), skipped, link)
            for o in corrupt:
                if on_outcome is not None:
                    on_outcome(o)
            tasks = (BatchTask(n, *packed[n], str(out), outputs, thumbnails) for n in todo)
            runner = _run_tasks(cl, tasks, window or 4 * max(1, cl.workers), timeout,
                                lambda: _save(record_path, Path(outputs_path).name, sha, shapes))
            with contextlib.closing(runner):  # closed at once on an error or Ctrl-C: tasks cancelled
                for outcome in runner:
                    shapes[outcome.name] = outcome.to_json()
                    if outcome.status == "built":
                        built += 1
                    else:
                        failures.append((outcome.name, outcome.error or ""))
                    if on_outcome is not None:
                        on_outcome(outcome)
            # Every task is done: the cluster stops (a second or more) while the index is written.
            closing = threading.Thread(target=cl.close, name="voxfab-batch-close", daemon=True)
            closing.start()
        finally:
            if closing is None:
                cl.close()
            if out.is_dir():
                _sweep(out)
                _save(record_path, Path(outputs_path).name, sha, shapes)
    else:
        _make_folder(out)
        if on_start is not None:
            on_start(0, skipped, None)
        for o in corrupt:
            if on_outcome is not None:
                on_outcome(o)
    try:
        _save(record_path, Path(outputs_path).name, sha, shapes)
        index = out / "index.html"
        if thumbnails:
            from ._index import write_index

            index = write_index(out, shapes)[0]
        hunted = hunt_summary(out, sorted(n for n, v in shapes.items() if v.get("status") == "built"))
    finally:
        if closing is not None:
            closing.join()
    seconds = time.perf_counter() - start
    return BatchReport(built, len(failures), skipped, seconds, n_workers, index, tuple(failures),
                       hunted if hunted.shapes else None)


def _voxel_count(bits: bytes) -> int:
    """Voxels of a shape from its packed bits (the padding bits are zeros)."""
    import numpy as np

    return int(np.unpackbits(np.frombuffer(bits, dtype=np.uint8)).sum())


def _run_tasks(cl: Cluster, tasks: Iterator[BatchTask], window: int, timeout: float,
               save: Callable[[], None]) -> Iterator[Outcome]:
    """Run ``tasks`` through a sliding window of ``window`` futures; yield each outcome as it arrives.

    The wait is bounded: without a worker (or a scheduler) for ``timeout``
    seconds the run stops with an error.  On any exit (an error, Ctrl-C) the
    tasks still in flight are cancelled, so no worker writes after the client
    has gone.
    """
    from distributed import as_completed

    run_id = uuid.uuid4().hex[:12]  # task keys are unique per run: several batches may share a scheduler
    in_flight: dict[str, Any] = {}
    names: dict[str, str] = {}

    def submit(t: BatchTask) -> Any:
        key = f"voxfab-batch-{run_id}-{t.name}"
        names[key] = t.name
        in_flight[key] = cl.client.submit(build_task, t, key=key, pure=False)
        return in_flight[key]

    pending = as_completed([submit(t) for _, t in zip(range(window), tasks)])
    saved = checked = seen = time.monotonic()
    try:
        while in_flight:
            if not pending.has_ready():
                now = time.monotonic()
                if now - checked > 0.5:
                    checked = now
                    if cl.client.status == "running" and cl.worker_count() > 0:
                        seen = now
                    elif now - seen > timeout:
                        what = "the scheduler" if cl.client.status != "running" else "every worker"
                        raise RepositoryError(
                            f"lost {what}: no worker for {timeout:g} s; {len(in_flight)} shapes in flight "
                            "and the rest not built (run again to resume)"
                        )
                time.sleep(0.02)
                continue
            future = next(pending)
            try:
                outcome: Outcome = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker (KilledWorker) fails one shape
                outcome = Outcome(names[future.key], "failed", 0.0, "lost",
                                  f"{type(exc).__name__}: {' '.join(str(exc).split())}")
            in_flight.pop(future.key, None)
            future.release()
            yield outcome
            nxt = next(tasks, None)
            if nxt is not None:
                pending.add(submit(nxt))
            if time.monotonic() - saved > _SAVE_EVERY_S:
                save()
                saved = time.monotonic()
    finally:
        if in_flight:
            with contextlib.suppress(Exception):
                cl.client.cancel(list(in_flight.values()), force=True)
