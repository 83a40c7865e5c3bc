"""The structure of the Python package: one description of the result fields, one place that
calls the classification bridge, and one-directional imports (no circles, no imports hidden
inside functions to dodge one)."""

from __future__ import annotations

import ast
import dataclasses
import inspect
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import eccjump
from eccjump import _core
from eccjump.classification import fields
from eccjump.classification.classify import JarmResult
from eccjump.maps import dask as scale
from eccjump.maps import xarray as labelled

PACKAGE = Path(eccjump.__file__).parent
SOURCES = sorted(PACKAGE.rglob("*.py"))


def module_name(path: Path) -> str:
    parts = ("eccjump", *path.relative_to(PACKAGE).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = sorted(module_name(p) for p in SOURCES)
IMPORTABLE = [m for m in MODULES if not m.endswith("__main__")]  # __main__ runs the CLI


def is_module(name: str) -> bool:
    rel = Path(*name.split(".")[1:])
    return (
        name == "eccjump._core"
        or (PACKAGE / rel).with_suffix(".py").exists()
        or (PACKAGE / rel / "__init__.py").exists()
    )


def eccjump_imports(path: Path) -> tuple[set[str], list[str]]:
    """The eccjump modules ``path`` imports, and those imported inside functions."""
    tree = ast.parse(path.read_text())
    found: set[str] = set()
    local: list[str] = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            names: list[str] = []
            if isinstance(child, ast.Import):
                names = [a.name for a in child.names]
            elif isinstance(child, ast.ImportFrom) and child.module and child.level == 0:
                for a in child.names:
                    sub = f"{child.module}.{a.name}"
                    names.append(sub if is_module(sub) else child.module)
            for name in names:
                if name == "eccjump" or name.startswith("eccjump."):
                    found.add(name)
                    if in_function:
                        local.append(name)
            fn = isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda)
            visit(child, in_function or fn)

    visit(tree, False)
    return found, local


GRAPH = {module_name(p): eccjump_imports(p) for p in SOURCES}


def test_no_eccjump_import_inside_functions():
    """Except one, named: a result's ``.plot()`` reaches up to the figures, the optional
    layer on top of every result (as pandas' ``.plot``); nothing below imports it."""
    hidden = {
        m: [n for n in local if n != "eccjump.plot"] for m, (_, local) in GRAPH.items() if local
    }
    hidden = {m: local for m, local in hidden.items() if local}
    assert not hidden, f"imports inside functions: {hidden}"


def test_imports_form_no_cycle():
    # a result's .plot() reaching up to the figures (the one allowed local import) is no edge
    edges = {
        m: {d for d in deps if d in GRAPH} - {m} - ({"eccjump.plot"} & set(local))
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


@pytest.mark.parametrize(
    ("module", "below"),
    [
        ("eccjump._base.checks", set()),
        ("eccjump.classification.fields", {"eccjump._core"}),
        (
            "eccjump._base.bridge",
            {
                "eccjump._core",
                "eccjump._base.arrays",
                "eccjump._base.checks",
                "eccjump.classification.fields",
            },
        ),
        ("eccjump.maps.layout", {"eccjump._core", "eccjump.classification.fields"}),
        (
            "eccjump.maps.dask",
            {"eccjump._base.bridge", "eccjump._base.checks", "eccjump.classification.fields"},
        ),
    ],
)
def test_layers(module, below):
    """fields <- _bridge, _layout, scale <- classification <- labelled <- store <- cli."""
    assert GRAPH[module][0] <= below


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
    assert scale.RECORD is fields.RECORD and fields.RECORD.names == names
    assert labelled.DTYPES is fields.DTYPES and labelled.FILL is fields.FILL
    for f in fields.TABLE + fields.DERIVATIVE_TABLE:
        assert labelled.FIELD_ATTRS[f.name] == {"units": f.units, "long_name": f.description}
        assert f.name in (JarmResult.__doc__ or "") and f.description in JarmResult.__doc__
        assert np.array(f.fill).astype(f.dtype).dtype == f.dtype


def test_results_have_the_described_dtypes():
    r = eccjump.jarm([0.5, 0.7], 0.15, 0.02, 1.0, derivatives=True)
    reg = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.15], km_frac=[0.1], derivatives=True)
    for name, dtype in fields.DTYPES.items():
        assert getattr(r, name).dtype == dtype and getattr(reg.result, name).dtype == dtype
    ds = pytest.importorskip("xarray") and reg.to_xarray()
    assert ds.theta_J.attrs["units"] == fields.BY_NAME["theta_J"].units
    assert list(ds.reason.attrs["flag_values"]) == [r.value for r in fields.Reason]
