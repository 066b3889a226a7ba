"""A batch run: select shapes, send small tasks to Dask workers, record outcomes, write the index."""

from __future__ import annotations

import dataclasses
import json
import time
import tomllib
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from voxfab._shared.typing import PathLike
from voxfab.errors import MissingDependencyError, RecipeError, RepositoryError

from ._task import RECIPES, BatchTask, Outcome, build_task, done, outputs_sha256, recipe_text

__all__ = ["BatchReport", "load_outputs", "parse_name_range", "select_names", "run_batch", "BATCH_FORMAT"]

BATCH_FORMAT = "voxfab-batch/1"
#: Top-level keys an outputs file may hold: what a recipe says about outputs, no source.
_OUTPUT_KEYS = {"outputs", "pitch", "seed", "description"}
#: Seconds between two saves of ``batch.json`` while tasks finish.
_SAVE_EVERY_S = 2.0


@dataclasses.dataclass(frozen=True)
class BatchReport:
    """What :func:`run_batch` did: counts, run time and where the index is."""

    built: int
    failed: int
    skipped: int
    seconds: float
    workers: int
    index: Path
    failures: tuple[tuple[str, str], ...]

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
    from voxfab.recipe import load_recipe

    p = Path(path)
    try:
        text = p.read_bytes().decode("utf-8")
        data = tomllib.loads(text)
    except OSError as exc:
        raise RecipeError(f"{p}: cannot read the outputs file: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise RecipeError(f"{p}: not UTF-8 text") from None
    except tomllib.TOMLDecodeError as exc:
        raise RecipeError(f"{p}: invalid TOML: {exc}") from None
    extra = sorted(set(data) - _OUTPUT_KEYS)
    if extra:
        raise RecipeError(f"{p}: {extra[0]}: unknown key; an outputs file accepts: {', '.join(sorted(_OUTPUT_KEYS))}")
    if not data.get("outputs"):
        raise RecipeError(f"{p}: no [outputs.*] table: nothing to build")
    with tempfile.TemporaryDirectory() as tmp:
        probe = Path(tmp) / "probe.toml"
        io.write(np.ones((1, 1, 1), dtype=bool), Path(tmp) / "probe.npy")
        probe.write_text(recipe_text(text, "probe"), encoding="utf-8")
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
        m = NAME_PATTERN.match(part)
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
    if not path.is_file():
        return {}
    try:
        data = json.loads(path.read_text())
        shapes = data["shapes"]
        previous_sha = data["outputs_sha256"]
    except (OSError, ValueError, KeyError, TypeError):
        raise RepositoryError(f"{path}: not a voxfab batch record; use another output folder") from None
    if previous_sha != sha:
        raise RepositoryError(
            f"{path}: this folder was built with other outputs; use another output folder to build these"
        )
    return dict(shapes)


def _save(path: Path, outputs_file: str, sha: str, shapes: dict[str, dict[str, Any]]) -> None:
    from voxfab._shared.atomic import write_text

    data = {"format": BATCH_FORMAT, "outputs_file": outputs_file, "outputs_sha256": sha, "shapes": shapes}
    write_text(path, json.dumps(data, indent=1, sort_keys=True) + "\n")


@dataclasses.dataclass
class _Cluster:
    client: Any
    cluster: Any
    workers: int

    def close(self) -> None:
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _connect(scheduler: str | None, workers: int, dashboard: str | None, timeout: float) -> _Cluster:
    try:
        from distributed import Client, LocalCluster
    except ImportError as exc:
        raise MissingDependencyError("batch needs Dask distributed: pip install 'dask[distributed]'") from exc
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=timeout)
        except (OSError, TimeoutError, ValueError) as exc:
            # ValueError: an address distributed cannot parse (no port, unknown protocol).
            raise RepositoryError(f"--scheduler: cannot reach {scheduler}: {' '.join(str(exc).split())}") from None
        try:
            client.wait_for_workers(1, timeout=timeout)
        except TimeoutError:
            client.close()
            raise RepositoryError(f"--scheduler: {scheduler} has no worker after {timeout:g} s") from None
        return _Cluster(client, None, len(client.scheduler_info()["workers"]))
    if workers < 1:
        raise RepositoryError(f"--workers: expected at least 1, got {workers}")
    # One thread per process: the builds hold the GIL (numpy, shapely, PIL) and each
    # worker gets its own memory, which the dashboard shows per worker.
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                           dashboard_address=dashboard, silence_logs=40)
    return _Cluster(Client(cluster), cluster, workers)


def _tasks(repo: Any, names: list[str], outdir: Path, outputs: str, thumbnails: bool) -> Iterator[BatchTask]:
    for name in names:
        bits, extents = repo.packed(name)
        yield BatchTask(name, bits, extents, str(outdir), outputs, thumbnails)


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

    Parameters
    ----------
    repo_path, outputs_path, outdir
        The repository, the outputs file (see :func:`load_outputs`) and ``DIR``.
    names, limit
        Selection: a name range ``A:B`` (inclusive) and/or the first ``limit`` shapes.
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:8786``); otherwise a local
        cluster of ``workers`` processes is started and stopped.
    dashboard : str, optional
        Dashboard address of the local cluster (``":8787"``, ``":0"`` for a free
        port); None turns it off.  It needs bokeh.
    thumbnails : bool
        Draw the index thumbnails on the workers, then write the index.
    window : int, optional
        Tasks in flight at once (default 4 per worker): the scheduler holds only
        these, however many shapes are selected.
    on_start, on_outcome : callable, optional
        Called with (shapes to build, shapes skipped, dashboard link), and with each outcome as it arrives.

    Returns
    -------
    BatchReport
    """
    from voxfab.repo import Repository

    outputs = load_outputs(outputs_path)
    sha = outputs_sha256(outputs)
    out = Path(outdir)
    if out.exists() and not out.is_dir():
        raise RepositoryError(f"{out}: exists and is not a folder")
    record_path = out / "batch.json"
    shapes = _read_previous(record_path, sha)
    with Repository(repo_path, create=False) as repo:
        selected = select_names(repo, names=names, limit=limit)
        if not selected:
            raise RepositoryError(f"{repo_path}: no shape matches the selection")
        todo = [n for n in selected if not done(out, n)]
        skipped = len(selected) - len(todo)
        out.mkdir(parents=True, exist_ok=True)
        (out / RECIPES).mkdir(exist_ok=True)
        for n in selected:
            if n not in todo and shapes.get(n, {}).get("status") != "built":
                shapes[n] = {"status": "built", "seconds": 0.0, "worker": "earlier run"}
        start = time.perf_counter()
        failures: list[tuple[str, str]] = []
        built = 0
        n_workers = 0
        if todo:
            from distributed import as_completed

            cl = _connect(scheduler, workers, dashboard, timeout)
            n_workers = cl.workers
            try:
                if on_start is not None:
                    link = cl.client.dashboard_link if dashboard is not None or scheduler is not None else None
                    on_start(len(todo), skipped, link)
                tasks = _tasks(repo, todo, out, outputs, thumbnails)
                size = window or 4 * max(1, cl.workers)
                # Task keys are unique per run: several batches may share one scheduler.
                run_id = uuid.uuid4().hex[:12]
                by_key: dict[str, str] = {}

                def submit(t: BatchTask) -> Any:
                    key = f"voxfab-batch-{run_id}-{t.name}"
                    by_key[key] = t.name
                    return cl.client.submit(build_task, t, key=key, pure=False)

                # A sliding window: the scheduler holds only the tasks in flight.
                pending = as_completed([submit(t) for _, t in zip(range(size), tasks)])
                saved = time.monotonic()
                for future in pending:
                    try:
                        outcome: Outcome = future.result()
                    except Exception as exc:  # noqa: BLE001 - a lost worker (KilledWorker) fails one shape
                        outcome = Outcome(by_key[future.key], "failed", 0.0, "lost",
                                          f"{type(exc).__name__}: {' '.join(str(exc).split())}")
                    by_key.pop(future.key, None)
                    future.release()
                    shapes[outcome.name] = outcome.to_json()
                    if outcome.status == "built":
                        built += 1
                    else:
                        failures.append((outcome.name, outcome.error or ""))
                    if on_outcome is not None:
                        on_outcome(outcome)
                    nxt = next(tasks, None)
                    if nxt is not None:
                        pending.add(submit(nxt))
                    if time.monotonic() - saved > _SAVE_EVERY_S:
                        _save(record_path, Path(outputs_path).name, sha, shapes)
                        saved = time.monotonic()
            finally:
                _save(record_path, Path(outputs_path).name, sha, shapes)
                cl.close()
        elif on_start is not None:
            on_start(0, skipped, None)
        seconds = time.perf_counter() - start
    _save(record_path, Path(outputs_path).name, sha, shapes)
    index = out / "index.html"
    if thumbnails:
        from ._index import write_index

        index = write_index(out, shapes)[0]
    return BatchReport(built, len(failures), skipped, seconds, n_workers, index, tuple(failures))
