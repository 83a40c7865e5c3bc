"""Motion maps (eccjump.motion_map): every point is what simulate gives there, the JARM points
are the region's, the map is reproducible for any thread count and chunking."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import eccjump
from eccjump.motion.maps import (
    FIELDS,
    INVALID,
    LANDINGS,
    STATUS_NAMES,
    motion_map,
    sequence_code,
    sequence_name,
)
from eccjump.testing import assert_maps_equal

ALPHA = np.radians([5.0, 25.0, 40.0, 60.0, 85.0])
CHI = np.array([0.15, 0.4, 0.7])
FRAC = np.array([0.05, 0.5, 0.9])


#: The reasons of a ROLL→FLIGHT that is the lift-off rule firing (docs/motion.md).
JARM_REASONS = {"paper": ("liftoff",), "normal_force": ("normal_force", "slip_inconsistent")}


def summary_from_simulate(point: dict, t_max: float, max_transitions: int) -> dict:
    """The summary of one point, extracted from a full simulate run independently of the
    core's extraction (the run goes on after the landing; only its head is read)."""
    chi, frac = point["chi"], point["km_frac"]
    body = eccjump.Cylinder(chi, frac * (1 - chi))
    m = eccjump.simulate(
        body,
        point["alpha"],
        mu_s=point["mu_s"],
        mu_k=point.get("mu_k"),
        restitution=point.get("restitution", 0.0),
        theta0=point.get("theta0", 0.0),
        omega0=point.get("omega0", 0.0),
        rule=point.get("rule", "paper"),
        t_max=t_max,
        max_transitions=max_transitions,
        integrator=point.get("integrator", "RK45"),
    )
    tr = list(m.transitions)
    status = m.status
    fl = next((k for k, t in enumerate(tr) if t.to_mode == "FLIGHT"), None)
    landing = "none"
    lost = float(m.dissipated[-1])
    if m.impacts and fl is not None:
        if len(tr) > fl + 1:
            tr = tr[: fl + 2]
            landing = {"ROLL": "sticks", "SLIP": "slides", "FLIGHT": "bounces"}[tr[-1].to_mode]
            status = "landed"
        else:
            landing = "ends"
        t_land = m.impacts[0].t
        # Nothing dissipates in flight: the ledger just before the landing, plus the impact.
        before = m.dissipated[m.t < t_land][-1]
        lost = float(before) + m.impacts[0].energy_lost
    head = tr[: fl if fl is not None else len(tr)]
    slip = next((t for t in head if t.to_mode == "SLIP"), None)
    f = m.flights[0] if m.flights else None
    nan = math.nan
    return {
        "status": status,
        "sequence": sequence_code([t.to_mode for t in tr]),
        "jarm": len(tr) > 1
        and tr[0].to_mode == "ROLL"
        and tr[1].to_mode == "FLIGHT"
        and tr[1].reason in JARM_REASONS[point.get("rule", "paper")],
        "slipped_first": slip is not None,
        "slip_theta": slip.theta if slip else nan,
        "liftoff_theta": tr[fl].theta if fl is not None else nan,
        "liftoff_t": tr[fl].t if fl is not None else nan,
        "apex": f.apex if f else nan,
        "distance": f.distance if f else nan,
        "landing": landing,
        "energy_lost": lost,
    }


@pytest.mark.parametrize(
    ("modes", "error", "says"),
    [
        (["roll"], ValueError, "'roll' is not a mode; use ROLL, SLIP, FLIGHT"),
        (["ROLL", None], ValueError, "None is not a mode"),
        ("ROLL", TypeError, "modes must be a list or tuple"),
    ],
)
def test_sequence_code_names_a_bad_mode(modes, error, says):
    # ['roll'] was "tuple.index(x): x not in tuple".
    with pytest.raises(error, match=re.escape(says)):
        sequence_code(modes)


def test_sequence_codes_round_trip():
    for modes in (["ROLL"], ["ROLL", "FLIGHT"], ["SLIP", "FLIGHT", "FLIGHT", "ROLL"]):
        assert sequence_name(sequence_code(modes)) == "→".join(modes)
    assert sequence_code(["ROLL", "FLIGHT"]) == 13
    assert sequence_name(0) == ""


@settings(max_examples=25, deadline=None)
@given(
    st.floats(0.05, 1.5),
    st.floats(0.05, 0.95),
    st.floats(0.05, 0.95),
    st.sampled_from([0.3, 0.7, 1.0]),
    st.sampled_from([0.0, 0.5]),
    st.sampled_from([0.0, -0.5, 1.0]),
    st.sampled_from(["paper", "normal_force"]),
    st.sampled_from(["RK45", "DOP853", "Vern9"]),
)
def test_every_point_is_what_simulate_gives_there(alpha, chi, frac, mu, e, omega0, rule, pair):
    point = {
        "rule": rule,
        "integrator": pair,
        "alpha": alpha,
        "chi": chi,
        "km_frac": frac,
        "mu_s": mu,
        "restitution": e,
        "omega0": omega0,
    }
    m = motion_map(**point, t_max=30.0, max_transitions=20)
    got = {k: m.fields[k][()] for k in FIELDS}
    want = summary_from_simulate(point, 30.0, 20)
    assert STATUS_NAMES[int(got["status"])] == want["status"]
    assert sequence_name(got["sequence"]) == sequence_name(want["sequence"])
    assert bool(got["jarm"]) == want["jarm"]
    assert bool(got["slipped_first"]) == want["slipped_first"]
    assert LANDINGS[int(got["landing"])] == want["landing"]
    for k in ("slip_theta", "liftoff_theta", "liftoff_t", "apex", "distance"):
        assert np.array_equal(got[k], want[k], equal_nan=True), k
    assert got["energy_lost"] == pytest.approx(want["energy_lost"], rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("rule", ["paper", "normal_force"])
def test_jarm_points_are_the_regions(rule):
    # A grid across the thin JARM region of the paper's Fig. 4 (33 JARM points of 216).
    grid = {
        "alpha": np.radians(np.linspace(20, 60, 9)),
        "chi": np.linspace(0.05, 0.3, 6),
        "km_frac": np.array([0.01, 0.03, 0.1, 0.3]),
    }
    m = motion_map(**grid, mu_s=1.0, rule=rule, t_max=1e3)
    r = eccjump.region(mu_s=1.0, **grid, rule=rule, method="ode")
    assert m.jarm.any()
    assert np.array_equal(m.jarm, r.result.is_jarm)
    # A JARM lifts off at the region's jump angle (same kernel: the same bits).
    assert np.array_equal(m.liftoff_theta[m.jarm], r.result.theta_J[m.jarm])


def test_the_start_is_a_grid_axis_too():
    m = motion_map(
        alpha=0.7, chi=0.15, km_frac=0.02 / 0.85, mu_s=1.0, theta0=[0.0, 0.3], omega0=[0.0, 0.5]
    )
    assert m.shape == (2, 2) and tuple(m.coords) == ("theta0", "omega0")
    for i, t0 in enumerate((0.0, 0.3)):
        r = eccjump.region(
            mu_s=1.0,
            alpha=[0.7],
            chi=[0.15],
            km_frac=[0.02 / 0.85],
            theta0=t0,
            omega0=0.0,
            method="ode",
        )
        assert bool(m.jarm[i, 0]) == bool(r.result.is_jarm.item())


def test_bit_identical_for_any_thread_count_and_chunks():
    kw = {"alpha": ALPHA, "chi": CHI, "km_frac": FRAC, "mu_s": 0.7, "restitution": [0.0, 0.6]}
    one = motion_map(**kw, n_threads=1)
    assert_maps_equal(motion_map(**kw, n_threads=2), one)
    pytest.importorskip("dask")
    lazy = motion_map(**kw, chunks=2)
    for k in FIELDS:
        assert np.array_equal(lazy[k].values, one.fields[k], equal_nan=True), k


def test_invalid_points_are_marked_and_bad_options_refused():
    m = motion_map(alpha=0.5, chi=0.5, km_frac=[0.0, 0.5], mu_s=0.5, mu_k=[0.4, 0.6])
    assert m.status[0, 0] == INVALID  # km = 0: spin in flight undetermined
    assert m.status[1, 0] == 6 and m.status[1, 1] == INVALID  # mu_k > mu_s
    for kwargs, name in (
        ({"t_max": -1.0}, "t_max"),
        ({"rule": "x"}, "rule"),
        ({"max_transitions": 0}, "max_transitions"),
        ({"rtol": math.nan}, "rtol"),
        ({"integrator": "rk45"}, "integrator"),
        ({"n_threads": 10**6}, "n_threads"),
        ({"alpha": [[0.5]]}, "alpha"),
        ({"chi": []}, "chi"),
    ):
        args = {"alpha": 0.5, "chi": 0.5, "km_frac": 0.5, "mu_s": 0.5, **kwargs}
        with pytest.raises(ValueError, match=name) as err:
            motion_map(**args)
        assert len(str(err.value)) < 200


def test_the_integrator_reaches_the_core_and_is_recorded():
    kw = {"alpha": ALPHA, "chi": CHI, "km_frac": FRAC, "mu_s": 0.7, "restitution": 0.3}
    rk = motion_map(**kw)
    assert motion_map(**kw, integrator="RK45").fields["liftoff_theta"].tobytes() == (
        rk.fields["liftoff_theta"].tobytes()
    )
    dop = motion_map(**kw, integrator="DOP853")
    assert rk.options["integrator"] == "RK45" and dop.options["integrator"] == "DOP853"
    assert "integrator" in eccjump.motion.maps.OPTIONS
    assert rk.fields["liftoff_theta"].tobytes() != dop.fields["liftoff_theta"].tobytes()
    ran = dop.status != INVALID
    assert np.allclose(
        rk.liftoff_theta[ran], dop.liftoff_theta[ran], rtol=1e-7, atol=1e-9, equal_nan=True
    )
    assert dop.attrs()["integrator"] == "DOP853"
    pytest.importorskip("xarray")
    ds = motion_map(**kw, integrator="DOP853", output="xarray")
    assert ds.attrs["integrator"] == "DOP853"
    assert eccjump.motion.maps.from_dataset(ds).options["integrator"] == "DOP853"


def test_labelled_output_names_every_code():
    pytest.importorskip("xarray")
    ds = motion_map(alpha=ALPHA, chi=CHI, km_frac=0.5, mu_s=1.0, output="xarray")
    assert ds.sizes == {"alpha": ALPHA.size, "chi": CHI.size}
    back = eccjump.motion.maps.from_dataset(ds)
    for k in FIELDS:
        assert np.array_equal(back.fields[k], ds[k].values, equal_nan=True)
    codes = set(np.unique(ds["sequence"].values).tolist())
    assert codes == set(ds["sequence"].attrs["flag_values"].tolist())
    assert ds.attrs["mu_k"] == "mu_s" and ds.attrs["mu_s"] == 1.0 and ds.attrs["rule"] == "paper"
    assert repr(motion_map(alpha=ALPHA, chi=0.5, km_frac=0.5, mu_s=1.0)).startswith("MotionMap(")


def test_km_is_the_body_and_a_maps_axis_is_km_frac(tmp_path):
    # Before 0.2 a map's km meant the fraction k_m/(1 - chi) (a trap: region(km=[0.02])
    # mapped the body k_m = 0.017 at chi = 0.15); now it is refused, naming km_frac.
    for call in (
        lambda: eccjump.motion_map(alpha=[0.5], chi=[0.2], km=0.4, mu_s=1.0),
        lambda: eccjump.region(mu_s=1.0, alpha=[0.698], chi=[0.15], km=[0.02]),
        lambda: eccjump.region_dataset(mu_s=1.0, alpha=[0.698], chi=[0.15], km=[0.02]),
    ):
        with pytest.raises(TypeError, match="km_frac"):
            call()
    reg = eccjump.region(mu_s=1.0, alpha=[0.698], chi=[0.15], km_frac=[0.02 / 0.85])
    one = eccjump.jarm(0.698, 0.15, 0.02, 1.0)
    assert float(reg.result.theta_J.ravel()[0]) == pytest.approx(float(one.theta_J), abs=1e-13)


def test_a_motion_map_file_from_before_0_2_reads_its_scalar_fraction(tmp_path):
    # Files written before 0.2 record a scalar fraction axis as the attribute "km".
    m = eccjump.motion_map(alpha=[0.5, 0.6], chi=[0.2, 0.3], km_frac=0.4, mu_s=1.0)
    path = tmp_path / "old.npz"
    eccjump.store.save(m, path)
    arrays = dict(np.load(path))
    meta = json.loads(str(arrays["__layout__"]))
    meta["attrs"]["km"] = meta["attrs"].pop("km_frac")
    arrays["__layout__"] = np.array(json.dumps(meta))
    np.savez(path, **arrays)
    old = eccjump.motion.maps.load(path)
    assert old.scalars["km_frac"] == 0.4
    assert np.array_equal(old.sequence, m.sequence)
