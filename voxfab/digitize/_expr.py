"""Safe compiler of math expression strings into vectorized numpy functions.

The text is parsed with :mod:`ast` and only a whitelist of node types is turned
into a tree of numpy closures: no ``eval``/``exec`` of user text ever happens.
``^`` means power (``x^2``), ``lhs = rhs`` means ``lhs - (rhs)``, and a product
may be written without ``*`` as on paper: ``0.3 sin(3y)``, ``2pi x``, ``(x+1)(x-1)``.
"""

from __future__ import annotations

import ast
import keyword
import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from voxfab._shared.limits import MAX_EXPRESSION_CHARS, MAX_EXPRESSION_DEPTH
from voxfab.errors import InvalidShapeError, LimitError, quote

__all__ = ["Expression", "compile_expression", "FUNCTIONS", "CONSTANTS"]


def _min(*a: np.ndarray) -> np.ndarray:
    out = a[0]
    for b in a[1:]:
        out = np.minimum(out, b)
    return out


def _max(*a: np.ndarray) -> np.ndarray:
    out = a[0]
    for b in a[1:]:
        out = np.maximum(out, b)
    return out


#: name → (numpy function, minimum arity, maximum arity or None for any).
FUNCTIONS: dict[str, tuple[Callable[..., np.ndarray], int, int | None]] = {
    "sin": (np.sin, 1, 1), "cos": (np.cos, 1, 1), "tan": (np.tan, 1, 1),
    "asin": (np.arcsin, 1, 1), "acos": (np.arccos, 1, 1), "atan": (np.arctan, 1, 1),
    "atan2": (np.arctan2, 2, 2), "sinh": (np.sinh, 1, 1), "cosh": (np.cosh, 1, 1),
    "tanh": (np.tanh, 1, 1), "asinh": (np.arcsinh, 1, 1), "acosh": (np.arccosh, 1, 1),
    "atanh": (np.arctanh, 1, 1), "exp": (np.exp, 1, 1), "log": (np.log, 1, 1),
    "ln": (np.log, 1, 1), "log2": (np.log2, 1, 1), "log10": (np.log10, 1, 1),
    "sqrt": (np.sqrt, 1, 1), "cbrt": (np.cbrt, 1, 1), "abs": (np.abs, 1, 1),
    "floor": (np.floor, 1, 1), "ceil": (np.ceil, 1, 1), "round": (np.round, 1, 1),
    "sign": (np.sign, 1, 1), "hypot": (np.hypot, 2, 2), "pow": (np.power, 2, 2),
    "mod": (np.mod, 2, 2), "min": (_min, 2, None), "max": (_max, 2, None),
}

#: Named constants usable in expressions.
CONSTANTS: dict[str, float] = {"pi": math.pi, "e": math.e, "tau": math.tau}

_BINOPS: dict[type, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {
    ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
    ast.Div: np.true_divide, ast.Pow: np.power, ast.Mod: np.mod,
}

Node = Callable[[Sequence[np.ndarray]], np.ndarray]


@dataclass(frozen=True)
class Expression:
    """A compiled expression: call it with one array per variable.

    Attributes
    ----------
    text : str
        The source text.
    variables : tuple of str
        Variable names, in call order.
    used : frozenset of str
        The variables that appear in the text.
    """

    text: str
    variables: tuple[str, ...]
    used: frozenset[str]
    _node: Node

    def __call__(self, *coords: np.ndarray) -> np.ndarray:
        if len(coords) != len(self.variables):
            raise InvalidShapeError(
                f"expression {quote(self.text)}: expected {len(self.variables)} coordinate arrays, got {len(coords)}"
            )
        args = [np.asarray(c, dtype=np.float64) for c in coords]
        with np.errstate(all="ignore"):
            return np.asarray(self._node(args), dtype=np.float64)


def _prepare(text: str) -> tuple[str, list[int]]:
    """Rewrite ``^`` to ``**`` and ``a = b`` to ``(a) - (b)``; map columns back to the source."""
    out: list[str] = []
    cols: list[int] = []
    i = 0
    eq_positions = [
        j for j, ch in enumerate(text)
        if ch == "=" and (j == 0 or text[j - 1] not in "<>=!") and (j + 1 >= len(text) or text[j + 1] != "=")
    ]
    split = eq_positions[0] if len(eq_positions) == 1 else None
    if split is not None:
        out.append("(")
        cols.append(0)
    while i < len(text):
        ch = text[i]
        if ch == "^":
            out.extend("**")
            cols.extend((i, i))
        elif i == split:
            out.extend(")-(")
            cols.extend((i, i, i))
        else:
            out.append(ch)
            cols.append(i)
        i += 1
    if split is not None:
        out.append(")")
        cols.append(len(text))
    cols.append(len(text))
    return "".join(out), cols


#: Numbers (with exponents), names, and any other single character.
_TOKEN = re.compile(r"(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)|(?P<name>[A-Za-z_]\w*)|(?P<other>\S)")


def _implicit_products(text: str, cols: list[int], values: set[str]) -> tuple[str, list[int]]:
    """Insert the ``*`` of products written side by side (``3y``, ``2 sin(x)``, ``)(``).

    A product is implied between a number, a variable, a constant or a closing
    bracket and a following number, name or opening bracket.  Any other name
    followed by ``(`` stays a call, and Python keywords are left alone, so the
    compiler still reports unknown functions and unsupported syntax as such.
    The inserted ``*`` takes the column of the factor after it, so error
    messages still point into the user's text.
    """
    out: list[str] = []
    out_cols: list[int] = []
    # Kind of the last token: "num", "value" (a variable or constant), "name" (any other
    # name: a function when "(" follows), ")" or "" (nothing that ends a factor).
    previous = ""
    pos = 0
    for m in _TOKEN.finditer(text):
        out.append(text[pos:m.start()])
        out_cols.extend(cols[pos:m.start()])
        kind = m.lastgroup
        token = m.group()
        is_keyword = kind == "name" and keyword.iskeyword(token)
        starts_factor = (kind in ("num", "name") and not is_keyword) or token == "("
        if token == "(" and previous == "name":
            starts_factor = False  # a call
        if starts_factor and previous in ("num", "value", "name", ")"):
            out.append("*")
            out_cols.append(cols[m.start()])
        out.append(token)
        out_cols.extend(cols[m.start():m.end()])
        pos = m.end()
        if kind == "num":
            previous = "num"
        elif kind == "name":
            previous = "" if is_keyword else ("value" if token in values else "name")
        else:
            previous = ")" if token == ")" else ""
    out.append(text[pos:])
    out_cols.extend(cols[pos:])
    return "".join(out), out_cols


def _depth(tree: ast.AST) -> int:
    """Depth of a syntax tree, counted without recursion."""
    deepest = 0
    stack = [(tree, 1)]
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node))
    return deepest


def compile_expression(text: str, variables: Sequence[str], *, name: str = "expression") -> Expression:
    """Compile ``text`` into a vectorized function of ``variables``.

    Parameters
    ----------
    text : str
        E.g. ``"x^2 + y^2 - 1"`` or ``"x^2 + y^2 = 1"``.
    variables : sequence of str
        The allowed variable names, in the order the function takes them.
    name : str
        The input's name, used in error messages.

    Raises
    ------
    InvalidShapeError
        On a syntax error (with its column) or an unknown name or function.
    LimitError
        On a text over :data:`~voxfab._shared.limits.MAX_EXPRESSION_CHARS`
        characters (1000) or nested over
        :data:`~voxfab._shared.limits.MAX_EXPRESSION_DEPTH` levels (100): CPython's
        parser and the compiler below recurse once per level.
    """
    if not isinstance(text, str) or not text.strip():
        raise InvalidShapeError(f"{name}: expected a non-empty expression string, got {quote(text)}")
    if len(text) > MAX_EXPRESSION_CHARS:
        raise LimitError(
            f"{name}: expression of {len(text):,} characters is over the limit of "
            f"{MAX_EXPRESSION_CHARS:,}: {quote(text)}"
        )
    prepared, cols = _implicit_products(*_prepare(text), {*variables, *CONSTANTS})
    try:
        tree = ast.parse(prepared.strip(), mode="eval")
    except SyntaxError as exc:
        lead = len(prepared) - len(prepared.lstrip())
        off = max(0, min((exc.offset or 1) - 1 + lead, len(cols) - 1))
        raise InvalidShapeError(
            f"{name}: syntax error at column {cols[off] + 1} of {quote(text)}: {exc.msg}"
        ) from None
    except (RecursionError, MemoryError):  # pragma: no cover - the length limit keeps the parser safe
        raise LimitError(f"{name}: expression nested too deeply to parse: {quote(text)}") from None
    depth = _depth(tree)
    if depth > MAX_EXPRESSION_DEPTH:
        raise LimitError(
            f"{name}: expression nested {depth} levels deep, over the limit of {MAX_EXPRESSION_DEPTH}: {quote(text)}"
        )
    used: set[str] = set()
    var_index = {v: i for i, v in enumerate(variables)}

    def bad(node: ast.AST, what: str) -> InvalidShapeError:
        col = getattr(node, "col_offset", 0)
        lead = len(prepared) - len(prepared.lstrip())
        col = cols[min(col + lead, len(cols) - 1)] + 1
        return InvalidShapeError(f"{name}: {what} at column {col} of {quote(text)}")

    def build(node: ast.AST) -> Node:
        if isinstance(node, ast.Expression):
            return build(node.body)
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise bad(node, f"unsupported constant {quote(node.value)}")
            value = float(node.value)
            return lambda a: value
        if isinstance(node, ast.Name):
            if node.id in var_index:
                used.add(node.id)
                idx = var_index[node.id]
                return lambda a: a[idx]
            if node.id in CONSTANTS:
                value = CONSTANTS[node.id]
                return lambda a: value
            known = ", ".join([*variables, *CONSTANTS])
            raise bad(node, f"unknown name {node.id!r} (known names: {known})")
        if isinstance(node, ast.BinOp):
            op = _BINOPS.get(type(node.op))
            if op is None:
                raise bad(node, f"unsupported operator {type(node.op).__name__}")
            left, right = build(node.left), build(node.right)
            return lambda a: op(left(a), right(a))
        if isinstance(node, ast.UnaryOp):
            operand = build(node.operand)
            if isinstance(node.op, ast.USub):
                return lambda a: np.negative(operand(a))
            if isinstance(node.op, ast.UAdd):
                return operand
            raise bad(node, f"unsupported operator {type(node.op).__name__}")
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name):
                raise bad(node, "only plain function names can be called")
            fname = node.func.id
            if fname not in FUNCTIONS:
                known = ", ".join(sorted(FUNCTIONS))
                raise bad(node, f"unknown function {fname!r} (known functions: {known})")
            if node.keywords:
                raise bad(node, f"{fname}() takes no keyword arguments")
            func, lo, hi = FUNCTIONS[fname]
            n = len(node.args)
            if n < lo or (hi is not None and n > hi):
                want = str(lo) if hi == lo else f"at least {lo}" if hi is None else f"{lo} to {hi}"
                raise bad(node, f"{fname}() takes {want} arguments, got {n}")
            args = [build(x) for x in node.args]
            return lambda a: func(*[f(a) for f in args])
        raise bad(node, f"unsupported syntax {type(node).__name__}")

    node = build(tree)
    return Expression(text, tuple(variables), frozenset(used), node)
