"""Error messages: one line, quoting at most about 80 characters of any input."""

from voxfab.errors import QUOTE_LIMIT, one_line, quote


def test_quote_keeps_short_input_and_cuts_long_input():
    assert quote("x^2") == "'x^2'"
    long = quote("-" * 10000 + "x")
    assert len(long) < QUOTE_LIMIT + 30 and long.endswith("...' (10001 characters)")


def test_one_line_cuts_quoted_input_and_folds_lines():
    message = "expression: bad at column 3 of " + repr("y" * 5000) + "\nsecond line"
    line = one_line(message)
    assert "\n" not in line and len(line) < 200 and line.endswith("...' second line")
    assert one_line("a" * 2000).endswith("...") and len(one_line("a" * 2000)) == 600
    assert one_line('path "short" ok') == 'path "short" ok'
