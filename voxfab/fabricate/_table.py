"""The one table of outputs: each output's name, options, pipeline function and the files it writes.

Recipes (``[outputs.NAME]``), the CLI, the studio's downloads, batch runs, the
warm-up and the README's option tables all read :func:`outputs`; nothing else
lists outputs.  A new output is one module with its pipeline and options, and
one row here.

The rows name their options classes and pipelines by import path, resolved on
first use: the table loads nothing heavy, and ``fabricate`` keeps no import of
the packages above it (``render`` makes the pictures and the animation).
"""

from __future__ import annotations

import dataclasses
import importlib
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from voxfab._shared.options import from_mapping, option_specs

from ._outputs import Artefact, OutputFile

__all__ = ["Output", "OptionTable", "BuildContext", "outputs", "output_for_download", "resolve", "build_order"]


def resolve(path: str | Any) -> Any:
    """The object named ``"package.module:name"`` (an object given itself is returned as it is)."""
    if not isinstance(path, str):
        return path
    module, _, name = path.partition(":")
    return getattr(importlib.import_module(module), name)


@dataclasses.dataclass(frozen=True)
class OptionTable:
    """One options dataclass of an output, the recipe keys it hides, and its README table's marker."""

    cls: str | type
    readme: str
    exclude: tuple[str, ...] = ()

    def keys(self) -> tuple[str, ...]:
        """The recipe keys of this class."""
        return tuple(s.name for s in option_specs(resolve(self.cls)) if s.recipe and s.name not in self.exclude)


@dataclasses.dataclass(frozen=True)
class BuildContext:
    """What an output may need beyond the shape and its options.

    A build starts from the source's fields; each output then adds what its row
    :attr:`Output.gives` to the context of the outputs after it.

    Attributes
    ----------
    maker, params, base_dir
        The source that made the shape (the animation re-runs a tube maker):
        maker name (None for a file), its parameters, and the folder its file
        names are relative to.
    net : Net or sequence of Net, optional
        A net, or its pieces, chosen already (the studio's gallery pick, or what the
        build's net output gave): the net output draws it instead of searching, the
        pictures show it when it is in one piece.
    paper_at_pitch : bool
        A net without a ``face_size`` is drawn at the shape's pitch, so the paper
        model is the printed object (a recipe's one-scale rule); False lets the net
        pipeline choose the face size for the sheet (the studio's default).
    placement : voxfab.fabricate.netdraw.Placement, optional
        Where the pieces of ``net`` go on the sheets (the studio's layout).
    """

    maker: str | None = None
    params: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    base_dir: Path | None = None
    net: Any = None
    paper_at_pitch: bool = True
    placement: Any = None


#: What an output may use: the fields of :class:`BuildContext`.
_CONTEXT_FIELDS = frozenset(f.name for f in dataclasses.fields(BuildContext))


@dataclasses.dataclass(frozen=True)
class Output:
    """One row of the table.

    Attributes
    ----------
    name : str
        ``[outputs.NAME]`` in a recipe.
    options : tuple of OptionTable
        Its options dataclasses (the net has two: the search and the drawing).
    pipeline : str
        Import path of the pipeline function that makes it (the one the CLI command calls).
    files : tuple of str
        The files it writes, relative to the output folder (``*`` for numbered sheets).
    run : callable
        ``run(shape, settings, outdir, *, name, seed, context) -> Artefact``: the pipeline
        called with checked settings.
    parse : callable, optional
        ``parse(table) -> settings``; by default the one options class reads the table.
    downloads : tuple of str
        The files the studio's Make tab offers for it.
    download_table : callable, optional
        ``download_table(download, values) -> table``: the recipe-style table that
        makes one download from the studio's values (checked by :attr:`parse`).
    maker : str, optional
        The source maker it needs (the animation re-runs a tube), checked when a recipe is read.
    unfolds : bool
        It may search a net (the build compiles the net engine aside first).
    warm_group : str, optional
        The warm-up kernel group of its compiled code (``voxfab warmup --group``).
    warm : callable, optional
        ``warm(folder)``: a small run of the pipeline that compiles that group.
    kernels : tuple of (module, function)
        The compiled kernels of that group, to tell whether numba's cache holds them.
    command : str, optional
        The ``voxfab`` command that makes it alone (``voxfab mesh``, ``voxfab render``...).
    gives : tuple of str
        What its run makes for the outputs after it and for the build's caller, by
        name, in its :attr:`Artefact.gives`: the net output gives ``"net"`` (a
        :class:`BuildContext` field, which the outputs after it read), the hunt
        ``"hunt_net"`` and ``"zipper_net"`` (the batch's thumbnails draw them).
    uses : tuple of str
        The :class:`BuildContext` fields, given by other outputs, that it draws on when
        they are set (the pictures use ``"net"``): a build runs it after the outputs that give them.
    """

    name: str
    options: tuple[OptionTable, ...]
    pipeline: str
    files: tuple[str, ...]
    run: Callable[..., Artefact]
    parse: Callable[[Mapping[str, Any]], Any] | None = None
    downloads: tuple[str, ...] = ()
    download_table: Callable[[str, Mapping[str, Any]], dict[str, Any]] | None = None
    maker: str | None = None
    unfolds: bool = False
    warm_group: str | None = None
    warm: Callable[[Path], None] | None = None
    kernels: tuple[tuple[str, str], ...] = ()
    command: str | None = None
    gives: tuple[str, ...] = ()
    uses: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for name in self.uses:
            if name not in _CONTEXT_FIELDS:
                raise ValueError(f"output {self.name}: {name!r} is not a BuildContext field")

    def pass_on(self, made: Artefact, context: BuildContext) -> BuildContext:
        """``context`` with what ``made`` (this output's run) gives the outputs after it."""
        if set(made.gives) != set(self.gives):
            raise RuntimeError(f"output {self.name}: its run gave {sorted(made.gives)}, its row declares "
                               f"{sorted(self.gives)}")
        return dataclasses.replace(context, **{k: v for k, v in made.gives.items() if k in _CONTEXT_FIELDS})

    @property
    def keys(self) -> tuple[str, ...]:
        """Every recipe key of the output."""
        return tuple(k for t in self.options for k in t.keys())

    def settings(self, table: Mapping[str, Any]) -> Any:
        """Checked settings from a recipe-style table (``OptionError`` or ``VoxfabError`` when bad)."""
        if self.parse is not None:
            return self.parse(table)
        return from_mapping(resolve(self.options[0].cls), table)


# ---- mesh ---------------------------------------------------------------------------------------

def _run_mesh(shape: Any, options: Any, outdir: Path, *, name: str, seed: int, context: BuildContext) -> Artefact:
    from voxfab.fabricate.mesh import fabricate_mesh

    del seed, context  # a mesh is deterministic
    made = fabricate_mesh(shape, options, outdir / f"mesh.{options.format}", name=name,
                          report_path=outdir / "mesh.json")
    if options.size is not None:
        # One object in every medium unless the recipe names another scale: say so when it does.
        pitch = made.report["pitch_mm"]
        note = (f"printed at size = {options.size:g} mm ({pitch:.4g} mm per voxel), {pitch / shape.pitch:.3g} x "
                f"the recipe's pitch of {shape.pitch:g} mm")
        made = dataclasses.replace(made, warnings=(note, *made.warnings))
    return made


def _given(values: Mapping[str, Any], download: str, fixed: Mapping[str, Any]) -> dict[str, Any]:
    """The studio's values of one download as a recipe table: every one kept (the output's options class
    refuses the unknown), ``None`` meaning the default, the download's own settings not overridable."""
    from voxfab._shared.options import OptionError

    for key in fixed:
        if key in values:
            raise OptionError(key, f"set by the download {download}, not by an option")
    return {**fixed, **{k: v for k, v in values.items() if v is not None}}


def _mesh_download(download: str, values: Mapping[str, Any]) -> dict[str, Any]:
    return _given(values, download, {"format": download.rsplit(".", 1)[1]})


# ---- slices -------------------------------------------------------------------------------------

def _run_slices(shape: Any, options: Any, outdir: Path, *, name: str, seed: int, context: BuildContext) -> Artefact:
    from voxfab.fabricate.plates import fabricate_plates

    del seed, context  # plates are deterministic
    art = fabricate_plates(shape, options, outdir / "slices", name=name)
    files = tuple(OutputFile(f"slices/{f.path}", f.purpose) for f in art.files)
    return dataclasses.replace(art, files=files)


def _slices_download(download: str, values: Mapping[str, Any]) -> dict[str, Any]:
    from voxfab._shared.options import OptionError

    table = _given(values, download, {})
    if "plate_sheet" in table:  # the page's name of the plates' sheet (its net has a sheet of its own)
        if "sheet" in table:
            raise OptionError("plate_sheet", "the plates' sheet given twice, as sheet and plate_sheet")
        table["sheet"] = table.pop("plate_sheet")
    return table


# ---- pictures -----------------------------------------------------------------------------------

def _run_pictures(shape: Any, options: Any, outdir: Path, *, name: str, seed: int,
                  context: BuildContext) -> Artefact:
    render_pictures = resolve(outputs()["pictures"].pipeline)  # render sits above fabricate: named, not imported

    # A net in pieces (a gallery pick, the net output's gift) is drawn as its pieces, each with its outline.
    return render_pictures(shape, options, outdir, name=name, seed=seed, net=context.net)


def _pictures_download(download: str, values: Mapping[str, Any]) -> dict[str, Any]:
    return {"size": 600, **_given(values, download, {"views": [], "triptych": True})}


# ---- net ----------------------------------------------------------------------------------------

#: Drawing options that are not recipe keys: the face size is ``face_size``; the rest are internal.
_DRAWING_HIDDEN = ("pitch", "title_height", "heading")


@dataclasses.dataclass(frozen=True)
class NetSettings:
    """The net output's checked options: the search and the drawing."""

    net: Any
    drawing: Any


def _parse_net(table: Mapping[str, Any]) -> NetSettings:
    from voxfab._shared.options import OptionError, check_values
    from voxfab.fabricate.netdraw import DrawingOptions, NetOptions

    net_keys = set(OptionTable("voxfab.fabricate.netdraw:NetOptions", "net").keys())
    drawing_keys = set(OptionTable("voxfab.fabricate.netdraw:DrawingOptions", "net-drawing", _DRAWING_HIDDEN).keys())
    for key in table:
        if key not in net_keys | drawing_keys:
            raise OptionError(str(key), f"unknown option; accepted: {', '.join(sorted(net_keys | drawing_keys))}")
    net = from_mapping(NetOptions, {k: v for k, v in table.items() if k in net_keys})
    drawing_values = check_values(DrawingOptions, {k: v for k, v in table.items() if k in drawing_keys})
    return NetSettings(net, DrawingOptions(pitch=net.face_size, **drawing_values))


def _run_net(shape: Any, settings: NetSettings, outdir: Path, *, name: str, seed: int,
             context: BuildContext) -> Artefact:
    from voxfab.fabricate.netdraw import fabricate_net

    drawing = settings.drawing
    if settings.net.face_size is None and context.paper_at_pitch:
        # One scale for the whole object: the paper faces are the print's voxels unless the
        # recipe gives another face size.
        drawing = dataclasses.replace(drawing, pitch=shape.pitch)
    made = fabricate_net(shape, settings.net, drawing, outdir, name=name, seed=seed, chosen=context.net,
                         placement=context.placement)
    face = settings.net.face_size
    if face is not None and abs(face - shape.pitch) > 1e-9 * shape.pitch:
        note = (f"the paper model is at face_size = {face:g} mm, {face / shape.pitch:.3g} x the recipe's pitch "
                f"of {shape.pitch:g} mm")
        made = dataclasses.replace(made, warnings=(note, *made.warnings))
    return made


def _net_download(download: str, values: Mapping[str, Any]) -> dict[str, Any]:
    # The page's options by the recipe's names (face_mm: the page's older name of face_size); the
    # options of other outputs on the page are not the net's.
    from voxfab._shared.options import OptionError

    ext = download.rsplit(".", 1)[1]
    table = _given(values, download, {"formats": [] if ext == "json" else [ext]})
    if "face_mm" in table:
        if "face_size" in table:
            raise OptionError("face_mm", "the face size given twice, as face_size and face_mm")
        table["face_size"] = table.pop("face_mm")
    return table


# ---- hunt ---------------------------------------------------------------------------------------

def _run_hunt(shape: Any, options: Any, outdir: Path, *, name: str, seed: int, context: BuildContext) -> Artefact:
    from voxfab.fabricate.hunt import fabricate_hunt

    del context  # the hunt searches its own nets: a chosen net answers none of its questions
    return fabricate_hunt(shape, options, outdir, name=name, seed=seed)


# ---- animation ----------------------------------------------------------------------------------

def _run_animation(shape: Any, options: Any, outdir: Path, *, name: str, seed: int,
                   context: BuildContext) -> Artefact:
    render_animation = resolve(outputs()["animation"].pipeline)  # as for the pictures

    del name, seed
    return render_animation(shape, options, outdir, maker=context.maker, params=context.params,
                            base_dir=context.base_dir)


def _animation_download(download: str, values: Mapping[str, Any]) -> dict[str, Any]:
    return {"size": 400, **_given(values, download, {})}


# ---- warm-up runs: small real runs that compile an output's kernels --------------------------------

def _warm_mesh(folder: Path) -> None:
    from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh
    from voxfab.shape import VoxelShape, examples

    fabricate_mesh(VoxelShape(examples.torus(5, 2)), MeshOptions(), folder / "mesh.3mf", name="warm-up")


#: Seconds the warm-up's net search may take, its kernels' first compile included.
WARM_NET_TIMEOUT = 1800.0


def _warm_net(folder: Path) -> None:
    from voxfab.fabricate.netdraw import DrawingOptions, NetOptions, fabricate_net
    from voxfab.shape import VoxelShape, examples

    # More faces than the net engine leaves to its plain-Python kernels, and tabs to make room for.
    shape = VoxelShape(examples.ball(4))
    # The search's clock runs while its kernels compile (minutes of a loaded machine's wall time): no budget
    # that a slow compile could use up.
    fabricate_net(shape, NetOptions(formats=("svg",), timeout=WARM_NET_TIMEOUT), DrawingOptions(pitch=10.0), folder,
                  name="warm-up", seed=0)


# ---- the table ----------------------------------------------------------------------------------

def _table() -> dict[str, Output]:
    rows = [
        Output("animation", (OptionTable("voxfab.render:AnimationOptions", "animation"),),
               "voxfab.render:render_animation", ("animation.gif",), _run_animation,
               downloads=("animation.gif",), download_table=_animation_download, maker="tube", command="render"),
        Output("hunt", (OptionTable("voxfab.fabricate.hunt:HuntOptions", "hunt"),),
               "voxfab.fabricate.hunt:fabricate_hunt", ("hunt.json", "hunt-net.json", "hunt-zipper.json"),
               _run_hunt, unfolds=True, command="build", gives=("hunt_net", "zipper_net")),
        Output("mesh", (OptionTable("voxfab.fabricate.mesh:MeshOptions", "mesh"),),
               "voxfab.fabricate.mesh:fabricate_mesh", ("mesh.3mf", "mesh.stl", "mesh.obj", "mesh.mtl", "mesh.glb",
                                                        "mesh.ply", "mesh.json"),
               _run_mesh, downloads=("mesh.3mf", "mesh.stl"), download_table=_mesh_download, command="mesh",
               warm_group="print", warm=_warm_mesh,
               kernels=(("voxfab.fabricate.mesh._contact_scan", "contact_scan"),
                        ("voxfab.fabricate.mesh._rectangles", "rectangle_mesh"),
                        ("voxfab.fabricate.mesh._edges", "edge_fan_shells"))),
        Output("net", (OptionTable("voxfab.fabricate.netdraw:NetOptions", "net"),
                       OptionTable("voxfab.fabricate.netdraw:DrawingOptions", "net-drawing", _DRAWING_HIDDEN)),
               "voxfab.fabricate.netdraw:fabricate_net", ("net.json", "net*.svg", "net*.dxf", "net*.pdf", "net*.png"),
               _run_net, parse=_parse_net, downloads=("net.svg", "net.dxf", "net.pdf", "net.json"),
               download_table=_net_download, unfolds=True, warm_group="net", warm=_warm_net, command="net",
               kernels=(("voxfab.unfold._growth", "grow"), ("voxfab.unfold._tabroom", "anneal")),
               gives=("net",), uses=("net",)),
        Output("pictures", (OptionTable("voxfab.render:PictureOptions", "pictures"),),
               "voxfab.render:render_pictures", ("render_*.png", "turntable.gif", "slices.png", "net_picture.png",
                                                 "triptych.png", "triptych.pdf"),
               _run_pictures, downloads=("triptych.png", "triptych.pdf"), download_table=_pictures_download,
               unfolds=True, command="render", uses=("net",)),
        Output("slices", (OptionTable("voxfab.fabricate.plates:PlateOptions", "slices"),),
               "voxfab.fabricate.plates:fabricate_plates", ("slices/*",), _run_slices,
               downloads=("plates.zip",), download_table=_slices_download, command="slices"),
    ]
    return {row.name: row for row in rows}


#: Output name → :class:`Output`, filled on first use.
OUTPUTS: dict[str, Output] = {}


def outputs() -> dict[str, Output]:
    """The outputs by name, in name order."""
    if not OUTPUTS:
        OUTPUTS.update(_table())
    return OUTPUTS


def build_order(names: Iterable[str]) -> tuple[str, ...]:
    """The outputs ``names`` in the order a build runs them, whatever order they are listed in.

    Each output runs after every other one that gives what it uses (the pictures
    after the net, so they draw the net written); otherwise outputs run in name order.
    """
    rows = outputs()
    left = sorted(set(names))
    order: list[str] = []

    def waits(name: str) -> bool:
        return any(set(rows[name].uses) & set(rows[other].gives) for other in left if other != name)

    while left:
        ready = next((n for n in left if not waits(n)), None)
        if ready is None:
            raise RuntimeError(f"outputs {', '.join(left)}: each uses what another gives")
        order.append(ready)
        left.remove(ready)
    return tuple(order)


def output_for_download(download: str) -> Output:
    """The output whose studio download is ``download`` (``"mesh.3mf"``, ``"plates.zip"``, ...)."""
    from voxfab.errors import InvalidShapeError

    for row in outputs().values():
        if download in row.downloads:
            return row
    offered = [d for row in outputs().values() for d in row.downloads]
    raise InvalidShapeError(f"artefact: expected one of {', '.join(offered)}, got {str(download)[:40]!r}")
