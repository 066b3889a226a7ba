"""Run the CLI in-process on hostile input and check the promise of issue 14.

Every run either succeeds or fails with exactly one ``voxfab: error:`` line and
no traceback, within a time bound.  A non-voxfab exception escaping ``main`` is a
bug: it propagates to the test, with its traceback.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import signal
import threading
import time
from collections.abc import Iterator, Sequence

from voxfab.cli import main
from voxfab.cli._common import STRICT_EXIT

#: Seconds one CLI run may take in the fuzz tests (shared 2-core machine: generous).
RUN_SECONDS = 30.0


class RunTimeout(Exception):
    """A run went over its time bound."""


@contextlib.contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`RunTimeout` in the main thread after ``seconds`` (SIGALRM)."""
    if threading.current_thread() is not threading.main_thread():  # pragma: no cover
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise RunTimeout(f"over {seconds} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


@dataclasses.dataclass(frozen=True)
class Outcome:
    """What one CLI run did."""

    argv: tuple[str, ...]
    code: int
    out: str
    err: str
    seconds: float
    usage: bool = False  # argparse refused the command line (exit 2, usage text)

    @property
    def error_lines(self) -> list[str]:
        return [line for line in self.err.splitlines() if line.startswith("voxfab: error:")]


def run_cli(argv: Sequence[object], *, seconds: float = RUN_SECONDS) -> Outcome:
    """Run ``voxfab ARGV`` in this process and capture its output."""
    args = tuple(str(a) for a in argv)
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    usage = False
    with time_limit(seconds), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(args))
        except SystemExit as exc:  # argparse: a usage error (2) or --help (0)
            code = exc.code if isinstance(exc.code, int) else 2
            usage = True
    return Outcome(args, code, out.getvalue(), err.getvalue(), time.perf_counter() - start, usage)


def check_outcome(o: Outcome, *, seconds: float = RUN_SECONDS) -> Outcome:
    """Assert the promise: success, or one clean error line; no traceback; in time."""
    assert "Traceback" not in o.err, (o.argv, o.err)
    assert o.seconds < seconds, (o.argv, o.seconds)
    if o.code == 0:
        return o
    if o.code == STRICT_EXIT and "--strict" in o.argv:
        # The output is made; --strict fails the run because of its warnings, one line each.
        assert o.err.count("voxfab: warning:") >= 1 and not o.error_lines, (o.argv, o.err)
        return o
    if o.usage:
        # argparse's own refusal: one "voxfab: error:" line, like every other error.
        assert o.code == 2 and o.err.splitlines() == o.error_lines and len(o.error_lines) == 1, (o.argv, o.err)
        return o
    assert len(o.error_lines) == 1, (o.argv, o.err)
    assert len(o.error_lines[0]) <= 700, (o.argv, o.error_lines[0][:200])
    return o


def refused(argv: Sequence[object], *, seconds: float = RUN_SECONDS) -> str:
    """Run ``argv``, assert it fails cleanly, and return its error line."""
    o = check_outcome(run_cli(argv, seconds=seconds), seconds=seconds)
    assert o.code != 0 and not o.usage, (o.argv, o.out[-300:], o.err[-300:])
    return o.error_lines[0]


# --- strategies -------------------------------------------------------------------------------------

import json as _json  # noqa: E402
import math as _math  # noqa: E402
import typing as _typing  # noqa: E402
from pathlib import Path as _Path  # noqa: E402

from hypothesis import strategies as st  # noqa: E402

#: Numbers that break naive code: zero, negatives, tiny, huge, non-finite.
NASTY_FLOATS = ["0", "-0", "-3", "1e-9", "0.0001", "1e9", "1e300", "-1e300", "nan", "inf", "-inf", "1e-320"]
NASTY_INTS = ["0", "-1", "1", "2", "3", "1000", "1000000000", str(2**63), "-99999999999"]
NASTY_TEXT = ["", " ", "x", "1x1", "0x0", "600x400", "1e9x1e9", "-3x4", "nanxnan", "A4", "a4 landscape",
              "../../../../etc/passwd", "\u00e9\u00e8", "x" * 300, "--", "-", "#ff0000", "red,blue"]


def number_text(kind: type) -> st.SearchStrategy[str]:
    """An option value for an int or float option: usual, extreme or not a number at all."""
    # Mostly values argparse takes, so runs reach voxfab's own checks; now and then not a number.
    if kind is int:
        usual = st.integers(0, 40).map(str)
        return st.one_of(usual, usual, usual, st.sampled_from(NASTY_INTS), st.sampled_from(NASTY_INTS),
                         st.sampled_from(["1.5", "x", "1e3"]))
    usual = st.floats(0.1, 100, allow_nan=False).map(lambda f: f"{f:.4g}")
    return st.one_of(usual, usual, usual, st.sampled_from(NASTY_FLOATS), st.sampled_from(NASTY_FLOATS),
                     st.sampled_from(["x", "1,5", ""]))


def toml_text(data: dict) -> str:
    """A TOML document for ``data`` (top-level scalars, then tables and arrays of tables)."""

    def value(v: object) -> str:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return str(v)
        if isinstance(v, float):
            return "nan" if _math.isnan(v) else ("inf" if v > 0 else "-inf") if _math.isinf(v) else repr(v)
        if isinstance(v, str):
            # TOML wants every character but controls raw; DEL is a control in TOML, not in JSON.
            return _json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f"{value(k)} = {value(x)}" for k, x in v.items()) + "}"
        raise TypeError(type(v))

    lines, tables = [], []
    for key, v in data.items():
        if isinstance(v, dict) and v and all(isinstance(x, dict) for x in v.values()):
            for sub, table in v.items():
                tables.append(f"[{value(key)}.{value(sub)}]")
                tables += [f"{value(k)} = {value(x)}" for k, x in table.items()]
        elif isinstance(v, dict):
            tables.append(f"[{value(key)}]")
            tables += [f"{value(k)} = {value(x)}" for k, x in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for table in v:
                tables.append(f"[[{value(key)}]]")
                tables += [f"{value(k)} = {value(x)}" for k, x in table.items()]
        else:
            lines.append(f"{value(key)} = {value(v)}")
    return "\n".join(lines + tables) + "\n"


TOML_SCALARS = st.one_of(
    st.integers(-(2**63), 2**63 - 1),
    st.floats(allow_nan=True, allow_infinity=True),
    st.booleans(),
    st.text(max_size=20),
)
#: Any TOML value, a little nested.
TOML_VALUES = st.recursive(TOML_SCALARS, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(min_size=1, max_size=8), inner, max_size=3)), max_leaves=8)

#: File names a recipe may give: drawings beside it, missing ones, escapes, odd kinds.
RECIPE_FILES = ["drawing.json", "drawing.csv", "drawing.svg", "bitmap.png", "ball.npy", "missing.json",
                "../outside.json", "../../../../../../etc/passwd", "/etc/passwd", "fifo.json", "folder.json",
                "deep.json", "bomb.png", "link.json", "bigint.json"]
EXPRESSIONS = ["x^2 + y^2 + z^2 - 1", "x^2 + y^2 - 1", "sin(x) + cos(y)", "x^", "1/0", "log(x)", "sqrt(-1)",
               "__import__('os')", "x" * 1200, "-" * 500 + "x", "max(x, y, z) - 0.5", "atan2(y, x) - t", "abs(x)+abs(y)-1"]


#: Sources that build, one per maker (files as :func:`hostile_recipe_folder` makes them).
GOOD_SOURCES = [
    {"maker": "implicit", "expression": "x^2 + y^2 + z^2 - 1"},
    {"maker": "focal", "foci": [[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]], "weights": [1.0, 2.0], "radius": 5.0},
    {"maker": "revolution", "curve": "x^2 + y^2 - 1", "generatrix": "drawing.json"},
    {"maker": "revolution", "curve": "drawing.svg", "generatrix": "bitmap.png"},
    {"maker": "tube", "spine": ["cos(2*pi*t)", "sin(2*pi*t)", "0"], "profile": "x^2 + y^2 - 1", "radius": 0.3},
]


def value_for(tp: object, strict: bool = False) -> st.SearchStrategy[object]:
    """A recipe value for a type hint: mostly of that type (often extreme), sometimes any TOML value.

    ``strict``: always of that type.
    """
    origin = _typing.get_origin(tp)
    args = _typing.get_args(tp)
    if origin is _typing.Literal:
        right = st.sampled_from(args)
    elif origin in (_typing.Union, __import__("types").UnionType):
        right = st.one_of([value_for(a, strict) for a in args if a is not type(None)])
    elif origin in (list, tuple) and strict and _typing.get_origin(args[0]) is list:
        # points: mostly 3D, as foci and spines want
        right = st.lists(st.lists(value_for(float, strict), min_size=3, max_size=3), min_size=1, max_size=4)
    elif origin in (list, tuple):
        right = st.lists(value_for(args[0], strict) if args else TOML_SCALARS, max_size=5)
    elif tp is float:
        usual = st.floats(0.1, 3) if strict else st.floats(-10, 10)
        right = st.one_of(usual, usual, st.sampled_from([0.0, -1.0, 1e-9, 1e300, float("inf"), float("nan")]))
    elif tp is int:
        usual = st.integers(0, 3) if strict else st.integers(-2, 30)
        right = st.one_of(usual, usual, st.sampled_from([0, 10**9, 2**62, -(2**62)]))
    elif tp is bool:
        right = st.booleans()
    elif tp is str and strict:
        right = st.one_of(st.sampled_from(EXPRESSIONS[:3]), st.sampled_from(EXPRESSIONS), st.sampled_from(RECIPE_FILES))
    elif tp is str:
        right = st.one_of(st.sampled_from(EXPRESSIONS), st.sampled_from(RECIPE_FILES), st.text(max_size=12))
    else:
        right = TOML_SCALARS
    return right if strict else st.one_of(right, right, right, TOML_VALUES)


@st.composite
def recipe_trees(draw: st.DrawFn, *, with_outputs: bool = True, strict: bool = False) -> dict:
    """A recipe over the real schema keys: makers and outputs with their real options, random values.

    ``strict``: the structure and value types are right (the values may still be
    extreme), so most recipes reach the makers.
    """
    from voxfab.digitize import available_makers, maker_params
    from voxfab.fabricate import outputs as output_kinds
    from voxfab.recipe._schema import _OPERATIONS

    def source() -> dict:
        if strict and draw(st.booleans()):
            # A working source with one key changed: the build reaches deep into the maker.
            src = dict(draw(st.sampled_from(GOOD_SOURCES)))
            src["size"] = draw(st.integers(4, 10))
            options = maker_params(src["maker"])
            key = draw(st.sampled_from(sorted(options)))
            src[key] = draw(value_for(options[key].hint, strict))
            return src
        if draw(st.integers(0, 4)) == 0:
            src: dict = {"file": draw(st.sampled_from(RECIPE_FILES))}
            if draw(st.booleans()):
                src["resolution"] = draw(value_for(int))
            return src
        maker = draw(st.sampled_from(available_makers() if strict else [*available_makers(), "nonsense"]))
        src = {"maker": maker}
        if maker == "nonsense":
            return src
        for key, param in maker_params(maker).items():
            if param.required and draw(st.integers(0, 9)) > 0 or draw(st.integers(0, 3)) == 0:
                src[key] = draw(value_for(param.hint, strict))
        if "size" in src and isinstance(src["size"], int) and not isinstance(src["size"], bool):
            src["size"] = draw(st.sampled_from([src["size"], 5, 8, 12]))
        if not strict and draw(st.integers(0, 9)) == 0:
            src[draw(st.sampled_from(["unknown", "Size", "maker2"]))] = draw(TOML_SCALARS)
        return src

    data: dict = {}
    if draw(st.booleans()):
        data["name"] = draw(st.one_of(st.sampled_from(["r", "a.b", "../up", "", "x" * 300]), st.text(max_size=10)))
    for key, tp in (("seed", int), ("pitch", float), ("description", str)):
        if not strict and draw(st.integers(0, 3)) == 0:
            data[key] = draw(value_for(tp))
    if strict or draw(st.integers(0, 19)):
        data["source"] = source()
    if draw(st.integers(0, 2)) == 0:
        ops = []
        for _ in range(draw(st.integers(0, 3))):
            op = draw(st.sampled_from([*_OPERATIONS] if strict else [*_OPERATIONS, "explode"]))
            item: dict = {"op": op}
            for key, tp in _OPERATIONS.get(op, {}).items():
                if draw(st.booleans()):
                    item[key] = source() if tp is dict else draw(value_for(tp, strict))
            ops.append(item)
        data["operations"] = ops
    if with_outputs and draw(st.integers(0, 2)) == 0:
        outputs = {}
        kinds = output_kinds()
        any_value = st.one_of(value_for(float), value_for(int), value_for(str), value_for(bool))
        for name in draw(st.lists(st.sampled_from([*sorted(kinds), "hologram"]), max_size=2, unique=True)):
            table = {}
            for key in kinds[name].keys if name in kinds else ():
                if draw(st.integers(0, 3)) == 0:
                    table[key] = draw(any_value)
            outputs[name] = table
        data["outputs"] = outputs
    if not strict and draw(st.integers(0, 19)) == 0:
        data[draw(st.sampled_from(["extra", "Source", "outputs.mesh"]))] = draw(TOML_VALUES)
    return data


def hostile_recipe_folder(folder: _Path) -> None:
    """The files :data:`RECIPE_FILES` names, good and hostile, in and around ``folder``."""
    import os

    import numpy as np
    from PIL import Image

    from voxfab import io
    from voxfab.shape import examples

    folder.mkdir(parents=True, exist_ok=True)
    (folder / "drawing.json").write_text("[[0.5, 0], [2, 0], [2, 3], [0.5, 3], [0.5, 0]]")
    (folder / "drawing.csv").write_text("0,0\n1,0\n1,2\n0,2\n0,0\n")
    (folder / "drawing.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L10 0 L10 10 Z"/></svg>')
    Image.fromarray(np.pad(np.zeros((8, 8), np.uint8), 4, constant_values=255)).save(folder / "bitmap.png")
    io.write(examples.ball(3), folder / "ball.npy")
    (folder.parent / "outside.json").write_text("[[0, 0], [1, 0], [1, 1]]")
    if not (folder / "fifo.json").exists():
        os.mkfifo(folder / "fifo.json")
    (folder / "folder.json").mkdir(exist_ok=True)
    (folder / "deep.json").write_text("[" * 100000)
    (folder / "bigint.json").write_text(f"[[0, 0], [1, {'7' * 5000}], [0, 1]]")
    (folder / "bomb.png").write_bytes(png_claiming(60000, 60000))
    link = folder / "link.json"
    if not link.is_symlink():
        link.symlink_to(folder.parent / "outside.json")


def png_claiming(width: int, height: int) -> bytes:
    """A small PNG file whose header claims ``width`` x ``height`` pixels."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0" * 64)) + chunk(b"IEND", b"")


#: Tokens that break text parsers.
NASTY_TOKENS = [b" nan", b" inf", b" 1e999", b" -1", b" 4294967295", b" 99999999999999999999", b"\n", b"\x00",
                b"\xff\xfe", b"//", b" 0", b"\r\n", b"#", b"solid", b"endsolid", b"facet normal", b"vertex",
                b"element vertex 1000000000", b"f 1 2 99999"]
_INTS = [0, 1, 255, 256, 65535, 2**31 - 1, 2**31, 2**32 - 1]


@st.composite
def mutated(draw: st.DrawFn, valid: bytes) -> bytes:
    """``valid`` with a few mutations: bit flips, cuts, insertions, huge integers, repeats, tokens."""
    data = bytearray(valid)
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["flip", "cut", "insert", "int", "repeat", "token", "garbage"]))
        pos = draw(st.integers(0, max(len(data) - 1, 0)))
        if kind == "flip" and data:
            data[pos] ^= 1 << draw(st.integers(0, 7))
        elif kind == "cut":
            del data[pos:]
        elif kind == "insert":
            data[pos:pos] = draw(st.binary(max_size=32))
        elif kind == "int":
            order = draw(st.sampled_from(["little", "big"]))
            data[pos:pos + 4] = draw(st.sampled_from(_INTS)).to_bytes(4, order)
        elif kind == "repeat":
            data[pos:pos] = bytes(data[pos:pos + draw(st.integers(1, 64))]) * draw(st.integers(1, 40))
        elif kind == "token":
            data[pos:pos] = draw(st.sampled_from(NASTY_TOKENS))
        else:
            data = bytearray(draw(st.binary(max_size=300)))
    return bytes(data)


def valid_files(folder: _Path) -> dict[str, bytes]:
    """Valid bytes of every readable format (for ``"/"``: of one PNG slice)."""
    import numpy as np
    import trimesh
    from PIL import Image

    from voxfab import io
    from voxfab.shape import examples

    folder.mkdir(parents=True, exist_ok=True)
    out: dict[str, bytes] = {}
    for ext in (".npy", ".npz", ".txt", ".vox", ".binvox"):
        io.write(examples.ball(3), folder / f"valid{ext}")
        out[ext] = (folder / f"valid{ext}").read_bytes()
    Image.fromarray(np.where(examples.ball(3)[:, :, 3], 0, 255).astype(np.uint8), "L").save(folder / "valid.png")
    out[".png"] = out["/"] = (folder / "valid.png").read_bytes()
    mesh = trimesh.creation.icosphere(subdivisions=1, radius=2.0)
    mesh.visual.face_colors = [200, 40, 40, 255]  # a coloured mesh: the colour readers are fuzzed too
    for ext in (".stl", ".obj", ".ply", ".3mf", ".glb"):
        mesh.export(folder / f"valid{ext}")
        out[ext] = (folder / f"valid{ext}").read_bytes()
    out[".stl-ascii"] = trimesh.exchange.stl.export_stl_ascii(mesh).encode()
    return out


def put(folder: _Path, ext: str, data: bytes, name: str = "input") -> _Path:
    """Store ``data`` as a file of format ``ext`` in ``folder``; return what to read."""
    folder.mkdir(parents=True, exist_ok=True)
    if ext == "/":
        stack = folder / name
        stack.mkdir(parents=True, exist_ok=True)
        (stack / "z0.png").write_bytes(data)
        (stack / "z1.png").write_bytes(data)
        return stack
    path = folder / f"{name}{ext.split('-')[0]}"
    path.write_bytes(data)
    return path


def command_parser(command: str):  # noqa: ANN201 - argparse type
    """The argparse parser of ``voxfab COMMAND``."""
    from voxfab.cli._main import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    return sub.choices[command]


def _numeric(action: object) -> type | None:
    """``float`` or ``int`` for an option whose argparse type takes numbers (builtin or voxfab's own)."""
    kind = getattr(action, "type", None)
    if kind in (int, float) or kind is None or kind in (str, _Path):
        return kind if kind in (int, float) else None
    for sample, result in (("2.5", float), ("3", int)):
        try:
            kind(sample)
        except Exception:  # noqa: BLE001, S112 - probing an unknown converter
            continue
        try:
            kind("not a number")
        except Exception:  # noqa: BLE001 - refuses text: a number option
            return result
        return None
    return None


@st.composite
def argv_for(draw: st.DrawFn, command: str, positionals: dict[str, st.SearchStrategy[str]],
             fixed: tuple[str, ...] = ()) -> list[str]:
    """A random command line for ``voxfab COMMAND`` built from its real options.

    ``positionals`` gives a value strategy per positional (and per option dest that
    needs a path); every other option gets values of its type, usual or extreme.
    Required options are always given, and at most one of mutually exclusive ones,
    so most command lines get past argparse to voxfab's own checks.
    """
    parser = command_parser(command)
    actions = [a for a in parser._actions if a.dest not in ("help", "debug")]
    exclusive = {id(a): i for i, g in enumerate(parser._mutually_exclusive_groups) for a in g._group_actions}
    taken: set[int] = set()
    argv = [command]
    for action in actions:
        if not action.option_strings:
            argv.append(draw(positionals[action.dest]))
    for action in actions:
        if not action.option_strings:
            continue
        if not action.required and (draw(st.integers(0, 4)) > 0 or exclusive.get(id(action), -1) in taken):
            continue
        if id(action) in exclusive:
            taken.add(exclusive[id(action)])
        flag = draw(st.sampled_from(action.option_strings))
        if action.dest in positionals:
            argv += [flag, draw(positionals[action.dest])]
        elif action.nargs == 0:
            argv.append(flag)
        elif action.choices:
            good = st.sampled_from(list(action.choices))
            argv += [flag, draw(st.one_of(good, good, good, good, good, st.sampled_from(NASTY_TEXT)))]
        elif _numeric(action) is not None:
            argv.append(f"{flag}={draw(number_text(_numeric(action)))}")
        else:
            argv.append(f"{flag}={draw(st.sampled_from(NASTY_TEXT))}")
    return argv + list(fixed)


#: Outputs a command line may name: usual ones, and ones that must be refused.
OUTPUT_NAMES = {
    "mesh": ["m.stl", "m.3mf", "m.obj", "m.glb", "m.ply", "missing/m.stl", "folder", "m"],
    "net": ["n.json", "n.svg", "n.pdf", "n.dxf", "n.png", "missing/n.json", "folder"],
    "slices": ["plates", "folder", "file.txt", "missing/plates"],
    "render": ["r.png", "r.pdf", "r.gif", "missing/r.png", "folder", "r.bmp"],
    "convert": ["c.npy", "c.npz", "c.txt", "c.vox", "c.binvox", "c.stl", "missing/c.npy", "folder"],
}
#: Hostile files given to options that read a side input (--net, --constraints).
SIDE_INPUTS = ["missing.json", "binary.json", "deep.json", "bigint.json", "fifo.json", "folder", "bar.npy"]
#: Options added to every command line: net searches are bounded by time.
CLI_FIXED = {"net": ("--timeout", "2")}
#: Commands fuzzed through their options.
CLI_COMMANDS = ["info", "convert", "mesh", "net", "slices", "render"]


def cli_corpus(folder: _Path) -> None:
    """The files the command-line fuzz names: a small shape, a corrupt one, a folder of someone's files."""
    import numpy as np

    from voxfab import io

    grid = np.zeros((3, 3, 3), bool)
    grid[1, 1, :] = True
    io.write(grid, folder / "bar.npy")
    (folder / "folder").mkdir(exist_ok=True)
    (folder / "folder" / "keep.txt").write_text("not an output")
    (folder / "file.txt").write_text("not a folder")
    (folder / "bad.npy").write_bytes(b"\x93NUMPY garbage")
    (folder / "out").mkdir(exist_ok=True)
    # Hostile side inputs (--net, --constraints, --repo): binary, deep, huge numbers, a FIFO.
    (folder / "binary.json").write_bytes(bytes(range(256)))
    (folder / "deep.json").write_text("[" * 100000)
    (folder / "bigint.json").write_text('{"cut": [[[0, 0, ' + "9" * 5000 + ', "+z"]]]}')
    if not (folder / "fifo.json").exists():
        import os

        os.mkfifo(folder / "fifo.json")


def cli_positionals(folder: _Path, command: str) -> dict[str, st.SearchStrategy[str]]:
    """Value strategies for the positionals and path options of ``command`` over :func:`cli_corpus`."""
    good = st.just(str(folder / "bar.npy"))
    bad = st.sampled_from([str(folder / "bad.npy"), str(folder / "missing.npy"), str(folder / "folder"),
                           "00001.001"])
    positionals = {
        "shape": st.one_of(good, good, bad),
        "input": st.one_of(good, good, bad),
        "repo": st.sampled_from([str(folder / "repo.sqlite"), str(folder / "file.txt"), str(folder / "fifo.json")]),
        "recipes": st.just(str(folder / "none.toml")),
        "constraints": st.sampled_from([str(folder / n) for n in SIDE_INPUTS]),
    }
    if command in OUTPUT_NAMES:
        names = [str(folder / "out" / n) if not n.startswith(("folder", "file")) else str(folder / n)
                 for n in OUTPUT_NAMES[command]]
        positionals["output"] = st.one_of(st.sampled_from(names[:2]), st.sampled_from(names))
        positionals["net"] = st.sampled_from([str(folder / "out" / "n.json"), *(str(folder / n) for n in SIDE_INPUTS)])
    return positionals


# --- JSON bodies (the studio's endpoints, constraint files) ------------------------------------------

#: Numbers JSON carries that no option takes: past float range, past 64 bits, and their negatives.
HUGE_NUMBERS = [10**400, -(10**400), 2**64, 2**63, -(2**63) - 1, 1e308, -1e308, 10**30]

JSON_SCALARS = st.one_of(
    st.none(), st.booleans(), st.integers(), st.sampled_from(HUGE_NUMBERS),
    st.floats(allow_nan=False, allow_infinity=False), st.text(max_size=12),
)
#: Any JSON value, nested a little (lists and objects of any of them).
JSON_VALUES = st.recursive(JSON_SCALARS, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=6), inner, max_size=3)), max_leaves=8)
