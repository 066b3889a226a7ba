"""voxfab studio: the local web app to draw, edit, keep shapes and choose nets."""

from __future__ import annotations

import argparse
from pathlib import Path

from ._common import DEFAULT_REPOSITORY

HELP = "open the studio: draw, edit and keep shapes, choose nets, download files (local web app)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``studio`` options."""
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: this computer only)")
    parser.add_argument("--port", type=int, default=8765, help="port (default 8765)")
    parser.add_argument("--repo", type=Path, default=DEFAULT_REPOSITORY, metavar="PATH",
                        help=f"repository database (default {DEFAULT_REPOSITORY})")
    parser.add_argument("--no-browser", action="store_true", help="do not open a browser")


def run(args: argparse.Namespace) -> int:
    """Serve until Ctrl+C."""
    from voxfab.studio import serve

    serve(host=args.host, port=args.port, repo=args.repo, open_browser=not args.no_browser)
    return 0
