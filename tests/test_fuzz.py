"""Fuzzing of every public entry point and of the command line (the generators and the
contract are in ``fuzz_cases.py``; ``benches/fuzz_campaign.py`` runs the long campaign).

Each call returns a result that passes its contract or raises ValueError/TypeError/
MemoryError naming a parameter in at most 200 characters. Budgets are small (the file runs in
well under a minute; hypothesis is derandomized, see conftest.py). Work parameters past
their bounds are drawn too; the reproducers found before the core bounded them are
``CORE_REGRESSIONS``.
"""

from __future__ import annotations

import re
import subprocess
import sys
import warnings

import pytest
from fuzz_cases import (
    CORE_REGRESSIONS,
    MAX_MESSAGE,
    HypothesisDrawer,
    Outcome,
    alarm,
    case_cli,
    check_cli,
    make_case,
    outcome,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference_points import JARM_BODY

import eccjump

#: Examples per entry point family (about 30 s in all on a 2-core machine).
BUDGET = {
    "jarm": 200,
    "region": 80,
    "region_dataset": 15,
    "roll": 150,
    "simulate": 150,
    "motion_map": 100,
    "motion_points": 100,
    "motion_options": 60,
    "uncertainty": 60,
    "uncertainty_map": 40,
    "to_si": 60,
    "sol": 60,
    "kinematics": 60,
    "alpha_intervals": 60,
    "mu_s_min_path": 60,
    "alpha_interval_around": 60,
    "closed_form": 200,
    "cylinder": 100,
    "units": 60,
    "store": 30,
    "results": 30,
    "plot": 16,
    "cli": 60,
    "jarm_fraction": 60,
    "start_map": 30,
    "optimal_start": 25,
    "design": 12,
    "build": 60,
    "analyze": 30,
    "track": 30,
    "explore": 80,
    "explore_api": 60,
    "explore_http": 60,
}


def _judge(family: str, data: st.DataObject) -> None:
    case = make_case(family, HypothesisDrawer(data))
    with warnings.catch_warnings(), alarm(120):  # a hang fails the test instead
        warnings.simplefilter("ignore")  # overflow in casts of drawn values, matplotlib
        result: Outcome = outcome(case)
    assert not result.violation, f"{result.kind}: {result.detail}\n  {case.describe()}"


@pytest.mark.parametrize("family", sorted(BUDGET))
def test_entry_point_keeps_its_contract(family):
    if family == "plot":
        pytest.importorskip("matplotlib")
        import matplotlib

        matplotlib.use("Agg")
    if family == "region_dataset":
        pytest.importorskip("xarray")
    if family == "explore":
        pytest.importorskip("anywidget", reason="eccjump.explore needs anywidget")

    @settings(
        max_examples=BUDGET[family],
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(st.data())
    def run(data):
        _judge(family, data)

    run()


@settings(max_examples=6, deadline=None)
@given(st.data())
def test_cli_subprocess_keeps_its_contract(data):
    """A few generated command lines through ``python -m eccjump.cli`` itself."""
    case = case_cli(HypothesisDrawer(data))
    argv = case.info["argv"]
    proc = subprocess.run(
        [sys.executable, "-m", "eccjump.cli", *argv],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    check_cli((proc.returncode, proc.stdout, proc.stderr), case)


@pytest.mark.parametrize("gap", list(CORE_REGRESSIONS.values()), ids=list(CORE_REGRESSIONS))
def test_core_regression(gap):
    """Each reproducer raises ValueError naming its parameter, in a short message (each used
    to hang, answer where an error was due, or print a 300-digit number)."""
    code = (
        "import eccjump\nfrom eccjump import *\n"
        f"try:\n    {gap.code}\nexcept ValueError as e:\n    print('ValueError:', e)\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=20, check=False
    )
    line = proc.stdout.strip()
    assert line.startswith("ValueError:"), f"no ValueError: {line[:200]} {proc.stderr[-200:]}"
    message = line.removeprefix("ValueError: ")
    assert gap.param in message and len(message) <= MAX_MESSAGE, message[:250]


def test_results_compare_after_a_deep_copy():
    import copy

    r = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0, dense_output=True)

    j = eccjump.jarm([0.5, 0.6, float("nan")], 0.2, 0.1, 1.0)
    g = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.2], km_frac=[0.1])
    for x in (r, j, g):
        assert x == copy.deepcopy(x) and not (x != copy.deepcopy(x))
        with pytest.raises(TypeError):
            hash(x)
    assert r.to_si() == r.to_si() and r != r.to_si()
    assert j != eccjump.jarm([0.5, 0.7, float("nan")], 0.2, 0.1, 1.0)


def test_every_public_function_is_fuzzed():
    """A public function joins the fuzz test the day it is added: each callable of
    ``eccjump.__all__`` (not a class) has a family in BUDGET or is called by a case."""
    import inspect
    from pathlib import Path

    source = (Path(__file__).parent / "fuzz_cases.py").read_text()
    public = [
        name
        for name in eccjump.__all__
        if inspect.isfunction(getattr(eccjump, name)) and not name.startswith("_")
    ]
    called = {n for n in public if re.search(rf'"{n}"|eccjump\.{n}\b', source)}
    missing = [n for n in public if n not in BUDGET and n not in called]
    assert public and not missing, f"not fuzzed: {missing}"
