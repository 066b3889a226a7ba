"""Pictures of voxel shapes, all headless: 3D renders, slice sheets, nets, triptychs, GIFs.

* :func:`render` — shaded cubes with dark voxel edges, isometric or from one of six sides.
* :func:`slice_sheet` — the layers in a grid, each numbered.
* :func:`net_picture` — a net with fold styles, glue tabs and seam labels.
* :func:`triptych` — net | slices | 3D under the shape's name (PNG and PDF).
* :func:`save_turntable`, :func:`save_animation` — GIFs of a turning shape or a sequence of shapes.
* :func:`contact_sheet`, :func:`repository_contact_sheet` — many shapes by volume with names.
* :func:`render_animation` — the animation pipeline (a tube's turning profile); :func:`tube_frames`
  and :func:`save_tube_animation` for its frames and GIF.
* :func:`save_fold_animation` — a net folding up from the flat sheet to the shape (:func:`fold_frames`).
* :func:`render_pictures` — the pictures pipeline of the recipe output ``pictures``, the studio and
  ``voxfab render``: options :class:`PictureOptions`, files :class:`Picture`.
"""

from __future__ import annotations

from voxfab.drawing.png import png_bytes

from ._animate import (
    animation_frames,
    render_animation,
    save_animation,
    save_tube_animation,
    save_turntable,
    tube_frames,
    turntable_frames,
)
from ._contact_sheet import contact_sheet, repository_contact_sheet, sheet_layout
from ._fold import fold_angles, fold_frames, save_fold_animation
from ._image import gif_bytes, pdf_bytes, save_picture
from ._net import DEFAULT_STYLES, LineStyle, net_picture
from ._options import AnimationOptions, PictureOptions
from ._pictures import PICTURE_FORMATS, Picture, PictureKind, pictures_asked, render_pictures, view_filename
from ._raster import DEFAULT_COLOR, Raster, fit_frame, rasterize
from ._render import render, render_raster, save_render, supersampling
from ._slices import SliceAxis, layers, slice_layout, slice_sheet
from ._triptych import make_net, triptych, triptych_layout
from ._views import Camera, View, camera_for, orbit_camera, profile_camera

__all__ = [
    "View",
    "Camera",
    "camera_for",
    "orbit_camera",
    "profile_camera",
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
    "render_animation",
    "fold_frames",
    "fold_angles",
    "save_fold_animation",
    "save_tube_animation",
    "tube_frames",
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
    "Picture",
    "PictureKind",
    "PICTURE_FORMATS",
    "pictures_asked",
]
