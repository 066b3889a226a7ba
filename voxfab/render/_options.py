"""The options of pictures, declared once (CLI flags, recipe keys, checks, README table)."""

from __future__ import annotations

import dataclasses

from voxfab._shared.options import Options, option

from ._views import View

VIEWS: tuple[str, ...] = tuple(v.value for v in View)


def color_problem(value: str) -> str | None:
    """Why ``value`` is not a colour name or ``#rrggbb``, or None."""
    from PIL import ImageColor

    try:
        ImageColor.getrgb(value)
    except ValueError:
        return "expected a colour name or #rrggbb"
    return None


@dataclasses.dataclass(frozen=True)
class PictureOptions(Options):
    """Which pictures of a shape to make, and how (see :func:`render`, :func:`triptych`)."""

    size: int = option(800, help="picture side (triptych panels too; the turntable uses half)", unit="px",
                       low=16, high=8192)
    views: tuple[str, ...] = option(("profile",), help="3D views written as render_VIEW.png (profile: turned "
                                    "towards the side whose silhouette says the most)", choices=VIEWS, cli=False)
    triptych: bool = option(True, help="also write triptych.png and triptych.pdf (net | slices | 3D)",
                            cli=False)
    net_picture: bool = option(False, help="also write net_picture.png, the triptych's net on its own", cli=False)
    turntable: bool = option(False, help="also write turntable.gif", cli=False)
    slices: bool = option(False, help="also write slices.png, the layers bottom up", cli=False)
    frames: int = option(36, help="turntable frames", low=1, high=720)
    background: str = option("white", help="paper colour (a name or #rrggbb)", check=color_problem,
                             metavar="COLOR")
    color: str = option("#eccc96", help="colour of the cubes (a name or #rrggbb)", check=color_problem,
                        metavar="COLOR")


@dataclasses.dataclass(frozen=True)
class AnimationOptions(Options):
    """The recipe output ``animation``: a tube's profile turning along its spine (see :func:`save_tube_animation`)."""

    steps: int = option(24, help="frames of the animation", low=1, high=720, cli=False)
    turn: float = option(360.0, help="rotation of the profile over the whole animation", unit="degrees",
                         low=-36000.0, high=36000.0, cli=False)
    view: str = option("iso", help="3D view", choices=VIEWS, cli=False)
    size: int = option(400, help="picture side", unit="px", low=16, high=8192, cli=False)
    duration_ms: int = option(80, help="time per frame", unit="ms", low=10, high=10000, cli=False)
