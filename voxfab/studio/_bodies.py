"""What each endpoint's JSON body may hold, and the checks of its numbers by the CLI's option declarations.

One table of fields per endpoint: a key outside it is refused
(:func:`._http.only_fields`), so nothing the page or a script sends is dropped
without a word.  The options of the gallery and of "does it fit?" are those of
:class:`~voxfab.fabricate.netdraw.NetOptions` and
:class:`~voxfab.fabricate.netdraw.DrawingOptions` that have an effect there; the
others are refused with the reason, in the CLI's words where it has some.
"""

from __future__ import annotations

from typing import Any

from voxfab.errors import InvalidShapeError

from ._http import declared, only_fields

#: The fields of each endpoint's body.
CHECK = ("grid",)
RECIPE = ("shape", "name", "pitch")
ANIMATE = ("shape", "steps")
REPO_ADD = ("grid", "draft")
NETS = ("grid", "seed", "count", "options", "constraints")
FITS = ("grid", "options")
MAKE = ("grid", "artefact", "pitch", "title", "options", "net", "placement", "shape")
EDIT = ("job", "index", "cut", "join", "undo", "split", "grid", "marks", "placement", "repack")
NET_PICK = ("job", "index")
PAINT_FIT = ("grid",)
JOIN = ("grid",)
SHAPE_FILE = ("grid", "format", "title", "pitch")

#: Frames of the studio's animation preview (fewer than the recipe's 720: it is sent as JSON grids).
ANIMATE_STEPS = (2, 72)

#: Net options a gallery takes no notice of, and why (the CLI's words where it has them).
GALLERY_WITHOUT_EFFECT = {
    "count": 'the gallery\'s number of nets is the body\'s "count"',
    "zipper": "for one JSON net (voxfab net NET.json --strategy exact --zipper); the gallery draws nets on sheets",
    "min_box": "for JSON nets (voxfab net NET.json --strategy exact --min-box); drawings fit their sheet",
    "fit": "drawn nets always fit their sheet",
    "formats": "the gallery draws no files; /api/make writes each one",
}

#: The options "does one piece fit this sheet?" reads: the sheet, the face size (else the smallest
#: legible one, from the marks), the search's time, and what sets the room on the sheet.
FITS_OPTIONS = ("sheet", "face_size", "timeout", "margin", "tab_width", "min_tab_depth", "numbers", "tabs",
                "label_height", "min_label_height")


def seed(value: Any) -> int:
    """A gallery's seed, by the CLI's declaration of ``--seed``."""
    from voxfab._shared.options import SeedOptions

    return int(declared(SeedOptions, "seed", value))


def count(value: Any, most: int) -> int:
    """A gallery's number of nets, by the declaration of ``--count``, and at most ``most`` on the page."""
    from voxfab.fabricate.netdraw import NetOptions

    n = int(declared(NetOptions, "count", value))
    if n > most:
        raise InvalidShapeError(f"count: expected an integer from 1 to {most} (the nets a gallery shows), got {n}")
    return n


def pitch(value: Any) -> float:
    """A shape's mm per voxel, by the declaration of ``--pitch`` (absent: 1)."""
    from voxfab.shape import ShapeOptions

    checked = declared(ShapeOptions, "pitch", value)
    return 1.0 if checked is None else float(checked)


def steps(value: Any) -> int:
    """Frames of the animation preview: the recipe's declaration, then the studio's bounds."""
    from voxfab.render import AnimationOptions

    n = int(declared(AnimationOptions, "steps", value))
    lo, hi = ANIMATE_STEPS
    if not lo <= n <= hi:
        raise InvalidShapeError(f"steps: expected an integer from {lo} to {hi} in the studio's preview, got {n}")
    return n


def whole(value: Any, *, name: str, lo: int, hi: int) -> int:
    """An index or count the page sends (a net's index, a page's size), whatever JSON number it is."""
    from voxfab._shared.options import quote

    if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
        raise InvalidShapeError(f"{name}: expected a whole number from {lo} to {hi}, got {quote(value, 40)}")
    return value


def flag(value: Any, *, name: str, default: bool = False) -> bool:
    """A true/false field (absent: ``default``)."""
    from voxfab._shared.options import quote

    if value is None:
        return default
    if not isinstance(value, bool):
        raise InvalidShapeError(f"{name}: expected true or false, got {quote(value, 40)}")
    return value


def gallery_options(values: Any, *, defaults: dict[str, Any]) -> tuple[Any, Any]:
    """The gallery's net and drawing options: each one checked by its declaration, none without effect."""
    from voxfab.fabricate import netdraw

    if values is None:
        values = {}
    if not isinstance(values, dict):
        raise InvalidShapeError("options: expected an object of option names and values")
    for key in sorted(values, key=str):
        if key in GALLERY_WITHOUT_EFFECT:
            raise InvalidShapeError(f"options.{key}: {GALLERY_WITHOUT_EFFECT[key]}")
    return netdraw.gallery_options(values, defaults=defaults)


def fits_options(values: Any, *, defaults: dict[str, Any]) -> tuple[Any, Any]:
    """The options of "does one piece fit this sheet?": only those it reads, checked by their declarations."""
    if values is None:
        values = {}
    if not isinstance(values, dict):
        raise InvalidShapeError("options: expected an object of option names and values")
    only_fields(values, FITS_OPTIONS, where="options",
                hint="one piece, found by the exact search with cavities filled; the gallery takes the others")
    return gallery_options(values, defaults=defaults)
