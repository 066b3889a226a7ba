"""Pictures of voxel shapes, all headless: 3D renders, slice sheets, nets, triptychs, GIFs.

* :func:`render` — shaded cubes with dark voxel edges, isometric or from one of six sides.
* :func:`slice_sheet` — the layers in a grid, each numbered.
* :func:`net_picture` — a net with fold styles, glue tabs and seam labels.
* :func:`triptych` — net | slices | 3D under the shape's name (PNG and PDF).
* :func:`save_turntable`, :func:`save_animation` — GIFs of a turning shape or a sequence of shapes.
* :func:`contact_sheet`, :func:`repository_contact_sheet` — many shapes by volume with names.
* :func:`render_pictures` — the pictures pipeline (recipe output ``pictures``), options :class:`PictureOptions`.
"""

from __future__ import annotations

from pathlib import Path

from voxfab.fabricate import Artefact, OutputFile
from voxfab.shape import VoxelShape
from voxfab.unfold import Net

from ._animate import animation_frames, save_animation, save_turntable, turntable_frames
from ._contact_sheet import contact_sheet, repository_contact_sheet, sheet_layout
from ._image import gif_bytes, pdf_bytes, png_bytes, save_picture
from ._net import DEFAULT_STYLES, LineStyle, net_picture
from ._options import AnimationOptions, PictureOptions
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
    "AnimationOptions",
    "PictureOptions",
    "render_pictures",
]


def view_filename(view: str) -> str:
    """File name of a view picture: ``render_iso.png``, ``render_x.png``, ``render_neg_x.png``, ..."""
    v = View(view).value
    return f"render_{'neg_' + v[1:] if v.startswith('-') else v}.png"


def render_pictures(
    shape: VoxelShape,
    options: PictureOptions,
    folder: Path,
    *,
    name: str,
    seed: int,
    net: Net | None = None,
) -> Artefact:
    """The pictures pipeline: views, the triptych, a slice sheet and a turntable, as asked.

    Parameters
    ----------
    shape : VoxelShape
        The shape.
    options : PictureOptions
        Checked options.
    folder : Path
        Folder to write into.
    name : str
        The shape's name (the triptych's title).
    seed : int
        Seed of the triptych's net when ``net`` is not given
        (``voxfab.unfold.unfold(grid, rng=seed)``, as the ``net`` output).
    net : Net, optional
        The net to draw in the triptych (the one the net output wrote).

    Returns
    -------
    Artefact
        The files written, relative to ``folder``.
    """
    from voxfab._shared.atomic import write_bytes

    out = Path(folder)
    o = options
    files: list[OutputFile] = []
    for v in dict.fromkeys(o.views):
        fname = view_filename(v)
        write_bytes(out / fname, png_bytes(render(shape, view=v, size=o.size, background=o.background,
                                                  color=o.color)))
        files.append(OutputFile(fname, f"3D picture of the voxels, view {v}"))
    if o.slices:
        write_bytes(out / "slices.png", png_bytes(slice_sheet(shape, size=o.size, background=o.background,
                                                               color=o.color)))
        files.append(OutputFile("slices.png", "the layers bottom up, each numbered"))
    if o.triptych:
        image = triptych(shape, name=name, rng=seed, net=net, panel=o.size, background=o.background,
                         color=o.color)
        write_bytes(out / "triptych.png", png_bytes(image))
        write_bytes(out / "triptych.pdf", pdf_bytes(image, title=name))
        files.append(OutputFile("triptych.png", "net | slices | 3D, titled with the shape's name"))
        files.append(OutputFile("triptych.pdf", "net | slices | 3D as a one-page PDF"))
    if o.turntable:
        save_turntable(shape, out / "turntable.gif", frames=o.frames, size=max(64, o.size // 2),
                       background=o.background, color=o.color)
        files.append(OutputFile("turntable.gif", "the shape turning once around its vertical axis"))
    return Artefact(tuple(files))
