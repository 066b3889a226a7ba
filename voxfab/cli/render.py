"""``voxfab render``: pictures of a shape (PNG, GIF, PDF) or a repository contact sheet."""

from __future__ import annotations

import argparse
from pathlib import Path

from voxfab.cli._common import add_repository_option, load_shape, print_json, print_notes
from voxfab.errors import InvalidShapeError, UnknownFormatError

HELP = "draw a shape: 3D view, turntable GIF, slice sheet, net, triptych, or a repository contact sheet"

_VIEWS = ("iso", "x", "-x", "y", "-y", "z", "-z")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``render`` options."""
    from voxfab.cli._options import add_option_arguments
    from voxfab.render import PictureOptions

    parser.add_argument("shape", metavar="SHAPE", nargs="?",
                        help="a shape file, or a repository name such as 00797.001")
    add_repository_option(parser)
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="OUT",
                        help="picture to write: .png, .gif (turntable), or .pdf (with --triptych)")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--triptych", action="store_true", help="net | slices | 3D under the shape's name")
    mode.add_argument("--slices", action="store_true", help="the layers in a grid, each numbered")
    mode.add_argument("--contact-sheet", action="store_true",
                      help="every shape of the repository (--repo) by volume, with names")
    parser.add_argument("--net", type=Path, metavar="NET.json",
                        help="a voxfab-net/1 file: draw it (or use it in --triptych) instead of unfolding")
    parser.add_argument("--view", choices=_VIEWS, default="iso", help="3D view (default iso)")
    parser.add_argument("--seed", type=int, default=0, metavar="N", help="seed of the triptych's net (default 0)")
    add_option_arguments(parser, PictureOptions)


def _suffix(path: Path, allowed: tuple[str, ...], what: str) -> str:
    ext = path.suffix.lower()
    if ext not in allowed:
        raise UnknownFormatError(f"{path}: {what} can be written as {' or '.join(allowed)}, not {ext or 'no extension'!r}")
    return ext


def run(args: argparse.Namespace) -> int:
    """Draw the requested picture and print a JSON summary."""
    from voxfab import render
    from voxfab._shared.atomic import check_output, write_bytes
    from voxfab.cli._options import options_from_args

    out: Path = args.output
    check_output(out)  # an existing folder, before the drawing
    # The default size depends on the picture: 200 px per contact-sheet tile, 400 for a GIF, else 800.
    size = 200 if args.contact_sheet else 400 if out.suffix.lower() == ".gif" and not (args.triptych or args.slices) \
        else 800
    o = options_from_args(render.PictureOptions, args, size=args.size if args.size is not None else size)
    if args.contact_sheet:
        if args.shape is not None:
            raise InvalidShapeError("render --contact-sheet: takes no SHAPE, only --repo PATH")
        _suffix(out, (".png", ".pdf"), "a contact sheet")
        image = render.repository_contact_sheet(args.repo, tile=o.size, background=o.background)
        render.save_picture(image, out, title=str(args.repo))
        print_json({"output": str(out), "kind": "contact-sheet", "width": image.width, "height": image.height})
        return 0
    if args.shape is None:
        raise InvalidShapeError("render: SHAPE is required (a file or a repository name)")
    shape, name, notes = load_shape(args.shape, args.repo)
    print_notes(notes)
    title = name or Path(args.shape).stem
    net = None
    if args.net is not None:
        from voxfab._shared.limits import read_input_bytes
        from voxfab.unfold import Net

        try:  # a regular file only: a FIFO would block
            text = read_input_bytes(args.net, what="a net").decode("utf-8")
        except UnicodeDecodeError:
            raise InvalidShapeError(f"{args.net}: the net file is not UTF-8 text") from None
        net = Net.from_json(text)

    summary: dict[str, object] = {"output": str(out), "shape": title}
    if args.triptych:
        _suffix(out, (".png", ".pdf"), "a triptych")
        image = render.triptych(shape, name=title, rng=args.seed, net=net, panel=o.size,
                                background=o.background, color=o.color)
        render.save_picture(image, out, title=title)
        summary.update(kind="triptych", seed=args.seed)
    elif args.slices:
        _suffix(out, (".png", ".pdf"), "a slice sheet")
        image = render.slice_sheet(shape, size=o.size, background=o.background, color=o.color)
        render.save_picture(image, out, title=title)
        summary.update(kind="slices")
    elif net is not None:
        _suffix(out, (".png", ".pdf"), "a net picture")
        image = render.net_picture(net, shape, size=o.size, background=o.background)
        render.save_picture(image, out, title=title)
        summary.update(kind="net")
    elif _suffix(out, (".png", ".gif"), "a 3D picture") == ".gif":
        frames = render.save_turntable(shape, out, frames=o.frames, size=o.size, background=o.background,
                                       color=o.color)
        summary.update(kind="turntable", frames=frames, width=o.size, height=o.size)
        print_json(summary)
        return 0
    else:
        image = render.render(shape, view=args.view, size=o.size, background=o.background, color=o.color)
        write_bytes(out, render.png_bytes(image))
        summary.update(kind="view", view=args.view)
    summary.update(width=image.width, height=image.height)
    print_json(summary)
    return 0
