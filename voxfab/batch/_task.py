"""One shape of a batch: the small task a worker receives, and what it does with it.

A task carries the shape's name, its packed bits and the outputs text: a few
hundred bytes, whatever the repository's size.  The worker rebuilds the grid,
writes the per-shape recipe (``DIR/recipes/<name>.toml`` and ``.npy``) and builds it
with :func:`voxfab.recipe.build_recipe`, so ``DIR/<name>/`` holds exactly what
``voxfab build DIR/recipes/<name>.toml -o DIR`` writes, and appears only complete.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import time
import traceback
from pathlib import Path

from voxfab._shared.typing import BoolGrid
from voxfab.errors import RecipeError, VoxfabError

from ._index import THUMBS

__all__ = ["BatchTask", "Outcome", "build_task", "shape_file_recipe", "folder_problem"]

#: Folder of DIR holding the per-shape recipes.
RECIPES = "recipes"
#: Side in pixels of the index thumbnails.
THUMB_SIZE = 160


@dataclasses.dataclass(frozen=True)
class BatchTask:
    """What a worker needs to build one shape.

    Attributes
    ----------
    name : str
        Repository name ``VVVVV.NNN``: the folder ``DIR/<name>/``.
    bits : bytes
        ``np.packbits`` of the cropped grid (C order), as stored in the repository.
    extents : (int, int, int)
    outdir : str
        ``DIR``, as the workers see it (a shared folder on a cluster).
    outputs : str
        The outputs file's text: ``[outputs.*]`` tables, optional ``pitch`` and ``seed``.
    thumbnails : bool
        Also draw the index thumbnails (render and net) into ``DIR/thumbs/``.
    """

    name: str
    bits: bytes
    extents: tuple[int, int, int]
    outdir: str
    outputs: str
    thumbnails: bool = True


@dataclasses.dataclass(frozen=True)
class Outcome:
    """What happened to one shape: ``status`` is ``built`` or ``failed`` (then ``error`` says why)."""

    name: str
    status: str
    seconds: float
    worker: str
    error: str | None = None
    files: int = 0
    notes: tuple[str, ...] = ()

    def to_json(self) -> dict[str, object]:
        data: dict[str, object] = {"status": self.status, "seconds": round(self.seconds, 3), "worker": self.worker}
        if self.error is not None:
            data["error"] = self.error
        if self.status == "built":
            data["files"] = self.files
        if self.notes:
            data["notes"] = list(self.notes)
        return data


def shape_file_recipe(outputs: str, name: str) -> str:
    """The recipe of one shape: the outputs file's text, then a ``[source]`` reading ``<name>.npy``.

    The source comes last so the outputs' lines keep their numbers in error
    messages; the recipe's name is its file's stem.
    """
    body = outputs if outputs.endswith("\n") or not outputs else outputs + "\n"
    return f'{body}\n[source]\nfile = "{name}.npy"\n'


def folder_problem(outdir: Path, name: str, outputs: str, grid: BoolGrid) -> str | None:
    """Why ``DIR/<name>/`` is not a sound build of ``grid`` with ``outputs``, or None when it is.

    A resumed batch trusts nothing it did not check: the manifest must parse, every
    file it lists must exist with its sha256, the recipe beside it
    (``DIR/recipes/<name>.toml`` and ``.npy``) must be this outputs text and this
    shape, and the manifest must name both.
    """
    from voxfab._shared.limits import parse_json, read_input_bytes
    from voxfab.shape import canonical_key

    root = outdir.resolve()
    folder = root / name
    try:
        manifest = parse_json(read_input_bytes(folder / "manifest.json", what="a manifest").decode("utf-8"),
                              name="manifest.json")
        files = manifest["files"]
        expected = {f["path"]: f["sha256"] for f in files}
        key = manifest["shape"]["key"]
        recipe_sha = manifest["recipe_sha256"]
    except VoxfabError as exc:
        return " ".join(str(exc).split())
    except (UnicodeDecodeError, KeyError, TypeError, AttributeError):
        return "manifest.json is not a voxfab manifest"
    recipe = shape_file_recipe(outputs, name).encode("utf-8")
    if recipe_sha != hashlib.sha256(recipe).hexdigest():
        return "built from another recipe"
    if key != canonical_key(grid):
        return "built from another shape"
    # (file, its sha256): the recipe beside the folder, then every file of the manifest.
    checks = [(root / RECIPES / f"{name}.toml", hashlib.sha256(recipe).hexdigest())]
    for path, sha in sorted(expected.items()):
        target = (folder / str(path)).resolve()
        if folder not in target.parents:
            return f"manifest.json lists a file outside the folder: {str(path)[:60]!r}"
        checks.append((target, sha))
    for target, sha in checks:
        try:
            data = read_input_bytes(target, what="a built file", limit=1 << 31)
        except VoxfabError:
            return f"{target.relative_to(root)}: missing"
        if hashlib.sha256(data).hexdigest() != sha:
            return f"{target.relative_to(root)}: changed since it was built"
    return _npy_problem(root / RECIPES / f"{name}.npy", grid)


def _npy_problem(path: Path, grid: BoolGrid) -> str | None:
    import numpy as np

    from voxfab import io

    try:
        stored = io.read(path).grid
    except VoxfabError:
        return f"{path.name}: missing or unreadable"
    return None if np.array_equal(stored, grid) else f"{path.name}: another shape"


def _worker_address() -> str:
    try:
        from distributed import get_worker

        return str(get_worker().address)
    except (ImportError, ValueError):
        return "local"


def build_task(task: BatchTask) -> Outcome:
    """Build one shape; never raises: a failure becomes an Outcome with the reason."""
    start = time.perf_counter()
    worker = _worker_address()
    try:
        files, notes = _build(task)
    except VoxfabError as exc:
        error = " ".join(str(exc).split())
        return Outcome(task.name, "failed", time.perf_counter() - start, worker, error)
    except Exception as exc:  # noqa: BLE001 - one broken shape must not stop a batch of thousands
        last = traceback.extract_tb(exc.__traceback__)[-1]
        error = f"{type(exc).__name__}: {' '.join(str(exc).split())} ({Path(last.filename).name}:{last.lineno})"
        return Outcome(task.name, "failed", time.perf_counter() - start, worker, error)
    return Outcome(task.name, "built", time.perf_counter() - start, worker, None, files, notes)


def _build(task: BatchTask) -> tuple[int, tuple[str, ...]]:
    from voxfab import io
    from voxfab._shared.atomic import write_text
    from voxfab.recipe import build_recipe, load_recipe
    from voxfab.repo import decode_bits

    outdir = Path(task.outdir)
    grid = decode_bits(task.bits, task.extents)
    recipes = outdir / RECIPES
    recipes.mkdir(parents=True, exist_ok=True)
    io.write(grid, recipes / f"{task.name}.npy")
    recipe_path = recipes / f"{task.name}.toml"
    write_text(recipe_path, shape_file_recipe(task.outputs, task.name))
    recipe = load_recipe(recipe_path)
    if recipe.name != task.name:
        raise RecipeError(f"{recipe_path}: builds {recipe.name!r}, expected {task.name!r}")
    built = build_recipe(recipe, outdir)
    files = len(json.loads((built.folder / "manifest.json").read_text())["files"])
    notes: tuple[str, ...] = ()
    if task.thumbnails:
        from ._index import draw_thumbnails

        notes = tuple(draw_thumbnails(grid, built.gives, outdir / THUMBS, name=task.name, seed=recipe.seed,
                                      size=THUMB_SIZE))
    return files, notes


def outputs_sha256(text: str) -> str:
    """Hash of an outputs text: a resumed batch must build the same outputs."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()
