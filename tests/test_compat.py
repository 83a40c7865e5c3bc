"""The module paths before the layers (``eccjump.rolling``, ``eccjump.design.search``, ...)
import for one release as the very modules at their new paths, with a DeprecationWarning naming
the new path (``eccjump/_compat.py``). The only tests that use the old paths: pyproject turns
their warning into an error everywhere else."""

from __future__ import annotations

import importlib
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

import eccjump
from eccjump import _compat

PACKAGE = Path(eccjump.__file__).parent


@pytest.fixture(autouse=True)
def first_import(monkeypatch):
    """Each test imports the old paths afresh, and leaves no old name behind (in
    ``sys.modules`` or as an attribute of eccjump) for the tests after it."""
    for name in [n for n in sys.modules if _compat.new_name(n)]:
        monkeypatch.delitem(sys.modules, name)
    before = set(vars(eccjump))
    yield
    for name in set(vars(eccjump)) - before:
        delattr(eccjump, name)
    for name in [n for n in sys.modules if _compat.new_name(n)]:
        del sys.modules[name]


@pytest.mark.parametrize(("old", "new"), sorted(_compat.MOVED.items()))
def test_an_old_path_is_the_module_at_its_new_path_and_warns(old, new):
    with pytest.warns(DeprecationWarning, match=rf"^{old} is deprecated: import {new} ") as seen:
        module = importlib.import_module(old)
    assert module is importlib.import_module(new)
    assert module.__name__ == module.__spec__.name == new  # its own spec, not the alias's
    assert seen[0].filename == __file__  # the warning points to the importing line


MOVED_NAMES = sorted(
    (m, n, new) for m, names in _compat.MOVED_NAMES.items() for n, new in names.items()
)


@pytest.mark.parametrize(("module", "name", "new"), MOVED_NAMES)
def test_a_name_that_left_a_module_is_served_with_a_warning(module, name, new):
    path, _, attr = new.partition(":")
    want = getattr(importlib.import_module(path), attr or name)
    old = importlib.import_module(module)
    warning = rf"^{module}\.{name} is deprecated: use {path}\.{attr or name} "
    with pytest.warns(DeprecationWarning, match=warning) as seen:
        assert getattr(old, name) is want
    assert seen[0].filename == __file__  # the warning points to the line that asked
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        _ = old.nothing


def test_the_old_paths_read_as_before():
    with pytest.warns(DeprecationWarning):
        import eccjump.design.search
        import eccjump.rolling
        from eccjump.labelled import FILL
        from eccjump.motion_points import MotionPoints
    assert eccjump.rolling.roll is eccjump.roll
    assert MotionPoints is eccjump.MotionPoints
    assert FILL is eccjump.classification.fields.FILL
    assert sys.modules["eccjump.design.search"] is eccjump.studies.design.search
    with pytest.warns(DeprecationWarning, match="eccjump.fields is deprecated"):
        assert eccjump.fields.FIELDS is eccjump.classification.FIELDS  # attribute, no import


def test_an_old_path_named_like_a_function_leaves_the_function():
    with pytest.warns(DeprecationWarning):
        import eccjump.design.search
        import eccjump.motion_points
        import eccjump.uncertainty.sampling
    for name in ("design", "uncertainty", "motion_points"):
        assert callable(getattr(eccjump, name)), name


@pytest.mark.parametrize(
    "old",
    [
        "eccjump.plot.trajectory",
        "eccjump.plot.uncertainty",
        "eccjump.studies.design.build",
        "eccjump.studies.experiment.reconstruct",
    ],
)
def test_a_renamed_module_leaves_the_function_of_its_name(old):
    """These modules were hidden by the function of their package of the same name: the old
    path imports the renamed module, and ``package.name`` stays the function."""
    package, _, name = old.rpartition(".")
    function = getattr(importlib.import_module(package), name)
    with pytest.warns(DeprecationWarning, match=rf"^{old} is deprecated"):
        module = importlib.import_module(old)
    assert getattr(module, name) is function
    assert getattr(sys.modules[package], name) is function


def test_a_pickle_made_before_the_move_loads():
    made = pickle.dumps(eccjump.Reason.JARM, protocol=0)
    old = made.replace(b"eccjump.classification.fields", b"eccjump.fields")
    assert old != made
    with pytest.warns(DeprecationWarning):
        assert pickle.loads(old) is eccjump.Reason.JARM


def test_no_old_path_hides_a_module():
    """The finder comes first on sys.meta_path: an old path that is a module again would be
    hidden by its alias."""
    for old, new in _compat.MOVED.items():
        rel = Path(*old.split(".")[1:])
        assert not rel.with_suffix(".py").exists() and not (PACKAGE / rel).exists(), old
        assert _compat.new_name(new) is None, new
    assert _compat.new_name("eccjump.motion") is None
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        _ = eccjump.nothing


def test_eccjump_uses_no_old_path():
    # every module of the package, imported with eccjump's deprecations as errors
    def name(p: Path) -> str:
        parts = ("eccjump", *p.relative_to(PACKAGE).with_suffix("").parts)
        return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)

    modules = sorted(name(p) for p in PACKAGE.rglob("*.py") if p.name != "__main__.py")
    code = "import importlib, sys\nfor m in sys.argv[1:]: importlib.import_module(m)"
    run = subprocess.run(
        [sys.executable, "-W", "error:eccjump.:DeprecationWarning", "-c", code, *modules],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr[-2000:]
