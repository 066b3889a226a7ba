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
    job.result = {
        "asked": count,
        "found": len(nets),
        "tries": tries,
        "seconds": round(time.monotonic() - start, 3),
        "nets": [
            {
                "index": i, "seed": int(n.seed), "faces": n.face_count, "mountain": int(n.mountain),
                "valley": int(n.valley), "seams_without_tab_room": int(n.seams_without_tab_room),
                "fit": sheet_fit(n, sheet=sheet, face_mm=face_mm), "layout": net_layout(n, grid),
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
    # NAME-net.svg in sheets: NAME-net-svg.zip, so the SVG, DXF and JSON zips of one net keep apart.
    stem = f"{Path(name).stem}-{Path(name).suffix[1:]}"
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
               settings: Any, tube: tuple[dict[str, Any], Path] | None = None, placement: Any = None) -> None:
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
                           paper_at_pitch=False, placement=placement)
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


# --- nets for a sheet, in one piece or several, with their placement ---------------------------

class NoFitError(InvalidShapeError):
    """No net of the shape fits the sheet as asked; ``ways_out`` lists the choices that would work.

    Each way out is ``{"label": plain words, "options": {option: value}}``: the
    page offers one button per way out, which sets those options and asks again.
    """

    def __init__(self, message: str, ways_out: list[dict[str, Any]]) -> None:
        super().__init__(message)
        self.ways_out = ways_out


def net_settings(values: dict[str, Any]) -> Any:
    """The net output's checked settings (search and drawing) from options by their Python names, as a recipe's."""
    from voxfab.fabricate import output_for_download

    return output_for_download("net.json").settings({**values, "formats": []})


def check_one_piece(grid: np.ndarray) -> None:
    """Refuse an empty shape, or one of several pieces, before a net search."""
    from voxfab.shape import well_formed_reasons

    reasons = well_formed_reasons(grid)
    if any("piece" in r for r in reasons) or not grid.any():
        raise InvalidShapeError("shape: a net needs one piece of face-connected voxels: "
                                + "; ".join(reasons or ["the shape is empty"]))


def ways_out(err: Exception, net: Any, drawing: Any, faces: int) -> list[dict[str, Any]]:
    """The choices that would give a net after ``err`` (a refused fit or face size), in the CLI's order.

    A net that does not fit the sheet (:class:`~voxfab.fabricate.netdraw.SheetFitError`):
    split into pieces, the smallest sheet that takes it, the largest face size
    at which it fits this sheet (when its marks stay legible).  Faces given too
    small for legible marks: the smallest face size that works.  A face size
    left to the pipeline that comes out too small, or a one-piece search that
    ran out of time: split into pieces.
    """
    from voxfab.fabricate.netdraw import SheetFitError
    from voxfab.fabricate.netdraw._labels import label_length
    from voxfab.fabricate.netdraw._legible import legibility_problem, smallest_face_size

    split = [{"label": "split into pieces", "options": {"pieces": "auto"}}] if net.pieces != "auto" else []
    # A one-piece net has at most F + 1 seams; pieces label seams by their surface edge, of which there are 2F.
    chars = label_length(2 * faces if net.pieces == "auto" else faces + 1)
    if isinstance(err, SheetFitError):
        out = list(split)
        if err.smallest_sheet:
            out.append({"label": f"use a larger sheet: {err.smallest_sheet}", "options": {"sheet": err.smallest_sheet}})
        size = err.largest_face_size
        if size > 0 and legibility_problem(drawing, size, chars) is None:
            out.append({"label": f"smaller faces: {size:g} mm", "options": {"face_size": size}})
        return out
    if drawing.pitch is not None and legibility_problem(drawing, float(drawing.pitch), chars):
        size = smallest_face_size(drawing, chars)
        return [{"label": f"larger faces: {size:g} mm", "options": {"face_size": size}}]
    return split


def pieces_layout(pieces: list[Any], grid: np.ndarray) -> dict[str, Any]:
    """The contract's LAYOUT of a net given as its pieces: every surface face by id, in its piece's own frame."""
    from voxfab.fabricate.netdraw._geometry import face_map
    from voxfab.shape import fill_cavities, surface_graph

    sg = surface_graph(fill_cavities(grid) if pieces[0].filled else grid)
    n = sg.face_count
    corners = np.zeros((n, 4, 2), dtype=np.int64)
    piece = np.full(n, -1, dtype=np.int64)
    folds = []
    for q, p in enumerate(pieces):
        fid = face_map(sg, p)
        corners[fid] = p.corners2d
        piece[fid] = q
        folds.append(fid[p.folds.reshape(-1, 2)])
    faces = [[int(v[0]), int(v[1]), int(v[2]), _DIRS[int(d)]] for v, d in zip(sg.voxel, sg.direction)]
    return {"faces": faces, "corners": corners.reshape(-1).tolist(),
            "folds": np.concatenate(folds).reshape(-1).tolist(), "neighbor": sg.neighbor.reshape(-1).tolist(),
            "fold_type": sg.fold.reshape(-1).tolist(), "piece": piece.tolist()}


def sheet_gallery(job: Job, grid: np.ndarray, *, count: int, seed: int, net: Any, drawing: Any,
                  constraints: Any) -> None:
    """Nets of ``grid`` that fit the sheet, by the net pipeline's own search (``find_sheet_nets``).

    One-piece nets come ``count`` distinct ones at a time; a net that has to be
    split (``pieces="auto"``) comes as one net in pieces.  Each carries its
    layout and the placement of its pieces on the sheets, which the page shows
    and the artist may change before making the files.  A net that does not fit
    ends the job with the pipeline's message and its ways out.
    """
    from voxfab.errors import UnfoldError
    from voxfab.fabricate.netdraw import SheetFitError, find_sheet_nets
    from voxfab.fabricate.netdraw._placement import placement_for
    from voxfab.fabricate.netdraw._sheets import fit_error
    from voxfab.shape import fill_cavities, surface_graph

    search: dict[str, Any] = {"strategy": net.strategy, "timeout": net.timeout, "fill": net.fill,
                              "compact": net.compact}
    if constraints is not None:
        search["constraints"] = constraints
    start = time.monotonic()
    job.step(0, count, "searching nets")
    faces = surface_graph(fill_cavities(grid) if net.fill else grid).face_count
    try:
        found = find_sheet_nets(grid, drawing, rng=seed, pieces=net.pieces,
                                count=1 if net.pieces == "auto" else count,
                                budget=min(net.budget, MAX_GALLERY_SECONDS), **search)
    except (SheetFitError, InvalidShapeError, UnfoldError) as exc:
        err: Exception = exc
        extent = getattr(exc, "best_extent", None)
        if extent is not None and drawing.pitch is not None and not isinstance(exc, SheetFitError):
            # Several one-piece nets asked for and none fits: say it as for one net, with what would fit.
            err = fit_error((int(extent[0]), int(extent[1])), drawing, float(drawing.pitch),
                            what="the most compact net found")
        options = ways_out(err, net, drawing, faces)
        if not options:
            if err is exc:
                raise
            raise err from None
        raise NoFitError(str(err), options) from None
    settled = found.options
    job.data["nets"] = [n if len(n) > 1 else n[0] for n in found.nets]
    items = []
    for i, pieces in enumerate(found.nets):
        placement = placement_for(pieces, settled)
        per_sheet = np.zeros(placement.sheets)
        for place, p in zip(placement.pieces, pieces):
            per_sheet[place.sheet] += p.face_count
        w, h = settled.sheet_size
        f = float(settled.pitch)
        # The share of each sheet under faces (the drawing adds its tabs when the files are made).
        items.append({
            "index": i, "seed": int(pieces[0].seed), "faces": sum(p.face_count for p in pieces),
            "pieces": len(pieces),
            "fit": {"sheet": settled.sheet, "face_size": f, "sheets": placement.sheets,
                    "fill": [round(float(k) * f * f / (w * h), 4) for k in per_sheet], "fits": True},
            "layout": pieces_layout(pieces, grid), "placement": placement.to_dict(),
        })
        job.step(i + 1, len(found.nets), f"{i + 1} of {len(found.nets)} nets laid out")
    job.result = {"asked": count, "found": len(items), "seconds": round(time.monotonic() - start, 3),
                  "options": {"face_size": float(settled.pitch), "sheet": settled.sheet, "pieces": net.pieces},
                  "notes": list(found.notes), "nets": items}
