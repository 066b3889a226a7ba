"""What the artist drew, as a recipe: the page's JSON becomes TOML plus input files.

Every drawn shape goes through the recipe path (``load_recipe`` then
``make_shape``) exactly as ``voxfab build`` runs it, so the preview, the saved
recipe and the CLI agree voxel for voxel, and every parameter gets the CLI's
validation and messages.

A curve source in the page's JSON is one of::

    {"kind": "expr", "text": "x^2 + y^2 = 1"}
    {"kind": "drawn", "polylines": [{"points": [[x, y], ...], "closed": true}, ...]}
    {"kind": "bitmap", "data": "<base64 of a PNG, GIF or BMP>"}

Drawings become ``<role>.json`` beside the recipe, bitmaps ``<role>.png`` (or
``.gif``, ``.bmp``); expressions stay in the TOML.
"""

from __future__ import annotations

import base64
import binascii
import json
import math
import re
import shutil
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from voxfab._shared.options import quote
from voxfab._shared.validate import finite_number
from voxfab.errors import InvalidShapeError, VoxfabError

#: Limits of a drawing: polylines, points in all, bytes of an uploaded bitmap, characters of an expression;
#: and of a list of numbers in a maker's form (a point, bounds, weights).
MAX_POLYLINES = 64
MAX_POINTS = 20000
MAX_BITMAP = 4 * 1024 * 1024
MAX_TEXT = 2000
MAX_NUMBERS = 64

#: The drawn keys of the page's JSON (curves, profiles, foci, spine) of the makers the page draws for, which
#: :func:`source_keys` reads itself.  Any maker of the table (``voxfab.digitize.MAKERS``) is made from its
#: form too: its numbers, words, flags and lists of numbers (:func:`form_keys`).  Any other key is refused.
SHAPE_KEYS = {
    "revolution": ("curve", "generatrix", "axis", "z_range", "arc"),
    "tube": ("profile", "arc", "spine"),
    "focal": ("foci", "weights", "radius"),
    "implicit": ("expression",),
}
#: The keys of a curve source, of a drawn polyline, and of a spine, by kind.
SOURCE_KEYS = {"expr": ("kind", "text"), "drawn": ("kind", "polylines"), "bitmap": ("kind", "data")}
SPINE_KEYS = {"expr": ("kind", "x", "y", "z", "t_min", "t_max"), "drawn": ("kind", "points", "closed")}

_MAGIC = {b"\x89PNG\r\n\x1a\n": ".png", b"GIF87a": ".gif", b"GIF89a": ".gif", b"BM": ".bmp"}
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$")


class SpecError(InvalidShapeError):
    """The page sent a drawing that cannot describe a shape."""


@dataclass(frozen=True)
class RecipeText:
    """A recipe ready to write: its TOML text and the input files it names."""

    name: str
    toml: str
    files: tuple[tuple[str, bytes], ...]

    def write(self, folder: Path) -> Path:
        """Write the recipe and its files into ``folder``; return the recipe's path."""
        for fname, data in self.files:
            (folder / fname).write_bytes(data)
        path = folder / f"{self.name}.toml"
        path.write_text(self.toml, encoding="utf-8")
        return path

    def download(self) -> tuple[str, bytes]:
        """The file the page downloads and its name: the TOML alone, or a zip of a folder with its files."""
        if not self.files:
            return f"{self.name}.toml", self.toml.encode()
        import io
        import zipfile

        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED) as zf:
            for fname, raw in ((f"{self.name}.toml", self.toml.encode()), *self.files):
                # fixed dates: the same drawing gives the same archive
                zf.writestr(zipfile.ZipInfo(f"{self.name}/{fname}", date_time=(1980, 1, 1, 0, 0, 0)), raw)
        return f"{self.name}.zip", buf.getvalue()


# --- reading the page's JSON ------------------------------------------------------------------

def _get(spec: Mapping[str, Any], key: str, kind: type | tuple[type, ...], default: Any = None, *,
         where: str) -> Any:
    value = spec.get(key, default)
    if value is None:
        return None
    kinds = kind if isinstance(kind, tuple) else (kind,)
    if (isinstance(value, bool) and bool not in kinds) or not isinstance(value, kinds):
        names = " or ".join(t.__name__ for t in kinds)
        raise SpecError(f"{where}.{key}: expected {names}, got {type(value).__name__} {value!r:.60}")
    if isinstance(value, (int, float)) and not isinstance(value, bool) and finite_number(value) is None:
        raise SpecError(f"{where}.{key}: expected a finite number, got {quote(value, 60)}")
    return value


def _only(obj: Mapping[str, Any], keys: tuple[str, ...], *, where: str) -> None:
    """Refuse a key the page's JSON does not have here: it would be dropped without a word."""
    unknown = sorted(str(k) for k in obj if k not in keys)
    if unknown:
        raise SpecError(f"{where}: unknown key {quote(unknown[0], 40)}; expected {', '.join(keys)}")


def _number(value: Any, *, where: str) -> float:
    number = finite_number(value)  # 10**400 from JSON is no number here, not an OverflowError
    if number is None:
        raise SpecError(f"{where}: expected a finite number, got {quote(value, 60)}")
    return number


def _points(raw: Any, dim: int, *, where: str) -> list[list[float]]:
    if not isinstance(raw, list):
        raise SpecError(f"{where}: expected a list of points")
    out = []
    for i, p in enumerate(raw):
        if not isinstance(p, list) or len(p) != dim:
            raise SpecError(f"{where}[{i}]: expected {dim} coordinates, got {p!r:.60}")
        out.append([_number(c, where=f"{where}[{i}]") for c in p])
    return out


def _text(value: Any, *, where: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise SpecError(f"{where}: expected a non-empty expression")
    if len(value) > MAX_TEXT:
        raise SpecError(f"{where}: expression longer than {MAX_TEXT} characters")
    return value.strip()


def _source(src: Any, role: str, files: dict[str, bytes]) -> str:
    """The recipe value of one curve source (an expression or a file name), adding its file."""
    where = role
    if not isinstance(src, dict):
        raise SpecError(f"{where}: expected an object with a 'kind'")
    kind = src.get("kind")
    if isinstance(kind, str) and kind in SOURCE_KEYS:
        _only(src, SOURCE_KEYS[kind], where=where)
    if kind == "expr":
        return _text(src.get("text"), where=f"{where}.text")
    if kind == "drawn":
        polys = src.get("polylines")
        if not isinstance(polys, list) or not polys:
            raise SpecError(f"{where}: draw at least one stroke")
        if len(polys) > MAX_POLYLINES:
            raise SpecError(f"{where}: at most {MAX_POLYLINES} strokes, got {len(polys)}")
        out = []
        total = 0
        for i, p in enumerate(polys):
            if not isinstance(p, dict):
                raise SpecError(f"{where}.polylines[{i}]: expected an object with points")
            _only(p, ("points", "closed"), where=f"{where}.polylines[{i}]")
            pts = _points(p.get("points"), 2, where=f"{where}.polylines[{i}].points")
            total += len(pts)
            closed = _get(p, "closed", bool, False, where=f"{where}.polylines[{i}]")
            out.append({"points": pts, "closed": bool(closed)})
        if total > MAX_POINTS:
            raise SpecError(f"{where}: at most {MAX_POINTS} points in all, got {total}")
        fname = f"{role}.json"
        files[fname] = (json.dumps({"polylines": out}, separators=(",", ":")) + "\n").encode()
        return fname
    if kind == "bitmap":
        data = src.get("data")
        if not isinstance(data, str):
            raise SpecError(f"{where}.data: expected the image as base64")
        if len(data) > MAX_BITMAP * 4 // 3 + 4:
            raise SpecError(f"{where}: image larger than {MAX_BITMAP // (1024 * 1024)} MB")
        try:
            raw = base64.b64decode(data, validate=True)
        except (binascii.Error, ValueError):
            raise SpecError(f"{where}.data: not base64") from None
        ext = next((e for magic, e in _MAGIC.items() if raw.startswith(magic)), None)
        if ext is None:
            raise SpecError(f"{where}: not a PNG, GIF or BMP image")
        fname = f"{role}{ext}"
        files[fname] = raw
        return fname
    raise SpecError(f"{where}.kind: expected 'expr', 'drawn' or 'bitmap', got {kind!r:.40}")


def _form(spec: Mapping[str, Any], maker: str, keys: dict[str, Any]) -> None:
    """The maker's form values the page sent, checked by the makers table (type and range)."""
    from voxfab.digitize import maker_params

    params = maker_params(maker)
    for name in form_keys(maker):
        value = spec.get(name)
        if value is None:
            continue
        if isinstance(value, list) and len(value) > MAX_NUMBERS:
            raise SpecError(f"shape.{name}: at most {MAX_NUMBERS} numbers, got {len(value)}")
        problem = params[name].problem(value)
        if problem:
            raise SpecError(f"shape.{name}: {problem}")
        keys[name] = params[name].normal(value)


def _arc(spec: Mapping[str, Any], keys: dict[str, Any]) -> None:
    """``arc = [start, end]`` (degrees): the open part of the curve of revolution or of the profile."""
    arc = spec.get("arc")
    if arc is not None:
        keys["arc"] = [_number(v, where="shape.arc") for v in _points([arc], 2, where="shape.arc")[0]]


#: Keys a maker's drawing reader takes from elsewhere (the spine's), or only in one case, not from the form.
_PLACED = {"revolution": ("axis",), "tube": ("t_min", "t_max", "closed"), "focal": ("radius",)}


def drawn_keys(maker: str) -> tuple[str, ...]:
    """The keys of ``maker`` that the page's drawing gives (none for a maker the page has no drawing for)."""
    return (*SHAPE_KEYS.get(maker, ()), *(k for k in _PLACED.get(maker, ()) if k not in SHAPE_KEYS.get(maker, ())))


def form_keys(maker: str) -> tuple[str, ...]:
    """The keys of ``maker`` the page asks for in a form, in its row's order: numbers, words, flags, lists of numbers.

    A text is not among them: it may name a file, and the studio's files are the ones it draws.
    """
    from voxfab.digitize import maker_params

    drawn = drawn_keys(maker)
    return tuple(n for n, p in maker_params(maker).items() if p.kind is not None and n not in drawn)


def maker_table() -> list[dict[str, Any]]:
    """The makers table as the page reads it (``/api/info``): per maker its name, summary and keys.

    Each key has its name, its ``label`` in plain words (:attr:`voxfab.digitize.Param.words`), help, type in words, range, default and requirement from the table,
    its form ``kind`` and ``choices`` (:attr:`voxfab.digitize.Param.kind`), and ``input``: ``"drawn"``
    when the page's drawing gives it, ``"form"`` when a form field does, None when the studio cannot.
    """
    from voxfab.digitize import MAKERS, maker_params

    table = []
    for name, row in MAKERS.items():
        drawn, form = drawn_keys(name), form_keys(name)
        table.append({"name": name, "help": row.help, "params": [
            {"name": p.name, "label": p.words, "help": p.help, "type": p.type_words, "low": p.low, "high": p.high,
             "default": p.default, "required": p.required, "kind": p.kind, "choices": list(p.choices),
             "input": "drawn" if p.name in drawn else "form" if p.name in form else None}
            for p in maker_params(name).values()]})
    return table


def _revolution(spec: Mapping[str, Any], keys: dict[str, Any], files: dict[str, bytes]) -> None:
    keys["curve"] = _source(spec.get("curve"), "curve", files)
    keys["generatrix"] = _source(spec.get("generatrix"), "generatrix", files)
    axis = _get(spec, "axis", (int, float), where="shape")
    if axis is not None and spec["generatrix"].get("kind") == "drawn":
        keys["axis"] = float(axis)
    z_range = spec.get("z_range")
    if z_range is not None and spec["generatrix"].get("kind") == "expr":
        keys["z_range"] = [_number(v, where="shape.z_range") for v in _points([z_range], 2,
                                                                              where="shape.z_range")[0]]
    _arc(spec, keys)


def _tube(spec: Mapping[str, Any], keys: dict[str, Any], files: dict[str, bytes]) -> None:
    keys["profile"] = _source(spec.get("profile"), "profile", files)
    _arc(spec, keys)
    spine = spec.get("spine")
    if not isinstance(spine, dict):
        raise SpecError("shape.spine: expected an object with a 'kind'")
    if isinstance(spine.get("kind"), str) and spine["kind"] in SPINE_KEYS:
        _only(spine, SPINE_KEYS[spine["kind"]], where="spine")
    if spine.get("kind") == "expr":
        keys["spine"] = [_text(spine.get(c), where=f"spine.{c}") for c in "xyz"]
        for key in ("t_min", "t_max"):
            value = _get(spine, key, (int, float), where="spine")
            if value is not None:
                keys[key] = float(value)
    elif spine.get("kind") == "drawn":
        pts = _points(spine.get("points"), 3, where="spine.points")
        if len(pts) > MAX_POINTS:
            raise SpecError(f"spine: at most {MAX_POINTS} points, got {len(pts)}")
        keys["spine"] = pts
        closed = _get(spine, "closed", bool, where="spine")
        if closed is not None:
            keys["closed"] = closed
    else:
        raise SpecError(f"spine.kind: expected 'expr' or 'drawn', got {spine.get('kind')!r:.40}")


def _focal(spec: Mapping[str, Any], keys: dict[str, Any], files: dict[str, bytes]) -> None:
    keys["foci"] = _points(spec.get("foci"), 3, where="shape.foci")
    if not keys["foci"]:
        raise SpecError("shape.foci: place at least one focus")
    weights = spec.get("weights")
    if weights is not None:
        if not isinstance(weights, list):
            raise SpecError("shape.weights: expected a list of numbers")
        keys["weights"] = [_number(w, where="shape.weights") for w in weights]
    keys["radius"] = _number(spec.get("radius"), where="shape.radius")


def _implicit(spec: Mapping[str, Any], keys: dict[str, Any], files: dict[str, bytes]) -> None:
    keys["expression"] = _text(spec.get("expression"), where="shape.expression")


#: The reader of each drawing of :data:`SHAPE_KEYS`: it sets the drawn keys and adds the drawn files.
_DRAWINGS = {"revolution": _revolution, "tube": _tube, "focal": _focal, "implicit": _implicit}


def source_keys(spec: Any) -> tuple[dict[str, Any], dict[str, bytes]]:
    """The ``[source]`` table (maker first) and input files of a drawn shape, or of any maker's form."""
    from voxfab.digitize import MAKERS

    if not isinstance(spec, dict):
        raise SpecError("shape: expected an object")
    maker = spec.get("maker")
    if not isinstance(maker, str) or maker not in MAKERS:
        raise SpecError(f"shape.maker: expected one of {', '.join(MAKERS)}, got {maker!r:.40}")
    _only(spec, ("maker", *SHAPE_KEYS.get(maker, ()), *form_keys(maker)), where=f"shape ({maker})")
    files: dict[str, bytes] = {}
    keys: dict[str, Any] = {"maker": maker}
    if maker in _DRAWINGS:
        _DRAWINGS[maker](spec, keys, files)
    _form(spec, maker, keys)
    return keys, files


# --- TOML -------------------------------------------------------------------------------------

def toml_value(value: Any) -> str:
    """A TOML literal for a string, number, bool or (nested) list."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SpecError(f"recipe: {value} has no TOML form")
        return repr(value)
    if isinstance(value, str):
        # JSON's escapes (\" \\ \n \u00e9) are valid in TOML basic strings
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise SpecError(f"recipe: cannot write {type(value).__name__} as TOML")


def drawing_recipe(spec: Any, *, name: str = "studio", pitch: float = 1.0, seed: int = 0) -> RecipeText:
    """The recipe of a drawn shape (no outputs: ``voxfab build`` makes the shape files, the page the rest)."""
    if not isinstance(name, str) or not _NAME.match(name):
        raise SpecError(f"name: expected letters, digits, _ . - (at most 64), got {name!r:.70}")
    pitch = _number(pitch, where="pitch")
    if pitch <= 0:
        raise SpecError(f"pitch: expected a positive number of mm per voxel, got {pitch:g}")
    keys, files = source_keys(spec)
    lines = [
        f"name = {toml_value(name)}",
        f"seed = {int(seed)}",
        f"pitch = {toml_value(pitch)}",
        'description = "Drawn in voxfab studio"',
        "",
        "[source]",
        *(f"{k} = {toml_value(v)}" for k, v in keys.items()),
        "",
        "# Add the outputs to make, for example:",
        "# [outputs.mesh]",
        "# [outputs.net]",
        "# [outputs.slices]",
        "# [outputs.pictures]",
    ]
    if keys["maker"] == "tube":
        lines.append("# [outputs.animation]   # the profile turning along the spine")
    return RecipeText(name, "\n".join(lines) + "\n", tuple(sorted(files.items())))


def _relabel(exc: VoxfabError, folder: Path) -> VoxfabError:
    """The error without the scratch folder's path: the artist sees ``studio.toml:7: source.k: ...``."""
    message = str(exc).replace(str(folder) + "/", "").replace(str(folder), "")
    try:
        return type(exc)(message)
    except TypeError:  # an error class with its own constructor arguments
        return VoxfabError(message)


def make_grid(spec: Any, work: Path) -> tuple[Any, RecipeText]:
    """Make a drawn shape through the recipe path in a scratch folder under ``work``.

    Returns
    -------
    grid, recipe
        The shape's bool grid and the recipe that makes it.

    Raises
    ------
    VoxfabError
        With the CLI's message, temporary paths removed.
    """
    from voxfab.recipe import load_recipe, make_shape

    recipe = drawing_recipe(spec)
    folder = Path(tempfile.mkdtemp(prefix="draw-", dir=work))
    try:
        path = recipe.write(folder)
        try:
            shape = make_shape(load_recipe(path))
        except VoxfabError as exc:
            raise _relabel(exc, folder) from None
        return shape.grid, recipe
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def tube_params(spec: Any, work: Path) -> tuple[dict[str, Any], Path]:
    """The validated ``tube`` maker keys of a drawn tube and a scratch folder holding its files.

    The caller removes the folder.
    """
    from voxfab.recipe import load_recipe

    if not isinstance(spec, dict) or spec.get("maker") != "tube":
        raise SpecError("animation: only a tube's profile can turn; choose Tube in Draw")
    recipe = drawing_recipe(spec)
    folder = Path(tempfile.mkdtemp(prefix="tube-", dir=work))
    try:
        loaded = load_recipe(recipe.write(folder))
    except VoxfabError as exc:
        shutil.rmtree(folder, ignore_errors=True)
        raise _relabel(exc, folder) from None
    return dict(loaded.source.params), folder
