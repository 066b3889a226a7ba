"""The options framework: checks, front ends and the documentation's tables, all from one declaration."""

from __future__ import annotations

import argparse
import dataclasses
import math
from pathlib import Path

import pytest

from voxfab._shared.options import (
    MAX_QUOTE,
    OptionError,
    Options,
    check_values,
    from_mapping,
    markdown_table,
    option,
    option_specs,
    quote,
)
from voxfab.cli._options import add_option_arguments, options_from_args

DOCS = Path(__file__).resolve().parents[2] / "docs"


@dataclasses.dataclass(frozen=True)
class Demo(Options):
    width: float = option(5.0, help="tab width", unit="mm", low=0.0, low_open=True, high=100.0)
    count: int = option(1, help="how many", low=1, high=10)
    mode: str = option("a", help="a mode", choices=("a", "b"))
    size: float | None = option(None, help="a size", unit="mm", low=0.0, low_open=True)
    score: bool = option(True, help="score the outline")
    solid: bool = option(True, help="fill cavities", flag="--keep-cavities", negate=True,
                         flag_help="do not fill cavities")
    views: tuple[str, ...] = option(["iso"], help="views", choices=("iso", "x"), cli=False)
    even: int = option(2, help="an even number", check=lambda v: None if v % 2 == 0 else "expected an even number")


def test_values_are_checked_and_normalised():
    d = Demo(width=2, views=["x", "iso"])
    assert d.width == 2.0 and isinstance(d.width, float) and d.views == ("x", "iso")
    assert hash(d) == hash(Demo(width=2.0, views=("x", "iso")))
    assert d.replace(count=3).count == 3


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"width": -3}, "width: expected a positive number of mm up to 100, got -3"),
        ({"width": 0}, "width: expected a positive number of mm up to 100, got 0"),
        ({"width": math.nan}, "width: expected a positive number of mm up to 100, got nan"),
        ({"width": math.inf}, "width: expected a positive number of mm up to 100, got inf"),
        ({"width": 10**400}, "width: expected a positive number of mm up to 100, got 1000"),
        ({"width": "5"}, "width: expected a positive number of mm up to 100, got str '5'"),
        ({"width": True}, "width: expected a positive number of mm"),
        ({"count": 1.5}, "count: expected an integer from 1 to 10, got float 1.5"),
        ({"count": 0}, "count: expected an integer from 1 to 10, got 0"),
        ({"mode": "c"}, "mode: unknown choice 'c'; expected one of a, b"),
        ({"score": 1}, "score: expected true or false, got int 1"),
        ({"views": ["iso", "top"]}, "views: unknown choice 'top'; expected one of iso, x"),
        ({"views": "iso"}, "views: expected a list of strings"),
        ({"even": 3}, "even: expected an even number, got 3"),
        ({"size": None, "count": None}, "count: expected an integer from 1 to 10, got none"),
    ],
)
def test_bad_values_name_the_option_and_the_value(changes, message):
    with pytest.raises(OptionError) as info:
        Demo(**changes)
    assert str(info.value).startswith(message)
    assert info.value.option == message.split(":")[0]


def test_long_values_are_quoted_short():
    text = "x" * 10_000
    with pytest.raises(OptionError) as info:
        Demo(mode=text)
    assert len(str(info.value)) < 200 and "10002 characters" in str(info.value)
    assert len(quote(text)) <= MAX_QUOTE + 20 and quote("ab") == "'ab'"


def test_from_mapping_refuses_unknown_names_and_hidden_fronts():
    assert from_mapping(Demo, {"width": 3}).width == 3.0
    with pytest.raises(OptionError, match="colour: unknown option; accepted: count, even, mode"):
        from_mapping(Demo, {"colour": 1})
    with pytest.raises(OptionError, match="views: unknown option"):
        from_mapping(Demo, {"views": ["x"]}, front="cli")
    assert check_values(Demo, {"width": 4}) == {"width": 4.0}


def test_cli_arguments_come_from_the_fields():
    parser = argparse.ArgumentParser()
    add_option_arguments(parser, Demo)
    assert Demo() == options_from_args(Demo, parser.parse_args([]))
    args = parser.parse_args(["--width", "7.5", "--count", "3", "--mode", "b", "--no-score", "--keep-cavities"])
    d = options_from_args(Demo, args)
    assert (d.width, d.count, d.mode, d.score, d.solid) == (7.5, 3, "b", False, False)
    with pytest.raises(OptionError, match=r"^--width: expected a positive number of mm up to 100, got -3"):
        options_from_args(Demo, parser.parse_args(["--width", "-3"]))
    with pytest.raises(OptionError, match=r"^--width: .*got inf"):
        options_from_args(Demo, parser.parse_args(["--width", "1e400"]))
    assert "--views" not in parser.format_help()
    assert "(default 5 mm)" in " ".join(parser.format_help().split())


def test_specs_and_table():
    specs = {s.name: s for s in option_specs(Demo)}
    assert specs["size"].optional and specs["width"].describe_range() == "> 0 and <= 100"
    table = markdown_table(Demo).splitlines()
    assert table[0] == "| recipe key | CLI | default | unit, range | meaning |"
    assert "| `width` | `--width` | 5 | mm, > 0 and <= 100 | tab width |" in table
    assert "| `score` | `--score`, `--no-score` | true |  | score the outline |" in table
    assert "| `views` | - | [\"iso\"] | iso, x | views |" in table


def test_every_options_table_has_its_place_in_the_docs():
    """The pages hold an empty block per table, which the docs build fills from the dataclasses (voxfab.cli._reference)."""
    from voxfab.cli._reference import fill, option_tables

    text = "\n".join(p.read_text(encoding="utf-8") for p in DOCS.glob("*.md"))
    tables = option_tables()
    assert {"options:shape", "options:mesh", "options:net", "options:slices", "options:maker-tube"} <= set(tables)
    for name, table in tables.items():
        assert f"<!-- gen:{name} -->" in text, f"docs pages have no gen:{name} block"
        assert table in fill(text, DOCS / "data")
