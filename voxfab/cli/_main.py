"""Entry point and subcommand registry.

Each subcommand is a module with ``HELP`` (one line), ``add_arguments(parser)``
and ``run(args) -> int``.  Command modules import only light code at module
level, so ``voxfab --version`` and ``voxfab info`` start fast.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import traceback
from collections.abc import Sequence

from voxfab._version import __version__
from voxfab.errors import EXIT_CODES, VoxfabError

#: Subcommand name → module.
COMMANDS: dict[str, str] = {
    "info": "voxfab.cli.info",
    "convert": "voxfab.cli.convert",
    "repo": "voxfab.cli.repo",
    "build": "voxfab.cli.build",
    "mesh": "voxfab.cli.mesh",
    "net": "voxfab.cli.net",
    "slices": "voxfab.cli.slices",
    "render": "voxfab.cli.render",
    "studio": "voxfab.cli.studio",
    "explore": "voxfab.cli.explore",
    "batch": "voxfab.cli.batch",
}


def build_parser() -> argparse.ArgumentParser:
    """Return the argument parser with every available subcommand."""
    parser = argparse.ArgumentParser(
        prog="voxfab", description="Fabrication CAD for voxel shapes."
    )
    parser.add_argument("--version", action="version", version=f"voxfab {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, module_name in COMMANDS.items():
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            if exc.name == module_name:
                continue  # a command whose module is not installed is left out
            raise
        p = sub.add_parser(name, help=module.HELP, description=module.HELP)
        p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                       help="show tracebacks on errors")
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def _exit_code(exc: VoxfabError) -> int:
    for cls in type(exc).__mro__:
        if cls in EXIT_CODES:
            return EXIT_CODES[cls]
    return 1


def _joined_negative_views(argv: list[str]) -> list[str]:
    """``--view -x`` as ``--view=-x``: argparse takes a value starting with ``-`` for an option."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        if argv[i] == "--view" and i + 1 < len(argv) and argv[i + 1] in ("-x", "-y", "-z"):
            out.append(f"--view={argv[i + 1]}")
            i += 2
            continue
        out.append(argv[i])
        i += 1
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; return the exit status."""
    from voxfab._shared import progress

    parser = build_parser()
    args = parser.parse_args(_joined_negative_views(sys.argv[1:] if argv is None else list(argv)))
    if not getattr(args, "command", None):
        parser.print_help()
        return 2
    progress.ENABLED = True
    try:
        return int(args._run(args) or 0)
    except VoxfabError as exc:
        if args.debug:
            traceback.print_exc()
        message = " ".join(str(exc).split("\n"))
        print(f"voxfab: error: {message}", file=sys.stderr)
        return _exit_code(exc)
    except KeyboardInterrupt:
        print("voxfab: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
