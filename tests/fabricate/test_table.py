"""The one table of outputs: every surface reads it, and each row says truly what it writes."""

from __future__ import annotations

import dataclasses
import fnmatch
import itertools
import json
import shutil
from pathlib import Path

import pytest

from voxfab.fabricate import Artefact, BuildContext, build_order, outputs
from voxfab.fabricate._table import resolve
from voxfab.recipe import SHAPE_FILES, build, load_recipe, make_shape

RECIPES = Path(__file__).resolve().parents[2] / "recipes"


def test_every_row_resolves_to_its_options_and_pipeline():
    from voxfab._shared.options import Options

    for row in outputs().values():
        assert callable(resolve(row.pipeline)), row.name
        for table in row.options:
            assert issubclass(resolve(table.cls), Options), (row.name, table.cls)
        assert row.keys and len(set(row.keys)) == len(row.keys)
        assert row.files and all(row.download_table is not None for _ in row.downloads)


def test_the_surfaces_list_what_the_table_lists():
    from voxfab.studio._work import artefacts
    from voxfab.warmup import GROUPS

    assert artefacts() == [d for row in outputs().values() for d in row.downloads]
    assert {row.warm_group for row in outputs().values() if row.warm_group} <= set(GROUPS)
    from voxfab.cli import COMMANDS

    assert {row.command for row in outputs().values()} <= set(COMMANDS)
    from voxfab.cli._reference import fill

    docs = RECIPES.parent / "docs"
    pages = fill("\n".join(p.read_text(encoding="utf-8") for p in docs.glob("*.md")), docs / "data")
    for row in outputs().values():
        assert f"[outputs.{row.name}]" in pages, row.name
        for table in row.options:
            assert f"<!-- gen:options:{table.readme} -->" in pages


@pytest.mark.parametrize("recipe", ["tubes/interlaced.toml"])
def test_a_build_writes_only_the_files_its_rows_declare(tmp_path, recipe):
    """A recipe with every output (the animation needs a tube) writes only files its rows name."""
    folder = tmp_path / "r"
    shutil.copytree((RECIPES / recipe).parent, folder)
    path = folder / Path(recipe).name
    text = path.read_text()
    # Small and quick: a coarse tube, plates and pictures of it, the net on a large sheet.
    text = text.replace("[source]\n", "[source]\nsize = 12\n").replace("[outputs.pictures]", "[outputs.pictures]\nsize = 120")
    text += "\n[outputs.animation]\nsteps = 2\nsize = 64\n\n[outputs.hunt]\nzipper_timeout = 1\n"
    path.write_text(text)
    built = build(load_recipe(path), tmp_path / "out")
    manifest = json.loads((built / "manifest.json").read_text())
    assert set(manifest["outputs"]) == set(outputs())
    patterns = [p for row in outputs().values() for p in row.files] + list(SHAPE_FILES)
    for entry in manifest["files"]:
        assert any(fnmatch.fnmatch(entry["path"], p) for p in patterns), entry["path"]
        assert (built / entry["path"]).is_file()
    for row in outputs().values():
        assert any(fnmatch.fnmatch(e["path"], p) for e in manifest["files"] for p in row.files), row.name


def test_outputs_run_after_those_that_give_what_they_use_whatever_their_listing():
    rows = outputs()
    order = build_order(rows)
    assert sorted(order) == sorted(rows)
    assert all(build_order(listing) == order for listing in itertools.permutations(rows))
    for row in rows.values():
        for other in rows.values():
            if other is not row and set(row.uses) & set(other.gives):
                assert order.index(other.name) < order.index(row.name), (other.name, row.name)
    assert order.index("net") < order.index("pictures")
    assert build_order(["pictures", "mesh"]) == ("mesh", "pictures")


def test_an_output_passes_on_exactly_what_its_row_declares():
    net_row = outputs()["net"]
    context = BuildContext(maker="revolution")
    made = Artefact((), gives={"net": ("the pieces",)})
    assert net_row.pass_on(made, context) == dataclasses.replace(context, net=("the pieces",))
    with pytest.raises(RuntimeError, match="declares"):
        net_row.pass_on(Artefact(()), context)
    with pytest.raises(RuntimeError, match="declares"):
        outputs()["mesh"].pass_on(made, context)
    # What no output can use goes to the build's caller only (the hunt's nets, for the batch's thumbnails).
    hunt = Artefact((), gives={"hunt_net": None, "zipper_net": ("a zipper net",)})
    assert outputs()["hunt"].pass_on(hunt, context) == context
    with pytest.raises(ValueError, match="not a BuildContext field"):
        dataclasses.replace(outputs()["pictures"], uses=("nett",))


def test_the_pictures_draw_a_net_given_as_its_pieces(tmp_path):
    """A gallery pick and the net output's gift are the net as its pieces: one piece is drawn as that net, a net
    in several pieces as those pieces (not a one-piece net of the pictures' own)."""
    from voxfab.render import PictureOptions, png_bytes
    from voxfab.render._net import net_picture
    from voxfab.render._triptych import make_net
    from voxfab.unfold import unfold

    shape = make_shape(load_recipe(RECIPES / "chess" / "pawn.toml"))
    row = outputs()["pictures"]
    settings = row.settings({"size": 160, "views": [], "triptych": False, "net_picture": True})

    def drawn(net, folder):
        folder.mkdir()
        row.run(shape, settings, folder, name="pawn", seed=0, context=BuildContext(net=net))
        return (folder / "net_picture.png").read_bytes()

    def picture(net):
        return png_bytes(net_picture(net, shape.grid, size=160, background=PictureOptions().background))

    picked = unfold(shape.grid, rng=3)
    assert not picked.filled
    assert drawn([picked], tmp_path / "one") == picture(picked) != picture(make_net(shape, rng=0))
    pieces = unfold(shape.grid, rng=0, fit=(20, 20), pieces="flat")
    assert len(pieces) > 1
    assert drawn(pieces, tmp_path / "several") == picture(pieces) != picture(make_net(shape, rng=0))
