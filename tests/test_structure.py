"""The structure of the Python package: subpackages in layers whose imports point down only
(no cycle, no import hidden inside a function to dodge one), at most ten modules at the top, no
public name hiding a module, one description of the result fields, one place that calls the
classification bridge. The import graph is read by ``scripts/python_layers.py``, which also
gives the counts of ``docs/architecture.md``."""

from __future__ import annotations

import ast
import dataclasses
import importlib
import importlib.util
import inspect
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from reference_points import JARM_BODY

import eccjump
from eccjump import _core
from eccjump.classification import fields
from eccjump.classification.classify import JarmResult

PACKAGE = Path(eccjump.__file__).parent
ROOT = Path(__file__).resolve().parent.parent


def _python_layers():
    spec = importlib.util.spec_from_file_location(
        "python_layers", ROOT / "scripts" / "python_layers.py"
    )
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


python_layers = _python_layers()
SOURCES = python_layers.sources(PACKAGE)
GRAPH = python_layers.graph(PACKAGE)  # module -> (eccjump modules it imports, inside functions)
MODULES = sorted(GRAPH)
IMPORTABLE = [m for m in MODULES if not m.endswith("__main__")]  # __main__ runs the CLI


def module_name(path: Path) -> str:
    return python_layers.module_name(PACKAGE, path)


# --- the layers -----------------------------------------------------------------------------

#: The layers, lowest first: a module imports from its own layer and those below, never above.
#: A module's layer is its longest dotted prefix here (``eccjump`` itself: the public API).
LAYERS = {
    "eccjump._core": 0,  # the compiled core
    "eccjump._base": 0,  # checks, arrays, the bridge, HTML, sizes, user files; Cylinder, Units
    "eccjump._compat": 0,  # the old module paths (imports nothing of eccjump's by name)
    "eccjump.maps": 1,  # the map type, kinds, layout, files, xarray, dask
    "eccjump.classification": 2,  # closed forms, fields, jarm, region, boundary, starts
    # above the classification: motion.fields builds on classification.fields (Field, ROUNDING)
    "eccjump.motion": 3,  # roll, simulate, dense output, motion points and maps
    "eccjump.studies": 4,  # design, uncertainty, experiment
    "eccjump.plot": 5,
    "eccjump.explorer": 6,
    "eccjump": 7,  # the public API, __init__.py
    "eccjump.cli": 8,  # argparse and printing over the public API
    # hypothesis strategies and assertions for the users' tests: anything public, imported by
    # nothing of eccjump (hypothesis is an optional dependency)
    "eccjump.testing": 9,
}

#: The imports that still run upward: none since issue 47's inversions (a map kind carries its
#: own fields and validator, the map layer reads and writes layouts, ...); this set only
#: shrinks. Besides these, a result's ``.plot()`` imports ``eccjump.plot`` inside the method
#: (the figures are the optional layer on top of every result, as pandas' ``.plot``).
UPWARD: set[tuple[str, str]] = set()


def layer(module: str) -> int:
    parts = module.split(".")
    for cut in range(len(parts), 0, -1):
        if ".".join(parts[:cut]) in LAYERS:
            return LAYERS[".".join(parts[:cut])]
    raise KeyError(module)


def upward_imports() -> set[tuple[str, str]]:
    return {
        (m, d)
        for m, (deps, local) in GRAPH.items()
        for d in deps
        if layer(d) > layer(m) and not (d == "eccjump.plot" and d in local)
    }


def test_every_module_has_a_layer():
    top = {m for m in MODULES if m.count(".") == 1 and m not in LAYERS}
    assert not top, f"modules at the top with no layer in LAYERS: {top}"


def test_imports_point_down():
    found = upward_imports()
    assert not found - UPWARD, f"imports running up a layer: {sorted(found - UPWARD)}"
    assert not UPWARD - found, f"turned round (strike from UPWARD): {sorted(UPWARD - found)}"


def test_no_eccjump_import_inside_functions():
    """Except a result's ``.plot()`` reaching up to the figures (see ``UPWARD``)."""
    hidden = {m: local - {"eccjump.plot"} for m, (_, local) in GRAPH.items()}
    hidden = {m: local for m, local in hidden.items() if local}
    assert not hidden, f"imports inside functions: {hidden}"


def test_imports_form_no_cycle():
    edges = {
        m: {d for d in deps if d in GRAPH} - {m} - ({"eccjump.plot"} & local)
        for m, (deps, local) in GRAPH.items()
    }
    state: dict[str, int] = {}

    def walk(m: str, path: list[str]) -> None:
        state[m] = 1
        for d in sorted(edges[m]):
            if state.get(d) == 1:
                cycle = [*path[path.index(d) :], d] if d in path else [m, d]
                pytest.fail("import cycle: " + " -> ".join(cycle))
            if d not in state:
                walk(d, [*path, d])
        state[m] = 2

    for m in sorted(edges):
        if m not in state:
            walk(m, [m])


def test_at_most_ten_modules_at_the_top():
    top = python_layers.top_level(PACKAGE)
    assert len(top) <= 10, f"{len(top)} modules at the top of eccjump: {top}"


#: Names bound in a package that hide a module of it (none: the last four were renamed in 0.2).
HIDING: set[tuple[str, str]] = set()


def bindings(init: Path) -> dict[str, str | None]:
    """The names a package's ``__init__.py`` binds at import time: to the module of that
    name, or (None) to anything else."""
    package = module_name(init)
    bound: dict[str, str | None] = {}

    def visit(body: list[ast.stmt]) -> None:
        for node in body:
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                for a in node.names:
                    sub = f"{node.module}.{a.name}"
                    bound[a.asname or a.name] = sub if sub in GRAPH else None
            elif isinstance(node, ast.Import):
                for a in node.names:
                    bound[a.asname or a.name.partition(".")[0]] = a.asname and a.name
            elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                bound[node.name] = None
            elif isinstance(node, ast.Assign | ast.AnnAssign | ast.AugAssign):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                bound.update(
                    {n.id: None for x in targets for n in ast.walk(x) if type(n) is ast.Name}
                )
            elif isinstance(node, ast.If | ast.Try):
                visit([*node.body, *node.orelse, *getattr(node, "finalbody", [])])

    visit(ast.parse(init.read_text(encoding="utf-8")).body)
    return {n: m for n, m in bound.items() if m != f"{package}.{n}"}


def test_no_name_in_a_package_hides_its_module():
    """``eccjump.design`` is the function, so the package of the studies is
    ``eccjump.studies.design``: a name equal to a module's of the same package makes
    ``pkg.name`` the one and ``import pkg.name`` the other."""
    hiding = set()
    for init in sorted(PACKAGE.rglob("__init__.py")):
        package = module_name(init)
        children = {m.rpartition(".")[2] for m in GRAPH if m.rpartition(".")[0] == package}
        hiding |= {(package, n) for n in bindings(init).keys() & children}
    assert hiding == HIDING, f"names hiding a module: {sorted(hiding ^ HIDING)}"


def test_the_bridge_is_called_from_one_module():
    callers = {
        module_name(p)
        for p in SOURCES
        for call in ("_core.jarm_points", "_core.jarm_grid")
        if call in p.read_text()
    }
    assert callers == {"eccjump._base.bridge"}


def keyword_only(f) -> list[str]:
    ps = inspect.signature(f).parameters.values()
    return sorted(p.name for p in ps if p.kind is p.KEYWORD_ONLY)


def test_the_bridges_option_classes_take_the_public_names():
    # The bridge's convention: shared options go in one options class, made from keyword-only
    # plain values under the public function's own names (no two floats swapped on the way).
    # derivatives: a second bridge call after the classification (_core.jarm_derivatives).
    public = [p for p in keyword_only(eccjump.jarm) if p != "derivatives"]
    assert keyword_only(_core.ClassifyOptions) == public
    searches = (eccjump.alpha_intervals, eccjump.mu_s_min_path, eccjump.alpha_interval_around)
    for f in searches:
        assert set(keyword_only(_core.BoundaryOptions)) <= set(inspect.signature(f).parameters)
    for f in (_core.jarm_points, _core.jarm_grid, *(getattr(_core, g.__name__) for g in searches)):
        assert "options" in keyword_only(f), f.__name__


# One interpreter imports numpy, then forks a child per module that imports it with no eccjump
# module loaded yet: an interpreter per module paid its start-up and numpy 75 times (54 s).
IMPORT_EACH_IN_A_FORK = r"""
import importlib, json, os, sys, traceback
import numpy  # what is checked is eccjump's own order of imports
failed = {}
for name in sys.argv[1:]:
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(r)
        try:
            importlib.import_module(name)
        except BaseException:
            os.write(w, traceback.format_exc().encode())
            os._exit(1)
        os._exit(0)
    os.close(w)
    with os.fdopen(r) as f:
        err = f.read()
    status = os.waitpid(pid, 0)[1]
    if status:
        failed[name] = err or f"wait status {status}"
print(json.dumps(failed))
"""


@pytest.fixture(scope="module")
def import_failures() -> dict[str, str]:
    """Each importable module's traceback where importing it alone failed."""
    run = subprocess.run(
        [sys.executable, "-c", IMPORT_EACH_IN_A_FORK, *IMPORTABLE],
        capture_output=True,
        text=True,
        check=True,
        timeout=600,
    )
    return json.loads(run.stdout.splitlines()[-1])


@pytest.mark.skipif(not hasattr(os, "fork"), reason="imports each module in a forked child")
@pytest.mark.parametrize("module", IMPORTABLE)
def test_each_module_imports_alone_in_a_fresh_interpreter(module, import_failures):
    assert module not in import_failures, import_failures[module]


def test_upper_modules_first_then_lower_in_one_interpreter():
    order = [
        "maps.xarray",
        "maps.dask",
        "maps.store",
        "classification.classify",
        "classification.fields",
        "cli.map",
        "_base.bridge",
    ]
    code = "; ".join(f"import eccjump.{m}" for m in order)
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)


# --- one description of the result fields --------------------------------------------------


def test_result_fields_come_from_one_table():
    names = tuple(f.name for f in fields.TABLE)
    assert fields.FIELDS == names
    derivatives = tuple(f.name for f in fields.DERIVATIVE_TABLE)
    assert fields.DERIVATIVES == derivatives
    assert tuple(f.name for f in dataclasses.fields(JarmResult)) == names + derivatives
    assert eccjump.classification.FIELDS is fields.FIELDS
    assert fields.JARM.fields is fields.FIELDS and fields.JARM.record().names == names
    assert fields.JARM.dtypes is fields.DTYPES and fields.JARM.fill is fields.FILL
    for f in fields.TABLE + fields.DERIVATIVE_TABLE:
        attrs = fields.JARM.var_attrs(f.name)
        assert {k: attrs[k] for k in ("units", "long_name")} == {
            "units": f.units,
            "long_name": f.description,
        }
        assert f.name in (JarmResult.__doc__ or "") and f.description in JarmResult.__doc__
        assert np.array(f.fill).astype(f.dtype).dtype == f.dtype


def test_results_have_the_described_dtypes():
    r = eccjump.jarm([0.5, 0.7], *JARM_BODY, 1.0, derivatives=True)
    reg = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.15], km_frac=[0.1], derivatives=True)
    for name, dtype in fields.DTYPES.items():
        assert getattr(r, name).dtype == dtype and getattr(reg.result, name).dtype == dtype
    ds = pytest.importorskip("xarray") and reg.to_xarray()
    assert ds.theta_J.attrs["units"] == fields.BY_NAME["theta_J"].units
    assert list(ds.reason.attrs["flag_values"]) == [r.value for r in fields.Reason]


def test_one_form_of_a_message_naming_a_file():
    """file_error and shown live in the base, below the overwrite policy and the maps, which
    re-export them; the command line's longest line is the same constant."""
    from eccjump._base import checks
    from eccjump.cli import _args
    from eccjump.maps import check

    assert check.file_error is checks.file_error and check.shown is checks.shown
    assert check.MAX_MESSAGE is _args.MAX_MESSAGE is checks.MAX_MESSAGE


def test_one_helper_imports_the_optional_dependencies(monkeypatch):
    """Each optional import fails with the pip command of its extra, through one helper in
    the base (the analysis figure took matplotlib through the figures' layer above it; now
    it and the figures take it from the base's canvas, with one message)."""
    from eccjump.maps import dask, layout
    from eccjump.plot import _common
    from eccjump.studies.experiment import figure

    for name in ("matplotlib.pyplot", "dask.array", "zarr"):
        monkeypatch.setitem(sys.modules, name, None)  # as if not installed
    for call, message in (
        (_common._plt, "matplotlib.pyplot is needed for eccjump.plot: pip install eccjump[plot]"),
        (dask.require_dask, "dask.array is needed for chunks=: pip install eccjump[dask]"),
        (lambda: layout.require("zarr"), "zarr is needed for labelled results"),
        (lambda: figure.analysis_figure(None), "matplotlib.pyplot is needed for eccjump.plot"),
    ):
        with pytest.raises(ImportError, match=re.escape(message)):
            call()
