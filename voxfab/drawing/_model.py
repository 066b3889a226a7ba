"""Pages and drawings: layered polylines, circles, preview fills and placed raster pictures in millimetres."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

from ._layers import LAYERS
from ._polylines import Polylines


@dataclasses.dataclass(frozen=True, eq=False)
class Fill:
    """An area painted in previews and prints (never sent to a laser).

    Attributes
    ----------
    rings : Polylines
        Closed rings; a point is inside when it is inside an odd number of them,
        so holes are rings inside rings.
    color : str
        ``#rrggbb``.
    nonzero : bool
        Fill by the nonzero winding rule (overlapping counter-clockwise rings
        make one area) instead of even-odd.
    name : str
        An id for the area (SVG ``id``), or ``""``.
    colors, names : tuple of str
        When given, one per ring: each ring is an area of its own in its own colour,
        with its own id (the faces of a coloured net, written in one pass).
    """

    rings: Polylines
    color: str
    nonzero: bool = False
    name: str = ""
    colors: tuple[str, ...] = ()
    names: tuple[str, ...] = ()

    @property
    def rgb(self) -> tuple[int, int, int]:
        """The colour as 0..255 integers."""
        return _rgb(self.color)


@dataclasses.dataclass(frozen=True, eq=False)
class PlacedImage:
    """A raster picture placed in a box of the page (previews and prints; never sent to a laser).

    Attributes
    ----------
    pixels : (rows, columns, 3) uint8 ndarray
        RGB pixels, the first row at the top of the box.
    x, y : float
        Lower-left corner of the box, mm.
    width, height : float
        Size of the box, mm; the pixels are stretched to fill it.
    """

    pixels: npt.NDArray[np.uint8]
    x: float
    y: float
    width: float
    height: float

    def __post_init__(self) -> None:
        p = self.pixels
        if p.dtype != np.uint8 or p.ndim != 3 or p.shape[2] != 3 or not p.shape[0] or not p.shape[1]:
            raise InvalidShapeError(f"drawing: an image is (rows, columns, 3) uint8 RGB pixels, got {p.dtype} "
                                    f"{p.shape}")
        if not (self.width > 0 and self.height > 0):
            raise InvalidShapeError(f"drawing: an image box needs a positive size, got {self.width} x {self.height}")

    @classmethod
    def of(cls, picture: Any, *, x: float, y: float, width: float, height: float) -> PlacedImage:
        """Place ``picture`` (a Pillow image or an RGB array) in the box at ``(x, y)``."""
        rgb = picture.convert("RGB") if hasattr(picture, "convert") else picture
        return cls(np.ascontiguousarray(np.asarray(rgb, dtype=np.uint8)), float(x), float(y), float(width),
                   float(height))


@dataclasses.dataclass(frozen=True, eq=False)
class Ink:
    """Part of a layer printed in a colour of its own over coloured fills (prints only).

    A coloured net prints its folds and labels black on light faces and white on
    dark ones; the layer keeps every line for DXF and laser files, and the
    print backends draw the layer's inks instead of the layer.

    Attributes
    ----------
    layer : str
        The layer whose lines these are (its dash style and visible width apply).
    lines : Polylines
    color : str
        ``#rrggbb`` of the lines.
    halo : str
        ``#rrggbb`` of a wider stroke drawn under them (a line between two faces
        stays clear of both), or ``""`` for none.
    """

    layer: str
    lines: Polylines
    color: str
    halo: str = ""

    @property
    def rgb(self) -> tuple[int, int, int]:
        """The colour as 0..255 integers."""
        return _rgb(self.color)

    @property
    def halo_rgb(self) -> tuple[int, int, int]:
        """The halo colour as 0..255 integers."""
        return _rgb(self.halo)


def _rgb(c: str) -> tuple[int, int, int]:
    return int(c[1:3], 16), int(c[3:5], 16), int(c[5:7], 16)


#: Width of an ink's halo beyond the line on each side, mm.
HALO = 0.25


def _no_circles() -> npt.NDArray[np.float64]:
    return np.zeros((0, 3))


@dataclasses.dataclass(frozen=True, eq=False)
class Page:
    """One page (a sheet of paper or material) of a drawing.

    Coordinates are mm with the origin at the page's lower-left corner and y
    up; the SVG and PNG backends flip y on output.

    Attributes
    ----------
    width, height : float
        Page size, mm.
    layers : mapping of str to Polylines
        Lines per layer; every name is a key of :data:`~voxfab.drawing.LAYERS`.
        Missing layers are empty.
    circles : mapping of str to (n, 3) float ndarray
        Circles per layer as ``x, y, radius`` (mm), e.g. dowel holes.
    fills : tuple of Fill
        Areas painted under the lines in previews and prints, in order.
    images : tuple of PlacedImage
        Raster pictures painted first, under fills and lines (PDF, PNG and
        SVG; DXF, for cutting, leaves them out).
    inks : tuple of Ink
        Layers printed in colours of their own (PDF, PNG and SVG draw a layer's
        inks instead of the layer; DXF keeps the layer).
    marks : Polylines
        Registration marks of a print-then-cut cutter: closed rings printed
        solid black, the same in the print and the cut file (DXF leaves them out).
    artwork : bool
        The fills are the picture itself (a coloured net): SVG writes them in
        laser files too.
    title : str
        Page title (SVG ``<title>``).
    """

    width: float
    height: float
    layers: Mapping[str, Polylines]
    circles: Mapping[str, npt.NDArray[np.float64]] = dataclasses.field(default_factory=dict)
    fills: tuple[Fill, ...] = ()
    images: tuple[PlacedImage, ...] = ()
    title: str = ""
    inks: tuple[Ink, ...] = ()
    marks: Polylines = dataclasses.field(default_factory=Polylines.empty)
    artwork: bool = False

    def __post_init__(self) -> None:
        for name in list(self.layers) + list(self.circles) + [i.layer for i in self.inks]:
            if name not in LAYERS:
                raise InvalidShapeError(f"drawing: unknown layer {name!r}; expected one of {', '.join(LAYERS)}")
        # Every writer draws a page's lines: a zero-length segment dropped here is dropped from every file.
        object.__setattr__(self, "layers", {k: v.without_repeats() for k, v in self.layers.items()})

    def lines(self, layer: str) -> Polylines:
        """The polylines of ``layer`` (empty when it has none)."""
        return self.layers.get(layer, Polylines.empty())

    def circles_of(self, layer: str) -> npt.NDArray[np.float64]:
        """The ``(n, 3)`` circles of ``layer``."""
        return self.circles.get(layer, _no_circles())

    def used_layers(self) -> list[str]:
        """Names of the layers holding something, in drawing order."""
        return [n for n in LAYERS if len(self.lines(n)) or len(self.circles_of(n))]

    def extents(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of all lines and circles, mm; the page box when empty."""
        lo, hi = [], []
        for name in LAYERS:
            pts = self.lines(name).points
            if pts.shape[0]:
                lo.append(pts.min(axis=0))
                hi.append(pts.max(axis=0))
            c = self.circles_of(name)
            if c.shape[0]:
                lo.append((c[:, :2] - c[:, 2:]).min(axis=0))
                hi.append((c[:, :2] + c[:, 2:]).max(axis=0))
        if not lo:
            return 0.0, 0.0, float(self.width), float(self.height)
        a, b = np.min(lo, axis=0), np.max(hi, axis=0)
        return float(a[0]), float(a[1]), float(b[0]), float(b[1])

    def shifted(self, shift: npt.ArrayLike, *, width: float, height: float) -> Page:
        """A copy moved by ``shift`` (2,) mm on a page of the given size."""
        d = np.asarray(shift, dtype=np.float64).reshape(2)
        return dataclasses.replace(
            self, width=float(width), height=float(height),
            layers={k: v.translated(d) for k, v in self.layers.items()},
            circles={k: v + (d[0], d[1], 0.0) for k, v in self.circles.items()},
            fills=tuple(dataclasses.replace(f, rings=f.rings.translated(d)) for f in self.fills),
            images=tuple(dataclasses.replace(i, x=i.x + float(d[0]), y=i.y + float(d[1])) for i in self.images),
            inks=tuple(dataclasses.replace(i, lines=i.lines.translated(d)) for i in self.inks),
            marks=self.marks.translated(d),
        )

    def inks_of(self, layer: str) -> tuple[Ink, ...] | None:
        """The inks ``layer`` is printed in, or None when it prints in its own colour."""
        found = tuple(i for i in self.inks if i.layer == layer)
        return found or None

    def with_layers(self, extra: Mapping[str, Polylines]) -> Page:
        """A copy with ``extra`` polylines appended to their layers."""
        merged = dict(self.layers)
        for name, lines in extra.items():
            merged[name] = Polylines.concat([self.lines(name), lines])
        return dataclasses.replace(self, layers=merged)


@dataclasses.dataclass(frozen=True, eq=False)
class Drawing:
    """Pages of layered lines, ready for the SVG, DXF, PDF and PNG backends.

    Attributes
    ----------
    pages : tuple of Page
    title : str
        Document title (PDF metadata).
    """

    pages: tuple[Page, ...]
    title: str = ""
