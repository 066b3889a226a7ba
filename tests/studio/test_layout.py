"""The studio's source stays in pieces one can read: no function over 150 lines, no module over 800 (issue #26)."""

from __future__ import annotations

import ast
from pathlib import Path

import voxfab.studio

STUDIO = Path(voxfab.studio.__file__).resolve().parent
MAX_FUNCTION_LINES = 150
MAX_MODULE_LINES = 800


def oversized(source: str, where: str) -> list[str]:
    """The functions (methods, nested functions) of ``source`` over the limit, and the module itself if it is."""
    found = []
    lines = len(source.splitlines())
    if lines > MAX_MODULE_LINES:
        found.append(f"{where}: {lines} lines")
    for node in ast.walk(ast.parse(source, filename=where)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            length = node.end_lineno - node.lineno + 1
            if length > MAX_FUNCTION_LINES:
                found.append(f"{where}:{node.lineno} {node.name}: {length} lines")
    return found


def test_no_function_or_module_of_the_studio_is_too_long():
    modules = sorted(STUDIO.rglob("*.py"))
    assert {"_app.py", "_session.py", "net.py"} <= {m.name for m in modules}  # the routes' subpackage is read too
    found = [f for m in modules for f in oversized(m.read_text(encoding="utf-8"), str(m.relative_to(STUDIO)))]
    assert not found, "split these: " + "; ".join(found)


def test_the_check_finds_a_long_function_a_nested_one_and_a_long_module():
    body = "".join(f"    x{i} = {i}\n" for i in range(MAX_FUNCTION_LINES))  # with its `def` line: one too many
    assert oversized(f"def long():\n{body}", "a.py") == [f"a.py:1 long: {MAX_FUNCTION_LINES + 1} lines"]
    nested = "def outer():\n    async def inner():\n" + body.replace("    ", "        ")
    assert [f.split()[1] for f in oversized(nested, "b.py")] == ["outer:", "inner:"]
    short = "def short():\n" + "".join(f"    x{i} = {i}\n" for i in range(MAX_FUNCTION_LINES - 1))
    assert oversized(short, "c.py") == []
    assert oversized("x = 1\n" * (MAX_MODULE_LINES + 1), "d.py") == [f"d.py: {MAX_MODULE_LINES + 1} lines"]
