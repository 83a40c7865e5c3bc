"""The full motion (`eccjump.simulate`, docs/motion.md): every physical statement checked
against an independent route: `roll` and the JARM classification for the first segment, the
independent scipy model (tests/reference_motion.py) for the sequence of modes, the energy
integrated with the slip for the ledger, closed forms for the impact."""

from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from properties import reach_rate
from reference_points import JARM, JARM_THETA_J_DEG, SLIP_FIRST, jump_points

import eccjump
from eccjump import Cylinder
from eccjump.motion import fields as motion_fields
from eccjump.motion import simulation as motion
from eccjump.motion.simulation import MODES, REASONS, STATUSES


def bodies():
    """(body, alpha) over the whole parameter space, k_m > 0."""
    return st.tuples(st.floats(0.0, 0.95), st.floats(0.02, 0.98), st.floats(0.02, math.pi / 2)).map(
        lambda x: (Cylinder(x[0], (1 - x[0]) * x[1]), x[2])
    )


def test_first_segment_from_rest_is_roll_bit_for_bit():
    for body, alpha in (JARM, SLIP_FIRST):
        for rule in ("paper", "normal_force"):
            m = eccjump.simulate(body, alpha, mu_s=1.0, rule=rule, max_transitions=1)
            r = eccjump.roll(body, alpha, mu_s=1.0, rule=rule)
            n = r.t.size
            rolled = m.mode[:n] == 0
            assert rolled.all()
            for k in ("t", "theta", "omega", "Fx", "Fy"):
                assert np.array_equal(getattr(m, k)[:n], getattr(r, k)), k
            assert m.transitions[1].t == r.t[-1]


def test_reference_points():
    m = eccjump.simulate(*JARM, mu_s=1.0, max_transitions=3)
    tr = m.transitions[1]
    assert (tr.from_mode, tr.to_mode, tr.reason) == ("ROLL", "FLIGHT", "liftoff")
    # RK45 at rtol 1e-10 against the closed form.
    assert math.degrees(tr.theta) == pytest.approx(JARM_THETA_J_DEG, abs=1e-7)
    s = eccjump.simulate(*SLIP_FIRST, mu_s=1.0, max_transitions=3)
    assert s.mode_names()[:3] == ["ROLL", "SLIP", "FLIGHT"]
    assert math.degrees(s.transitions[1].theta) == pytest.approx(316.471677233, abs=1e-7)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(jump_points()), st.floats(1e-6, 2.0))
def test_a_jarm_point_flies_straight_from_rolling_at_theta_J(point, above):
    """JARM points fly straight from ROLL, at the closed form's θ_J."""
    alpha, chi, km, _, needed = point
    mu = needed * (1 + above)
    m = eccjump.simulate(Cylinder(chi, km), alpha, mu_s=mu, max_transitions=1, t_max=1e4)
    j = eccjump.jarm(alpha, chi, km, mu)
    assert bool(j.is_jarm)
    start, tr = m.transitions[:2]
    assert (start.to_mode, tr.to_mode, tr.reason) == ("ROLL", "FLIGHT", "liftoff")
    assert tr.theta == pytest.approx(float(j.theta_J), abs=1e-7)


#: Bodies off centre on ramps of 9° to 57°: nearly all start rolling and leave it by a slip
#: (over the whole space a quarter never leave rolling or start sliding).
SLIP_DRAWS = st.tuples(
    st.tuples(st.floats(0.05, 0.95), st.floats(0.02, 0.98), st.floats(0.15, 1.0)).map(
        lambda x: (Cylinder(x[0], (1 - x[0]) * x[1]), x[2])
    ),
    st.sampled_from([0.5, 1.0]),
)


def first_transition(draw) -> eccjump.motion.Transition | None:
    """The transition that ends the first segment, if that segment rolls and ends by a
    slip (or a slip with no consistent sliding)."""
    (body, alpha), mu = draw
    m = eccjump.simulate(body, alpha, mu_s=mu, max_transitions=1, t_max=1e4)
    if len(m.transitions) < 2 or m.transitions[0].to_mode != "ROLL":
        return None
    tr = m.transitions[1]
    return tr if tr.reason in ("slip", "slip_inconsistent") else None


@settings(max_examples=40, deadline=None)
@given(SLIP_DRAWS)
def test_a_point_that_slips_first_slips_at_the_classifications_angle(draw):
    """Points that slip first go to SLIP (or fly where sliding is inconsistent) at the
    classification's event angle."""
    tr = first_transition(draw)
    assume(tr is not None)
    (body, alpha), mu = draw
    j = eccjump.jarm(alpha, body.chi, body.km, mu)
    assert not bool(j.is_jarm)
    # RK45 at rtol 1e-10 against the closed form: a global error that grows with the
    # turns rolled (one draw slips after 104 turns, 1.6e-7 rad off).
    assert tr.theta == pytest.approx(float(j.theta_event), rel=1e-9, abs=1e-7)


def test_the_filtered_property_reaches_its_assertion():
    assert reach_rate(SLIP_DRAWS, lambda d: first_transition(d) is not None) >= 0.9


@settings(max_examples=40, deadline=None)
@given(
    bodies(),
    st.floats(0.1, 1.5),
    st.floats(0.0, 1.0),
    st.sampled_from(["paper", "normal_force"]),
    st.sampled_from(["RK45", "DOP853", "Vern9"]),
)
def test_energy_ledger_closes_and_impacts_never_gain(point, mu, e, rule, integrator):
    body, alpha = point
    m = eccjump.simulate(
        body, alpha, mu_s=mu, restitution=e, rule=rule, t_max=10.0, integrator=integrator
    )
    assert np.abs(m.energy + m.dissipated - m.energy0).max() < 1e-6
    assert all(i.energy_lost >= -1e-12 for i in m.impacts)
    assert m.dissipated_slip >= -1e-12
    # Energy is conserved in rolling (integrated) and in flight (exact).
    for code, tol in ((0, 1e-7), (2, 1e-11)):
        seg = np.flatnonzero(m.mode == code)
        if seg.size:
            # Split where rows stop being consecutive or time repeats (an impact).
            cut = (np.diff(seg) > 1) | (np.diff(m.t[seg]) == 0)
            runs = np.split(seg, np.flatnonzero(cut) + 1)
            for r in runs:
                assert np.ptp(m.energy[r]) < tol * (1 + abs(m.energy0))


def test_liftoff_from_slip_meets_both_rules_together():
    body, alpha = SLIP_FIRST
    m = eccjump.simulate(body, alpha, mu_s=1.0, max_transitions=2)
    tr = m.transitions[2]
    assert (tr.from_mode, tr.to_mode, tr.reason) == ("SLIP", "FLIGHT", "normal_force")
    i = np.flatnonzero(m.t == tr.t)[0]  # the slip's last point
    assert m.mode[i] == 1 and abs(m.Fy[i]) < 1e-10
    lift = body.chi * tr.omega**2 * math.cos(tr.theta) - math.cos(alpha)
    assert abs(lift) < 1e-10
    n = eccjump.simulate(body, alpha, mu_s=1.0, rule="normal_force", max_transitions=2)
    assert n.mode_names() == m.mode_names() and n.transitions[2].t == tr.t


def test_painleve_cases_under_the_normal_force_rule_fly_at_theta_slip():
    body, alpha = JARM
    m = eccjump.simulate(body, alpha, mu_s=1.0, rule="normal_force", max_transitions=1)
    tr = m.transitions[1]
    assert (tr.to_mode, tr.reason) == ("FLIGHT", "slip_inconsistent")
    r = eccjump.roll(body, alpha, mu_s=1.0, rule="normal_force")
    assert r.terminal_event == "slip" and tr.theta == r.theta[-1]
    assert math.degrees(tr.theta) - 334.344 > 1.0  # later than the paper's lift-off


def test_impacts_with_and_without_friction():
    body, alpha = SLIP_FIRST
    # mu = 0, e = 1: no energy lost at any impact.
    m = eccjump.simulate(body, alpha, mu_s=0.0, restitution=1.0, omega0=2.0, t_max=15.0)
    assert m.transitions[0].to_mode == "FLIGHT" and m.impacts
    assert all(abs(i.energy_lost) < 1e-12 for i in m.impacts)
    # e = 0: the contact point does not separate at once (ḃ = 0 after every landing).
    z = eccjump.simulate(body, alpha, mu_s=1.0, t_max=15.0)
    for tr in z.transitions:
        if tr.reason == "impact":
            assert tr.bdot == 0.0


@settings(max_examples=25, deadline=None)
@given(st.floats(0.05, 0.9), st.floats(0.05, 0.9), st.floats(0.0, 3.0), st.floats(0.3, 2.0))
def test_flat_ground_never_jumps_from_rolling_once_rolled(chi, frac, omega0, mu):
    """α = 0 (the paper's proof): no lift-off straight from pure rolling once it rolls; a
    start with χθ̇0² > 1 (θ0 = 0) flies at once."""
    body = Cylinder(chi, (1 - chi) * frac)
    m = eccjump.simulate(body, 0.0, mu_s=mu, omega0=omega0, t_max=20.0)
    if chi * omega0**2 > 1.0:
        assert m.transitions[0].to_mode == "FLIGHT"
        return
    for tr in m.transitions[1:]:
        assert not (tr.from_mode == "ROLL" and tr.to_mode == "FLIGHT" and tr.reason == "liftoff")


def test_si_units_scale_every_quantity():
    m = eccjump.simulate(*SLIP_FIRST, mu_s=1.0, max_transitions=5)
    g, R, M = 9.81, 0.05, 0.2
    s = m.to_si(g=g, R=R, M=M)
    T, V = math.sqrt(R / g), math.sqrt(g * R)
    assert np.allclose(s.t, m.t * T, rtol=1e-15)
    assert np.allclose(s.ldot, m.ldot * V, rtol=1e-15)
    assert np.allclose(s.energy, m.energy * M * g * R, rtol=1e-15)
    assert s.flights[0].apex == pytest.approx(m.flights[0].apex * R, rel=1e-15)
    assert np.array_equal(s.theta, m.theta) and s.units is not None


def test_dense_output_across_segments():
    m = eccjump.simulate(*SLIP_FIRST, mu_s=1.0, max_transitions=6, dense_output=True)
    inner = [i for i in range(1, m.t.size - 1) if m.t[i - 1] < m.t[i] < m.t[i + 1]]
    y = m.sol(m.t[inner])
    for k, name in enumerate(("theta", "omega", "l", "ldot", "b", "bdot")):
        assert np.allclose(y[k], getattr(m, name)[inner], atol=1e-9), name
    with pytest.raises(ValueError, match="t"):
        m.sol(m.t[-1] + 1.0)


@pytest.mark.parametrize(
    "body, alpha, kwargs",
    [  # found by the fuzz test: a flight's last sample rounded past the next segment's start
        (
            Cylinder(0.53, 0.0799),
            1.2267919312268143,
            {"mu_s": 1.146, "restitution": 0.011, "theta0": 7.0, "omega0": -2.628, "slip0": 2},
        ),
        (
            Cylinder(0.23, 0.6776),
            math.pi / 2,
            {"mu_s": 2.0, "mu_k": 1.035, "restitution": 0.641, "theta0": 7.0, "omega0": 3.0},
        ),
    ],
)
def test_times_never_decrease_and_sol_covers_every_point(body, alpha, kwargs):
    m = eccjump.simulate(body, alpha, t_max=9.76, max_transitions=50, dense_output=True, **kwargs)
    assert (np.diff(m.t) >= 0).all()
    y = m.sol(m.t)
    assert np.isfinite(y).all()


@pytest.mark.parametrize("integrator", ["RK45", "DOP853", "Vern9"])
def test_a_nearly_uniform_body_is_recorded_at_least_every_half_radian(integrator):
    # Issue 38: at chi = 1e-9 the error estimate alone let RK45 step over two turns at once
    # and the ledger drifted to 7e-7; each step now turns the body by at most 0.5 rad.
    m = eccjump.simulate(Cylinder(1e-9, 0.5), 0.5, mu_s=1.0, t_max=20.0, integrator=integrator)
    assert m.theta[-1] > 60.0
    assert np.abs(np.diff(m.theta)).max() <= 0.5
    assert np.abs(m.energy + m.dissipated - m.energy0).max() < 1e-8


def test_reproducible_to_the_last_bit():
    a = eccjump.simulate(*SLIP_FIRST, mu_s=0.8, restitution=0.3, max_transitions=20)
    b = eccjump.simulate(*SLIP_FIRST, mu_s=0.8, restitution=0.3, max_transitions=20)
    assert a == b
    assert set(a.mode.tolist()) <= set(range(len(MODES)))
    assert a.status in STATUSES and all(t.reason in REASONS for t in a.transitions)


def test_the_names_and_bounds_are_the_cores():
    core = eccjump._core
    assert [MODES, REASONS, STATUSES] == [
        tuple(name for _, name in codes())
        for codes in (core.mode_codes, core.transition_reason_codes, core.status_codes)
    ]
    assert (motion.MAX_TRANSITIONS, motion.MAX_STEPS) == (10**6, 10**7)
    assert motion_fields.SEQUENCE_LEN == 8
    assert motion_fields.INVALID == core.INVALID == 255


@given(st.lists(st.sampled_from(MODES), max_size=12))
def test_a_sequence_code_is_the_cores_and_reads_back(modes):
    # The code is the core's own (a map stores it), read back by sequence_name.
    code = motion_fields.sequence_code(modes)
    assert code == eccjump._core.sequence_code([MODES.index(m) for m in modes])
    assert motion_fields.sequence_name(code) == "→".join(modes[: motion_fields.SEQUENCE_LEN])


def test_a_core_that_packs_sequences_otherwise_is_refused_at_import(monkeypatch):
    # Three bits per mode instead of two: every sequence_name would be wrong.
    monkeypatch.setattr(
        eccjump._core,
        "sequence_code",
        lambda codes: sum((c + 1) << (3 * i) for i, c in enumerate(codes)),
    )
    spec = importlib.util.spec_from_file_location("fields_again", motion_fields.__file__)
    assert spec is not None and spec.loader is not None
    with pytest.raises(ImportError, match="cannot read the core's codes"):
        spec.loader.exec_module(importlib.util.module_from_spec(spec))


@pytest.mark.parametrize("table", ["mode_codes", "transition_reason_codes", "status_codes"])
def test_a_core_whose_names_moved_is_refused_at_import(monkeypatch, table):
    names = [name for _, name in getattr(eccjump._core, table)()]
    monkeypatch.setattr(eccjump._core, table, lambda: list(enumerate(names[::-1])))
    spec = importlib.util.spec_from_file_location("motion_again", motion.__file__)
    assert spec is not None and spec.loader is not None
    with pytest.raises(ImportError, match="differ from the core's: rebuild eccjump"):
        spec.loader.exec_module(importlib.util.module_from_spec(spec))


@pytest.mark.parametrize(
    "kwargs, param",
    [
        ({"mu_s": 0.5, "mu_k": 0.6}, "mu_k"),
        ({"mu_s": -1.0}, "mu_s"),
        ({"mu_s": 1.0, "restitution": 1.5}, "restitution"),
        ({"mu_s": 1.0, "t_max": 0.0}, "t_max"),
        ({"mu_s": 1.0, "l_max": -1.0}, "l_max"),
        ({"mu_s": 1.0, "max_transitions": 0}, "max_transitions"),
        ({"mu_s": 1.0, "rule": "x"}, "rule"),
        ({"mu_s": math.nan}, "mu_s"),
    ],
)
def test_bad_input_is_a_value_error_naming_the_parameter(kwargs, param):
    with pytest.raises(ValueError, match=param) as err:
        eccjump.simulate(*SLIP_FIRST, **kwargs)
    assert len(str(err.value)) <= 200


@pytest.mark.parametrize(
    "kwargs, error, param",
    [
        ({"t_max": "1"}, TypeError, "t_max"),
        ({"rule": None}, TypeError, "rule"),
        ({"max_transitions": 2.0}, TypeError, "max_transitions"),
        ({"max_steps": 0}, ValueError, "max_steps"),
        ({"max_transitions": 10**6 + 1}, ValueError, "max_transitions"),
        ({"integrator": 45}, TypeError, "integrator"),
        ({"rtol": 1e-3}, ValueError, "rtol"),  # the core's range, by to_core
        ({"t_max": -1.0}, ValueError, "t_max"),
        ({"integrator": "RK4"}, ValueError, "integrator"),
    ],
)
def test_motion_options_name_the_keyword_of_a_bad_option(kwargs, error, param):
    from eccjump.motion import MotionOptions

    with pytest.raises(error, match=param) as err:
        MotionOptions(**kwargs).to_core(0)
    assert len(str(err.value)) <= 200
    with pytest.raises(ValueError, match="n_threads"):
        MotionOptions().to_core(257)


def test_motion_options_carry_plain_values_and_the_defaults_of_every_entry_point():
    # One list of the run's options: every entry point of the full motion takes its keywords
    # with its defaults (uncertainty all but max_steps, the explorer rule and its own t_max),
    # and a map records them.
    import inspect

    from eccjump.motion import MotionOptions

    o = MotionOptions(t_max=np.float64(20.0), max_steps=np.int64(50_000))
    assert type(o.t_max) is float and type(o.max_steps) is int and o.max_steps == 50_000
    default = MotionOptions().keywords()
    for f in (eccjump.simulate, eccjump.motion_map, eccjump.motion_points, eccjump.uncertainty):
        ps = inspect.signature(f).parameters
        given = {k: ps[k].default for k in default if k in ps}
        assert given == {k: default[k] for k in given}, f.__name__
        assert set(default) - set(given) <= {"max_steps"}, f.__name__
    m = eccjump.motion_map(0.7, 0.15, 0.1, 1.0, t_max=5.0, integrator="Vern9")
    assert m.options == MotionOptions(t_max=5.0, integrator="Vern9").keywords()


def test_a_body_without_inertia_about_its_centre_of_mass_is_refused():
    with pytest.raises(ValueError, match="km") as err:
        eccjump.simulate(Cylinder(0.5, 0.0), 0.5, mu_s=1.0)
    assert len(str(err.value)) <= 200


@pytest.mark.parametrize(
    "name", ["jarm_paper", "slipjump_e05", "slip_at_start_mu01", "slip0_backspin", "flies_at_once"]
)
@pytest.mark.parametrize("integrator", ["RK45", "DOP853", "Vern9"])
def test_same_sequence_and_angles_as_the_independent_scipy_model(name, integrator):
    from reference_motion import simulate_reference
    from scipy_motion_cases import CASES

    kw = {**dict(CASES)[name], "max_transitions": 5}
    ref = simulate_reference(**kw)
    body = Cylinder(kw.pop("chi"), kw.pop("km"))
    m = eccjump.simulate(body, kw.pop("alpha"), integrator=integrator, **kw)
    assert [(t.to_mode, t.reason) for t in m.transitions] == [
        (t[2], t[3]) for t in ref["transitions"]
    ]
    for ours, theirs in zip(m.transitions, ref["transitions"], strict=True):
        assert ours.theta == pytest.approx(theirs[4], abs=1e-7)
        assert ours.t == pytest.approx(theirs[0], abs=1e-7)


def test_a_settle_never_creates_energy():
    """Found by hypothesis: a micro-bounce (u_n = 1.7e-6) landing while sliding fast. The Zeno
    rule used to set the centre's normal velocity to 0, which created 8e-8 of energy; its
    plastic impulse at the contact point dissipates u_n^2/(2 W_nn) instead."""
    m = eccjump.simulate(Cylinder(0.375, 0.3125), 0.5625, mu_s=1.0, restitution=0.5, t_max=10.0)
    assert any(t.reason == "settle" for t in m.transitions)
    assert min(i.energy_lost for i in m.impacts) >= 0.0
    assert np.abs(m.energy + m.dissipated - m.energy0).max() < 1e-7


@pytest.mark.parametrize("integrator", ["RK45", "DOP853", "Vern9"])
def test_a_settle_that_ends_stuck_never_creates_energy(integrator):
    """Found by hypothesis: a micro-bounce (u_n = 1.7e-6) whose impact ends stuck. A normal-only
    settle impulse made it slip again and setting l' = theta' afterwards (an impulse at the
    centre) created 6.3e-7 of energy; the settle is now -W^-1 (0, u_n), which keeps it stuck
    and dissipates."""
    m = eccjump.simulate(
        Cylinder(0.5, 0.25), 0.5625, mu_s=1.0, restitution=0.5, t_max=10.0, integrator=integrator
    )
    stuck = [i for i in m.impacts if i.sticking and i.normal_speed < 1e-5]
    assert stuck, "the case no longer has a stuck micro-impact"
    assert min(i.energy_lost for i in m.impacts) >= 0.0
    assert np.abs(m.energy + m.dissipated - m.energy0).max() < 1e-7


def test_fast_result_construction_equals_the_dataclass_init():
    # simulate makes its MotionResult without the dataclass __init__ (_arrays.frozen_result):
    # the same object as the ordinary way, every field and record filled.
    import dataclasses

    from eccjump.motion.simulation import (
        FlightRecord,
        ImpactRecord,
        MotionResult,
        Segment,
        Transition,
    )

    r = eccjump.simulate(*SLIP_FIRST, mu_s=1.0, max_transitions=6, dense_output=True)

    assert r.flights and r.impacts
    names = [f.name for f in dataclasses.fields(MotionResult)]
    assert set(vars(r)) == set(names)  # every field (in the order the bridge gives them)
    again = MotionResult(**{n: getattr(r, n) for n in names})
    assert repr(again) == repr(r)
    for n in names:
        a, b = getattr(again, n), getattr(r, n)
        assert a.tobytes() == b.tobytes() if isinstance(a, np.ndarray) else a is b, n
    kinds = [
        (r.transitions, Transition),
        (r.flights, FlightRecord),
        (r.impacts, ImpactRecord),
        (r.segments, Segment),
    ]
    for recs, cls in kinds:
        for rec in recs:
            assert type(rec) is cls and rec == cls(*rec) and rec._fields == cls._fields
    assert r.transitions[0].from_mode is None and r.transitions[1].from_mode == "ROLL"
    assert type(r.mode) is np.ndarray and r.mode.dtype == np.int8
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.status = "t_max"  # type: ignore[misc]


def test_the_bridge_takes_simulates_options_by_their_names():
    # The bridge's convention: the body and the ramp positionally, every option keyword-only
    # under simulate's own name for it (so no two floats can be swapped on the way).
    import inspect

    from eccjump import _core

    def options(f):
        ps = inspect.signature(f).parameters.values()
        return sorted(p.name for p in ps if p.kind is p.KEYWORD_ONLY)

    assert options(_core.simulate) == options(eccjump.simulate)
    positional = inspect.signature(_core.simulate).parameters.values()
    assert [p.name for p in positional if p.kind != p.KEYWORD_ONLY] == ["chi", "km", "alpha"]


@pytest.mark.parametrize("sensitivities", [False, True])
def test_the_bridge_gives_the_run_by_the_names_of_its_result(sensitivities):
    # One output convention (as the maps): the run by MotionResult's field names, each kind
    # of record one list per field of its named tuple, so that the field order is written in
    # the classes only.
    import dataclasses

    from eccjump import _core
    from eccjump.motion import (
        FlightRecord,
        ImpactRecord,
        MotionOptions,
        MotionResult,
        Segment,
        Transition,
    )

    body, alpha = Cylinder(0.5, 0.4), math.radians(30)
    raw = _core.simulate(
        body.chi, body.km, alpha, mu_s=1.0, mu_k=1.0, restitution=0.0, theta0=0.0,
        omega0=0.0, slip0=0.0, l_max=math.inf, **MotionOptions(t_max=9.0).keywords(),
        dense_output=False, sensitivities=sensitivities,
    )  # fmt: skip
    added = {"body", "alpha", "mu_s", "mu_k", "restitution", "rule", "units"}  # simulate's
    assert set(raw) == {f.name for f in dataclasses.fields(MotionResult)} - added
    kinds = {
        "transitions": Transition,
        "flights": FlightRecord,
        "impacts": ImpactRecord,
        "segments": Segment,
    }
    r = eccjump.simulate(body, alpha, mu_s=1.0, t_max=9.0, sensitivities=sensitivities)
    for name, cls in kinds.items():
        assert set(raw[name]) == set(cls._fields), name
        rows = tuple(map(cls._make, zip(*(raw[name][f] for f in cls._fields), strict=True)))
        assert repr(getattr(r, name)) == repr(rows) and rows, name  # NaN: by repr
    assert (raw["d_transitions"] is None) is not sensitivities
