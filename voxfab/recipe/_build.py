"""Build a recipe: make the shape, apply operations, write outputs and a manifest."""

from __future__ import annotations

import dataclasses
import hashlib
import json
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from voxfab._shared.atomic import atomic_dir, check_output, write_text
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import as_grid, confine_inputs
from voxfab._version import __version__
from voxfab.errors import RecipeError, VoxfabError
from voxfab.shape import VoxelShape, canonical_key

from ._schema import OperationSpec, Recipe, SourceSpec

if TYPE_CHECKING:
    from voxfab.warmup import Aside

MANIFEST_FORMAT = "voxfab-manifest/1"

#: The shape files every build writes beside its outputs, and what each is for.
SHAPE_FILES = {
    "shape.npz": "the voxel shape with its pitch and colours: what every voxfab command reads at the recipe's scale",
    "shape.npy": "the voxel shape as a NumPy bool array [x, y, z], z up",
    "shape.vox": "the voxel shape in its colours for MagicaVoxel and other voxel editors",
}


def built_shape_name(path: PathLike) -> str | None:
    """The recipe's name when ``path`` is one of a build's :data:`SHAPE_FILES` beside its ``manifest.json``,
    else None: a net or a print made from ``output/queen/shape.npz`` is titled "queen", not "shape"."""
    path = Path(path)
    if path.name not in SHAPE_FILES:
        return None
    try:
        manifest = json.loads((path.parent / "manifest.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    name = manifest.get("recipe") if isinstance(manifest, dict) and manifest.get("format") == MANIFEST_FORMAT else None
    return name if isinstance(name, str) and name.strip() else None


def make_source(source: SourceSpec, base_dir: Path, pitch: float = 1.0) -> VoxelShape:
    """Return the shape a source describes (a maker's output, or a file's content with its colours)."""
    if source.file is not None:
        from voxfab import io

        return io.read(source.file, **dict(source.params)).shape(pitch)
    from voxfab.digitize import get_maker

    grid = get_maker(source.maker or "")(base_dir=base_dir, **dict(source.params))
    try:
        return VoxelShape(as_grid(grid, name=f"{source.keypath} (maker {source.maker!r})"), pitch)
    except VoxfabError as exc:
        raise RecipeError(str(exc)) from None


def paint_mask(grid: BoolGrid, where: str | None) -> BoolGrid:
    """The voxels of ``grid`` where the expression ``where`` of the voxel indices x, y, z is < 0 (all when None).

    The sign convention is the implicit maker's: ``"z - 12"`` is the part below z = 12.
    """
    if where is None:
        return np.asarray(grid, dtype=bool)
    from voxfab.digitize import compile_expression

    x, y, z = np.indices(np.shape(grid), dtype=np.float64)
    return np.asarray(grid, dtype=bool) & (compile_expression(where, ("x", "y", "z"), name="where")(x, y, z) < 0)


def apply_operation(shape: VoxelShape, op: OperationSpec, base_dir: Path) -> VoxelShape:
    """Apply one recipe operation to a shape (its colours move with its voxels)."""
    params = dict(op.params)
    if op.op == "fill":
        return shape.fill_cavities()
    if op.op == "largest":
        return shape.largest_component()
    if op.op == "crop":
        return shape.crop()
    if op.op == "rotate":
        return shape.rotate(params.get("axis", "z"), params.get("turns", 1))
    if op.op == "mirror":
        return shape.mirror(params.get("axis", "x"))
    if op.op == "join":
        return shape.joined()[0]
    if op.op == "paint":
        from voxfab.shape import parse_colour

        return shape.painted(parse_colour(params["colour"]), paint_mask(shape.grid, params.get("where")))
    if op.op == "shift":
        try:
            return shape.translate(tuple(params["by"]))
        except VoxfabError as exc:
            raise RecipeError(f"{op.keypath} (shift): {exc}") from None
    assert op.source is not None
    other = make_source(op.source, base_dir, shape.pitch)
    return {"union": VoxelShape.__or__, "intersection": VoxelShape.__and__,
            "difference": VoxelShape.__sub__}[op.op](shape, other)


def make_shape(recipe: Recipe) -> VoxelShape:
    """Make the recipe's shape: its source, then each operation in order.

    Files the recipe names must be inside its folder unless it was loaded with
    ``allow_outside=True``.
    """
    with confine_inputs(None if recipe.allow_outside else recipe.base_dir):
        shape = make_source(recipe.source, recipe.base_dir, recipe.pitch)
        for op in recipe.operations:
            shape = apply_operation(shape, op, recipe.base_dir)
            if not shape.grid.any():
                raise RecipeError(f"{recipe.path}: {op.keypath} ({op.op}) left an empty shape")
    return shape




def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@dataclasses.dataclass(frozen=True, eq=False)
class BuiltRecipe:
    """A recipe built.

    Attributes
    ----------
    folder : Path
        Its output folder, holding ``shape.npz`` (the voxels, their pitch and
        colours), ``shape.npy``, ``shape.vox``, each output's files and ``manifest.json``.
    gives : mapping
        What its outputs made, by the names the table of outputs declares
        (:attr:`voxfab.fabricate.Output.gives`): ``"net"``, the pieces of the net
        written, when it has a net output.
    """

    folder: Path
    gives: Mapping[str, Any]


def build(recipe: Recipe, outdir: PathLike) -> Path:
    """Build a recipe into ``outdir/<recipe.name>/``, replacing it only on success.

    Returns
    -------
    Path
        The recipe's output folder (:func:`build_recipe`, which also hands back what
        its outputs made).
    """
    return build_recipe(recipe, outdir).folder


def build_recipe(recipe: Recipe, outdir: PathLike) -> BuiltRecipe:
    """Build a recipe into ``outdir/<recipe.name>/``, replacing it only on success."""
    from voxfab.fabricate import outputs as output_kinds
    from voxfab.warmup import compile_aside

    target = Path(outdir) / recipe.name
    check_output(target, folder=True, parents=True, marker="manifest.json")  # before the work
    # Right after an install the net engine's kernels are not compiled yet: a second
    # process compiles them while this one makes the shape and the print.
    unfolds = any(output_kinds()[spec.name].unfolds for spec in recipe.outputs)
    with compile_aside(["net"] if unfolds else []) as aside:
        gives = _build_into(recipe, target, aside)
    return BuiltRecipe(target, gives)


def _build_into(recipe: Recipe, target: Path, aside: Aside) -> dict[str, Any]:
    """Make the shape, write every output and the manifest into ``target``, and return what the outputs gave."""
    from voxfab import io
    from voxfab._shared.progress import progress
    from voxfab.fabricate import BuildContext, OutputFile, build_order
    from voxfab.fabricate import outputs as output_kinds

    shape = make_shape(recipe)
    source = recipe.source
    context = BuildContext(maker=source.maker, params=dict(source.params), base_dir=recipe.base_dir)
    kinds = output_kinds()
    specs = {spec.name: spec for spec in recipe.outputs}
    # Each output hands what it made to those after it (the net output its net, which the
    # pictures draw), so the order is the table's, not the recipe's.
    order = build_order(specs)
    with atomic_dir(target, marker="manifest.json") as tmp:
        files = []
        for file_name, purpose in SHAPE_FILES.items():
            io.write(shape, tmp / file_name)
            files.append(OutputFile(file_name, purpose))
        warnings: list[str] = []
        gives: dict[str, Any] = {}
        for spec in progress([specs[name] for name in order], desc="outputs"):
            kind = kinds[spec.name]
            if kind.unfolds:
                aside.wait()  # the net kernels are compiled by now, or never will be aside
            settings = spec.settings if spec.settings is not None else kind.settings(dict(spec.options))
            made = kind.run(shape, settings, tmp, name=recipe.name, seed=recipe.seed, context=context)
            context = kind.pass_on(made, context)
            gives.update(made.gives)
            files += made.files
            warnings += [f"{spec.name}: {w}" for w in made.warnings]
        manifest = {
            "format": MANIFEST_FORMAT,
            "voxfab": __version__,
            "recipe": recipe.name,
            "recipe_file": recipe.path.name,
            "recipe_sha256": recipe.sha256,
            "seed": recipe.seed,
            "pitch_mm": recipe.pitch,
            "shape": {
                "volume": shape.volume,
                "extents": list(shape.extents),
                "well_formed": shape.well_formed,
                "reasons": shape.reasons,
                "key": canonical_key(shape.grid),
                "colours": 0 if shape.colours is None else shape.colours.count,
            },
            "outputs": list(order),
            "warnings": warnings,
            "files": [
                {"path": f.path, "sha256": _sha256(tmp / f.path), "purpose": f.purpose}
                for f in sorted(files, key=lambda f: f.path)
            ],
        }
        write_text(tmp / "manifest.json", json.dumps(manifest, indent=2, sort_keys=True) + "\n")
    return gives
