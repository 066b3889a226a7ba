"""The recipe outputs: each ``[outputs.NAME]`` table → its options object → its artefact pipeline.

Every output is listed here with explicit imports of the package that makes it;
the recipe keys are the fields of that package's options dataclass, so a recipe
is checked, values and all, before anything is built (``voxfab build --check``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from voxfab._shared.options import OptionError, check_values, from_mapping, option_specs
from voxfab.fabricate import Artefact, OutputFile
from voxfab.shape import VoxelShape


@dataclasses.dataclass(frozen=True)
class OutputKind:
    """One recipe output.

    Attributes
    ----------
    name : str
        The table name, ``[outputs.NAME]``.
    keys : tuple of str
        The recipe keys it accepts.
    parse : callable
        ``parse(table) -> settings``: checked options; raises ``OptionError`` or
        another ``VoxfabError`` for a bad value.
    run : callable
        ``run(shape, settings, outdir, name=..., seed=..., recipe=...) -> Artefact``; ``recipe``
        is the :class:`Recipe` being built (an animation re-runs its maker).
    maker : str or None
        The source maker the output needs (the animation re-runs a tube), checked
        when the recipe is read; None for outputs of any shape.
    """

    name: str
    keys: tuple[str, ...]
    parse: Callable[[Mapping[str, Any]], Any]
    run: Callable[..., Artefact]
    maker: str | None = None


def _recipe_keys(cls: type, *, exclude: tuple[str, ...] = ()) -> tuple[str, ...]:
    return tuple(s.name for s in option_specs(cls) if s.recipe and s.name not in exclude)


def _parse_with(cls: type) -> Callable[[Mapping[str, Any]], Any]:
    return lambda table: from_mapping(cls, table)


# ---- mesh ---------------------------------------------------------------------------------------

def _run_mesh(shape: VoxelShape, options: Any, outdir: Path, *, name: str, seed: int, recipe: Any) -> Artefact:
    from voxfab.fabricate.mesh import fabricate_mesh

    del seed, recipe  # a mesh is deterministic
    made = fabricate_mesh(shape, options, outdir / f"mesh.{options.format}", name=name,
                          report_path=outdir / "mesh.json")
    if options.size is not None:
        # One object in every medium unless the recipe names another scale: say so when it does.
        pitch = made.report["pitch_mm"]
        note = (f"printed at size = {options.size:g} mm ({pitch:.4g} mm per voxel), {pitch / shape.pitch:.3g} x "
                f"the recipe's pitch of {shape.pitch:g} mm")
        made = dataclasses.replace(made, warnings=(note, *made.warnings))
    return made


# ---- slices -------------------------------------------------------------------------------------

def _run_slices(shape: VoxelShape, options: Any, outdir: Path, *, name: str, seed: int, recipe: Any) -> Artefact:
    from voxfab.fabricate.plates import fabricate_plates

    del seed, recipe  # plates are deterministic
    art = fabricate_plates(shape, options, outdir / "slices", name=name)
    files = tuple(OutputFile(f"slices/{f.path}", f.purpose) for f in art.files)
    return dataclasses.replace(art, files=files)


# ---- pictures -----------------------------------------------------------------------------------

def _run_pictures(shape: VoxelShape, options: Any, outdir: Path, *, name: str, seed: int, recipe: Any) -> Artefact:
    from voxfab.render import render_pictures
    from voxfab.unfold import Net

    del recipe

    # The build runs the `net` output before this one: the triptych and the net picture
    # draw that very net instead of searching again (a search may take a while on large shapes).
    net_file = outdir / "net.json"
    wants_net = options.triptych or options.net_picture
    net = Net.from_json(net_file.read_text()) if wants_net and net_file.exists() else None
    return render_pictures(shape, options, outdir, name=name, seed=seed, net=net)


# ---- net ----------------------------------------------------------------------------------------

#: Drawing options that are not recipe keys: the face size is ``face_size``; the rest are internal.
_DRAWING_HIDDEN = ("pitch", "title_height", "heading")


@dataclasses.dataclass(frozen=True)
class NetSettings:
    """The net output's checked options: the search and the drawing."""

    net: Any
    drawing: Any


def _parse_net(table: Mapping[str, Any]) -> NetSettings:
    from voxfab.fabricate.netdraw import DrawingOptions, NetOptions

    net_keys = set(_recipe_keys(NetOptions))
    drawing_keys = set(_recipe_keys(DrawingOptions, exclude=_DRAWING_HIDDEN))
    for key in table:
        if key not in net_keys | drawing_keys:
            raise OptionError(str(key), f"unknown option; accepted: {', '.join(sorted(net_keys | drawing_keys))}")
    net = from_mapping(NetOptions, {k: v for k, v in table.items() if k in net_keys})
    drawing_values = check_values(DrawingOptions, {k: v for k, v in table.items() if k in drawing_keys})
    return NetSettings(net, DrawingOptions(pitch=net.face_size, **drawing_values))


def _run_net(shape: VoxelShape, settings: NetSettings, outdir: Path, *, name: str, seed: int,
             recipe: Any) -> Artefact:
    from voxfab.fabricate.netdraw import fabricate_net

    del recipe
    drawing = settings.drawing
    if settings.net.face_size is None:
        # One scale for the whole object: the paper faces are the print's voxels unless the
        # recipe gives another face size.
        drawing = dataclasses.replace(drawing, pitch=shape.pitch)
    made = fabricate_net(shape, settings.net, drawing, outdir, name=name, seed=seed)
    face = settings.net.face_size
    if face is not None and abs(face - shape.pitch) > 1e-9 * shape.pitch:
        note = (f"the paper model is at face_size = {face:g} mm, {face / shape.pitch:.3g} x the recipe's pitch "
                f"of {shape.pitch:g} mm")
        made = dataclasses.replace(made, warnings=(note, *made.warnings))
    return made


# ---- animation ----------------------------------------------------------------------------------

def _run_animation(shape: VoxelShape, options: Any, outdir: Path, *, name: str, seed: int,
                   recipe: Any) -> Artefact:
    from voxfab.render._animate import recipe_output

    o = options
    files = recipe_output(shape, outdir, name=name, seed=seed, source=recipe.source, base_dir=recipe.base_dir,
                          steps=o.steps, turn=o.turn, view=o.view, size=o.size, duration_ms=o.duration_ms)
    return Artefact(tuple(files))


def _net_keys() -> tuple[str, ...]:
    from voxfab.fabricate.netdraw import DrawingOptions, NetOptions

    return _recipe_keys(NetOptions) + _recipe_keys(DrawingOptions, exclude=_DRAWING_HIDDEN)


def _outputs() -> dict[str, OutputKind]:
    from voxfab.fabricate.mesh import MeshOptions
    from voxfab.fabricate.plates import PlateOptions
    from voxfab.render import AnimationOptions, PictureOptions

    return {
        "animation": OutputKind("animation", _recipe_keys(AnimationOptions), _parse_with(AnimationOptions),
                                _run_animation, maker="tube"),
        "mesh": OutputKind("mesh", _recipe_keys(MeshOptions), _parse_with(MeshOptions), _run_mesh),
        "net": OutputKind("net", _net_keys(), _parse_net, _run_net),
        "pictures": OutputKind("pictures", _recipe_keys(PictureOptions), _parse_with(PictureOptions),
                               _run_pictures),
        "slices": OutputKind("slices", _recipe_keys(PlateOptions), _parse_with(PlateOptions), _run_slices),
    }


#: Output name → :class:`OutputKind`, filled on first use (the packages load only when a recipe is read).
OUTPUTS: dict[str, OutputKind] = {}


def outputs() -> dict[str, OutputKind]:
    """The recipe outputs by name."""
    if not OUTPUTS:
        OUTPUTS.update(_outputs())
    return OUTPUTS
