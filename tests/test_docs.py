"""The documentation: the docstrings' examples run as doctests, every public function has its
numpydoc sections, and the site's API reference documents every name of ``eccjump.__all__``.

The site itself is built strictly by CI (``mkdocs build --strict``, README "Documentation").
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import eccjump

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "docs" / "reference"

#: Modules whose examples take a second or more (searches, maps): marked slow.
SLOW_MODULES = {"eccjump.studies.design.search", "eccjump.classification.starts"}


def _modules() -> list[str]:
    names = ["eccjump"]
    for info in pkgutil.walk_packages(eccjump.__path__, "eccjump."):
        if not info.name.endswith("__main__"):
            names.append(info.name)
    return sorted(names)


def _functions() -> list[str]:
    return [n for n in eccjump.__all__ if inspect.isfunction(getattr(eccjump, n))]


@pytest.mark.parametrize(
    "name",
    [pytest.param(m, marks=pytest.mark.slow) if m in SLOW_MODULES else m for m in _modules()],
)
def test_examples_run_as_doctests(name: str) -> None:
    module = importlib.import_module(name)
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testmod(module, optionflags=flags, verbose=False, report=True)
    assert result.failed == 0, f"{result.failed} doctest(s) of {name} failed (see above)"


def test_every_public_function_has_a_doctest() -> None:
    finder = doctest.DocTestFinder()
    missing = [n for n in _functions() if not finder.find(getattr(eccjump, n))[0].examples]
    assert not missing, f"no example in the docstrings of {missing}"


def _section(doc: str, title: str) -> str | None:
    """The text of the numpydoc section ``title`` of ``doc``, or None."""
    match = re.search(rf"^{title}\n-+\n(.*?)(?=^\S[^\n]*\n-+\n|\Z)", doc, re.MULTILINE | re.DOTALL)
    return match.group(1) if match else None


@pytest.mark.parametrize("name", _functions())
def test_function_docstrings_have_numpydoc_sections(name: str) -> None:
    func = getattr(eccjump, name)
    doc = inspect.getdoc(func) or ""
    for title in ("Parameters", "Returns", "Raises", "Examples"):
        assert _section(doc, title) is not None, f"eccjump.{name}: no {title} section"
    params = _section(doc, "Parameters") or ""
    documented = {
        p.strip().lstrip("*")
        for line in params.splitlines()
        if line and not line[0].isspace()
        for p in line.split(" : ")[0].split(",")
    }
    signature = set(inspect.signature(func).parameters)
    assert signature <= documented, f"eccjump.{name}: undocumented {signature - documented}"


def _public_docstrings() -> list[tuple[str, str]]:
    """(where, docstring) of every public module, class, function and method of eccjump."""
    out: list[tuple[str, str]] = []
    for name in _modules():
        module = importlib.import_module(name)
        out.append((name, module.__doc__ or ""))
        for attr, obj in vars(module).items():
            if attr.startswith("_") or getattr(obj, "__module__", None) != name:
                continue
            if inspect.isclass(obj) or inspect.isfunction(obj):
                out.append((f"{name}.{attr}", obj.__doc__ or ""))
            if inspect.isclass(obj):
                for meth, member in vars(obj).items():
                    doc = getattr(member, "__doc__", None)
                    if not meth.startswith("_") and isinstance(doc, str):
                        out.append((f"{name}.{attr}.{meth}", doc))
    return out


def test_docstrings_point_to_no_file_the_wheel_lacks() -> None:
    """The wheel has no docs/: a docstring names the site's page instead."""
    bad = [where for where, doc in _public_docstrings() if re.search(r"docs/\w+\.md", doc)]
    assert not bad, f"docstrings that point to docs/*.md: {bad}"


def test_region_spells_out_its_arguments() -> None:
    doc = inspect.getdoc(eccjump.region) or ""
    assert "Other arguments as" not in doc
    for option in ("method", "rule", "rtol", "max_turns", "stop_at_slip", "integrator"):
        assert re.search(rf"^{option} : ", doc, re.MULTILINE), option


def _documented_names() -> set[str]:
    text = "\n".join(p.read_text(encoding="utf-8") for p in REFERENCE.glob("*.md"))
    return set(re.findall(r"^::: eccjump\.(\w+)\s*$", text, re.MULTILINE))


def test_api_reference_documents_every_public_name() -> None:
    missing = set(eccjump.__all__) - _documented_names()
    assert not missing, f"names of eccjump.__all__ without a ::: entry in docs/reference: {missing}"


def test_api_reference_documents_no_stale_name() -> None:
    stale = _documented_names() - set(eccjump.__all__)
    assert not stale, f"docs/reference documents names eccjump no longer exports: {stale}"


def test_site_nav_lists_every_page() -> None:
    """Every page of docs/ is in the site's navigation (mkdocs --strict also refuses one that
    is not; this says which, without building)."""
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    pages = {
        str(p.relative_to(ROOT / "docs"))
        for p in (ROOT / "docs").rglob("*.md")
        if "_ext" not in p.parts
    }
    missing = sorted(p for p in pages if p not in nav)
    assert not missing, f"pages missing from the nav of mkdocs.yml: {missing}"


def test_ci_builds_the_site_with_the_readme_command() -> None:
    """The README's "Documentation" command, verbatim, is a line of .ci/run after the test
    command's line."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("\n## Documentation\n", 1)[1].split("\n## ", 1)[0]
    command = re.findall(r"```bash\n(.*?)\n```", section, re.DOTALL)[0].strip()
    assert "mkdocs build --strict" in command and command.startswith("pip install")
    lines = (ROOT / ".ci" / "run").read_text(encoding="utf-8").strip().splitlines()
    assert command in lines
    docs = lines.index(command)
    assert any("pytest" in line and "cargo test" in line for line in lines[:docs])
