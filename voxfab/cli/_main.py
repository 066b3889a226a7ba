"""Entry point and subcommand registry.

Each subcommand is a module with ``HELP`` (one line), ``add_arguments(parser)``
and ``run(args) -> int``.  Command modules import only light code at module
level, so ``voxfab --version`` and ``voxfab info`` start fast.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import importlib
import signal
import sys
import threading
import traceback
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import NoReturn

from voxfab._version import __version__
from voxfab.errors import EXIT_CODES, VoxfabError, VoxfabWarning, one_line


def _commands() -> dict[str, str]:
    from voxfab.fabricate import outputs

    # The commands of the outputs come from the table of outputs, in its order.
    made = dict.fromkeys(o.command for o in outputs().values() if o.command)
    names = ["info", "convert", "repo", "build", *made, "studio", "explore", "batch", "census", "warmup"]
    return {name: f"voxfab.cli.{name}" for name in names}


#: Subcommand name → module.
COMMANDS: dict[str, str] = _commands()


class _Parser(argparse.ArgumentParser):
    """An argument parser whose refusals are one line, like every other voxfab error.

    argparse prints the whole usage block before its message; on a long command
    line that buries the one fact the user needs, so the usage stays behind ``--help``.
    Subcommand parsers are made from the same class.
    """

    def error(self, message: str) -> NoReturn:
        command = self.prog.partition(" ")[2]  # "net" of "voxfab net"; empty for voxfab itself
        where = f"{command}: " if command else ""
        self.exit(2, f"voxfab: error: {where}{message} (see {self.prog} --help)\n")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """Return the argument parser with every available subcommand.

    With ``only`` (a command name, or ``""`` for none), only that command's module is imported and its
    arguments added; the others are bare names, so a command loads what it runs and
    no other command's options (their classes pull in the plates, the pictures, the census).
    """
    from voxfab.cli._reference import help_link

    parser = _Parser(prog="voxfab", description="Fabrication CAD for voxel shapes.", epilog=help_link(""))
    parser.add_argument("--version", action="version", version=f"voxfab {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, module_name in COMMANDS.items():
        if only is not None and name != only:
            sub.add_parser(name)
            continue
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            if exc.name == module_name:
                continue  # a command whose module is not installed is left out
            raise
        p = sub.add_parser(name, help=module.HELP, description=module.HELP, epilog=help_link(name))
        p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                       help="show tracebacks on errors")
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def _command_named(argv: Sequence[str]) -> str | None:
    """The command ``argv`` runs: None for every command (``voxfab --help`` lists them), ``""`` for none.

    voxfab's own options (``--debug``, ``--version``) take no value, so the first word
    that is not an option is the command.
    """
    for arg in argv:
        if arg == "--version":
            return ""
        if arg in ("-h", "--help"):
            return None
        if not arg.startswith("-"):
            return arg if arg in COMMANDS else None
    return None


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


_PACKAGE_DIR = str(Path(__file__).resolve().parent.parent)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised as an exception so that temporary outputs are removed on the way out."""


def _terminate(signum: int, frame: object) -> None:
    raise Terminated


@contextlib.contextmanager
def _terminate_as_exception() -> Iterator[None]:
    """Turn SIGTERM into :class:`Terminated` while a command runs (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                  file: object = None, line: str | None = None) -> None:
    """voxfab's own warnings as one line each; library warnings (numpy, Pillow...) are not the user's business.

    voxfab's own are :class:`VoxfabWarning` or a plain ``UserWarning`` raised in voxfab's code.
    """
    own = category is UserWarning and str(filename).startswith(_PACKAGE_DIR)
    if issubclass(category, VoxfabWarning) or own:
        print(f"voxfab: warning: {one_line(message)}", file=sys.stderr)


@contextlib.contextmanager
def _quiet_warnings(debug: bool) -> Iterator[None]:
    """Show voxfab's warnings as one line; hide library warnings and log records unless ``--debug``.

    Libraries log through :mod:`logging` (trimesh logs the tracebacks of parsers it
    falls back from); with no handler configured, Python prints those records on
    stderr, so a handler that drops them stands in while the command runs.
    """
    import logging

    root = logging.getLogger()
    quiet = logging.NullHandler()
    with warnings.catch_warnings():
        if not debug:
            warnings.simplefilter("default")
            warnings.showwarning = _show_warning
            root.addHandler(quiet)
        try:
            yield
        finally:
            root.removeHandler(quiet)


#: Allocations between two young collections while a command runs (Python's default is 700).  Loading
#: numba and the search kernels makes objects by the hundred thousand that live as long as the process;
#: collecting them over and over at the default cost a tenth of a second of a net's run.
GC_YOUNG = 10_000


def _stopped(code: int, ends_process: bool) -> int:
    """The exit status of a stopped command; a process that ends with it ends here, once its exit handlers ran.

    What the command made is cleaned up already (its ``finally`` blocks ran as the interrupt left them).  A
    thread a library still runs (a solver's workers that the same Ctrl-C stopped half way) is not waited for
    nor torn down by the interpreter's exit, which aborted such a process ("terminate called without an
    active exception") instead of ending it with ``code``.
    """
    if not ends_process:
        return code
    import atexit
    import os

    atexit._run_exitfuncs()  # noqa: SLF001 - the handlers an exit runs (Dask's, logging's), then no teardown
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; return the exit status.

    Every error caused by input ends here as one line ``voxfab: error: ...`` (at
    most 600 characters, quoting at most 80 of any input) and the exit status of
    its class; an interrupt (SIGINT, SIGTERM) removes temporary outputs and
    exits with 130 or 143.
    """
    from voxfab._shared import progress

    ends_process = argv is None  # run as the program (the console script, python -m voxfab), not called
    argv = _joined_negative_views(sys.argv[1:] if argv is None else list(argv))
    parser = build_parser(_command_named(argv))
    for arg in argv:
        # argparse (3.11) turns the value of "--opt=--" into [] and skips its type check.
        if arg.startswith("-") and arg.endswith("=--"):
            parser.error(f"argument {arg[:-3]}: expected a value, got '--'")
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return 2
    progress.ENABLED = True
    thresholds = gc.get_threshold()
    gc.set_threshold(GC_YOUNG, *thresholds[1:])
    try:
        with _terminate_as_exception(), _quiet_warnings(args.debug):
            return int(args._run(args) or 0)
    except VoxfabError as exc:
        if args.debug:
            traceback.print_exc()
        print(f"voxfab: error: {one_line(exc)}", file=sys.stderr)
        return _exit_code(exc)
    except Terminated:
        print("voxfab: terminated", file=sys.stderr)
        return _stopped(143, ends_process)
    except KeyboardInterrupt:
        print("voxfab: interrupted", file=sys.stderr)
        return _stopped(130, ends_process)
    finally:
        gc.set_threshold(*thresholds)
        if ends_process:
            # The process ends with this command: leave what it made to the exit, unscanned (a last full
            # collection of numba's objects costs a net a fifth of a second).
            gc.freeze()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
