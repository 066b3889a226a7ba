"""The input limits: each refuses over-limit input with a message that gives the count."""

from __future__ import annotations

import os

import pytest

from voxfab._shared import limits
from voxfab._shared.limits import (
    check_count,
    check_regular_file,
    nesting_depth,
    open_image,
    parse_json,
    parse_toml,
    read_input_bytes,
)
from voxfab.errors import FormatError, InvalidShapeError, LimitError


def test_json_within_the_limits_parses():
    deep = "[" * limits.MAX_NESTING + "]" * limits.MAX_NESTING
    assert nesting_depth(parse_json(deep, name="d")) == limits.MAX_NESTING
    assert parse_json('{"a": "[[[[[[", "b": [1, -123456789012345678901234567890]}', name="d")["b"][1] < 0


@pytest.mark.parametrize(("text", "message"), [
    ("[" * 65 + "]" * 65, "JSON nested 65 levels, over the limit of 64 levels"),
    ('{"a": ' * 70 + "1" + "}" * 70, "JSON nested 70 levels"),
    ("[" + "1" * 31 + "]", "an integer of 31 digits is over the limit of 30 digits"),
])
def test_json_over_the_limits(text, message):
    with pytest.raises(LimitError, match=message):
        parse_json(text, name="d")


def test_invalid_json_is_a_format_error():
    with pytest.raises(FormatError, match="not valid JSON: .*line 1 column"):
        parse_json("[1, 2", name="d")


def test_toml_depth_inline_and_by_dotted_keys():
    assert parse_toml("a.b.c = 1\nx = [[1], [2]]\n", name="r") == {"a": {"b": {"c": 1}}, "x": [[1], [2]]}
    with pytest.raises(LimitError, match="TOML nested 100 levels, over the limit of 64"):
        parse_toml("a = " + "[" * 100 + "]" * 100, name="r")
    with pytest.raises(LimitError, match="deeper than the limit of 64"):
        parse_toml("a" + ".a" * 70 + " = 1", name="r")
    # brackets inside strings do not count
    assert parse_toml('a = "' + "[" * 100 + '"', name="r")["a"] == "[" * 100
    with pytest.raises(FormatError, match="invalid TOML"):
        parse_toml("a = ", name="r")


def test_counts():
    assert check_count(10, 10, name="n") == 10
    with pytest.raises(LimitError, match="samples: 1,000,000,000 is over the limit of 100,000"):
        check_count(10**9, 100_000, name="samples")
    with pytest.raises(InvalidShapeError, match="expected an integer >= 2"):
        check_count(1, 10, name="n", least=2)
    with pytest.raises(InvalidShapeError, match="expected an integer"):
        check_count(2.5, 10, name="n")


def test_only_regular_files_are_read(tmp_path):
    os.mkfifo(tmp_path / "f")
    with pytest.raises(FormatError, match="is a FIFO"):
        read_input_bytes(tmp_path / "f")
    with pytest.raises(FormatError, match="is a folder"):
        check_regular_file(tmp_path)
    with pytest.raises(FormatError, match="is a device"):
        check_regular_file("/dev/null")
    with pytest.raises(FormatError, match="no such file"):
        check_regular_file(tmp_path / "missing")
    (tmp_path / "big").write_bytes(b"x" * 101)
    with pytest.raises(LimitError, match="101 bytes is over the limit of 100 bytes"):
        read_input_bytes(tmp_path / "big", limit=100)


def test_images_are_checked_from_their_header(tmp_path):
    from _fuzz import png_claiming
    from PIL import Image

    (tmp_path / "bomb.png").write_bytes(png_claiming(5000, 4000))
    with pytest.raises(LimitError, match="5000x4000 = 20,000,000 pixels is over the limit of 16,777,216"):
        open_image(tmp_path / "bomb.png", name="bitmap")
    Image.new("L", (30, 20)).save(tmp_path / "ok.png")
    with open_image(tmp_path / "ok.png", name="bitmap") as im:
        assert im.size == (30, 20)
    # Pillow's own limit is restored after the header is read.
    assert Image.MAX_IMAGE_PIXELS is not None


def test_limits_are_documented_in_the_docs():
    from pathlib import Path

    from voxfab.cli._reference import fill

    docs = Path(__file__).parents[2] / "docs"
    readme = fill((docs / "limits.md").read_text(), docs / "data")
    for name in ("MAX_EXPRESSION_CHARS", "MAX_NESTING", "MAX_PIXELS", "MAX_SAMPLES", "MAX_FOCI", "MAX_TRIANGLES"):
        value = getattr(limits, name)
        assert f"{value:,}" in readme, name
