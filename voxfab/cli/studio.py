"""voxfab studio: the local web app to draw, edit, keep shapes and choose nets."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ._common import DEFAULT_REPOSITORY, add_join_option, add_pitch_option, check_repository_path
from ._options import integer_argument

HELP = "open the studio: draw, edit and keep shapes, choose nets, download files (local web app)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``studio`` options."""
    parser.add_argument("shape", nargs="?", metavar="SHAPE",
                        help="open the page with this shape: a file voxfab reads (.npy, .vox, .binvox, ...) "
                             "or a repository name such as 00797.001")
    add_pitch_option(parser)
    add_join_option(parser)
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: this computer only)")
    parser.add_argument("--port", type=integer_argument, default=8765, help="port (default 8765)")
    parser.add_argument("--repo", type=Path, default=DEFAULT_REPOSITORY, metavar="PATH",
                        help=f"repository database (default {DEFAULT_REPOSITORY})")
    parser.add_argument("--no-browser", action="store_true", help="do not open a browser")


def run(args: argparse.Namespace) -> int:
    """Serve until Ctrl+C."""
    import ipaddress
    import os
    import socket

    from voxfab.errors import InvalidShapeError
    from voxfab.studio import serve

    if not args.host.strip():
        raise InvalidShapeError("--host: expected an address such as 127.0.0.1, got ''")
    check_repository_path(args.repo)  # now, not inside the page at the first keep
    initial = _initial(args) if args.shape else None
    try:
        found = {info[4][0] for info in socket.getaddrinfo(args.host, None, type=socket.SOCK_STREAM)}
    except (socket.gaierror, UnicodeError) as exc:
        raise InvalidShapeError(f"--host: cannot use {args.host[:60]!r} as an address: "
                                f"{getattr(exc, 'strerror', None) or exc}") from None
    if not all(ipaddress.ip_address(a.split("%")[0]).is_loopback for a in found):
        print(f"voxfab: warning: --host {args.host}: the studio is reachable from the network, by anyone who "
              "can reach this computer; use 127.0.0.1 to keep it to yourself", file=sys.stderr, flush=True)
    serve(host=args.host, port=args.port, repo=args.repo, open_browser=not args.no_browser, initial=initial)
    # Stopped: jobs cancelled, the session's folder removed.  The interpreter's own teardown (the
    # compiled kernels, the solver) takes another 0.5-1 s that would only delay Ctrl-C, so end here.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


def _initial(args: argparse.Namespace):  # noqa: ANN202 - voxfab.studio._grid.InitialShape, imported lazily
    """SHAPE as the page's first shape, in its colours: read as every command reads it (joined into one piece
    with ``--join``), checked to fit the 25³ editor now."""
    from voxfab.repo import load_shape
    from voxfab.studio._grid import InitialShape

    from ._common import file_title, joined_if_asked, print_notes, shape_pitch

    shape, name, notes, scaled = load_shape(args.shape, args.repo, pitch=shape_pitch(args))
    shape = joined_if_asked(args, shape, notes)
    print_notes(notes)
    title = file_title(args.shape)  # a build's shape file goes by its recipe's name, any other by its file name
    label = name or (title if title != Path(args.shape).stem else Path(args.shape).name)
    return InitialShape.of(shape.grid, label=label, name=name,
                           pitch=float(shape.pitch) if scaled else None, colours=shape.colours)
