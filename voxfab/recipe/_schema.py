"""Recipe parsing and validation: TOML in, a frozen Recipe out, every key checked.

A recipe is fully validated before anything runs.  Maker and output options are
checked against the keyword-only parameters (and type hints) of the function that
takes them, so each option is declared in exactly one place.
"""

from __future__ import annotations

import dataclasses
import hashlib
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

from voxfab._shared.limits import parse_toml, read_input_bytes
from voxfab._shared.options import OptionError, SeedOptions
from voxfab._shared.typing import PathLike
from voxfab._shared.validate import check_confined, type_fits, type_name
from voxfab.errors import RecipeError, VoxfabError

_TOP_KEYS = {"name", "seed", "pitch", "description", "source", "operations", "outputs"}
_OPERATIONS: dict[str, dict[str, type | tuple]] = {
    "fill": {},
    "largest": {},
    "crop": {},
    "rotate": {"axis": str, "turns": int},
    "mirror": {"axis": str},
    "shift": {"by": tuple[int, int, int]},
    "paint": {"colour": str, "where": str},
    "join": {},
    "union": {"source": dict},
    "intersection": {"source": dict},
    "difference": {"source": dict},
}
# Suffixes of the files a maker option may name (drawings, bitmaps, point lists).
_FILE_SUFFIXES = {".svg", ".json", ".csv", ".png", ".gif", ".bmp", ".jpg", ".jpeg", ".txt"}
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")


@dataclasses.dataclass(frozen=True)
class SourceSpec:
    """Where the shape comes from: a maker with parameters, or a file."""

    maker: str | None
    file: Path | None
    params: tuple[tuple[str, Any], ...]
    keypath: str


@dataclasses.dataclass(frozen=True)
class OperationSpec:
    """One operation applied to the shape, in order."""

    op: str
    params: tuple[tuple[str, Any], ...]
    source: SourceSpec | None
    keypath: str


@dataclasses.dataclass(frozen=True)
class OutputSpec:
    """One requested output with its options.

    Attributes
    ----------
    name : str
        The output, ``[outputs.NAME]``.
    options : tuple of (str, value)
        The recipe's keys as written.
    settings : object
        The checked options object its pipeline takes (see :func:`voxfab.fabricate.outputs`).
    """

    name: str
    options: tuple[tuple[str, Any], ...]
    settings: Any = dataclasses.field(default=None, compare=False)


@dataclasses.dataclass(frozen=True)
class Recipe:
    """A validated recipe.

    Attributes
    ----------
    name : str
        Folder name of the build (``DIR/<name>/``).
    seed : int
    pitch : float
        Millimetres per voxel.
    source : SourceSpec
    operations : tuple of OperationSpec
    outputs : tuple of OutputSpec
    path : Path
        The recipe file.
    sha256 : str
        Hash of the recipe file's bytes.
    allow_outside : bool
        Whether the files it names may lie outside its folder.
    """

    name: str
    seed: int
    pitch: float
    description: str
    source: SourceSpec
    operations: tuple[OperationSpec, ...]
    outputs: tuple[OutputSpec, ...]
    path: Path
    sha256: str
    allow_outside: bool = False

    @property
    def base_dir(self) -> Path:
        """The recipe's folder, for relative file names."""
        return self.path.parent


class _Locator:
    """Find the line of a key path in TOML text (tomllib keeps no positions)."""

    _HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?")

    def __init__(self, text: str) -> None:
        self.lines = text.splitlines()

    def line(self, keypath: str) -> int | None:
        parts = [p for p in re.split(r"\.|\[\d+\]", keypath) if p]
        index = [int(i) for i in re.findall(r"\[(\d+)\]", keypath)]
        if not parts:
            return None
        key = parts[-1]
        table = ".".join(parts[:-1])
        current = ""
        occurrence: dict[str, int] = {}
        want = index[0] if index else None
        for n, raw in enumerate(self.lines, start=1):
            m = self._HEADER.match(raw)
            if m:
                current = m.group(1).replace(" ", "")
                occurrence[current] = occurrence.get(current, -1) + 1
                if current == keypath.split("[")[0] and not index:
                    return n
                continue
            if re.match(rf"^\s*{re.escape(key)}\s*=", raw) or re.search(rf"[{{,]\s*{re.escape(key)}\s*=", raw):
                in_table = current == table or current == table.split(".")[0] or table.startswith(current + ".")
                if not table:
                    in_table = current == ""
                if in_table and (want is None or occurrence.get(current, 0) == want):
                    return n
        return None


def _error(path: Path, locator: _Locator, keypath: str, message: str) -> RecipeError:
    line = locator.line(keypath)
    where = f"{path}:{line}" if line else f"{path}"
    return RecipeError(f"{where}: {keypath}: {message}")


def _check_maker_keys(maker: str, given: dict[str, Any], *, where: str,
                      err: Callable[[str, str], RecipeError]) -> None:
    """Check a maker's keys against its row of the makers table: known, typed, in range, none missing."""
    from voxfab.digitize import maker_params

    params = maker_params(maker)
    for key, value in given.items():
        if key not in params:
            raise err(f"{where}.{key}", f"unknown key; {where} accepts: {', '.join(sorted(params))}")
        problem = params[key].problem(value)
        if problem:
            raise err(f"{where}.{key}", problem)
    for key, param in params.items():
        if param.required and key not in given:
            raise err(f"{where}.{key}", "missing required key")


def _check_inside(name: str, base: Path, keypath: str, err: Callable[[str, str], RecipeError]) -> None:
    """Refuse a file name that resolves outside the recipe's folder ``base``."""
    try:
        check_confined(base / name, base, name=keypath, shown=name)
    except RecipeError as exc:
        raise err(keypath, str(exc).removeprefix(f"{keypath}: ")) from None


def _parse_source(
    data: Any, keypath: str, base: Path, err: Callable[[str, str], RecipeError], confine: bool = True
) -> SourceSpec:
    from voxfab.digitize import MAKERS

    if not isinstance(data, dict):
        raise err(keypath, f"expected a table, got {type(data).__name__}")
    has_maker, has_file = "maker" in data, "file" in data
    if has_maker == has_file:
        raise err(keypath, "expected exactly one of 'maker' or 'file'")
    if has_file:
        extra = set(data) - {"file", "resolution"}
        if extra:
            raise err(f"{keypath}.{sorted(extra)[0]}", "unknown key; a file source accepts: file, resolution")
        if not isinstance(data["file"], str):
            raise err(f"{keypath}.file", "expected a string path")
        if "resolution" in data and not type_fits(data["resolution"], int):
            raise err(f"{keypath}.resolution", "expected int")
        params = tuple(sorted((k, v) for k, v in data.items() if k == "resolution"))
        if confine:
            _check_inside(data["file"], base, f"{keypath}.file", err)
        return SourceSpec(None, base / data["file"], params, keypath)
    maker_name = data["maker"]
    if not isinstance(maker_name, str):
        raise err(f"{keypath}.maker", "expected a string")
    if maker_name not in MAKERS:
        raise err(f"{keypath}.maker", f"unknown maker {maker_name!r}; expected one of {', '.join(sorted(MAKERS))}")
    params = {k: v for k, v in data.items() if k != "maker"}
    _check_maker_keys(maker_name, params, where=keypath, err=err)
    if confine:
        for key, value in params.items():
            if isinstance(value, str) and Path(value).suffix.lower() in _FILE_SUFFIXES:
                _check_inside(value, base, f"{keypath}.{key}", err)
    return SourceSpec(maker_name, None, tuple(sorted(params.items())), keypath)


def _check_paint(op: dict[str, Any], keypath: str, err: Callable[[str, str], RecipeError]) -> None:
    """A paint operation's colour and expression, checked before anything runs."""
    from voxfab.digitize import compile_expression
    from voxfab.shape import parse_colour

    if "colour" not in op:
        raise err(keypath, "op 'paint' needs 'colour = \"#rrggbb\"' (and 'where', an expression of x, y, z "
                           "painted where it is < 0)")
    for key, check in (("colour", lambda v: parse_colour(v)),
                       ("where", lambda v: compile_expression(v, ("x", "y", "z"), name="where"))):
        if key in op:
            try:
                check(op[key])
            except VoxfabError as exc:
                raise err(f"{keypath}.{key}", str(exc).split(": ", 1)[-1]) from None


def load_recipe(path: PathLike, *, allow_outside: bool = False) -> Recipe:
    """Read and fully validate a recipe file.

    Parameters
    ----------
    path : path
        The recipe (TOML, at most 16 MiB, nested at most 64 levels).
    allow_outside : bool
        Let the recipe name files outside its own folder (``file =``, drawings,
        profiles, spines).  By default such a file is refused, so a recipe from
        someone else cannot read the rest of the disk.

    Raises
    ------
    RecipeError
        Naming the file, line and key path of the first problem.
    """
    from voxfab.fabricate import outputs as output_kinds
    from voxfab.shape import ShapeOptions

    p = Path(path)
    try:
        raw = read_input_bytes(p, what="a recipe")
    except VoxfabError as exc:
        raise RecipeError(f"cannot read recipe: {exc}") from None
    try:
        text = raw.decode("utf-8")
        data = parse_toml(text, name=str(p))
    except UnicodeDecodeError:
        raise RecipeError(f"{p}: not UTF-8 text") from None
    except VoxfabError as exc:
        raise RecipeError(str(exc)) from None
    loc = _Locator(text)

    def err(keypath: str, message: str) -> RecipeError:
        return _error(p, loc, keypath, message)

    for key in data:
        if key not in _TOP_KEYS:
            raise err(key, f"unknown key; a recipe accepts: {', '.join(sorted(_TOP_KEYS))}")
    name = data.get("name", p.stem)
    if not isinstance(name, str) or not _NAME.fullmatch(name):
        raise err("name", f"expected a folder-safe name (letters, digits, _ . -), got {name!r}")
    try:
        seed = SeedOptions(seed=data.get("seed", 0)).seed
    except OptionError as exc:
        raise err("seed", exc.reason) from None
    pitch = data.get("pitch", 1.0)
    try:
        pitch = ShapeOptions(pitch=pitch).pitch
    except OptionError as exc:
        raise err("pitch", exc.reason) from None
    description = data.get("description", "")
    if not isinstance(description, str):
        raise err("description", "expected a string")
    if "source" not in data:
        raise RecipeError(f"{p}: missing the [source] table")
    source = _parse_source(data["source"], "source", p.parent, err, not allow_outside)

    ops = []
    raw_ops = data.get("operations", [])
    if not isinstance(raw_ops, list):
        raise err("operations", "expected an array of tables [[operations]]")
    for i, op in enumerate(raw_ops):
        kp = f"operations[{i}]"
        if not isinstance(op, dict) or "op" not in op:
            raise err(kp, "expected a table with an 'op' key")
        kind = op["op"]
        if kind not in _OPERATIONS:
            raise err(f"{kp}.op", f"unknown operation {kind!r}; expected one of {', '.join(_OPERATIONS)}")
        allowed = _OPERATIONS[kind]
        sub = None
        params = []
        for key, value in op.items():
            if key == "op":
                continue
            if key not in allowed:
                known = ", ".join(allowed) or "(no keys)"
                raise err(f"{kp}.{key}", f"unknown key for op {kind!r}; accepts: {known}")
            if key == "source":
                sub = _parse_source(value, f"{kp}.source", p.parent, err, not allow_outside)
                continue
            if not type_fits(value, allowed[key]):
                raise err(f"{kp}.{key}", f"expected {type_name(allowed[key])}, got {value!r}")
            if key == "axis" and value not in ("x", "y", "z"):
                raise err(f"{kp}.axis", f"expected 'x', 'y' or 'z', got {value!r}")
            params.append((key, value if key != "by" else tuple(value)))
        if kind == "paint":
            _check_paint(op, kp, err)
        if kind == "shift" and "by" not in op:
            raise err(kp, "op 'shift' needs 'by = [dx, dy, dz]' (voxels)")
        if kind in ("union", "intersection", "difference") and sub is None:
            raise err(kp, f"op {kind!r} needs a 'source' table")
        ops.append(OperationSpec(kind, tuple(sorted(params)), sub, kp))

    outputs = []
    raw_out = data.get("outputs", {})
    if not isinstance(raw_out, dict):
        raise err("outputs", "expected a table of output tables, e.g. [outputs.mesh]")
    kinds = output_kinds()
    for out_name in sorted(raw_out):
        options = raw_out[out_name]
        if not isinstance(options, dict):
            raise err(f"outputs.{out_name}", "expected a table")
        if out_name not in kinds:
            raise err(f"outputs.{out_name}", f"unknown output {out_name!r}; expected one of {', '.join(sorted(kinds))}")
        kind = kinds[out_name]
        if kind.maker is not None and source.maker != kind.maker:
            raise err(f"outputs.{out_name}", f"needs a {kind.maker} source (maker = {kind.maker!r}), "
                      f"got {source.maker or 'a file'!r}")
        for key in options:
            if key not in kind.keys:
                raise err(f"outputs.{out_name}.{key}", f"unknown key; outputs.{out_name} accepts: "
                          f"{', '.join(sorted(kind.keys))}")
        try:
            settings = kind.settings(options)
        except OptionError as exc:
            raise err(f"outputs.{out_name}.{exc.option}", exc.reason) from None
        except VoxfabError as exc:
            raise err(f"outputs.{out_name}", str(exc)) from None
        outputs.append(OutputSpec(out_name, tuple(sorted(options.items())), settings))

    return Recipe(
        name=name,
        seed=int(seed),
        pitch=float(pitch),
        description=description,
        source=source,
        operations=tuple(ops),
        outputs=tuple(outputs),
        path=p,
        sha256=hashlib.sha256(raw).hexdigest(),
        allow_outside=allow_outside,
    )
