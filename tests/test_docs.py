"""The documentation: the docstrings' examples run as doctests, every public function has its
numpydoc sections, and the site's API reference documents every name of ``eccjump.__all__``.

The site itself is built strictly by CI (``mkdocs build --strict``, README "Documentation").
"""

from __future__ import annotations

import ast
import doctest
import importlib
import importlib.util
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import eccjump
from eccjump._base import docs

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "docs" / "reference"

#: Modules whose examples take a second or more (searches, maps): marked slow.
SLOW_MODULES = {
    "eccjump.studies.design.search",
    "eccjump.classification.starts",
    "eccjump.testing.strategies",  # tracks() analyses two tracks
}


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


# --- the shared entries of eccjump._base.docs -------------------------------------------------


def _with_placeholders() -> list[tuple[str, str]]:
    """(module, qualified name) of every function, class and method whose docstring in the
    source names a shared entry (``%(alpha)s``)."""
    found = []
    for name in _modules():
        path = Path(importlib.import_module(name).__file__ or "")
        if path.suffix != ".py":  # the compiled core
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        scopes = [("", tree.body)]
        for prefix, body in scopes:
            for node in body:
                if not isinstance(node, ast.FunctionDef | ast.ClassDef):
                    continue
                if "%(" in (ast.get_docstring(node, clean=False) or ""):
                    found.append((name, prefix + node.name))
                if isinstance(node, ast.ClassDef):
                    scopes.append((f"{prefix}{node.name}.", node.body))
    return found


WITH_PLACEHOLDERS = _with_placeholders()


def _runtime(module: str, qualname: str) -> object:
    obj: object = importlib.import_module(module)
    for part in qualname.split("."):
        obj = getattr(obj, part)
    return obj


def test_the_shared_entries_are_in_use() -> None:
    assert len(WITH_PLACEHOLDERS) >= 35  # closed_form, boundary, starts, design, jarm, motion, ...
    used = set()
    for module, qualname in WITH_PLACEHOLDERS:
        source = inspect.getsource(_runtime(module, qualname))
        used |= set(re.findall(r"%\((\w+)\)s", source))
    assert used == set(docs.ENTRIES), f"unused: {set(docs.ENTRIES) - used}"


@pytest.mark.parametrize(("module", "qualname"), WITH_PLACEHOLDERS)
def test_every_placeholder_is_filled_with_the_entry_of_its_parameter(module, qualname) -> None:
    obj = _runtime(module, qualname)
    doc = inspect.getdoc(obj) or ""
    assert "%(" not in doc, f"{module}.{qualname}: a placeholder not filled (no @fill?)"
    params = _section(doc, "Parameters") or ""
    documented = [  # numpydoc groups names ("a, b : float") and writes "**kwargs"
        name.strip().lstrip("*")
        for line in params.splitlines()
        if line[:1].isalpha() or line[:1] == "*"
        for name in line.split(" : ")[0].split(",")
    ]
    signature = [p for p in inspect.signature(obj).parameters if p != "self"]  # type: ignore[arg-type]
    assert documented == signature, f"{module}.{qualname}"


def test_an_entry_takes_the_indentation_of_its_placeholder() -> None:
    doc = "One line.\n\n    Parameters\n    ----------\n    %(alpha)s\n    x : int\n"
    want = (
        "    alpha : array_like of float\n"
        "        Ramp angle [rad], in [0, π/2] (``math.radians`` for degrees).\n"
    )
    assert docs.render(doc) == doc.replace("    %(alpha)s\n", want)
    assert docs.render("%(alpha)s") == docs.ENTRIES["alpha"]
    assert docs.render("a 100%(alpha)s share") == "a 100%(alpha)s share"  # not a line of its own
    with pytest.raises(KeyError, match=r"%\(alpah\)s"):
        docs.render("    %(alpah)s")


def test_the_site_reads_the_filled_docstrings() -> None:
    griffe = pytest.importorskip("griffe")
    spec = importlib.util.spec_from_file_location("ext", ROOT / "docs/_ext/griffe_eccjump.py")
    assert spec is not None and spec.loader is not None
    ext = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ext)
    pkg = griffe.load(
        "eccjump",
        search_paths=[str(ROOT / "python")],
        extensions=griffe.Extensions(ext.EccjumpDocstrings()),
    )
    for module, qualname in WITH_PLACEHOLDERS:
        seen = pkg[f"{module.removeprefix('eccjump.')}.{qualname}"].docstring.value
        assert "%(" not in seen, f"{module}.{qualname}"


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


# --- equations in the docstrings: the guide's Unicode ----------------------------------------

#: ASCII math the docstrings no longer write (the guide's forms: √, ≤, ≥, θ̇, θ̈, ², π).
ASCII_MATH = re.compile(r"sqrt\(|<=|>=|\btheta'|\^2\b|\^3\b|\bpi\b|\b(alpha|chi|theta|mu_s)\b")
#: Where names stay as typed: code spans, roles, options, placeholders, quoted text.
CODE_SPANS = re.compile(r"--[\w-]+|``.*?``|:\w+:`[^`]*`|`[^`]*`|%\(\w+\)s|\"[^\"]*\"|'[^' ]*'")


def _docstring_prose(source: str) -> list[str]:
    """The lines of every docstring of ``source`` that are prose: not doctest input or
    output, not a numpydoc ``name : type`` line, code spans removed."""
    lines = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef)):
            continue
        doc = ast.get_docstring(node, clean=False)
        output = False
        for line in (doc or "").splitlines():
            s = line.strip()
            output = s.startswith((">>>", "...")) or (output and s != "")
            if output or re.match(r"^\s*\**[\w, *]+ : ", line):
                continue
            lines.append(CODE_SPANS.sub("", line))
    return lines


#: Files not yet converted (issue 49): none is left, and this set only shrinks.
NOT_YET_UNICODE: set[str] = set()


def test_docstring_equations_use_the_guides_unicode() -> None:
    """The site renders the docstrings next to the guide, which writes θ, √(g/R), ≤ and χ θ̇²
    cos θ = cos α: the docstrings write the same (names as typed stay in ``code``)."""
    package = ROOT / "python" / "eccjump"
    found = [
        f"{path.relative_to(ROOT)}: {line.strip()}"
        for path in sorted(package.rglob("*.py"))
        if path.relative_to(package).as_posix() not in NOT_YET_UNICODE
        for line in _docstring_prose(path.read_text(encoding="utf-8"))
        if ASCII_MATH.search(line)
    ]
    assert not found, "ASCII math in docstrings:\n" + "\n".join(found[:20])
