"""The studio's heavy work: a gallery of distinct nets, and the fabrication files of the current shape.

Both run inside a :class:`~voxfab.studio._jobs.Job` on a worker thread and call
the same library functions as the CLI: ``voxfab.unfold.unfold`` and
``validate`` (``voxfab net``), ``netdraw.write_drawing`` (``voxfab net -o
NET.svg``), and the recipe outputs ``mesh``, ``slices`` and ``pictures``
(``voxfab build``).
"""

from __future__ import annotations

import inspect
import math
import shutil
import time
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError

from ._jobs import Job

#: Limits of a gallery: nets, seconds per net, seconds in all.
MAX_NETS = 12
MAX_NET_SECONDS = 60.0
MAX_GALLERY_SECONDS = 180.0


def artefacts() -> list[str]:
    """The files the page can ask for: the studio downloads of the table of outputs."""
    from voxfab.fabricate import outputs

    return [d for row in outputs().values() for d in row.downloads]

_DIRS = ("+x", "-x", "+y", "-y", "+z", "-z")


def check_number(value: Any, *, name: str, lo: float, hi: float, integer: bool = False) -> float:
    """``value`` as a number in ``[lo, hi]`` (an int when ``integer``), or an error naming it."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InvalidShapeError(f"{name}: expected a number, got {value!r:.40}")
    if integer and value != int(value):
        raise InvalidShapeError(f"{name}: expected a whole number, got {value!r}")
    if not lo <= value <= hi:
        raise InvalidShapeError(f"{name}: expected {lo:g} to {hi:g}, got {value:g}")
    return int(value) if integer else float(value)


# --- the net gallery --------------------------------------------------------------------------

def outline_key(net: Any) -> bytes:
    """The net's cells up to the 8 rotations and mirrors of the sheet: equal keys look the same cut out."""
    cells = net.corners2d.min(axis=1)
    best = None
    for swap in (False, True):
        c = cells[:, ::-1] if swap else cells
        for sx in (1, -1):
            for sy in (1, -1):
                t = c * np.array([sx, sy])
                t = t - t.min(axis=0)
                order = np.lexsort((t[:, 1], t[:, 0]))
                key = t[order].astype(np.int32).tobytes()
                if best is None or key < best:
                    best = key
    assert best is not None
    return best


def sheet_fit(net: Any, *, sheet: str, face_mm: float | None, margin: float = 10.0,
              tab_width: float = 5.0) -> dict[str, Any]:
    """How the net sits on the sheet: its extent in faces, the largest face size that fits, and the fit at ``face_mm``."""
    from voxfab.fabricate.netdraw import parse_sheet

    sw, sh = parse_sheet(sheet)
    x0, y0, x1, y1 = net.bounds()
    w, h = x1 - x0, y1 - y0
    # the drawable area loses the margins and room for glue tabs all around
    aw, ah = sw - 2 * margin - 2 * tab_width, sh - 2 * margin - 2 * tab_width
    largest = max(min(aw / w, ah / h), min(aw / h, ah / w))
    out: dict[str, Any] = {"extent": [int(w), int(h)], "sheet": sheet, "largest_face_mm": math.floor(largest * 10) / 10}
    if face_mm is not None:
        out["face_mm"] = face_mm
        out["fits"] = bool(largest >= face_mm)
        out["size_mm"] = [round(w * face_mm, 1), round(h * face_mm, 1)]
    return out


def net_layout(net: Any, grid: np.ndarray) -> dict[str, Any]:
    """What the page draws and marks: faces, 2D corners, folds, and each edge's neighbour and fold type."""
    from voxfab.shape import fill_cavities, surface_graph

    sg = surface_graph(fill_cavities(grid) if net.filled else grid)
    faces = [[int(v[0]), int(v[1]), int(v[2]), _DIRS[int(d)]] for v, d in zip(sg.voxel, sg.direction)]
    return {
        "faces": faces,
        "corners": net.corners2d.reshape(-1).tolist(),
        "folds": net.folds.reshape(-1).tolist(),
        "neighbor": sg.neighbor.reshape(-1).tolist(),
        "fold_type": sg.fold.reshape(-1).tolist(),
    }


def edge_constraints(data: Any) -> Any:
    """``voxfab.unfold.EdgeConstraints`` from the page's JSON, or None when nothing is marked."""
    if data is None or (isinstance(data, dict) and not data.get("cut") and not data.get("keep")):
        return None
    try:
        from voxfab.unfold import EdgeConstraints
    except ImportError:
        raise InvalidShapeError("constraints: this voxfab's net engine does not take marked edges") from None
    return EdgeConstraints.from_dict(data)


def net_gallery(job: Job, grid: np.ndarray, *, count: int, seed: int, timeout: float, sheet: str,
                face_mm: float | None, constraints: Any, budget: float = MAX_GALLERY_SECONDS) -> None:
    """Search ``count`` nets that look different once cut out, validate each, and lay them out for the page.

    Nets are ``unfold(grid, rng=s)`` for seeds ``s`` drawn from ``seed``, as
    ``voxfab net --count``; a net whose outline repeats an earlier one (up to
    turning or flipping the sheet) is skipped, and so is a seed whose search runs
    out of time (three in a row end the search).  Stops at ``budget`` seconds.
    """
    from voxfab.unfold import unfold, validate

    options: dict[str, Any] = {"timeout": timeout}
    if constraints is not None:
        if "constraints" not in inspect.signature(unfold).parameters:
            raise InvalidShapeError("constraints: this voxfab's net engine does not take marked edges")
        options["constraints"] = constraints
    from voxfab.errors import UnfoldError

    gen = np.random.default_rng(seed)
    start = time.monotonic()
    nets, seen, tries, failed = [], set(), 0, 0
    job.step(0, count, "searching nets")
    while len(nets) < count and tries < 4 * count + 8 and time.monotonic() - start < budget:
        tries += 1
        s = int(gen.integers(0, 2**31 - 1))
        try:
            net = unfold(grid, rng=s, **options)
        except UnfoldError:
            # a seed whose search ran out of time: the next seed may do; three in a row end the gallery
            failed += 1
            if failed >= 3 or (failed == tries and tries >= count):
                if nets:
                    break
                raise
            continue
        failed = 0
        key = outline_key(net)
        if key in seen:
            continue
        seen.add(key)
        from voxfab.shape import fill_cavities

        report = validate(fill_cavities(grid) if net.filled else grid, net)
        if not report.ok:  # pragma: no cover - the engine validates its own nets
            continue
        nets.append(net)
        job.step(len(nets), count, f"{len(nets)} of {count} nets")
    job.data["nets"] = nets
    job.data["grid"] = grid  # for /api/nets/edit
    from ._edit import net_layout as edited_layout
    job.result = {
        "asked": count,
        "found": len(nets),
        "tries": tries,
        "seconds": round(time.monotonic() - start, 3),
        "nets": [
            {
                "index": i, "seed": int(n.seed), "faces": n.face_count, "mountain": int(n.mountain),
                "valley": int(n.valley), "seams_without_tab_room": int(n.seams_without_tab_room),
                "fit": sheet_fit(n, sheet=sheet, face_mm=face_mm), "layout": edited_layout(grid, n),
            }
            for i, n in enumerate(nets)
        ],
    }


def warm_up() -> None:
    """Compile (or load from numba's cache) every kernel group in this process, so the first real request is not slowed.

    numba compiles on the first call in each process, and that time would otherwise
    count against the artist's first preview or the first net's budget.
    """
    from voxfab.errors import VoxfabError
    from voxfab.warmup import warm_up as warm_kernels

    try:
        warm_kernels(processes=1)  # here, not in child processes: this process serves the requests
    except VoxfabError:  # pragma: no cover - the warm-up jobs are fixed and valid
        pass


# --- fabrication files ------------------------------------------------------------------------

def _zip(folder: Path, files: list[Path], target: Path) -> Path:
    # fixed dates and order: the same shape gives the same archive
    with zipfile.ZipFile(target, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for f in sorted(files):
            info = zipfile.ZipInfo(f.relative_to(folder).as_posix(), date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, f.read_bytes())
    return target


def _one(job: Job, name: str, paths: list[Path]) -> None:
    """Offer one download: the file itself, or a zip of several (a net over several sheets)."""
    if len(paths) == 1:
        job.files.append((name if paths[0].suffix == Path(name).suffix else paths[0].name, paths[0]))
        return
    stem = Path(name).stem
    job.files.append((f"{stem}.zip", _zip(job.folder, paths, job.folder / f"{stem}.zip")))


#: Most triangles of an assembly sent to the page's 3D view.
MAX_VIEW_TRIANGLES = 200_000


def assembly_triangles(path: Path) -> dict[str, Any]:
    """The plates of an ``assembly.3mf`` as flat triangle lists (mm), one per plate, for the page's 3D view."""
    import trimesh

    scene = trimesh.load(path, force="scene")
    plates = []
    total = 0
    for node in sorted(scene.graph.nodes_geometry):
        transform, geometry_name = scene.graph[node]
        mesh = scene.geometry[geometry_name]
        tris = trimesh.transform_points(np.asarray(mesh.vertices), transform)[np.asarray(mesh.faces)]
        name = node
        total += len(tris)
        if total > MAX_VIEW_TRIANGLES:
            raise InvalidShapeError(f"assembly: over {MAX_VIEW_TRIANGLES:,} triangles to show")
        plates.append({"name": str(name), "triangles": np.round(tris.reshape(-1), 3).tolist()})
    return {"plates": plates}


def download_settings(artefact: str, values: dict[str, Any]) -> Any:
    """The checked settings of one download, by the output's own options dataclass (as a recipe's)."""
    from voxfab.fabricate import output_for_download

    row = output_for_download(artefact)
    assert row.download_table is not None
    return row.settings(row.download_table(artefact, values))


def make_files(job: Job, grid: np.ndarray, *, artefact: str, title: str, pitch: float, net: Any,
               settings: Any, tube: tuple[dict[str, Any], Path] | None = None) -> None:
    """Write one artefact of the shape into the job's folder through its pipeline in the table of outputs."""
    from voxfab.fabricate import BuildContext, output_for_download
    from voxfab.shape import VoxelShape

    row = output_for_download(artefact)
    shape = VoxelShape(grid, pitch)
    out = job.folder / "made"
    out.mkdir(exist_ok=True)
    stem = title.replace(" ", "_")
    job.step(0, 1, f"making {artefact}")
    if row.maker == "tube" and tube is None:
        raise InvalidShapeError("animation: only a drawn tube has a turning profile; choose Tube in Draw")
    params, folder = tube if tube is not None else ({}, None)
    context = BuildContext(maker="tube" if tube is not None else None, params=params, base_dir=folder, net=net,
                           paper_at_pitch=False)
    try:
        made = row.run(shape, settings, out, name=title, seed=0, context=context)
    finally:
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)
    job.result["warnings"] = list(made.warnings)
    assembly = next((out / f.path for f in made.files if f.path.endswith("assembly.3mf")), None)
    if assembly is not None:
        job.result["assembly"] = assembly_triangles(assembly)
    stem_of, ext = artefact.rsplit(".", 1)
    if ext == "zip":  # the whole folder the output wrote (the plates and their sheets)
        files = [out / f.path for f in made.files]
        job.files.append((f"{stem}-{stem_of}.zip", _zip(out, files, job.folder / f"{stem}-{stem_of}.zip")))
    else:
        # The files of the asked kind: one, or several sheets (zipped).
        files = [out / f.path for f in made.files if f.path.endswith(f".{ext}") and f.path.startswith(stem_of)]
        name = f"{stem}.{ext}" if row.name == "mesh" else f"{stem}-{artefact}"
        _one(job, name, files)
    job.step(1, 1, "done")
