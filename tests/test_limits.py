"""Regression tests of the hardening issue, core side: every work parameter bounded, output
too large for memory a MemoryError (never an abort or a panic), invalid input an error or an
INVALID/NaN marker (never a plausible number), Ctrl-C honoured within about a second."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
from reference_points import JARM_ARGS, JARM_BODY, SLIP_FIRST_BODY

import eccjump
from eccjump import Cylinder, Reason
from eccjump.classification import closed_form as cf

B = Cylinder(*JARM_BODY)
TAU = 2 * math.pi


def short_error(exc_type, fn, *args, name: str, **kwargs) -> str:
    with pytest.raises(exc_type) as info:
        fn(*args, **kwargs)
    msg = str(info.value)
    assert name in msg and len(msg) <= 200, msg
    return msg


# --- the interpreter never dies ----------------------------------------------------------


def test_output_too_large_is_a_memory_error():
    # 10^10 points (about 1 TB of results) from 88 KB of input: refused before allocating.
    short_error(
        MemoryError,
        eccjump.region,
        mu_s=1.0,
        alpha=np.full(10000, 0.5),
        chi=np.full(1000, 0.5),
        km_frac=np.full(1000, 0.5),
        name="result",
    )


def test_grid_size_overflow_is_a_memory_error_not_a_panic():
    # 2^64 points: the size overflows 64 bits (was PanicException: capacity overflow;
    # 2^22 x 2^21 x 2^21 wrapped to 0 in release builds). Refused by the size check, which
    # counts in Python integers, before the core is asked.
    a, c = np.full(2**22, 0.5), np.full(2**21, 0.5)
    short_error(MemoryError, eccjump.region, mu_s=1.0, alpha=a, chi=c, km_frac=c, name="the result")
    a = np.full(2**20, 0.5)
    short_error(MemoryError, eccjump.region, mu_s=1.0, alpha=a, chi=a, km_frac=a, name="alpha, chi")


# --- the size check counts every field, before any work (issue 46, item 3) ----------------


@pytest.fixture
def small_machine(monkeypatch):
    """A machine with 1 GiB of memory available."""
    from eccjump._base import sizes as _sizes

    monkeypatch.setattr(_sizes, "memory_limit", lambda: 2**30)


def _refuse_work(monkeypatch, module, name, *, above: int = 0):
    """Make ``module.name`` fail if it is called on more than ``above`` points: the check
    must come before the work."""
    real = getattr(module, name)

    def guarded(*args, **kwargs):
        sizes = [np.size(a) for a in args if isinstance(a, np.ndarray)]
        if max(sizes, default=0) > above:  # above=-1: any call
            raise AssertionError(f"{name} was called: the work began")
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, guarded)


def test_the_size_check_counts_the_derivative_fields(small_machine, monkeypatch):
    # region(400^3, derivatives=True) computed for 86 s, then numpy's MemoryError named one
    # 488 MiB array. 200^3 points: 0.56 GB of fields fit in 1 GiB, 1.7 GB with derivatives.
    from eccjump.classification import classify as classification

    _refuse_work(monkeypatch, classification, "jarm_grid")
    a = np.linspace(0.1, 1.5, 200)
    with pytest.raises(AssertionError, match="the work began"):  # the fields alone fit
        eccjump.region(a, a / 2, a / 2, 1.0)
    msg = short_error(MemoryError, eccjump.region, a, a / 2, a / 2, 1.0, derivatives=True,
                      name="derivatives=False")  # fmt: skip
    assert "GiB" in msg and "8,000,000 points" in msg and "alpha, chi or km_frac" in msg
    # priced from the field tables by the caller (sizes knows no field): 70 bytes of fields,
    # 97 of derivative fields and 48 of the derivative pass's columns
    assert "(215 bytes each)" in msg


def test_jarm_points_with_derivatives_are_checked_too(small_machine, monkeypatch):
    from eccjump.classification import classify as classification

    _refuse_work(monkeypatch, classification, "jarm_points")
    a = np.full(5_000_000, 0.5)  # 0.5 GB of inputs and fields; 1.2 GB with derivatives
    with pytest.raises(AssertionError, match="the work began"):
        eccjump.jarm(a, *JARM_BODY, 1.0)
    short_error(MemoryError, eccjump.jarm, a, *JARM_BODY, 1.0, derivatives=True, name="inputs")


def test_motion_maps_and_points_are_checked_before_the_work(small_machine, monkeypatch):
    from eccjump import _core

    _refuse_work(monkeypatch, _core, "motion_grid", above=1)
    _refuse_work(monkeypatch, _core, "motion_points", above=1)
    a = np.linspace(0.1, 1.5, 400)  # 400^3 points of 73 bytes: 4.7 GB
    msg = short_error(MemoryError, eccjump.motion_map, a, a / 2, a / 2, 1.0, name="the axes")
    assert "(73 bytes each)" in msg  # MOTION.bytes_per_point()
    b = np.full(10_000_000, 0.5)  # 10^7 points, 1.4 GB with their inputs
    msg = short_error(MemoryError, eccjump.motion_points, b, *JARM_BODY, 1.0, name="the inputs")
    assert "(129 bytes each)" in msg  # and 7 input columns of float64


def test_uncertainty_counts_its_samples_before_drawing_them(small_machine, monkeypatch):
    # n = 10^8 was allowed and failed after 15 s naming one array.
    from eccjump.studies.uncertainty import study

    _refuse_work(monkeypatch, study, "draw", above=-1)
    body = Cylinder(*JARM_BODY)
    msg = short_error(MemoryError, eccjump.uncertainty, body, 0.7, 1.0, sd={"chi": 0.01},
                      n=10**8, name="shrink n")  # fmt: skip
    assert "100,000,000 samples" in msg


@pytest.mark.slow
def test_memory_error_under_an_address_space_limit():
    # 10^8 points (8.8 GB of results) under a 6 GiB limit: MemoryError, the process lives on.
    code = textwrap.dedent(
        """
        import resource, numpy as np, eccjump
        resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))
        try:
            eccjump.region(mu_s=1.0, alpha=np.full(1000, .5), chi=np.full(1000, .5),
                           km_frac=np.full(100, .5))
        except MemoryError as e:
            print("MemoryError", e)
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.startswith("MemoryError"), out.stdout


def test_dense_output_too_large_is_a_memory_error():
    # A dense output evaluated at more times than its result fits in: MemoryError naming
    # what did not fit, the process lives on (roll's states and kinematics were collected
    # infallibly: an abort). The 2e7 times fit (160 MB, never touched); the address-space
    # limit leaves 64 MiB above them, less than the (2 or 6) x 160 MB of the result.
    code = textwrap.dedent(
        """
        import math, resource, numpy as np, eccjump
        b = eccjump.Cylinder(0.5, 0.4)
        rolled = eccjump.roll(b, math.radians(30), dense_output=True)
        moved = eccjump.simulate(b, math.radians(30), mu_s=1.0, t_max=9.0, dense_output=True)
        calls = {"roll": rolled.sol, "kinematics": rolled.sol.kinematics, "simulate": moved.sol}
        t = np.zeros(20_000_000)
        for f in calls.values():
            f(t[:3])
        used = int(open("/proc/self/statm").read().split()[0]) * resource.getpagesize()
        resource.setrlimit(resource.RLIMIT_AS, (used + (64 << 20), used + (64 << 20)))
        for name, f in calls.items():
            try:
                f(t)
                print(name, "returned")
            except MemoryError as e:
                print(name, "MemoryError", e)
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr[-2000:]
    lines = out.stdout.splitlines()
    assert [line.split()[:2] for line in lines] == [
        [name, "MemoryError"] for name in ("roll", "kinematics", "simulate")
    ], out.stdout
    assert all("the dense" in line and len(line) <= 200 for line in lines), out.stdout


# --- every call ends ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: eccjump.jarm(0.7, *JARM_BODY, 1.0, theta0=-1e16, omega0=2.0), "theta0"),
        (
            lambda: eccjump.region(mu_s=1.0, alpha=[0.7], chi=[0.2], km_frac=[0.1], theta0=-1e300),
            "theta0",
        ),
        (lambda: eccjump.jarm(0.7, *JARM_BODY, 1.0, n_threads=3000), "n_threads"),
        (lambda: eccjump.jarm(0.7, *JARM_BODY, 1.0, max_turns=10**7), "max_turns"),
        (lambda: eccjump.jarm(1e-10, *JARM_BODY, 1.0, max_turns=2**32 - 1), "max_turns"),
        (lambda: eccjump.alpha_intervals(*JARM_BODY, 1.0, n_scan=2**31), "n_scan"),
        (lambda: eccjump.roll(B, 1e-10, max_steps=10**12, dense_output=True), "max_steps"),
        (lambda: eccjump.roll(B, 0.7, theta0=TAU * 1e12), "theta0"),
        (lambda: eccjump.roll(B, 0.7, omega0=1e200), "omega0"),
    ],
)
def test_work_parameters_are_bounded(call, name):
    short_error(ValueError, call, name=name)


def test_the_turn_cap_counts_from_the_start():
    # The motion is 2 pi periodic in theta0: a start 10000 turns on is the same problem (was
    # NO_ROOT at 10000 turns but JARM at 9999: the cap counted from 0).
    a = eccjump.jarm(0.7, *JARM_BODY, 1.0, theta0=TAU * 9999)
    b = eccjump.jarm(0.7, *JARM_BODY, 1.0, theta0=TAU * 10000)
    assert Reason(int(a.reason)) == Reason(int(b.reason)) == Reason.JARM
    assert float(b.theta_J) - float(a.theta_J) == pytest.approx(TAU, abs=1e-6)
    assert int(b.n) == int(a.n) + 1


def test_a_jump_in_the_first_half_turn_is_on_turn_one():
    # Under the classical rule a steep ramp loses F_y within the first half turn: that JARM
    # is on turn 1 (was n = 0, the "none" value).
    a = np.radians(np.linspace(60, 89, 30))
    r = eccjump.jarm(a[:, None], 0.5, np.linspace(0, 0.5, 6), 1.0, rule="normal_force")
    early = r.is_jarm & (r.theta_J < math.pi)
    assert early.any()
    assert (r.n[r.is_jarm] >= 1).all() and (r.n[early] == 1).all()
    assert (r.n[r.reason != int(Reason.NO_ROOT)] >= 1).all()


# --- no number where an error is due --------------------------------------------------------


def test_invalid_input_is_never_answered_with_a_number():
    # a scalar ramp angle out of range is an error (issue 49); a point of an array is NaN
    short_error(ValueError, eccjump.mu_s_min_path, float("nan"), *JARM_BODY, name="alpha")
    assert math.isnan(float(eccjump.mu_s_min_path([float("nan")], *JARM_BODY)[0]))
    msg = short_error(ValueError, eccjump.alpha_intervals, 2.0, 0.02, 1.0, name="chi")
    assert "index 0" in msg
    short_error(ValueError, cf.jump_forces, 5.0, *JARM_BODY, 5.8, name="alpha")
    short_error(ValueError, cf.J, float("inf"), 0.7, *JARM_BODY, name="theta")
    short_error(ValueError, cf.mu, *JARM_BODY, float("nan"), name="theta_J")
    short_error(ValueError, cf.theta_J_range, *SLIP_FIRST_BODY, -1.0, name="mu_s")
    short_error(ValueError, cf.liftoff_function, 1.0, 0.7, *JARM_BODY, omega0=-1.0, name="omega0")
    for kw, name in (({"atol": 1e300}, "atol"), ({"rtol": 1.0}, "rtol")):
        short_error(ValueError, eccjump.jarm, 0.7, *JARM_BODY, 1.0, method="ode", name=name, **kw)
    # the closed form checks the tolerances it records too
    short_error(ValueError, eccjump.jarm, 0.7, *JARM_BODY, 1.0, rtol=float("nan"), name="rtol")


@pytest.mark.parametrize("mu_s", [float("nan"), -1.0, float("inf")])
def test_a_grid_with_an_invalid_mu_s_is_an_error(mu_s):
    # (was: a "complete" map of INVALID_PARAMS points, also from `eccjump map --mu-s nan`)
    short_error(
        ValueError, eccjump.region, mu_s=mu_s, alpha=[0.7], chi=[0.2], km_frac=[0.1], name="mu_s"
    )


def test_messages_are_short():
    msg = short_error(ValueError, eccjump.roll, B, 0.7, mu_s=-1, name="mu_s")
    assert "inf" in msg  # the open end, not the f64 maximum in 309 digits


# --- Ctrl-C ------------------------------------------------------------------------------------


def interrupted_after(code: str, delay: float) -> float:
    """Runs ``code`` (which prints "start", then works for seconds) in a child, sends it
    SIGINT ``delay`` s after "start", and returns how long the child took to end; the child
    must print "interrupted"."""
    p = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert p.stdout is not None
    assert p.stdout.readline().strip() == "start"
    time.sleep(delay)
    sent = time.time()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=30)
    assert out.startswith("interrupted"), (out, err[-2000:])
    return time.time() - sent


@pytest.mark.skipif(os.name != "posix", reason="needs POSIX signals")
def test_a_long_run_honours_ctrl_c_within_a_second():
    code = textwrap.dedent(
        """
        import eccjump
        print("start", flush=True)
        try:  # 10^7 steps rolling over and over on flat ground: about 6 s
            eccjump.roll(eccjump.Cylinder(0.2, 0.2), 0.0, omega0=1.0, t_max=1e9,
                         max_steps=10**7, dense_output=True)
            print("finished")
        except KeyboardInterrupt:
            print("interrupted", flush=True)
        """
    )
    assert interrupted_after(code, 0.5) < 1.5


@pytest.mark.skipif(os.name != "posix", reason="needs POSIX signals")
def test_a_long_map_honours_ctrl_c_within_a_second():
    code = textwrap.dedent(
        """
        import sys, time, numpy as np, eccjump
        a = np.linspace(0.01, 1.5, 60)
        print("start", flush=True)
        t = time.time()
        try:
            eccjump.region(a, a / 1.6, np.linspace(0, .9, 60), 1.0, method="ode")
            print("finished", time.time() - t)
        except KeyboardInterrupt:
            print("interrupted", time.time() - t, flush=True)
        """
    )
    assert interrupted_after(code, 1.0) < 1.5  # the map takes about 10 s


@pytest.mark.slow
@pytest.mark.skipif(os.name != "posix", reason="needs POSIX signals")
def test_a_long_motion_map_and_simulate_honour_ctrl_c_within_a_second():
    for call in (
        # a motion map of about 2.5 * 10^5 points: tens of seconds
        "eccjump.motion_map(alpha=np.linspace(0.02, 1.5, 64), chi=np.linspace(0.05, 0.9, 64), "
        "km_frac=np.linspace(0.05, 0.9, 64), mu_s=1.0)",
        # one run hopping down a shallow ramp for 10^6 time units with 10^6 transitions
        "eccjump.simulate(eccjump.Cylinder(0.5, 0.4), 0.05, mu_s=1.0, restitution=0.5, "
        "t_max=1e6, max_transitions=10**6, max_steps=10**7)",
    ):
        code = textwrap.dedent(
            f"""
            import numpy as np, eccjump
            print("start", flush=True)
            try:
                {call}
                print("finished")
            except KeyboardInterrupt:
                print("interrupted", flush=True)
            """
        )
        assert interrupted_after(code, 1.0) < 1.5


@pytest.mark.parametrize(
    ("argv", "name"),
    [
        (["map", "--mu-s", "nan", "--grid", "4"], "mu_s"),
        (["map", "--mu-s", "-1", "--grid", "4"], "mu_s"),
        (["map", "--mu-s", "1", "--grid", "4", "--theta0", "1e300"], "theta0"),
        (["map", "--mu-s", "1", "--grid", "4", "--threads", "3000"], "n_threads"),
        (["roll", *JARM_ARGS, "--omega0", "1e200"], "omega0"),
    ],
)
def test_the_command_line_refuses_bad_options_in_one_line(tmp_path, argv, name):
    # (was: exit 0 with a "complete" map of INVALID points, or NaN printed as JSON)
    out = tmp_path / "m.npz"
    if argv[0] == "map":
        argv = [*argv, "-o", str(out)]
    else:
        argv = [*argv, "--json"]
    p = subprocess.run(
        [sys.executable, "-m", "eccjump.cli", *argv], capture_output=True, text=True, timeout=60
    )
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2 and len(lines) == 1, (p.returncode, p.stderr)
    assert lines[0].startswith("eccjump: error:") and name in lines[0], lines[0]
    assert p.stdout == "" and list(tmp_path.iterdir()) == []


def test_a_body_with_next_to_no_inertia_about_its_centre_of_mass_is_refused_by_the_full_motion():
    # Issue 46's campaign: at k_m = 1e-100 an impact "lost" -1e168 (energy gained): the
    # impact law's 1/I_CM loses every digit. simulate refuses I_CM < 1e-10, a map marks it.
    with pytest.raises(ValueError, match=r"^km = .*I_CM >= 1e-10") as info:
        eccjump.simulate(eccjump.Cylinder(0.804, 1e-100), 0.6, mu_s=2.5, omega0=-2.6)
    assert len(str(info.value)) <= 200
    m = eccjump.motion_map(alpha=[0.6], chi=[0.804], km_frac=[1e-300, 1e-6], mu_s=[2.586])
    assert m.fields["status"].ravel().tolist()[0] == 255  # invalid point
    assert np.isfinite(m.fields["energy_lost"].ravel()[1])


def test_a_design_at_the_rim_of_the_body_range_keeps_its_odds():
    # Issue 46's campaign: a rod at the rim gives chi = 1 - km to an ulp above 1 - chi, which
    # the core's Cylinder accepts; the tolerance sampling refused it ("km = 0.1425 is
    # outside [0, 0.1425]").
    from eccjump.studies.uncertainty.sampling import check_nominal

    km = 0.1425
    chi = 1.0 * (1.0 - km)
    assert km > 1.0 - chi
    eccjump.Cylinder(chi, km)
    nominal = dict(chi=chi, km=km, alpha=0.7, mu_s=0.74, mu_k=0.74, restitution=0.0)
    check_nominal({**nominal, "theta0": 0.0, "omega0": 0.0})
