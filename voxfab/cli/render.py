"""``voxfab render``: pictures of a shape (PNG, GIF, PDF) or a repository contact sheet."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from voxfab.cli._common import add_frame_option, add_repository_option, load_command_shape, print_json
from voxfab.cli._options import integer_argument
from voxfab.errors import InvalidShapeError, UnknownFormatError

if TYPE_CHECKING:
    from voxfab.render import Picture
    from voxfab.unfold import Net

HELP = "draw a shape: 3D view, turntable GIF, slice sheet, net, triptych, or a repository contact sheet"

_VIEWS = ("iso", "x", "-x", "y", "-y", "z", "-z", "profile")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``render`` options."""
    from voxfab._shared.options import SeedOptions
    from voxfab.cli._options import add_option_arguments
    from voxfab.render import PictureOptions

    parser.add_argument("shape", metavar="SHAPE", nargs="?",
                        help="a shape file, or a repository name such as 00797.001")
    add_repository_option(parser)
    add_frame_option(parser)
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="OUT",
                        help="picture to write: .png, .gif (turntable), or .pdf (with --triptych)")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--triptych", action="store_true", help="net | slices | 3D under the shape's name")
    mode.add_argument("--slices", action="store_true", help="the layers in a grid, each numbered")
    mode.add_argument("--contact-sheet", action="store_true",
                      help="every shape of the repository (--repo) by volume, with names")
    mode.add_argument("--fold", type=Path, metavar="NET.json",
                      help="a GIF of this net folding up from the flat sheet to the shape (SHAPE, when given, "
                           "colours its faces)")
    parser.add_argument("--steps", type=integer_argument, default=36, metavar="N",
                        help="frames of the --fold animation, 2 to 240 (default 36)")
    parser.add_argument("--net", type=Path, metavar="NET.json",
                        help="a voxfab-net/1 file: draw it (or use it in --triptych) instead of unfolding")
    parser.add_argument("--view", choices=_VIEWS, default="iso", help="3D view (default iso; profile: turned towards the side whose silhouette says the most)")
    add_option_arguments(parser, SeedOptions)  # the triptych's net
    add_option_arguments(parser, PictureOptions)


def _picture(args: argparse.Namespace, out: Path, has_net: bool) -> Picture:
    """The one picture the flags ask for, written at ``out``."""
    from voxfab.render import Picture, PictureKind

    # --size is the picture's side; without it a turntable takes the pipeline's half size.
    if args.triptych:
        return Picture(PictureKind.TRIPTYCH, out.name, size=args.size)
    if args.slices:
        return Picture(PictureKind.SLICES, out.name, size=args.size)
    if has_net:
        return Picture(PictureKind.NET, out.name, size=args.size)
    ext = out.suffix.lower()
    if ext not in (".png", ".gif"):
        raise UnknownFormatError(f"{out}: a 3D picture can be written as .png or .gif, not {ext or 'no extension'!r}")
    if ext == ".gif":
        return Picture(PictureKind.TURNTABLE, out.name, size=args.size)
    return Picture(PictureKind.VIEW, out.name, view=args.view, size=args.size)


def _contact_sheet(args: argparse.Namespace, out: Path, tile: int, background: str) -> int:
    from voxfab import render

    if args.shape is not None:
        raise InvalidShapeError("render --contact-sheet: takes no SHAPE, only --repo PATH")
    if out.suffix.lower() not in (".png", ".pdf"):
        raise UnknownFormatError(f"{out}: a contact sheet can be written as .png or .pdf, "
                                 f"not {out.suffix.lower() or 'no extension'!r}")
    image = render.repository_contact_sheet(args.repo, tile=tile, background=background)
    render.save_picture(image, out, title=str(args.repo))
    print_json({"output": str(out), "kind": "contact-sheet", "width": image.width, "height": image.height})
    return 0


def _read_net(path: Path) -> Net:
    from voxfab._shared.limits import read_input_bytes
    from voxfab.unfold import Net

    try:  # a regular file only: a FIFO would block
        text = read_input_bytes(path, what="a net").decode("utf-8")
    except UnicodeDecodeError:
        raise InvalidShapeError(f"{path}: the net file is not UTF-8 text") from None
    return Net.from_json(text)


def _fold(args: argparse.Namespace, out: Path, size: int | None) -> int:
    from voxfab.render import save_fold_animation
    from voxfab.render._net import unfolded_shape

    if out.suffix.lower() != ".gif":
        raise UnknownFormatError(f"{out}: a fold animation is written as .gif, not {out.suffix.lower() or 'no extension'!r}")
    net = _read_net(args.fold)
    colours = None
    if args.shape is not None:  # the shape the net unfolds: its faces take their voxels' colours
        colours = unfolded_shape(load_command_shape(args)[0], net).colours
    frames = save_fold_animation(net, out, steps=args.steps, view=args.view, size=size or 400, colours=colours)
    print_json({"output": str(out), "kind": "fold", "faces": net.face_count, "frames": frames, "view": args.view})
    return 0


def run(args: argparse.Namespace) -> int:
    """Draw the requested picture through the pictures pipeline and print a JSON summary."""
    from voxfab import render
    from voxfab._shared.atomic import check_output
    from voxfab._shared.options import SeedOptions
    from voxfab.cli._options import options_from_args

    out: Path = args.output
    check_output(out)  # an existing folder, before the drawing
    if args.contact_sheet:
        # A repository picture, not a shape's: tiles of 200 px unless --size says otherwise.
        o = options_from_args(render.PictureOptions, args, size=args.size if args.size is not None else 200)
        return _contact_sheet(args, out, o.size, o.background)
    o = options_from_args(render.PictureOptions, args)
    seed = options_from_args(SeedOptions, args).seed
    if args.fold is not None:
        return _fold(args, out, args.size)
    if args.shape is None:
        raise InvalidShapeError("render: SHAPE is required (a file or a repository name)")
    picture = _picture(args, out, args.net is not None)
    shape, title, _ = load_command_shape(args)
    net = _read_net(args.net) if args.net is not None else None
    made = render.render_pictures(shape, o, out.parent, name=title, seed=seed, net=net, pictures=(picture,))
    drawn = dict(made.report["pictures"][0])
    kind = drawn.pop("kind")
    del drawn["path"]
    summary: dict[str, object] = {"output": str(out), "shape": title, "kind": kind}
    if kind == "triptych":
        summary["seed"] = seed
    elif kind == "view":
        summary["view"] = args.view
    summary.update(drawn)
    print_json(summary)
    return 0
