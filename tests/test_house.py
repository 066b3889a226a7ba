"""House rules of the source tree: no module over 800 lines, no import circle between the modules of a package, no import upward."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1] / "voxfab"
#: Longest module, in lines (issue #26: a module past it holds more than one thing).
MAX_LINES = 800
#: Packages whose modules must not import each other in a circle, however late the import.
NO_CIRCLES = ("voxfab.unfold",)


def module_name(path: Path, root: Path) -> str:
    """The dotted name of a module file under ``root`` (the ``voxfab`` folder); a package's ``__init__`` is the package."""
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def package_imports(path: Path, root: Path, package: str) -> set[str]:
    """Modules of ``package`` that the file ``path`` imports anywhere (at the top or inside a function).

    ``from . import _board`` names the module ``package._board``; ``from . import Net``
    (a name, not a module) names the package itself, whose ``__init__`` it runs.
    """
    modules = {module_name(p, root) for p in (root.parent / package.replace(".", "/")).glob("*.py")}
    me = module_name(path, root)
    found: set[str] = set()

    def add(name: str) -> None:
        # The module of ``package`` that importing ``name`` loads: ``package.x.y`` loads ``package.x``.
        if name == package or name.startswith(package + "."):
            parts = name.split(".")
            found.add(".".join(parts[: len(package.split(".")) + 1]) if name != package else package)

    for base, names in import_statements(path, root):
        if base == package and names:
            for alias in names:
                sub = f"{package}.{alias}"
                add(sub if sub in modules else package)
        else:
            add(base)
    found.discard(me)
    return found


def import_statements(path: Path, root: Path) -> list[tuple[str, list[str]]]:
    """Each import of ``path`` as (absolute module, names taken from it); ``import a, b`` gives one row per module."""
    me = module_name(path, root)
    here = me if path.name == "__init__.py" else me.rpartition(".")[0]
    rows: list[tuple[str, list[str]]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            rows += [(alias.name, []) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = ".".join(here.split(".")[: len(here.split(".")) - node.level + 1])
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module or ""
            rows.append((base, [alias.name for alias in node.names]))
    return rows


def import_circles(root: Path, package: str) -> list[list[str]]:
    """Each group of modules of ``package`` that import one another in a circle (strongly connected, two or more)."""
    folder = root.parent / package.replace(".", "/")
    graph = {module_name(p, root): sorted(package_imports(p, root, package)) for p in sorted(folder.glob("*.py"))}
    # Tarjan's strongly connected components.
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    circles: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                circles.append(sorted(group))

    for v in graph:
        if v not in index:
            visit(v)
    return circles


def write_tree(folder: Path, files: dict[str, str]) -> Path:
    """A made-up package for the checks' own tests: ``files`` by name, in ``folder``."""
    folder.mkdir(parents=True)
    for name, text in files.items():
        (folder / name).write_text(text)
    return folder


def test_no_module_is_over_800_lines() -> None:
    long = {str(p.relative_to(ROOT.parent)): n for p in sorted(ROOT.rglob("*.py"))
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
    assert not long, f"modules over {MAX_LINES} lines: {long}"


@pytest.mark.parametrize("package", NO_CIRCLES)
def test_no_import_circle_inside_the_package(package: str) -> None:
    assert import_circles(ROOT, package) == []


def test_the_circle_check_finds_a_late_import_and_a_package_import(tmp_path: Path) -> None:
    """On a made-up package: a circle closed by an import inside a function, and one through ``__init__``."""
    pkg = write_tree(tmp_path / "voxfab" / "demo", {
        "__init__.py": "from ._search import unfold\n",
        "_search.py": "from ._job import Job\n\ndef unfold():\n    from ._pieces import split\n",
        "_pieces.py": "from ._search import Board\n",
        "_job.py": "import numpy\n",
        "_many.py": "from voxfab.demo._job import Job\nfrom . import _job\n",
    })
    root = tmp_path / "voxfab"
    assert import_circles(root, "voxfab.demo") == [["voxfab.demo._pieces", "voxfab.demo._search"]]
    (pkg / "_job.py").write_text("from voxfab.demo import unfold\n")  # runs __init__, which imports _search
    assert import_circles(root, "voxfab.demo") == [
        ["voxfab.demo", "voxfab.demo._job", "voxfab.demo._pieces", "voxfab.demo._search"]]
    assert package_imports(pkg / "_many.py", root, "voxfab.demo") == {"voxfab.demo._job"}


#: The surfaces over the library (the CLI, the studio, batch runs, the census on Dask): the library never
#: imports them.
SURFACES = ("voxfab.cli", "voxfab.studio", "voxfab.batch", "voxfab.census")
#: Packages and what stands above them in the library: outputs name the packages above by import path
#: (``fabricate._table.resolve``), never by an import.
BELOW = {"voxfab.fabricate": ("voxfab.render", "voxfab.recipe", "voxfab.generate", "voxfab.warmup")}


def upward_imports(root: Path) -> list[str]:
    """``module -> name`` for each import of a surface by the library, or of a package above by one below it."""
    out = []
    for path in sorted(root.rglob("*.py")):
        me = module_name(path, root)
        if me == "voxfab.__main__" or any(me == s or me.startswith(s + ".") for s in SURFACES):
            continue
        banned = list(SURFACES)
        for package, above in BELOW.items():
            if me == package or me.startswith(package + "."):
                banned += above
        for name in sorted({base for base, _ in import_statements(path, root)}):
            if any(name == b or name.startswith(b + ".") for b in banned):
                out.append(f"{me} -> {name}")
    return out


def test_the_library_never_imports_what_stands_above_it() -> None:
    assert upward_imports(ROOT) == []


def test_the_upward_check_finds_a_late_import(tmp_path: Path) -> None:
    write_tree(tmp_path / "voxfab" / "fabricate", {
        "__init__.py": "",
        "_table.py": "def run():\n    from voxfab.render import render_pictures\n",
        "_ok.py": "from voxfab.unfold import Net\nfrom . import _table\n",
    })
    (tmp_path / "voxfab" / "shape.py").write_text("from .studio import pack\n")
    assert upward_imports(tmp_path / "voxfab") == ["voxfab.fabricate._table -> voxfab.render",
                                                   "voxfab.shape -> voxfab.studio"]
