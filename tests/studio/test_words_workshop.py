"""The studio's words for the artist (issue #44, item 3): refused joins name the pieces, ways out say
"seam labels" as the checkbox does, no CLI word is left over, and the maker forms show plain labels."""

from __future__ import annotations

import re
import types
from pathlib import Path

import pytest

from voxfab.errors import UnfoldError
from voxfab.studio._netedit import apply_edit
from voxfab.studio._words import explained, plain

ROOT = Path(__file__).resolve().parents[2]
STATIC = ROOT / "voxfab" / "studio" / "static"


@pytest.fixture(scope="module")
def pawn_pieces():
    from voxfab.recipe import load_recipe, make_shape
    from voxfab.unfold import unfold

    grid = make_shape(load_recipe(ROOT / "recipes" / "chess" / "pawn.toml")).grid
    return grid, unfold(grid, rng=0, pieces="flat", fit=(10, 10), timeout=30)


def test_a_refused_join_names_its_two_pieces_in_plain_words(pawn_pieces):
    grid, pieces = pawn_pieces
    job = types.SimpleNamespace(id="j1", data={"nets": [pieces], "grid": grid}, items=[], result=None)
    # face [7,9,0,-y] is on piece 28 and [7,9,0,-z] on piece 1: joining them would make the piece overlap itself
    with pytest.raises(UnfoldError) as info:
        apply_edit(job, {"index": 0, "join": [[7, 9, 0, "-y"], [7, 9, 0, "-z"]]})
    said = explained(str(info.value))
    assert said["text"] == "pieces 1 and 28 cannot be joined along that edge: the joined piece would overlap itself"
    assert "[7,9,0,-y]-[7,9,0,-z]" in said["detail"]  # the technical line stays in the tooltip
    assert not re.search(r"\[\d+,\d+,\d+,[+-][xyz]\]", said["text"])


def test_the_piece_numbers_named_are_the_printed_ones(pawn_pieces):
    from voxfab.fabricate.netdraw import DrawingOptions, draw_pieces

    grid, pieces = pawn_pieces
    drawing = draw_pieces(grid, pieces, options=DrawingOptions(sheet="A3", pitch=10.0))
    # piece i (0-based) of the list is printed i + 1 on the sheets, the number the refusal names
    assert drawing.pieces == len(pieces)
    for i in range(3):
        assert int(drawing.face_piece[sum(p.face_count for p in pieces[:i])]) == i


def test_the_ways_out_say_seam_labels_as_the_checkbox_does():
    from voxfab.fabricate.netdraw import DrawingOptions
    from voxfab.fabricate.netdraw._fit import legibility_ways_out

    assert "seam labels" in (STATIC / "index.html").read_text()
    labels = [w["label"] for w in legibility_ways_out(DrawingOptions(pitch=3.0), 3)]
    assert any("seam labels" in w for w in labels) and not any("edge labels" in w for w in labels)
    assert "edge labels" not in plain("faces of 3 mm are too small for 2 mm edge labels of 3 characters")


def test_a_larger_sheet_is_named_without_a_cli_word():
    from voxfab.fabricate.netdraw import DrawingOptions
    from voxfab.fabricate.netdraw._sheets import HopelessSheetError, check_pieces_sheet

    with pytest.raises(HopelessSheetError) as info:
        check_pieces_sheet(862, DrawingOptions(sheet="60x60", pitch=8.6), 8.6, 8.6)
    text = plain(str(info.value))
    assert "use a larger sheet, A5" in text
    assert "--" not in text and "A5, sheet" not in text and "(A5, " not in text


def test_no_tooltip_speaks_of_the_exact_search():
    for path in [STATIC / "index.html", *sorted((STATIC / "js").glob("*.js"))]:
        for title in re.findall(r'title="([^"]*)"', path.read_text()):
            assert "exact" not in title, (path.name, title)


def test_the_maker_forms_show_plain_labels(client):
    info = client.get("/api/info").json()
    rows = {m["name"]: {p["name"]: p for p in m["params"]} for m in info["makers"]}
    assert rows["revolution"]["curve_threshold"]["label"] == "curve grey level"
    assert rows["tube"]["profile_open"]["label"] == "open profile (a ribbon)"
    for row in rows.values():
        for p in row.values():
            if p["input"] == "form":
                assert "_" not in p["label"], p
    assert "p.label" in (STATIC / "js" / "makers.js").read_text()  # the form shows the label, not the key
