"""The core's non-test Rust in lines, as issue 36 counts it (the "lean core" measure).

A file counts up to its first ``#[cfg(test)]`` line; a module declared under
``#[cfg(test)]`` in its own file (``mod tests;`` beside ``foo.rs`` as ``foo/tests.rs``)
is test code and does not count. ``examples/`` and ``tests/`` are reported apart::

    python scripts/core_lines.py                # this checkout
    python scripts/core_lines.py /path/to/tree --top 20
"""

from __future__ import annotations

import argparse
import itertools
import re
from pathlib import Path

_TEST_MOD = re.compile(r"\s*(pub(\(crate\))?\s+)?mod (\w+);")


def _test_modules(src: Path) -> set[Path]:
    """The files of modules declared right after a ``#[cfg(test)]`` line."""
    found = set()
    for path in src.rglob("*.rs"):
        lines = path.read_text().splitlines()
        for attr, decl in itertools.pairwise(lines):
            m = _TEST_MOD.match(decl)
            if attr.strip().startswith("#[cfg(test)]") and m:
                parent = path.parent if path.name in ("mod.rs", "lib.rs") else path.with_suffix("")
                name = m.group(3)
                candidates = (parent / f"{name}.rs", parent / name / "mod.rs")
                found.update(p for p in candidates if p.exists())
    return found


def _before_tests(path: Path) -> int:
    """Lines of ``path`` before its first ``#[cfg(test)]``."""
    n = 0
    for line in path.read_text().splitlines():
        if line.strip().startswith("#[cfg(test)]"):
            break
        n += 1
    return n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tree", nargs="?", type=Path, default=Path("."), help="a checkout")
    ap.add_argument("--top", type=int, default=0, help="list the N largest files")
    args = ap.parse_args()
    core = args.tree / "rust" / "eccjump-core"
    src = core / "src"
    tests = _test_modules(src)
    rows = sorted(
        ((_before_tests(p), p.relative_to(core)) for p in src.rglob("*.rs") if p not in tests),
        reverse=True,
    )
    print(f"core non-test: {sum(n for n, _ in rows)} lines in {len(rows)} files")
    print(f"test modules in src/: {sum(len(p.read_text().splitlines()) for p in tests)} lines")
    for sub in ("examples", "tests"):
        files = list((core / sub).rglob("*.rs"))
        print(f"{sub}/: {sum(len(p.read_text().splitlines()) for p in files)} lines")
    for n, p in rows[: args.top]:
        print(f"{n:6d}  {p}")


if __name__ == "__main__":
    main()
