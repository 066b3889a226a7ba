"""Safe expression compiler."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.digitize import compile_expression
from voxfab.errors import InvalidShapeError


def test_values_and_operators():
    e = compile_expression("x^2 + y**2 - 2*x*y / 4 + sqrt(abs(x)) - min(x, y, 0) + atan2(y, x) % 1", ("x", "y"))
    x, y = np.array([1.5, -2.0]), np.array([0.5, 3.0])
    expect = x**2 + y**2 - 2 * x * y / 4 + np.sqrt(np.abs(x)) - np.minimum(np.minimum(x, y), 0) + np.arctan2(y, x) % 1
    assert np.allclose(e(x, y), expect)
    assert e.used == {"x", "y"}


def test_equation_form_and_constants():
    e = compile_expression("x^2 + y^2 = 1", ("x", "y"))
    assert np.allclose(e(np.array([0.0, 2.0]), np.array([0.0, 0.0])), [-1.0, 3.0])
    assert np.isclose(float(compile_expression("cos(pi) + tau - 2*pi + e", ("t",))(np.zeros(1))), np.e - 1)


def test_broadcasts_and_constant_expressions():
    e = compile_expression("x + 0*y", ("x", "y"))
    assert e(np.zeros((3, 1)), np.zeros((1, 4))).shape == (3, 4)
    assert float(compile_expression("2^3", ("x",))(np.zeros(2))) == 8.0


@pytest.mark.parametrize(
    ("text", "pattern"),
    [
        ("x^2 + foo", r"unknown name 'foo'.*column 7"),
        ("x^2 + (y", r"syntax error at column 7"),
        ("x +* 2", r"syntax error at column"),
        ("sin(x, y)", r"sin\(\) takes 1 arguments, got 2"),
        ("frobnicate(x)", r"unknown function 'frobnicate'"),
        ("__import__('os').system('true')", r"only plain function names"),
        ("x.real", r"unsupported syntax Attribute"),
        ("(lambda: 1)()", r"only plain function names|unsupported"),
        ("'text'", r"unsupported constant"),
        ("x if y else 1", r"unsupported syntax IfExp"),
        ("", r"non-empty expression"),
    ],
)
def test_bad_expressions_name_the_problem(text, pattern):
    with pytest.raises(InvalidShapeError, match=pattern):
        compile_expression(text, ("x", "y"), name="curve")


def test_error_names_the_input():
    with pytest.raises(InvalidShapeError, match=r"^generatrix: unknown name 'z'"):
        compile_expression("x + z", ("x", "y"), name="generatrix")


@pytest.mark.parametrize(
    ("implicit", "explicit"),
    [
        ("0.6 + 0.3 sin(3y)", "0.6 + 0.3*sin(3*y)"),
        ("2pi x", "2*pi*x"),
        ("(x+1)(x-1)", "(x+1)*(x-1)"),
        ("2e-3x + 3e", "2e-3*x + 3*e"),
        ("x y^2", "x*y^2"),
        ("max(x, y)2", "max(x, y)*2"),
        ("3(x + y)", "3*(x + y)"),
    ],
)
def test_products_written_side_by_side(implicit, explicit):
    x, y = np.linspace(-2, 2, 7), np.linspace(-1, 3, 7)
    a = compile_expression(implicit, ("x", "y"))(x, y)
    b = compile_expression(explicit, ("x", "y"))(x, y)
    assert np.array_equal(a, b)


def test_implied_products_keep_their_error_columns():
    with pytest.raises(InvalidShapeError, match=r"unknown name 'q' \(.*\) at column 7 of '0\.3 x q'"):
        compile_expression("0.3 x q", ("x", "y"))
    with pytest.raises(InvalidShapeError, match=r"unknown function 'sinn'"):
        compile_expression("0.3 sinn(3y)", ("x", "y"))
