"""The studio's heavy work: a gallery of distinct nets, and the fabrication files of the current shape.

Both run inside a :class:`~voxfab.studio._jobs.Job` on a worker thread and call
the same library functions as the CLI: ``voxfab.unfold.unfold`` and
``validate`` (``voxfab net``), ``netdraw.write_net_drawing`` (``voxfab net -o
NET.svg``), and the recipe outputs ``mesh``, ``slices`` and ``pictures``
(``voxfab build``).
"""

from __future__ import annotations

import io
import shutil
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from voxfab.errors import InvalidShapeError

from ._jobs import Job

#: Most nets in a gallery, and its default budget in seconds (the search options are NetOptions').
MAX_NETS = 12
MAX_GALLERY_SECONDS = 180.0


def artefacts() -> list[str]:
    """The files the page can ask for: the studio downloads of the table of outputs."""
    from voxfab.fabricate import outputs

    return [d for row in outputs().values() for d in row.downloads]


# --- the net gallery --------------------------------------------------------------------------

#: What the page gets unless it says otherwise: short searches, as a gallery is browsed, not waited for.
GALLERY_DEFAULTS = {"timeout": 5.0, "budget": MAX_GALLERY_SECONDS}


def edge_constraints(data: Any) -> Any:
    """``voxfab.unfold.EdgeConstraints`` from the page's JSON, or None when nothing is marked."""
    if data is None:
        return None
    from voxfab.unfold import EdgeConstraints

    # checked whole (unknown keys, every field) even when it marks nothing, as the CLI checks a file
    marks = EdgeConstraints.from_dict(data)
    return marks or None


class NoNetFitsError(InvalidShapeError):
    """No net of the gallery fits the sheet: the best one's words, and the choices that would work."""

    def __init__(self, message: str, ways_out: list[dict[str, Any]]) -> None:
        super().__init__(message)
        self.ways_out = ways_out


def net_gallery(job: Job, grid: np.ndarray, *, count: int, seed: int, net: Any, drawing: Any,
                constraints: Any) -> None:
    """The library's gallery (:func:`voxfab.fabricate.netdraw.net_gallery`) as a job: nets kept for /api/make.

    Each net goes to ``job.items`` (the page's JSON) and ``job.data["nets"]`` (for /api/make and
    /api/nets/edit) as soon as the library hands it over, so the page shows it while the
    next is made.  A failure that has ways out (faces too small, no fit) carries them to
    the job's status as ``ways_out`` beside the one-line message (:class:`._jobs.Jobs`).
    """
    from voxfab.fabricate import netdraw
    from voxfab.fabricate.netdraw._gallery import gallery_item_json
    from voxfab.shape import fill_cavities, surface_graph

    graphs: dict[bool, Any] = {}
    job.data["grid"] = grid  # for /api/nets/edit
    job.data["nets"] = []

    # The page shows "WHAT (done of total)": the words say what the count counts.
    def searching(done: int, total: int) -> None:
        if done > len(job.items):  # nets found, not yet laid out (one-piece nets are laid out once all are found)
            job.step(done, total, "nets found")

    def made(index: int, item: Any) -> None:
        filled = item.pieces[0].filled
        if filled not in graphs:  # one surface graph for every net of the gallery
            graphs[filled] = surface_graph(fill_cavities(grid) if filled else grid)
        shown = gallery_item_json(index, item, grid, graph=graphs[filled])
        job.data["options"] = (net, drawing.replace(pitch=item.fit["face_size"]))
        job.data["nets"].append(item.pieces)
        job.items.append(shown)  # last: the page may ask for this net once it sees it
        job.step(index + 1, count, "nets made and shown")

    job.step(0, count, "searching nets")
    gallery = netdraw.net_gallery(grid, net, drawing, count=count, seed=seed, constraints=constraints,
                                  progress=searching, on_item=made)
    if gallery.nets and not any(item.fit["fits"] for item in gallery.nets):
        # Nothing to print on this sheet: the page says so in the CLI's words and offers each way out.
        best = gallery.nets[0].fit
        raise NoNetFitsError(best["message"], list(best.get("ways_out", [])))
    job.data["options"] = (net, gallery.options)
    job.step(len(gallery.nets), len(gallery.nets), "nets made and shown")
    job.result = netdraw.gallery_json(gallery, grid, nets=list(job.items))


def warm_kernels_here(scratch: Path) -> None:
    """Compile (or load from numba's cache) every kernel group in this process, so the first real request is not slowed.

    numba compiles on the first call in each process, and that time would otherwise
    count against the artist's first preview or the first net's budget.  The
    pipelines write into ``scratch`` (the session's work folder): a studio stopped
    meanwhile removes their files with its own.
    """
    from voxfab.errors import VoxfabError
    from voxfab.warmup import warm_up

    try:
        warm_up(processes=1, scratch=scratch)  # here, not in child processes: this process serves the requests
        warm_gallery_here()
    except VoxfabError:  # pragma: no cover - the warm-up jobs are fixed and valid
        pass
    except OSError:
        if scratch.is_dir():
            raise
        # the studio stopped and removed its work folder under the warm-up: nothing to warm up for


def warm_gallery_here() -> None:
    """A small gallery in pieces, laid out as the page gets it: the imports and kernels of cutting,
    packing and the page's JSON (seconds of imports on a first call) are loaded before the
    artist's first gallery, whose first net should be on screen within seconds."""
    from voxfab.fabricate import netdraw
    from voxfab.fabricate.netdraw._gallery import gallery_item_json
    from voxfab.shape import examples

    ball = examples.ball(3)
    net, drawing = netdraw.gallery_options({"sheet": "80x80", "face_size": 10, "pieces": "auto", "timeout": 5.0})
    netdraw.net_gallery(ball, net, drawing, count=2, seed=0,
                        on_item=lambda index, item: gallery_item_json(index, item, ball))


# --- fabrication files ------------------------------------------------------------------------

def _zip(named: list[tuple[str, Path]], target: Path) -> Path:
    """A zip of ``(name in the zip, file)`` pairs, written to a temporary name and renamed."""
    from voxfab._shared.atomic import write_bytes

    buf = io.BytesIO()
    # fixed dates and order: the same shape gives the same archive
    with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for arcname, f in sorted(named):
            info = zipfile.ZipInfo(arcname, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, f.read_bytes())
    write_bytes(target, buf.getvalue())
    return target


def _flat_name(prefix: str, path: str) -> str:
    """``PREFIX-REST`` for an output's file ``FOLDER/REST``: named after the shape, no folder of the output's left
    (``slices/sheet-01.dxf`` of the plates: ``queen-plates-sheet-01.dxf``)."""
    parts = Path(path).parts
    return "-".join([prefix, *(parts[1:] if len(parts) > 1 else parts)])


def _one(job: Job, name: str, paths: list[Path], *, shape: str) -> None:
    """Offer one download: the file itself, or a zip of several (a net over several sheets), each named after ``shape``."""
    if len(paths) == 1:
        job.files.append((name if paths[0].suffix == Path(name).suffix else f"{shape}-{paths[0].name}", paths[0]))
        return
    # NAME-net.svg in sheets: NAME-net-svg.zip, so the SVG, DXF and JSON zips of one net keep apart;
    # in it NAME-net.sheet-1.svg and so on, each file named after the shape wherever it is unpacked.
    stem = f"{Path(name).stem}-{Path(name).suffix[1:]}"
    named = [(f"{shape}-{p.name}", p) for p in paths]
    job.files.append((f"{stem}.zip", _zip(named, job.folder / f"{stem}.zip")))


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
        named = [(_flat_name(f"{stem}-{stem_of}", f.path), out / f.path) for f in made.files]
        job.files.append((f"{stem}-{stem_of}.zip", _zip(named, job.folder / f"{stem}-{stem_of}.zip")))
    else:
        # The files of the asked kind: one, or several sheets (zipped).
        files = [out / f.path for f in made.files if f.path.endswith(f".{ext}") and f.path.startswith(stem_of)]
        name = f"{stem}.{ext}" if row.name == "mesh" else f"{stem}-{artefact}"
        _one(job, name, files, shape=stem)
    job.step(1, 1, "done")
