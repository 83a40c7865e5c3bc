"""The Python package's structure in numbers, as ``docs/architecture.md`` cites them (issue 47):
its top-level modules, the import edges between its modules, its functions over 80 lines and
its longest import chain. ``tests/test_structure.py`` reads the import graph from here (one
reading of the imports)::

    python scripts/python_layers.py                 # this checkout
    python scripts/python_layers.py /path/to/tree   # another, e.g. a worktree of an old commit

An edge is an ``import`` or ``from ... import`` of one eccjump module by another, wherever in
the file (``from eccjump.maps import store`` is an edge to ``eccjump.maps.store``, ``from
eccjump.maps import Map`` one to ``eccjump.maps``); the compiled core ``eccjump._core`` is a
module. The chain follows the imports made at import time (not those inside functions, which
run later). A function's lines run from its ``def`` to its end, its docstring left out.
"""

from __future__ import annotations

import argparse
import ast
import functools
from pathlib import Path

LONG_FUNCTION = 80  # lines


def module_name(package: Path, path: Path) -> str:
    """The dotted name of the module in file ``path`` of ``package`` (the eccjump folder)."""
    parts = ("eccjump", *path.relative_to(package).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def sources(package: Path) -> list[Path]:
    return sorted(package.rglob("*.py"))


def _is_module(package: Path, name: str) -> bool:
    rel = Path(*name.split(".")[1:])
    return (
        name == "eccjump._core"
        or (package / rel).with_suffix(".py").exists()
        or (package / rel / "__init__.py").exists()
    )


def imports(package: Path, path: Path) -> tuple[set[str], set[str]]:
    """The eccjump modules the file ``path`` imports at import time, and those it imports
    inside functions."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    top: set[str] = set()
    local: set[str] = set()

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            names: list[str] = []
            if isinstance(child, ast.Import):
                names = [a.name for a in child.names]
            elif isinstance(child, ast.ImportFrom) and child.module and child.level == 0:
                for a in child.names:
                    sub = f"{child.module}.{a.name}"
                    names.append(sub if _is_module(package, sub) else child.module)
            for name in names:
                if name == "eccjump" or name.startswith("eccjump."):
                    (local if in_function else top).add(name)
            fn = isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda)
            visit(child, in_function or fn)

    visit(tree, False)
    return top, local


def graph(package: Path) -> dict[str, tuple[set[str], set[str]]]:
    """Each module's (imported eccjump modules, of which imported inside functions)."""
    found = {}
    for p in sources(package):
        top, local = imports(package, p)
        found[module_name(package, p)] = (top | local, local)
    return found


def edges(package: Path) -> dict[str, set[str]]:
    """Each module's imports of other eccjump modules (``eccjump._core`` a module too)."""
    found = {m: deps - {m} for m, (deps, _) in graph(package).items()}
    found.setdefault("eccjump._core", set())
    return found


def longest_chain(package: Path) -> list[str]:
    """The longest chain of modules each importing the next at import time; a cycle raises."""
    at_import = {module_name(package, p): imports(package, p)[0] for p in sources(package)}
    at_import = {m: deps - {m} for m, deps in at_import.items()}

    @functools.cache
    def chain(m: str, seen: frozenset[str] = frozenset()) -> tuple[str, ...]:
        if m in seen:
            raise ValueError(f"import cycle through {m}")
        below = [chain(d, seen | {m}) for d in sorted(at_import.get(m, ()))]
        return (m, *max(below, key=len, default=()))

    return list(max((chain(m) for m in sorted(at_import)), key=len))


def top_level(package: Path) -> list[str]:
    """The modules and packages right in the eccjump folder (not ``__init__``, the core's
    stub and library, ``py.typed``)."""
    return sorted(
        p.stem if p.is_file() else p.name
        for p in package.iterdir()
        if (p.suffix == ".py" and p.stem != "__init__") or (p / "__init__.py").exists()
    )


def _body_lines(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    first = fn.body[0]
    doc = isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
    doc_lines = (first.end_lineno or first.lineno) - first.lineno + 1 if doc else 0
    return (fn.end_lineno or fn.lineno) - fn.lineno + 1 - doc_lines


def long_functions(package: Path, limit: int = LONG_FUNCTION) -> list[tuple[str, int]]:
    """(module.function, lines) of every function and method over ``limit`` lines."""
    found = []
    for p in sources(package):
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                if (n := _body_lines(node)) > limit:
                    found.append((f"{module_name(package, p)}.{node.name}", n))
    return sorted(found, key=lambda f: -f[1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("tree", nargs="?", default=Path(__file__).resolve().parents[1], type=Path)
    package = parser.parse_args().tree / "python" / "eccjump"
    top = top_level(package)
    n_edges = sum(len(d) for d in edges(package).values())
    long = long_functions(package)
    chain = longest_chain(package)
    print(f"top-level modules: {len(top)} ({', '.join(top)})")
    print(f"modules: {len(sources(package))}; import edges between them: {n_edges}")
    print(f"functions over {LONG_FUNCTION} lines: {len(long)}")
    for name, n in long:
        print(f"  {n:4d}  {name}")
    print(f"longest import chain: {len(chain)} modules: {' -> '.join(chain)}")


if __name__ == "__main__":
    main()
