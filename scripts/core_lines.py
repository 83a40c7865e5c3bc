"""The core's non-test Rust in lines, as issue 36 counts it (the "lean core" measure).

Every line of a file counts except the items under ``#[cfg(test)]``, wherever they are in the
file: ``mod tests { ... }`` blocks, test-only functions, types and impls, and the declarations
``#[cfg(test)] mod tests;``, whose own files (``foo/tests.rs`` beside ``foo.rs``) are test
code too. ``examples/`` and ``tests/`` are reported apart::

    python scripts/core_lines.py                # this checkout
    python scripts/core_lines.py /path/to/tree --top 20
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

_CFG_TEST = "#[cfg(test)]"
_MOD_DECL = re.compile(r"\s*(pub(\([\w:]+\))?\s+)?mod (\w+)\s*;")
# What braces and semicolons inside do not count: comments, strings and character literals.
_NOISE = re.compile(r'//.*|"(\\.|[^"\\])*"|\'(\\.|[^\\\'])\'')


def _item_end(lines: list[str], start: int) -> int:
    """The index of the last line of the item starting at ``lines[start]``: the line of its
    ``;`` if it has no body, else the line where its braces close."""
    depth = 0  # of (), [] and {} together: `[f64; K]` in a signature ends nothing
    for i in range(start, len(lines)):
        for ch in _NOISE.sub("", lines[i]):
            if ch in "([{":
                depth += 1
            elif ch in ")]}":
                depth -= 1
                if depth == 0 and ch == "}":
                    return i
            elif ch == ";" and depth == 0:
                return i
    return len(lines) - 1


def _split(path: Path) -> tuple[int, list[str]]:
    """The non-test lines of ``path`` and the names of the modules it declares, without a
    body, under ``#[cfg(test)]``."""
    lines = path.read_text().splitlines()
    kept, test_mods, i = 0, [], 0
    while i < len(lines):
        if not lines[i].strip().startswith(_CFG_TEST):
            kept += 1
            i += 1
            continue
        # The item the attribute applies to: after any other attributes and doc comments.
        start = i
        rest = lines[i].strip()[len(_CFG_TEST) :].strip()
        if not rest:
            start += 1
            while start < len(lines) and lines[start].strip().startswith(("#[", "///", "//")):
                start += 1
        end = _item_end(lines, start) if rest or start < len(lines) else start
        if m := _MOD_DECL.match(rest or (lines[start] if start < len(lines) else "")):
            test_mods.append(m.group(3))
        i = end + 1
    return kept, test_mods


def _counts(src: Path) -> dict[Path, int]:
    """Non-test lines of every non-test file under ``src``."""
    kept, tests = {}, set()
    for path in src.rglob("*.rs"):
        kept[path], mods = _split(path)
        parent = path.parent if path.name in ("mod.rs", "lib.rs") else path.with_suffix("")
        for name in mods:
            tests.update(p for p in (parent / f"{name}.rs", parent / name / "mod.rs") if p.exists())
    # A test module's own file is test code whole, and so are the files of its submodules.
    for path in list(tests):
        below = path.parent if path.name == "mod.rs" else path.with_suffix("")
        tests.update(p for p in kept if p.is_relative_to(below))
    return {p: n for p, n in kept.items() if p not in tests}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tree", nargs="?", type=Path, default=Path("."), help="a checkout")
    ap.add_argument("--top", type=int, default=0, help="list the N largest files")
    args = ap.parse_args()
    core = args.tree / "rust" / "eccjump-core"
    src = core / "src"
    kept = _counts(src)
    rows = sorted(((n, p.relative_to(core)) for p, n in kept.items()), reverse=True)
    print(f"core non-test: {sum(n for n, _ in rows)} lines in {len(rows)} files")
    total = sum(len(p.read_text().splitlines()) for p in src.rglob("*.rs"))
    print(f"test code in src/: {total - sum(kept.values())} lines")
    for sub in ("examples", "tests"):
        files = list((core / sub).rglob("*.rs"))
        print(f"{sub}/: {sum(len(p.read_text().splitlines()) for p in files)} lines")
    for n, p in rows[: args.top]:
        print(f"{n:6d}  {p}")


if __name__ == "__main__":
    main()
