"""The filaments of a coloured print: the shape's colours in extruder order, merged perceptually when too many.

A print takes one filament per colour, and a printer holds 1 to 16 of them.
The colours a print needs are those of its visible surface (a colour only
inside the solid is printed with the filament nearest to it in CIELAB).  When
a limit is given, the visible colours are merged by weighted agglomerative
clustering in CIELAB (Ward's criterion, each colour weighted by its visible
area): the pair of groups whose merge adds the least area-weighted squared
colour difference goes first, so a small detail in an odd colour is given up
before a large area changes colour.  A group is printed in the colour of its
largest member, a colour of the model itself.  Filaments are numbered by
visible area, largest first: extruder 1 holds the colour most of the print
shows.  Ties fall to the smaller ``#rrggbb``, so the result is deterministic.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from functools import lru_cache
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.shape import srgb_to_lab

from ._data import MeshData

#: Most filaments a printer holds (tool changers and filament switchers stop at 16).
MAX_FILAMENTS = 16

#: Plain names of filament colours, to tell the filaments apart in a report.
_NAMES = {
    "white": (245, 245, 245), "light grey": (190, 190, 190), "grey": (128, 128, 128),
    "dark grey": (64, 64, 64), "black": (20, 20, 20), "red": (200, 30, 30), "dark red": (120, 15, 25),
    "pink": (240, 130, 170), "orange": (240, 130, 30), "yellow": (245, 215, 30), "gold": (205, 155, 25),
    "beige": (240, 200, 160), "brown": (110, 65, 25), "dark brown": (65, 38, 12), "olive": (120, 120, 30),
    "green": (40, 160, 60), "light green": (140, 215, 110), "dark green": (20, 80, 35),
    "teal": (20, 130, 130), "cyan": (40, 200, 220), "light blue": (130, 180, 240), "blue": (40, 80, 200),
    "navy": (25, 35, 100), "purple": (120, 50, 160), "magenta": (210, 40, 190), "silver": (175, 178, 185),
}


@dataclasses.dataclass(frozen=True)
class Filament:
    """One filament of a coloured print.

    Attributes
    ----------
    extruder : int
        Its extruder, 1-based (tool ``T{extruder - 1}`` in G-code).
    hex : str
        ``"#rrggbb"``: the colour it prints.
    name : str
        A plain name of that colour (``"red"``, ``"dark brown"``).
    voxels : int
        Voxels printed in it.
    area : float
        Visible surface printed in it, mm².
    merged : tuple of str
        The shape's other colours (``"#rrggbb"``) printed with it.
    """

    extruder: int
    hex: str
    name: str
    voxels: int
    area: float
    merged: tuple[str, ...]

    def as_dict(self) -> dict[str, object]:
        """Plain JSON values."""
        return {"extruder": self.extruder, "colour": self.hex, "name": self.name, "voxels": self.voxels,
                "area_mm2": round(self.area, 6), "merged": list(self.merged)}


@dataclasses.dataclass(frozen=True)
class Filaments:
    """The filaments of a print, in extruder order, and where the shape's colours went.

    Attributes
    ----------
    filaments : tuple of Filament
    shape_colours : int
        Distinct colours of the printed voxels.
    visible : int
        Those of them on the print's surface.
    limit : int or None
        The most filaments asked for (None: one per visible colour).
    """

    filaments: tuple[Filament, ...]
    shape_colours: int
    visible: int
    limit: int | None

    @property
    def merged(self) -> bool:
        """Whether some colours of the shape share a filament."""
        return any(f.merged for f in self.filaments)

    def as_dict(self) -> dict[str, object]:
        """Plain JSON values (mesh.json's ``colours``)."""
        return {"filaments": [f.as_dict() for f in self.filaments], "shape_colours": self.shape_colours,
                "visible_colours": self.visible, "limit": self.limit}

    def line(self) -> str:
        """One line: the extruders' colours, and what merged into what (see :func:`filaments_line`)."""
        return filaments_line(self.as_dict())


def filaments_line(colours: Mapping[str, Any]) -> str:
    """One line from mesh.json's ``colours``: each extruder's colour, and the colours merged into it."""
    filaments = colours["filaments"]
    parts = []
    for f in filaments:
        text = f"{f['extruder']} {f['colour']} {f['name']}"
        if f["merged"]:
            text += f" (with {', '.join(f['merged'])})"
        parts.append(text)
    head = f"{len(filaments)} filament(s)"
    if any(f["merged"] for f in filaments):
        head = f"{colours['shape_colours']} colours merged into {len(filaments)} filament(s)"
    return f"{head}, by extruder: " + "; ".join(parts)


@lru_cache(maxsize=1)
def _name_table() -> tuple[list[str], npt.NDArray[np.float64]]:
    names = list(_NAMES)
    return names, srgb_to_lab(np.array([_NAMES[n] for n in names]))


def colour_names(rgb: npt.ArrayLike) -> list[str]:
    """The plain name nearest in CIELAB to each sRGB colour of ``(N, 3 or 4)`` values 0..255."""
    names, lab = _name_table()
    c = srgb_to_lab(np.asarray(rgb).reshape(-1, np.shape(rgb)[-1]))
    d = ((c[:, None, :] - lab[None, :, :]) ** 2).sum(axis=2)
    return [names[i] for i in np.argmin(d, axis=1).tolist()]


def colour_hexes(rgb: npt.ArrayLike) -> list[str]:
    """``"#rrggbb"`` of each colour of ``(N, 3 or 4)`` values (the same as :func:`hex_colour`, for many)."""
    return [f"#{r:02x}{g:02x}{b:02x}" for r, g, b, *_ in np.asarray(rgb).tolist()]


def material_labels(palette: npt.NDArray[np.uint8]) -> list[str]:
    """A label per colour of a mesh's palette for its file's materials: ``"red #c82828"``."""
    return [f"{n} {h}" for n, h in zip(colour_names(palette), colour_hexes(palette))]


def ward_groups(lab: npt.NDArray[np.float64], weight: npt.NDArray[np.float64], n: int) -> npt.NDArray[np.int64]:
    """Group colours into ``n`` by weighted agglomerative clustering (Ward) in CIELAB.

    Parameters
    ----------
    lab : (K, 3) float ndarray
        The colours in CIELAB, in a fixed order (ties go to the lower indices).
    weight : (K,) float ndarray
        Positive weight of each colour (its visible area).
    n : int
        Groups wanted (``1 <= n``).

    Returns
    -------
    (K,) int64 ndarray
        The group of each colour: the index of its group's first colour.
    """
    k = len(lab)
    group = np.arange(k)
    centre = np.array(lab, dtype=np.float64)
    w = np.array(weight, dtype=np.float64)

    def costs(i: int) -> npt.NDArray[np.float64]:
        """The cost of merging group ``i`` with each group (Ward: the weighted squared colour difference added)."""
        return w[i] * w / (w[i] + w) * ((centre - centre[i]) ** 2).sum(axis=1)

    cost = np.stack([costs(i) for i in range(k)]) if k else np.zeros((0, 0))
    np.fill_diagonal(cost, np.inf)
    for _ in range(max(k - n, 0)):
        # The first minimum in row order has the lower index first: ties go to the lowest pair.
        a, b = np.unravel_index(int(np.argmin(cost)), cost.shape)
        centre[a] = (w[a] * centre[a] + w[b] * centre[b]) / (w[a] + w[b])
        w[a] += w[b]
        group[group == b] = a
        cost[b, :] = cost[:, b] = np.inf
        row = costs(a)
        alive = np.isfinite(cost[a]) | (np.arange(k) == b)
        alive[a] = alive[b] = False
        cost[a, alive] = cost[alive, a] = row[alive]
    return group


def assign_filaments(
    mesh: MeshData, index: npt.NDArray[np.integer], palette: npt.NDArray[np.uint8], limit: int | None
) -> tuple[MeshData, Filaments]:
    """Turn a mesh coloured by the shape's colour indices into one coloured by filament.

    Parameters
    ----------
    mesh : MeshData
        ``mesh.colour`` holds the shape's colour index (1..255) of each triangle.
    index : (X, Y, Z) integer ndarray
        The colour index of every printed voxel (0 where empty).
    palette : (256, 4) uint8 ndarray
        The shape's palette.
    limit : int, optional
        Most filaments; more visible colours are merged (see the module's text).

    Returns
    -------
    MeshData
        The same triangles, ``colour`` the filament (0-based extruder) of each
        and ``palette`` the filaments' RGBA in extruder order.
    Filaments
    """
    assert mesh.colour is not None
    rgb = palette[:, :3].astype(np.int64)
    key = (rgb[:, 0] << 16) | (rgb[:, 1] << 8) | rgb[:, 2]  # one key per distinct colour, ordered like its hex
    voxels_by_index = np.bincount(index.ravel(), minlength=256)[:256]
    voxels_by_index[0] = 0
    tri = mesh.vertices[mesh.triangles]
    areas = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1) / 2.0
    area_by_index = np.bincount(mesh.colour, weights=areas, minlength=256)[:256]
    used = np.flatnonzero(voxels_by_index | (area_by_index > 0))
    keys, inverse = np.unique(key[used], return_inverse=True)  # the distinct colours, ascending by hex
    distinct_of_index = np.full(256, -1, dtype=np.int64)
    distinct_of_index[used] = inverse
    area = np.bincount(inverse, weights=area_by_index[used], minlength=len(keys))
    voxels = np.bincount(inverse, weights=voxels_by_index[used], minlength=len(keys)).astype(np.int64)
    colours = np.column_stack([(keys >> 16) & 255, (keys >> 8) & 255, keys & 255])
    lab = srgb_to_lab(colours)
    visible = np.flatnonzero(area > 0)
    group = np.full(len(keys), -1, dtype=np.int64)
    n = len(visible) if limit is None else min(limit, len(visible))
    group[visible] = visible[ward_groups(lab[visible], area[visible], n)]
    hidden = np.flatnonzero(area <= 0)
    if hidden.size:
        # A colour only inside the solid goes with the filament whose colour is nearest.
        d = np.linalg.norm(lab[hidden][:, None, :] - lab[visible][None, :, :], axis=2)
        group[hidden] = group[visible[np.argmin(d, axis=1)]]
    heads, group_of = np.unique(group, return_inverse=True)
    group_of = group_of.reshape(-1)
    g_area = np.bincount(group_of, weights=area, minlength=len(heads))
    # Each group prints in its largest member's colour: the largest visible area, then the smaller hex.
    by_size = np.lexsort((np.arange(len(keys)), -area, group_of))
    rep = by_size[np.searchsorted(group_of[by_size], np.arange(len(heads)))]
    order = np.lexsort((keys[rep], -g_area))  # extruders by area, then by hex
    filament_of_group = np.empty(len(heads), dtype=np.int64)
    filament_of_group[order] = np.arange(len(heads))
    filament_of_distinct = filament_of_group[group_of]
    hexes = colour_hexes(colours)
    names = colour_names(colours[rep[order]])
    filaments = []
    for f, i in enumerate(order.tolist()):
        members = np.flatnonzero(group_of == i)
        filaments.append(Filament(
            extruder=f + 1, hex=hexes[rep[i]], name=names[f], voxels=int(voxels[members].sum()),
            area=float(g_area[i]), merged=tuple(hexes[m] for m in members.tolist() if m != rep[i]),
        ))
    new_palette = np.full((len(order), 4), 255, dtype=np.uint8)
    new_palette[:, :3] = colours[rep[np.array(order)]]
    out = dataclasses.replace(mesh, colour=filament_of_distinct[distinct_of_index[mesh.colour]], palette=new_palette)
    return out, Filaments(tuple(filaments), len(keys), len(visible), limit)
