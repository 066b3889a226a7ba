"""The pictures pipeline: which pictures of a shape to make, each drawn once and written by its extension.

The recipe output ``pictures``, the studio and ``voxfab render`` all go through
:func:`render_pictures`: the recipe and the studio ask for the files their
:class:`PictureOptions` name (:func:`pictures_asked`); the command asks for one
:class:`Picture` at the path the user gave.
"""

from __future__ import annotations

import dataclasses
import enum
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voxfab.errors import InvalidShapeError, UnknownFormatError

from ._options import PictureOptions
from ._views import View

if TYPE_CHECKING:
    from PIL import Image

    from voxfab.fabricate._outputs import Artefact
    from voxfab.shape import VoxelShape
    from voxfab.unfold import Net

__all__ = ["PictureKind", "Picture", "PICTURE_FORMATS", "pictures_asked", "render_pictures", "view_filename"]


class PictureKind(enum.StrEnum):
    """What a picture shows."""

    VIEW = "view"  # shaded cubes from one view
    SLICES = "slices"  # the layers in a grid
    TRIPTYCH = "triptych"  # net | slices | 3D under the name
    NET = "net"  # the net with folds, tabs and seam numbers
    TURNTABLE = "turntable"  # a GIF of the shape turning


#: The file extensions each kind of picture can be written as.
PICTURE_FORMATS: dict[PictureKind, tuple[str, ...]] = {
    PictureKind.VIEW: (".png",),
    PictureKind.SLICES: (".png", ".pdf"),
    PictureKind.TRIPTYCH: (".png", ".pdf"),
    PictureKind.NET: (".png", ".pdf"),
    PictureKind.TURNTABLE: (".gif",),
}

# What each kind shows, for the list of files written (a view also names its view).
_SHOWS = {PictureKind.SLICES: "the layers bottom up, each numbered", PictureKind.TRIPTYCH: "net | slices | 3D",
          PictureKind.NET: "the net with folds, tabs and seam numbers",
          PictureKind.TURNTABLE: "the shape turning once around its vertical axis"}
# The picture sides PictureOptions allows, px.
_SIZES = (16, 8192)
# What a kind is called in an error message.
_NAMES = {PictureKind.VIEW: "a 3D picture", PictureKind.SLICES: "a slice sheet", PictureKind.TRIPTYCH: "a triptych",
          PictureKind.NET: "a net picture", PictureKind.TURNTABLE: "a turntable"}


@dataclasses.dataclass(frozen=True)
class Picture:
    """One picture file to write.

    Attributes
    ----------
    kind : PictureKind
    path : str
        File path relative to the output folder; its extension picks the format
        (one of :data:`PICTURE_FORMATS`).
    view : str
        The view of a ``VIEW`` picture.
    size : int, optional
        Side in pixels (panel side of a triptych) instead of the options' size;
        by default a turntable is half the options' size, every other picture the size.
    """

    kind: PictureKind
    path: str
    view: str = "iso"
    size: int | None = None

    def __post_init__(self) -> None:
        try:
            object.__setattr__(self, "kind", PictureKind(self.kind))
        except ValueError:
            raise InvalidShapeError(f"picture: unknown kind {self.kind!r}; expected one of "
                                    f"{', '.join(k.value for k in PictureKind)}") from None
        if self.view not in {v.value for v in View}:
            raise InvalidShapeError(f"view: unknown view {self.view!r}; expected one of "
                                    f"{', '.join(v.value for v in View)}")
        low, high = _SIZES
        if self.size is not None and (isinstance(self.size, bool) or not isinstance(self.size, int)
                                      or not low <= self.size <= high):
            raise InvalidShapeError(f"size: expected a whole number of px from {low} to {high}, got {self.size!r}")

    @property
    def format(self) -> str:
        """The file extension, lower case."""
        return Path(self.path).suffix.lower()

    def purpose(self) -> str:
        """One line saying what the file shows."""
        if self.kind is PictureKind.VIEW:
            return f"3D picture of the voxels, view {self.view}"
        if self.format == ".pdf":
            return f"{_SHOWS[self.kind]} as a one-page PDF"
        if self.kind is PictureKind.TRIPTYCH:
            return f"{_SHOWS[self.kind]}, titled with the shape's name"
        return _SHOWS[self.kind]


def view_filename(view: str) -> str:
    """File name of a view picture: ``render_iso.png``, ``render_x.png``, ``render_neg_x.png``, ..."""
    v = View(view).value
    return f"render_{'neg_' + v[1:] if v.startswith('-') else v}.png"


def pictures_asked(options: PictureOptions) -> tuple[Picture, ...]:
    """The files ``options`` ask for, in the order they are written (the recipe's file names)."""
    pics = [Picture(PictureKind.VIEW, view_filename(v), view=v) for v in dict.fromkeys(options.views)]
    if options.slices:
        pics.append(Picture(PictureKind.SLICES, "slices.png"))
    if options.triptych:
        pics += [Picture(PictureKind.TRIPTYCH, "triptych.png"), Picture(PictureKind.TRIPTYCH, "triptych.pdf")]
    if options.net_picture:
        pics.append(Picture(PictureKind.NET, "net_picture.png"))
    if options.turntable:
        pics.append(Picture(PictureKind.TURNTABLE, "turntable.gif"))
    return tuple(pics)


def _check_format(picture: Picture, folder: Path) -> None:
    allowed = PICTURE_FORMATS[picture.kind]
    if picture.format not in allowed:
        raise UnknownFormatError(f"{folder / picture.path}: {_NAMES[picture.kind]} can be written as "
                                 f"{' or '.join(allowed)}, not {picture.format or 'no extension'!r}")


def _side(picture: Picture, options: PictureOptions) -> int:
    if picture.size is not None:
        return picture.size
    return max(64, options.size // 2) if picture.kind is PictureKind.TURNTABLE else options.size


def _draw(p: Picture, shape: VoxelShape, o: PictureOptions, *, side: int, name: str, seed: int,
          net: Net | Sequence[Net] | None) -> Image.Image | list[Image.Image]:
    """The picture ``p`` shows (a list of frames for a turntable)."""
    if p.kind is PictureKind.VIEW:
        from ._render import render

        return render(shape, view=p.view, size=side, background=o.background, color=o.color)
    if p.kind is PictureKind.SLICES:
        from ._slices import slice_sheet

        return slice_sheet(shape, size=side, background=o.background, color=o.color)
    if p.kind is PictureKind.TRIPTYCH:
        from ._triptych import triptych

        return triptych(shape, name=name, rng=seed, net=net, panel=side, background=o.background, color=o.color)
    if p.kind is PictureKind.NET:
        from ._net import net_picture, unfolded_shape
        from ._triptych import make_net

        the_net = net if net is not None else make_net(shape, rng=seed)
        # A net of the outer surface unfolds the shape with its cavities filled (as in the triptych).
        return net_picture(the_net, unfolded_shape(shape, the_net), size=side, background=o.background)
    from ._animate import turntable_frames

    return turntable_frames(shape, frames=o.frames, size=side, background=o.background, color=o.color)


def render_pictures(
    shape: VoxelShape,
    options: PictureOptions,
    folder: Path,
    *,
    name: str,
    seed: int,
    net: Net | Sequence[Net] | None = None,
    pictures: Sequence[Picture] | None = None,
) -> Artefact:
    """The pictures pipeline: views, slice sheet, triptych, net picture and turntable, as asked.

    Parameters
    ----------
    shape : VoxelShape
        The shape.
    options : PictureOptions
        Checked options: sizes and colours, and (unless ``pictures`` is given)
        which files to write.
    folder : Path
        Folder to write into.
    name : str
        The shape's name (the triptych's title, the PDFs' title).
    seed : int
        Seed of the net of the triptych and net picture when ``net`` is not
        given (``voxfab.unfold.unfold(grid, rng=seed)``, as the ``net`` output).
    net : Net or sequence of Net, optional
        The net to draw (the one the net output wrote, or the user's file), or
        its pieces (a net split to fit its sheet), each drawn with its own outline.
    pictures : sequence of Picture, optional
        The files to write instead of :func:`pictures_asked` ``(options)``.

    Returns
    -------
    Artefact
        The files written, relative to ``folder``; ``report["pictures"]`` holds
        each file's ``path``, ``kind``, ``width`` and ``height`` in pixels (and
        a turntable's ``frames``).

    Raises
    ------
    UnknownFormatError
        Before any drawing, when a picture's extension is not one of its kind's formats.
    """
    from voxfab._shared.atomic import write_bytes
    from voxfab.drawing.png import png_bytes
    from voxfab.fabricate._outputs import Artefact, OutputFile

    from ._image import gif_bytes, pdf_bytes

    out = Path(folder)
    asked = tuple(pictures) if pictures is not None else pictures_asked(options)
    for p in asked:
        _check_format(p, out)
    # A triptych written as PNG and PDF is drawn once.
    drawn: dict[tuple[PictureKind, str, int], Any] = {}

    def draw(p: Picture) -> Image.Image | list[Image.Image]:
        key = (p.kind, p.view, _side(p, options))
        if key not in drawn:
            drawn[key] = _draw(p, shape, options, side=key[2], name=name, seed=seed, net=net)
        return drawn[key]

    files: list[OutputFile] = []
    report: list[dict[str, Any]] = []
    for p in asked:
        picture = draw(p)
        entry: dict[str, Any] = {"path": p.path, "kind": p.kind.value}
        if isinstance(picture, list):  # turntable frames
            write_bytes(out / p.path, gif_bytes(picture, duration_ms=80))
            first = picture[0]
            entry.update(width=first.width, height=first.height, frames=len(picture))
        else:
            data = pdf_bytes(picture, title=name) if p.format == ".pdf" else png_bytes(picture)
            write_bytes(out / p.path, data)
            entry.update(width=picture.width, height=picture.height)
        files.append(OutputFile(p.path, p.purpose()))
        report.append(entry)
    return Artefact(tuple(files), report={"pictures": report})
