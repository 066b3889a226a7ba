"""Pictures of voxel shapes, all headless: 3D renders, slice sheets, nets, triptychs, GIFs.

* :func:`render` — shaded cubes with dark voxel edges, isometric or from one of six sides.
* :func:`slice_sheet` — the layers in a grid, each numbered.
* :func:`net_picture` — a net with fold styles, glue tabs and seam numbers.
* :func:`triptych` — net | slices | 3D under the shape's name (PNG and PDF).
* :func:`save_turntable`, :func:`save_animation` — GIFs of a turning shape or a sequence of shapes.
* :func:`contact_sheet`, :func:`repository_contact_sheet` — many shapes by volume with names.
* :func:`recipe_output` — the recipe output ``pictures``.
"""

from __future__ import annotations

from pathlib import Path

from voxfab.errors import RecipeError, VoxfabError
from voxfab.fabricate import OutputFile
from voxfab.shape import VoxelShape
from voxfab.unfold import Net

from ._animate import animation_frames, save_animation, save_turntable, turntable_frames
from ._contact_sheet import contact_sheet, repository_contact_sheet, sheet_layout
from ._image import gif_bytes, pdf_bytes, png_bytes, save_picture
from ._net import DEFAULT_STYLES, LineStyle, net_picture
from ._raster import DEFAULT_COLOR, Raster, fit_frame, rasterize
from ._render import render, render_raster, save_render, supersampling
from ._slices import SliceAxis, layers, slice_layout, slice_sheet
from ._triptych import make_net, triptych, triptych_layout
from ._views import Camera, View, camera_for, orbit_camera

__all__ = [
    "View",
    "Camera",
    "camera_for",
    "orbit_camera",
    "Raster",
    "rasterize",
    "fit_frame",
    "DEFAULT_COLOR",
    "render",
    "render_raster",
    "save_render",
    "supersampling",
    "SliceAxis",
    "layers",
    "slice_layout",
    "slice_sheet",
    "LineStyle",
    "DEFAULT_STYLES",
    "net_picture",
    "make_net",
    "triptych",
    "triptych_layout",
    "turntable_frames",
    "animation_frames",
    "save_turntable",
    "save_animation",
    "contact_sheet",
    "sheet_layout",
    "repository_contact_sheet",
    "png_bytes",
    "pdf_bytes",
    "gif_bytes",
    "save_picture",
    "view_filename",
    "recipe_output",
]


def view_filename(view: str) -> str:
    """File name of a view picture: ``render_iso.png``, ``render_x.png``, ``render_neg_x.png``, ..."""
    v = View(view).value
    return f"render_{'neg_' + v[1:] if v.startswith('-') else v}.png"


def recipe_output(
    shape: VoxelShape,
    outdir: Path,
    *,
    name: str,
    seed: int,
    size: int = 800,
    views: list[str] = ["iso"],  # noqa: B006 - read only; the recipe loader reads this default
    triptych: bool = True,
    turntable: bool = False,
    frames: int = 36,
    slices: bool = False,
    background: str = "white",
    color: str = "#eccc96",
) -> list[OutputFile]:
    """The recipe output ``pictures``: views, the triptych, a slice sheet and a turntable.

    Parameters
    ----------
    shape : VoxelShape
        The recipe's shape.
    outdir : Path
        Folder to write into.
    name : str
        The recipe's name (the triptych's title).
    seed : int
        Seed of the triptych's net (``voxfab.unfold.unfold(grid, rng=seed)``, as the ``net`` output).
    size : int
        Picture side in pixels (triptych panels too; the turntable uses half).
    views : list of str
        Views to write as ``render_<view>.png`` (``"iso"``, ``"x"``, ``"-x"``, ... ``"-z"``).
    triptych, turntable, slices : bool
        Also write ``triptych.png`` + ``triptych.pdf``, ``turntable.gif``, ``slices.png``.
    frames : int
        Turntable frames.
    background, color : str
        Paper and cube colours (names or ``#rrggbb``).

    Returns
    -------
    list of OutputFile
        The files written, relative to ``outdir``.
    """
    from voxfab._shared.atomic import write_bytes

    from ._raster import parse_color
    from ._render import check_size

    out = Path(outdir)
    try:
        check_size(size)
        parse_color(background, name="background")
        parse_color(color, name="color")
        names = [view_filename(View(v).value) if v in {m.value for m in View} else None for v in views]
        bad = [v for v, n in zip(views, names) if n is None]
        if bad:
            choices = ", ".join(m.value for m in View)
            raise RecipeError(f"unknown view {bad[0]!r}; expected one of {choices}")
    except VoxfabError as exc:
        raise RecipeError(f"outputs.pictures: {exc}") from None
    files: list[OutputFile] = []
    for v, fname in zip(dict.fromkeys(views), dict.fromkeys(names)):
        write_bytes(out / fname, png_bytes(render(shape, view=v, size=size, background=background, color=color)))
        files.append(OutputFile(fname, f"3D picture of the voxels, view {v}"))
    if slices:
        write_bytes(out / "slices.png", png_bytes(slice_sheet(shape, size=size, background=background,
                                                               color=color)))
        files.append(OutputFile("slices.png", "the layers bottom up, each numbered"))
    if triptych:
        # The build runs the `net` output before this one: draw that very net
        # instead of searching again (a search may take a while on large shapes).
        net_file = out / "net.json"
        net = Net.from_json(net_file.read_text()) if net_file.exists() else None
        image = _triptych(shape, name=name, rng=seed, net=net, panel=size, background=background,
                          color=color)
        write_bytes(out / "triptych.png", png_bytes(image))
        write_bytes(out / "triptych.pdf", pdf_bytes(image, title=name))
        files.append(OutputFile("triptych.png", "net | slices | 3D, titled with the shape's name"))
        files.append(OutputFile("triptych.pdf", "net | slices | 3D as a one-page PDF"))
    if turntable:
        save_turntable(shape, out / "turntable.gif", frames=frames, size=max(64, size // 2),
                       background=background, color=color)
        files.append(OutputFile("turntable.gif", "the shape turning once around its vertical axis"))
    return files


_triptych = triptych
