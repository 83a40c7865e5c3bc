"""Generated calls of every public entry point, with their contracts: shared by
``tests/test_fuzz.py`` (hypothesis, a small budget) and ``benches/fuzz_campaign.py`` (a long
campaign, each call in a worker subprocess with a time and memory limit).

A generator takes a :class:`Drawer` (``integer(lo, hi)``, ``choice(seq)``), backed by
hypothesis (``HypothesisDrawer``) or by ``random.Random`` (``RandomDrawer``), and returns a
:class:`Case`: the call and the check of its result. The contract of every call
(:func:`outcome`): it returns a result that passes the case's check, or raises
ValueError/TypeError/MemoryError whose message names a parameter of the function and is at
most 200 characters (store: OSError too, for files). A call given an input of a wrong type
(a bool, None, text, complex, a masked array) must raise.

Work parameters past their bounds (huge thread counts, turn caps, scans, step budgets, starts)
are drawn too: the core refuses them before any work (docs/limits.md). The reproducers that
were found while it did not are kept in :data:`CORE_REGRESSIONS`.
"""

from __future__ import annotations

import atexit
import json
import math
import os
import random
import re
import shutil
import signal
import socket
import sys
import tempfile
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from reference_points import JARM_BODY

import eccjump
from eccjump.classification import closed_form
from eccjump.classification import load as load_region
from eccjump.classification.boundary import alpha_interval_around
from eccjump.maps import store
from eccjump.motion import MotionOptions
from eccjump.studies.design import Build


@dataclass(frozen=True)
class Gap:
    """A call the Rust core once answered wrongly (a hang, an answer where an error is due, a
    message of hundreds of characters): ``code`` (an expression over ``eccjump``'s names)
    must raise ValueError naming ``param`` in <= 200 characters. ``hangs``: it used to run
    without bound."""

    code: str
    param: str
    what: str
    hangs: bool = False


#: Reproducers found by the fuzzing before the core bounded these inputs (each hung,
#: allocated without bound, answered where an error was due, or printed a 300-digit number).
CORE_REGRESSIONS: dict[str, Gap] = {
    "n_threads-huge": Gap(
        "jarm(0.3, 0.5, 0.2, 1.0, n_threads=100_000)", "n_threads",
        "n_threads is not bounded: a pool of 100000 threads is built (hangs)", hangs=True,
    ),
    "n_threads-huge-intervals": Gap(
        "alpha_intervals(0.3, 0.1, 1.0, n_threads=10**6)", "n_threads",
        "n_threads is not bounded (hangs)", hangs=True,
    ),
    "n_scan-huge": Gap(
        "alpha_intervals(0.3, 0.1, 1.0, n_scan=10**9)", "n_scan",
        "n_scan is not bounded: 10**9 angles are scanned (hangs)", hangs=True,
    ),
    "theta0-huge-jarm": Gap(
        "jarm(0.3, 0.5, 0.2, 1.0, theta0=1e15)", "theta0",
        "|theta0| > 2 pi 1e6 gives an answer (NO_ROOT) computed without a digit of theta0",
    ),
    "theta0-huge-roll": Gap(
        "roll(Cylinder(0.3, 0.2), 0.5, theta0=1e15)", "theta0",
        "|theta0| > 2 pi 1e6: the run fails (status -1) instead of a ValueError",
    ),
    "omega0-huge": Gap(
        "jarm(0.3, 0.5, 0.2, 1.0, omega0=1e300)", "omega0",
        "omega0 > 1e6 is accepted (LIFTOFF_EARLIER at theta 0)",
    ),
    "max_turns-huge": Gap(
        "jarm(0.05, 0.1, 0.0, 10.0, method='ode', max_turns=10**9)", "max_turns",
        "max_turns > 1e6 is accepted (a search that can run for hours)",
    ),
    "max_steps-huge": Gap(
        "roll(Cylinder(0.3, 0.2), 0.5, max_steps=10**12)", "max_steps",
        "max_steps > 1e7 is accepted (the recorded steps can exhaust memory)",
    ),
    "range-bound-message": Gap(
        "roll(Cylinder(0.3, 0.2), 0.5, theta0=5e-324, theta_max=float('nan'))", "theta_max",
        "a range bound (theta0 = 5e-324) is printed with all its decimals (394 characters)",
    ),
    "inertia-bound-message": Gap(
        "Cylinder.from_inertia(1e-300, 1.78, 0.468, 1.316)", "I_C",
        "the bounds [M d^2, M R^2] are printed with all their decimals (over 300 characters)",
    ),
    "dense-t-message": Gap(
        "roll(Cylinder(0.15, 0.02), 0.7, mu_s=1.0, dense_output=True).sol(-5e-324)", "t",
        "a time outside the run is printed with all its decimals (406 characters)",
    ),
    "dense-t-message-kinematics": Gap(
        "roll(Cylinder(0.15, 0.02), 0.7, mu_s=1.0, dense_output=True).sol.kinematics([-1e300])",
        "t", "a time outside the run is printed with all its digits (381 characters)",
    ),
}  # fmt: skip

HALF_PI = math.pi / 2
MAX_MESSAGE = 200
N_REASONS = len(eccjump.Reason)
EVENT_NAMES = set(eccjump.EVENT_NAMES)


class Drawer:
    """Draws integers and choices (hypothesis or random). ``clean``: draw only good types and
    values inside the ranges (ends included), for calls that must return a result."""

    clean = False

    def integer(self, lo: int, hi: int) -> int:
        raise NotImplementedError

    def choice(self, seq: Sequence[Any]) -> Any:
        return seq[self.integer(0, len(seq) - 1)]

    def pick(self, *options: Any) -> Any:
        """One of ``options``; a callable one is called, and only once chosen: a draw that
        is made and then not used must not mark the case (a wrong type it drew would make
        ``must_raise`` stale)."""
        x = self.choice(options)
        return x() if callable(x) else x


class RandomDrawer(Drawer):
    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)

    def integer(self, lo: int, hi: int) -> int:
        return self.rng.randint(lo, hi)


class HypothesisDrawer(Drawer):
    def __init__(self, data: Any) -> None:
        from hypothesis import strategies as st

        self.data, self.st = data, st

    def integer(self, lo: int, hi: int) -> int:
        return self.data.draw(self.st.integers(lo, hi))


class Bad:
    """Marks that a value of a wrong type was drawn (the call must raise)."""


@dataclass
class Case:
    name: str
    fn: Callable[..., Any]
    args: tuple = ()
    kwargs: dict[str, Any] = field(default_factory=dict)
    params: tuple[str, ...] = ()
    check: Callable[[Any, Case], None] | None = None
    must_raise: bool = False
    allow_oserror: bool = False
    info: dict[str, Any] = field(default_factory=dict)

    def describe(self) -> str:
        def short(v: object) -> str:
            r = repr(v).replace("\n", " ")
            return r if len(r) <= 60 else r[:57] + "..."

        parts = [short(a) for a in self.args] + [f"{k}={short(v)}" for k, v in self.kwargs.items()]
        return f"{self.name}({', '.join(parts)})"


# --- values -----------------------------------------------------------------------------

SPECIAL = (
    math.nan,
    math.inf,
    -math.inf,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e300,
    -1e300,
    1e-300,
)
HUGE_INTS = (10**400, -(10**400), 2**64, 2**63)
WRONG = (
    True,
    False,
    None,
    "0.5",
    b"1",
    1 + 0j,
    np.complex128(0.5),
    np.bool_(True),
    np.ma.masked_array([0.5], mask=[True]),
    np.ma.masked_array(0.5),
    object(),
    [0.5, [0.5, 0.6]],  # ragged
    np.array(["a"]),
    np.array([None], dtype=object),
    np.array([0.5 + 1j]),
    np.array([True]),
)


def wrong(d: Drawer, case: Case) -> Any:
    case.must_raise = True
    return d.choice(WRONG)


def real_or_none(d: Drawer, case: Case, lo: float, hi: float) -> Any:
    """:func:`real` for a parameter whose default is None (mu_k, alpha, marker_radius): a
    drawn None is a valid value there, not a wrong type."""
    before = case.must_raise
    x = real(d, case, lo, hi)
    if x is None:
        case.must_raise = before
    return x


def real(d: Drawer, case: Case, lo: float, hi: float, *, bad: bool = True) -> Any:
    """A scalar: mostly inside [lo, hi], its ends and one ulp past them, specials, numpy
    scalars, ints, huge ints, and (if ``bad``) a wrong type."""
    kind = d.integer(0, 11 if bad else 10)
    x = lo + (hi - lo) * d.integer(0, 1000) / 1000
    if d.clean and kind in (5, 6, 9, 11):
        kind = 0
    if kind <= 3:
        return x
    if kind == 4:
        return d.choice((lo, hi))
    if kind == 5:
        return float(d.choice((np.nextafter(lo, -math.inf), np.nextafter(hi, math.inf))))
    if kind == 6:
        return d.choice(SPECIAL)
    if kind == 7:
        return d.choice((np.float64, np.float32, np.float16, np.longdouble))(x)
    if kind == 8:
        return d.choice(
            (int(lo), int(hi), np.int64(round(x)), np.uint8(min(255, max(0, round(x)))))
        )
    if kind == 9:
        return d.choice(HUGE_INTS)
    if kind == 10:
        return np.array(x) if d.integer(0, 1) else np.array(x, dtype=">f8")
    return wrong(d, case)


SHAPES = ((), (0,), (1,), (2,), (3,), (2, 2), (1, 3))


def array(d: Drawer, case: Case, lo: float, hi: float, *, max_size: int = 4) -> Any:
    """An array-like of values from :func:`real` (no wrong types inside) in some layout."""
    shape = d.choice([s for s in SHAPES if math.prod(s) <= max_size])
    size = math.prod(shape)
    vals = []
    for _ in range(size):
        v = real(d, case, lo, hi, bad=False)
        vals.append(math.nan if isinstance(v, int) and abs(v) > 2**1000 else float(v))
    a = np.array(vals, dtype=np.float64).reshape(shape)
    layout = d.integer(0, 10)
    if d.clean and layout == 7:
        layout = 8
    if layout == 0:
        return a.tolist()
    if layout == 1:
        return a.astype(">f8")
    if layout == 2:  # strided
        b = np.repeat(a.ravel(), 2)[::2].reshape(shape) if size else a
        return b
    if layout == 3:
        a.setflags(write=False)
        return a
    if layout == 4:
        with np.errstate(over="ignore"):  # huge values become inf in float32, on purpose
            return a.astype(np.float32)
    if layout == 5 and size and np.isfinite(a).all() and (np.abs(a) < 2**62).all():
        return np.round(a).astype(np.int64)
    if layout == 6:
        return real(d, case, lo, hi)  # a scalar (may be a wrong type)
    if layout == 7:
        return wrong(d, case)
    return a


def integer_param(d: Drawer, case: Case, good: Sequence[int], bad_values: Sequence[Any]) -> Any:
    k = d.integer(0, 5)
    if k <= 2 or (d.clean and k > 3):
        return d.choice(good)
    if k == 3:
        v = d.choice(good)
        return d.choice((np.int64(v), np.uint32(v), np.array(v)))
    v = d.choice(bad_values)
    if isinstance(v, float) or isinstance(v, bool | np.bool_) or v is None or isinstance(v, str):
        case.must_raise = True
    return v


INT_BAD = (-1, 0, 2.5, 0.5, 1.0, True, None, "2", 2**32, 2**64, 10**400, -(10**400))


def turn(d: Drawer, case: Case, *, allow_none: bool = True, per_point: bool = False) -> Any:
    if allow_none and d.integer(0, 2) == 0:
        return None
    if per_point and d.integer(0, 3) == 0 and not d.clean:
        return d.choice(([1, 2], np.array([[1], [2]]), np.array([1, 0]), [1.0, 2.0], [True]))
    return integer_param(d, case, (1, 2, 3), [v for v in INT_BAD if v is not None])


def threads(d: Drawer, case: Case) -> Any:
    # 257 and 10**6 are past the core's bound (256): refused before a pool is made.
    return integer_param(d, case, (0, 1, 2), (-1, 2.5, True, None, 257, 10**6, 2**64, 10**400))


#: The Runge–Kutta pairs the integrating entry points take.
INTEGRATORS = ("RK45", "DOP853", "Vern9")


def text_param(d: Drawer, case: Case, good: Sequence[str]) -> Any:
    k = d.integer(0, 4)
    if k <= 2 or d.clean:
        return d.choice(good)
    if k == 3:
        return d.choice(("bogus", "", "PAPER"))
    case.must_raise = True
    return d.choice((None, 1, b"paper", True))


def flag(d: Drawer, case: Case) -> Any:
    k = d.integer(0, 3)
    if k <= 2 or d.clean:
        return d.choice((True, False, np.bool_(True)))
    case.must_raise = True
    return d.choice((1, 0.0, None, "yes"))


# --- checks -------------------------------------------------------------------------------


def expect(cond: bool, what: str) -> None:
    if not cond:
        raise ContractViolation(what)


class ContractViolation(AssertionError):
    """A result that breaks the documented contract (silent garbage)."""


def _points(case: Case) -> tuple[np.ndarray, ...] | None:
    """The broadcast float inputs of a point-wise call, or None if they do not convert."""
    try:
        vals = [np.asarray(case.info[k], dtype=np.float64) for k in case.info["points"]]
        return tuple(np.broadcast_arrays(*vals))
    except (TypeError, ValueError, OverflowError):
        return None


def check_jarm_result(res: Any, case: Case, shape: tuple[int, ...] | None = None) -> None:
    expect(isinstance(res, eccjump.JarmResult), "not a JarmResult")
    fields = res.fields()
    if shape is None:
        pts = _points(case)
        shape = pts[0].shape if pts else res.shape
        n = case.kwargs.get("n")
        if pts and isinstance(n, list | np.ndarray):  # a turn per point broadcasts too
            shape = np.broadcast_shapes(shape, np.shape(n))
    for k, v in fields.items():
        expect(v.shape == shape, f"{k} has shape {v.shape}, not {shape}")
    reason = res.reason.astype(int)
    expect(bool(((reason >= 0) & (reason < N_REASONS)).all()), "reason codes out of range")
    expect(bool((res.is_jarm == (reason == 0)).all()), "is_jarm differs from reason == JARM")
    jarm = reason == 0
    expect(bool(np.isfinite(res.theta_J[jarm]).all()), "JARM point without a finite theta_J")
    if case.kwargs.get("rule") == "paper":  # normal_force: JARMs outside any green turn, n 0
        expect(bool((res.n[jarm] >= 1).all()), "JARM point with n < 1")
    check_derivatives(res, case, shape)
    pts = _points(case) if case.name == "jarm" else None
    if pts is not None and pts[0].shape != shape:
        pts = tuple(np.broadcast_to(p, shape) for p in pts)
    if pts is not None and pts[0].shape == shape:
        alpha, chi, km, mu = pts[:4]
        with np.errstate(invalid="ignore"):
            bad = (
                np.isnan(alpha + chi + km + mu)
                | (alpha < 0)
                | (alpha > HALF_PI + 1e-12)
                | (chi < 0)
                | (chi > 1)
                | (km < 0)
                | (km > 1 - chi + 1e-12)
                | (mu < 0)
            )
            good = (
                (alpha >= 0)
                & (alpha <= HALF_PI)
                & (chi >= 0)
                & (chi <= 1)
                & (km >= 0)
                & (km <= 1 - chi - 1e-12)
                & (mu >= 0)
                & np.isfinite(mu)
            )
        invalid = reason == int(eccjump.Reason.INVALID_PARAMS)
        expect(bool(invalid[bad].all()), "an invalid point is not INVALID_PARAMS")
        expect(not bool(invalid[good].any()), "a valid point is INVALID_PARAMS")


def _km_is_zero(case: Case, shape: tuple[int, ...]) -> np.ndarray | None:
    """Where km = 0 among the points of a ``jarm`` or ``region`` call (None: not known)."""
    try:
        if case.name == "jarm":
            pts = _points(case)
            return None if pts is None else np.broadcast_to(pts[2] == 0, shape)
        if case.name == "region":  # axes (alpha, chi, km_frac): km = km_frac (1 - chi)
            chi = np.atleast_1d(np.asarray(case.args[1], dtype=np.float64))
            frac = np.atleast_1d(np.asarray(case.args[2], dtype=np.float64))
            return np.broadcast_to((chi[:, None] == 1) | (frac[None, :] == 0), shape)
    except (TypeError, ValueError):
        return None
    return None


def check_derivatives(res: Any, case: Case, shape: tuple[int, ...]) -> None:
    """The derivative fields: there iff asked for, of the shape plus (3,); finite exactly
    where theta_J is finite and the point is not flagged singular (no silent NaN), the
    forces' only where the forces are."""
    asked = case.kwargs.get("derivatives", False)
    derivs = res.derivatives()
    expect(bool(derivs) == bool(asked), "derivative fields present iff derivatives=True")
    if not derivs:
        return
    expect(derivs["d_singular"].shape == shape, "d_singular shape")
    for k in ("d_theta_J", "d_Fx_J", "d_Fy_J", "d_mu_J"):
        expect(derivs[k].shape == (*shape, 3), f"{k} has shape {derivs[k].shape}")
    singular = derivs["d_singular"]
    jump = np.isfinite(res.theta_J)
    expect(not bool(singular[~jump].any()), "a point without theta_J flagged singular")
    finite = np.isfinite(derivs["d_theta_J"])
    due = jump & ~singular
    expect(
        bool((finite[..., :2].all(axis=-1) == due).all()), "d_theta_J finite where it must not be"
    )
    # The km column is one-sided, so NaN, at km = 0 (where the inputs say which points those are).
    km_zero = _km_is_zero(case, shape)
    km_due = due if km_zero is None else due & ~km_zero
    expect(bool((finite[..., 2] <= due).all()), "d_theta_J/dkm finite without a jump")
    if km_zero is not None:
        expect(bool((finite[..., 2] == km_due).all()), "d_theta_J/dkm finite where it must not be")

    return None
    for k in ("d_Fx_J", "d_Fy_J"):
        ok = np.isfinite(derivs[k]).all(axis=-1)
        expect(bool((ok == (np.isfinite(res.Fx_J) & ~singular)).all()), f"{k} finite or NaN")


def check_region(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.Region), "not a Region")
    shape = (res.alpha.size, res.chi.size, res.km_frac.size)
    check_jarm_result(res.result, case, shape)


def check_dataset(res: Any, case: Case) -> None:
    expect(hasattr(res, "data_vars") and "reason" in res.data_vars, "not a map dataset")
    r = np.asarray(res["reason"]).astype(int)
    expect(bool(((r >= 0) & (r < N_REASONS)).all()), "reason codes out of range")


def check_roll(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.RollResult), "not a RollResult")
    n = res.t.size
    expect(n >= 1, "no initial point")
    for k in ("theta", "omega", "omega_dot", "Fx", "Fy", "l", "friction_ratio"):
        expect(getattr(res, k).shape == (n,), f"{k} has another length than t")
    expect(bool(np.isfinite(res.t).all()), "t not finite")
    expect(bool((np.diff(res.t) >= 0).all()), "t decreases")
    expect(bool(np.isfinite(res.theta).all() and np.isfinite(res.omega).all()), "state not finite")
    expect(res.status in (-1, 0, 1), f"status {res.status}")
    expect((res.status == 1) == (res.terminal_event is not None), "status vs terminal_event")
    expect(res.terminal_event is None or res.terminal_event in EVENT_NAMES, "unknown event")
    expect(all(e.name in EVENT_NAMES for e in res.events), "unknown event name")
    expect(isinstance(res.message, str) and len(res.message) <= MAX_MESSAGE, "message")
    expect(res == res, "a result is not equal to itself")


def check_si(res: Any, case: Case) -> None:
    check_roll(res, case)
    expect(res.units is not None, "units not recorded")


def check_states(res: Any, case: Case) -> None:
    expect(isinstance(res, np.ndarray) and res.shape[0] == 2, "not a (2, ...) array")
    expect(bool(np.isfinite(res).all()), "dense states not finite")


def check_kinematics(res: Any, case: Case) -> None:
    expect(isinstance(res, dict) and "theta" in res, "not a dict of arrays")
    for k, v in res.items():
        expect(bool(np.isfinite(v[np.isfinite(v)]).all()), k)
        if k in ("theta", "omega", "omega_dot", "Fx", "Fy"):
            expect(bool(np.isfinite(v).all()), f"{k} not finite")


def check_intervals(res: Any, case: Case) -> None:
    pts = _points(case)
    expect(isinstance(res, list), "not a list")
    if pts is not None:
        expect(len(res) == pts[0].size, "one list per body")
    for ivs in res:
        for lo, hi in ivs:
            expect(math.isfinite(lo) and math.isfinite(hi), "interval end not finite")
            expect(0 <= lo <= hi <= HALF_PI + 1e-12, f"interval ({lo}, {hi}) outside [0, pi/2]")


def check_mu_min(res: Any, case: Case) -> None:
    pts = _points(case)
    expect(isinstance(res, np.ndarray) and res.dtype == np.float64, "not a float64 array")
    if pts is not None:
        expect(res.shape == pts[0].shape, "shape")
    with np.errstate(invalid="ignore"):
        expect(bool((np.isnan(res) | (res >= 0)).all()), "negative mu_s,min")


def check_around(res: Any, case: Case) -> None:
    lo, hi = res
    expect(lo.shape == hi.shape, "lo and hi shapes")
    expect(bool((np.isnan(lo) == np.isnan(hi)).all()), "one end NaN, not the other")
    ok = ~np.isnan(lo)
    expect(bool((lo[ok] <= hi[ok]).all()), "lo > hi")


def check_pointwise(res: Any, case: Case) -> None:
    outs = res if isinstance(res, tuple) else (res,)
    pts = _points(case)
    for o in outs:
        expect(isinstance(o, np.ndarray), "not an array")
        if pts is not None:
            expect(o.shape == pts[0].shape, f"shape {o.shape}, not {pts[0].shape}")


def check_cylinder(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.Cylinder), "not a Cylinder")
    expect(0 <= res.chi <= 1 and 0 <= res.km <= 1 - res.chi + 1e-12, "body out of range")
    expect(math.isfinite(res.Ic) and res.Icm >= -1e-12, "inertia")
    expect(res == eccjump.Cylinder(res.chi, res.km), "not equal to its copy")


def check_units(res: Any, case: Case) -> None:
    for k in ("time", "rate", "length", "acceleration", "force"):
        v = getattr(res, k)
        expect(math.isfinite(v) and v > 0, f"{k} scale {v}")


def check_any(res: Any, case: Case) -> None:
    pass


def check_figure(res: Any, case: Case) -> None:
    """A figure; closed at once (pyplot keeps every open figure: a long campaign would fill
    its worker's memory limit with them)."""
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    plt.close(res)
    assert isinstance(res, Figure), type(res)


# --- cases --------------------------------------------------------------------------------


def _classification_options(d: Drawer, case: Case, ode_ok: bool) -> dict[str, Any]:
    method = text_param(d, case, ("closed_form", "ode") if ode_ok else ("closed_form",))
    return {
        "method": method,
        "rule": text_param(d, case, ("paper", "normal_force")),
        "theta0": d.pick(lambda: real(d, case, -7.0, 7.0), *(() if d.clean else (1e15, -1e300))),
        "omega0": d.pick(lambda: real(d, case, 0.0, 3.0), *(() if d.clean else (1e7, 1e300))),
        "rtol": d.choice((1e-10, 1e-6, 1e-3, *(() if d.clean else (0.0, -1.0, math.nan, 1.0)))),
        "atol": d.choice((1e-12, 1e-8, *(() if d.clean else (0.0, -1.0, math.nan, math.inf)))),
        "max_turns": integer_param(d, case, (1, 3, 20), (*INT_BAD, 10**6 + 1, 10**9)),
        "refine_extrema": flag(d, case),
        "stop_at_slip": flag(d, case),
        "n_threads": threads(d, case),
    }


def case_jarm(d: Drawer) -> Case:
    c = Case("jarm", eccjump.jarm, params=JARM_PARAMS, check=check_jarm_result)
    alpha = array(d, c, 0.0, HALF_PI)
    chi = array(d, c, 0.0, 1.0)
    km = array(d, c, 0.0, 0.5)
    mu = array(d, c, 0.0, 3.0)
    c.args = (alpha, chi, km, mu)
    c.kwargs = {
        "n": turn(d, c, per_point=True),
        **_classification_options(d, c, True),
        "integrator": text_param(d, c, INTEGRATORS),
        "derivatives": flag(d, c),
    }
    c.info = {
        "alpha": alpha,
        "chi": chi,
        "km": km,
        "mu_s": mu,
        "points": ("alpha", "chi", "km", "mu_s"),
    }
    return c


JARM_PARAMS = (
    "alpha", "chi", "km", "mu_s", "n", "method", "rule", "theta0", "omega0", "rtol", "atol",
    "max_turns", "refine_extrema", "stop_at_slip", "n_threads", "shapes", "integrator",
    "derivatives",
)  # fmt: skip
#: A map's axes: the fraction km_frac, not the body's km.
MAP_PARAMS = tuple("km_frac" if p == "km" else p for p in JARM_PARAMS)


def _axis(d: Drawer, c: Case, lo: float, hi: float) -> Any:
    a = array(d, c, lo, hi, max_size=3)
    return a


def case_region(d: Drawer) -> Case:
    c = Case("region", eccjump.region, params=(*MAP_PARAMS, "output", "chunks", "progress"),
             check=check_region)  # fmt: skip
    opts = _classification_options(d, c, False)
    mu, n = real(d, c, 0.0, 3.0), turn(d, c)
    axes = (_axis(d, c, 0.0, HALF_PI), _axis(d, c, 0.0, 1.0), _axis(d, c, 0.0, 1.0))
    c.args = (*axes, mu, n)  # (alpha, chi, km_frac, mu_s, n): the point first, then mu_s
    c.kwargs = {**opts, "integrator": text_param(d, c, INTEGRATORS), "derivatives": flag(d, c)}
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    return c


def case_region_dataset(d: Drawer) -> Case:
    c = Case(
        "region_dataset", eccjump.region_dataset, params=(*MAP_PARAMS, "output", "chunks"),
        check=check_dataset,
    )  # fmt: skip
    mu = d.choice((1.0, [0.5, 2.0], [], [[1.0]], "1", None, [math.nan]))
    if mu in ("1", None):
        c.must_raise = True
    n = turn(d, c)
    axes = (_axis(d, c, 0.0, HALF_PI), _axis(d, c, 0.0, 1.0), _axis(d, c, 0.0, 1.0))
    c.args = (*axes, mu, n)  # (alpha, chi, km_frac, mu_s, n): the point first, then mu_s
    c.kwargs = {
        "theta0": d.choice((0.0, [0.0, 0.1], True)),
        "omega0": real(d, c, 0.0, 2.0),
    }
    if c.kwargs["theta0"] is True:
        c.must_raise = True
    return c


ROLL_PARAMS = (
    "body", "alpha", "theta0", "omega0", "mu_s", "t_max", "theta_max", "rtol", "atol",
    "dense_output", "max_steps", "rule", "integrator",
)  # fmt: skip


def _body(d: Drawer, c: Case) -> Any:
    if d.integer(0, 7) == 0:
        c.must_raise = True
        return d.choice((None, (0.3, 0.1), 0.3, "body"))
    chi = d.integer(0, 100) / 100
    return eccjump.Cylinder(chi, (1 - chi) * d.integer(0, 100) / 100)


def case_roll(d: Drawer) -> Case:
    c = Case("roll", eccjump.roll, params=ROLL_PARAMS, check=check_roll)
    c.args = (_body(d, c), real(d, c, 0.0, HALF_PI))
    c.kwargs = {
        "theta0": real(d, c, -7.0, 7.0),
        "omega0": real(d, c, 0.0, 3.0),
        "mu_s": None if d.integer(0, 2) == 0 else real(d, c, 0.0, 3.0),
        "t_max": real(d, c, 0.0, 50.0),
        "theta_max": d.choice((math.inf, 10.0, 1e300, *(() if d.clean else (-1.0, math.nan)))),
        "rtol": d.choice((1e-10, 1e-6, *(() if d.clean else (0.0, math.nan, 1e-16)))),
        "atol": d.choice((1e-12, 1e-8, *(() if d.clean else (0.0, -1.0)))),
        "dense_output": flag(d, c),
        # good max_steps up to 10**4 (10**7 steps are slow, not wrong); past 10**7: refused.
        "max_steps": integer_param(d, c, (1, 10, 10_000), (*INT_BAD, 10**7 + 1, 10**12)),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "integrator": text_param(d, c, INTEGRATORS),
    }
    return c


SIMULATE_PARAMS = (
    "body",
    "alpha",
    "mu_s",
    "mu_k",
    "restitution",
    "rule",
    "theta0",
    "omega0",
    "slip0",
    "t_max",
    "l_max",
    "max_transitions",
    "rtol",
    "atol",
    "max_steps",
    "dense_output",
    "km",
    "integrator",
    "sensitivities",
)


def check_simulate(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.MotionResult), "not a MotionResult")
    n = res.t.size
    expect(n >= 1, "no initial point")
    for k in ("theta", "omega", "l", "ldot", "b", "bdot", "Fx", "Fy", "energy", "mode"):
        expect(getattr(res, k).shape == (n,), f"{k} has another length than t")
    expect(bool((np.diff(res.t) >= 0).all()), "t decreases")
    expect(res.status in eccjump.motion.STATUSES, f"status {res.status}")
    expect(all(tr.reason in eccjump.motion.REASONS for tr in res.transitions), "reason")
    expect(isinstance(res.message, str) and len(res.message) <= 300, "message")
    if res.status != "failed":
        expect(bool(np.isfinite(res.theta).all() and np.isfinite(res.b).all()), "state")
    expect(res == res, "a result is not equal to itself")
    if case.kwargs["sensitivities"]:
        check_sensitivities(res)
    else:
        expect(res.d_transitions is None and res.d_singular is None, "sensitivities given")


def check_sensitivities(res: Any) -> None:
    """(n, 2, 8) derivatives, NaN exactly where flagged, a flag kept once raised."""
    d, singular = res.d_transitions, res.d_singular
    n = len(res.transitions)
    expect(d.shape == (n, 2, 8) and singular.shape == (n,), "sensitivities' shape")
    expect(bool((np.isnan(d).all(axis=(1, 2)) == singular).all()), "NaN where not flagged")
    expect(bool(np.isfinite(d[~singular]).all()), "a derivative not flagged is not finite")
    expect(bool(np.all(np.diff(singular.astype(int)) >= 0)), "a flag does not propagate")


def case_simulate(d: Drawer) -> Case:
    c = Case("simulate", eccjump.simulate, params=SIMULATE_PARAMS, check=check_simulate)
    c.args = (_body(d, c), real(d, c, 0.0, HALF_PI))
    c.kwargs = {
        "mu_s": real(d, c, 0.0, 3.0),
        "restitution": real(d, c, 0.0, 1.0),
        "theta0": real(d, c, -7.0, 7.0),
        "omega0": real(d, c, -3.0, 3.0),
        "slip0": real(d, c, -2.0, 2.0),
        "t_max": real(d, c, 0.0, 20.0),
        "l_max": d.choice((math.inf, 5.0, *(() if d.clean else (0.0, math.nan)))),
        "max_transitions": integer_param(d, c, (1, 5, 50), (*INT_BAD, 10**6 + 1)),
        "rtol": d.choice((1e-10, 1e-6, *(() if d.clean else (0.0, math.nan, 1e-16)))),
        "max_steps": integer_param(d, c, (1, 100, 100_000), (*INT_BAD, 10**7 + 1)),
        "dense_output": flag(d, c),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "integrator": text_param(d, c, INTEGRATORS),
        "sensitivities": flag(d, c),
    }
    if d.integer(0, 2) == 0:
        c.kwargs["mu_k"] = real_or_none(d, c, 0.0, 3.0)
    return c


MOTION_MAP_PARAMS = (
    *eccjump.motion.maps.AXES,
    "rule",
    "t_max",
    "max_transitions",
    "rtol",
    "atol",
    "max_steps",
    "n_threads",
    "chunks",
    "output",
    "integrator",
    "progress",
)


def check_motion_map(res: Any, case: Case) -> None:
    mm = eccjump.motion.maps
    expect(isinstance(res, eccjump.MotionMap), "not a MotionMap")
    for name in mm.FIELDS:
        expect(res.fields[name].shape == res.shape, f"{name} has another shape than the grid")
    status = res.status.astype(int)
    expect(all(int(s) in mm.STATUS_NAMES for s in np.unique(status)), "status code")
    ran = status != mm.INVALID
    expect(bool((res.landing < len(mm.LANDINGS)).all()), "landing code")
    names = [mm.sequence_name(c) for c in np.unique(res.sequence[ran])]
    expect(all(n for n in names), "a point that ran has no sequence")
    expect(bool(np.isfinite(res.energy_lost[ran & (status != 5)]).all()), "energy_lost NaN")
    expect(not bool((res.jarm & res.slipped_first).any()), "a JARM that slipped first")
    expect(isinstance(repr(res), str), "repr")


def case_motion_map(d: Drawer) -> Case:
    c = Case("motion_map", eccjump.motion_map, params=MOTION_MAP_PARAMS, check=check_motion_map)
    c.kwargs = {
        "alpha": _axis(d, c, 0.0, HALF_PI),
        "chi": _axis(d, c, 0.0, 1.0),
        "km_frac": _axis(d, c, 0.0, 1.0),
        "mu_s": d.pick(lambda: real(d, c, 0.0, 3.0), lambda: _axis(d, c, 0.0, 3.0)),
        "restitution": real(d, c, 0.0, 1.0),
        "theta0": real(d, c, -7.0, 7.0),
        "omega0": real(d, c, -3.0, 3.0),
        "t_max": real(d, c, 0.0, 20.0),
        "max_transitions": integer_param(d, c, (1, 5, 50), (*INT_BAD, 10**6 + 1)),
        "rtol": d.choice((1e-10, 1e-6, *(() if d.clean else (0.0, math.nan, 1e-16)))),
        "max_steps": integer_param(d, c, (1, 100, 100_000), (*INT_BAD, 10**7 + 1)),
        "n_threads": integer_param(d, c, (0, 1, 2), (*INT_BAD, 257)),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "integrator": text_param(d, c, INTEGRATORS),
    }
    if d.integer(0, 2) == 0:
        c.kwargs["mu_k"] = d.pick(
            lambda: real_or_none(d, c, 0.0, 3.0), lambda: _axis(d, c, 0.0, 3.0), None
        )
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    return c


MOTION_POINTS_PARAMS = (
    "alpha", "chi", "km", "mu_s", "mu_k", "restitution", "theta0", "omega0", "rule", "t_max",
    "max_transitions", "rtol", "atol", "max_steps", "n_threads", "integrator", "shapes",
    "progress",
)  # fmt: skip


def check_motion_points(res: Any, case: Case) -> None:
    mm = eccjump.motion.maps
    expect(isinstance(res, eccjump.MotionPoints), "not MotionPoints")
    shapes = {getattr(res, f).shape for f in mm.FIELDS}
    expect(len(shapes) == 1, f"fields of different shapes {shapes}")
    ran = res.status != mm.INVALID
    expect(all(int(v) in mm.STATUS_NAMES for v in np.unique(res.status)), "status code")
    expect(all(mm.sequence_name(int(c)) for c in np.unique(res.sequence[ran])), "no sequence")
    expect(not bool((res.jarm & res.slipped_first).any()), "a JARM that slipped first")
    expect(bool(np.isnan(res.apex[~ran]).all()), "an invalid point has an apex")


def case_motion_points(d: Drawer) -> Case:
    c = Case("motion_points", eccjump.motion_points, params=MOTION_POINTS_PARAMS,
             check=check_motion_points)  # fmt: skip
    c.args = (
        array(d, c, 0.0, HALF_PI),
        array(d, c, 0.0, 1.0),
        array(d, c, 0.0, 0.6),
        array(d, c, 0.0, 3.0),
    )
    c.kwargs = {
        "restitution": array(d, c, 0.0, 1.0),
        "theta0": array(d, c, -7.0, 7.0),
        "omega0": array(d, c, -3.0, 3.0),
        "t_max": real(d, c, 0.0, 20.0),
        "max_transitions": integer_param(d, c, (1, 5, 50), (*INT_BAD, 10**6 + 1)),
        "rtol": d.choice((1e-10, 1e-6, *(() if d.clean else (0.0, math.nan, 1e-16)))),
        "max_steps": integer_param(d, c, (1, 100, 100_000), (*INT_BAD, 10**7 + 1)),
        "n_threads": integer_param(d, c, (0, 1, 2), (*INT_BAD, 257)),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "integrator": text_param(d, c, INTEGRATORS),
    }
    if d.integer(0, 2) == 0:
        c.kwargs["mu_k"] = array(d, c, 0.0, 3.0)
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    return c


MOTION_OPTIONS_PARAMS = (
    "rule", "t_max", "max_transitions", "rtol", "atol", "max_steps", "integrator", "n_threads",
)  # fmt: skip


def _motion_options_for_core(*, n_threads: Any = 0, **options: Any) -> Any:
    """``MotionOptions`` made and converted for the core, as a map or ``motion_points`` does."""
    return MotionOptions(**options).to_core(n_threads)


def check_motion_options(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump._core.MotionMapOptions), "not the core's options")


def case_motion_options(d: Drawer) -> Case:
    c = Case("motion_options", _motion_options_for_core, params=MOTION_OPTIONS_PARAMS,
             check=check_motion_options)  # fmt: skip
    c.kwargs = {
        "rule": text_param(d, c, ("paper", "normal_force")),
        "t_max": real(d, c, 0.0, 2e6),
        "max_transitions": integer_param(d, c, (1, 5, 10**6), (*INT_BAD, 10**6 + 1)),
        "rtol": d.choice((1e-10, 1e-6, *(() if d.clean else (0.0, math.nan, 1e-16, 1e-3)))),
        "atol": d.choice((1e-12, 1e-8, *(() if d.clean else (0.0, -1.0, math.nan, math.inf)))),
        "max_steps": integer_param(d, c, (1, 100, 10**7), (*INT_BAD, 10**7 + 1)),
        "integrator": text_param(d, c, INTEGRATORS),
        "n_threads": integer_param(d, c, (0, 1, 256), (*INT_BAD, 257)),
    }
    return c


UNCERTAINTY_PARAMS = (
    "body", "alpha", "mu_s", "mu_k", "restitution", "theta0", "omega0", "sd", "bounds", "n",
    "seed", "sampling", "question", "invalid", "confidence", "rule", "t_max",
    "max_transitions", "rtol", "atol", "integrator", "n_threads", "chi", "km", "progress",
    "indices",
)  # fmt: skip


def check_uncertainty(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.Uncertainty), "not an Uncertainty")
    lo, hi = res.p_jarm_ci
    expect(0 <= lo <= res.p_jarm <= hi <= 1, f"p_jarm {res.p_jarm} outside [{lo}, {hi}]")
    expect(0 < res.n_valid <= res.n == res.valid.size, "n_valid")
    expect(sum(res.counts.values()) == res.n_valid, "the outcomes do not add up")
    expect(all(v.size == res.n for v in res.samples.values()), "a sample column's length")
    for name, s in res.distributions.items():
        ok = s.n == 0 or (s.q025 <= s.median <= s.q975 and math.isfinite(s.mean))
        expect(ok, f"distribution {name}: {s}")
    for p, x in res.samples.items():  # every valid sample in its physical range
        expect(bool(np.isfinite(x[res.valid]).all()), f"sample {p} not finite")
    expect(isinstance(res._repr_html_(), str), "html")
    if res.indices is not None:  # one per varied parameter, finite, total >= 0
        expect(list(res.indices) == list(res.samples), f"indices of {list(res.indices)}")
        for name, ix in res.indices.items():
            for est in ix:
                expect(all(map(math.isfinite, est)), f"index of {name}: {est}")
                expect(est.low <= est.high, f"{name}: {est}")  # a percentile interval
            expect(ix.total.value >= 0 and ix.total.low >= 0, f"total of {name}: {ix.total}")
    try:  # "JSON-ready": no inf or NaN, whatever the spreads
        json.dumps(res.to_dict(), allow_nan=False)
    except ValueError as err:
        expect(False, f"to_dict: {err}")


def _spread_dict(d: Drawer, c: Case, names: Sequence[str], pair: bool) -> Any:
    out: dict[Any, Any] = {}
    for _ in range(d.integer(0, 2)):
        name = d.choice(names) if d.clean or d.integer(0, 5) else d.choice(("bogus", 1, "KM"))
        huge = not d.clean and d.integer(0, 9) == 0  # once an OverflowError, an inf in to_dict
        if pair:
            lo = real(d, c, -0.1, 1.0, bad=False)
            out[name] = (lo, d.choice((lo, 1.0, 0.5, -1.0))) if not d.clean else (0.1, 0.4)
            if huge:
                out[name] = d.choice(((-1.7e308, 1.7e308), (0.0, 1e300), (-1e101, 0.0)))
        else:
            out[name] = d.choice((1e300, 1e101, 1.5e154)) if huge else real(d, c, 0.0, 0.1)
        c.must_raise |= huge
    if not d.clean and d.integer(0, 9) == 0:
        return d.choice(([0.1], "alpha", 0.1))
    return out


#: Confidence levels outside (0, 1 - 1e-15]: 1 - 1e-16 was a StatisticsError.
BAD_CONFIDENCE = (0.0, 1.0, math.nan, 1 - 1e-16, -0.5, 2.0)


def _no_progress(done: int, total: int) -> None:
    """A progress callback that does nothing."""


def _sane_progress(done: int, total: int) -> None:
    """A progress callback that holds the calls to their contract: two ints, 0 <= done <=
    total (an AssertionError out of the call is a wrong exception: a violation)."""
    assert type(done) is int and type(total) is int, (type(done), type(total))
    assert 0 <= done <= total, (done, total)


#: ``progress=`` values: the good ones (off, a bar, a callable) and the wrong types.
PROGRESS_GOOD = (None, False, True, np.bool_(False), _sane_progress)
PROGRESS_BAD = (1, "bar", 2.5, [])


def progress_param(d: Drawer, case: Case) -> Any:
    """A ``progress=`` value, sometimes of a wrong type (then the case must raise)."""
    value = d.choice(PROGRESS_GOOD + (() if d.clean else PROGRESS_BAD))
    case.must_raise |= any(value is bad for bad in PROGRESS_BAD)
    return value


def _is_study(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.Uncertainty), "not an Uncertainty")


def case_uncertainty_load(d: Drawer) -> Case:
    """``Uncertainty.load``: a study saved here (.csv, .nc), or a path that is no study."""
    where = tmpdir()
    good = {suffix: where / f"study{suffix}" for suffix in (".csv", ".nc")}
    if not all(p.exists() for p in good.values()):
        study = eccjump.uncertainty(
            eccjump.Cylinder(*JARM_BODY), 0.7, 1.0, sd={"chi": 0.01}, n=16, seed=1
        )
        for p in good.values():
            study.save(p, overwrite=True)
        (where / "cut.csv").write_bytes(good[".csv"].read_bytes()[:200])
        (where / "other.csv").write_text("a,b\n1,2\n")
    path = d.choice((*good.values(), str(good[".csv"]), where / "cut.csv", where / "other.csv",
                     where / "missing.csv", where / "study.txt", None, 5))  # fmt: skip
    params = ("path", Path(path).name) if isinstance(path, str | Path) else ("path",)
    c = Case("Uncertainty.load", eccjump.Uncertainty.load, params=params, allow_oserror=True,
             check=_is_study)  # fmt: skip
    c.must_raise = path not in (*good.values(), str(good[".csv"]))
    c.args = (path,)
    return c


def case_uncertainty(d: Drawer) -> Case:
    if d.integer(0, 7) == 0:
        return case_uncertainty_load(d)
    c = Case("uncertainty", eccjump.uncertainty, params=UNCERTAINTY_PARAMS,
             check=check_uncertainty)  # fmt: skip
    question = d.choice(("jarm", "jarm", "motion"))
    names = ("chi", "km", "alpha", "mu_s") if question == "jarm" else (
        "chi", "km", "alpha", "mu_s", "mu_k", "restitution", "theta0", "omega0")  # fmt: skip
    c.args = (_body(d, c), real(d, c, 0.0, HALF_PI), real(d, c, 0.0, 2.0))
    sd = _spread_dict(d, c, names, pair=False)
    bounds = _spread_dict(d, c, names, pair=True)
    if isinstance(sd, dict) and isinstance(bounds, dict):
        bounds = {k: v for k, v in bounds.items() if k not in sd or not d.clean}
    c.kwargs = {
        "sd": sd,
        "bounds": bounds,
        "question": text_param(d, c, (question,)),
        "n": integer_param(d, c, (1, 7, 64), (*INT_BAD, 10**9)),
        "seed": integer_param(d, c, (0, 1, 12345), (-1, 2.5, None, "1", 2**64)),
        "sampling": text_param(d, c, ("random", "sobol")),
        "invalid": text_param(d, c, ("truncate", "count")),
        "confidence": d.choice((0.95, 0.5, *(() if d.clean else BAD_CONFIDENCE))),
        "n_threads": integer_param(d, c, (0, 1, 2), (*INT_BAD, 257)),
    }
    c.must_raise |= c.kwargs["confidence"] in BAD_CONFIDENCE
    # The full motion's options, checked whatever the question (t_max = NaN passed "jarm").
    c.kwargs["t_max"] = real(d, c, 0.0, 10.0)
    c.kwargs["max_transitions"] = integer_param(d, c, (1, 5), (*INT_BAD, 10**6 + 1))
    if d.integer(0, 3) == 0:
        c.kwargs["rtol"] = d.choice((1e-8, *(() if d.clean else (1.0, math.nan, 0.0))))
        c.kwargs["integrator"] = text_param(d, c, ("RK45", "Vern9"))
        c.must_raise |= c.kwargs["rtol"] != 1e-8 or c.kwargs["integrator"] not in ("RK45", "Vern9")
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    if d.integer(0, 2) == 0:
        c.kwargs["restitution"] = real(d, c, 0.0, 1.0)
    if d.integer(0, 2) == 0:  # n (d + 2) runs: n stays small (64 at most)
        c.kwargs["indices"] = flag(d, c)
    return c


_RUN: list[eccjump.RollResult] = []


def dense_run() -> eccjump.RollResult:
    if not _RUN:
        _RUN.append(eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0, dense_output=True))
    return _RUN[0]


def case_to_si(d: Drawer) -> Case:
    c = Case("to_si", dense_run().to_si, params=("units", "g", "R", "M"), check=check_si)
    if d.integer(0, 4) == 0:
        c.args = (d.choice((eccjump.Units(), None, "SI", 9.81)),)
        c.must_raise = c.args[0] not in (None,) and not isinstance(c.args[0], eccjump.Units)
    else:
        c.kwargs = {k: real(d, c, 1e-3, 1e3) for k in ("g", "R", "M")}
    return c


def _times(d: Drawer, c: Case) -> Any:
    r = dense_run()
    return array(d, c, float(r.t[0]), float(r.t[-1]), max_size=4)


def case_sol(d: Drawer) -> Case:
    c = Case("sol", dense_run().sol, params=("t",), check=check_states)
    c.args = (_times(d, c),)
    return c


def case_kinematics(d: Drawer) -> Case:
    c = Case("sol.kinematics", dense_run().sol.kinematics, params=("t",), check=check_kinematics)
    c.args = (_times(d, c),)
    return c


def case_alpha_intervals(d: Drawer) -> Case:
    c = Case(
        "alpha_intervals", eccjump.alpha_intervals,
        params=("chi", "km", "mu_s", "n", "rule", "n_scan", "n_threads", "shapes"),
        check=check_intervals,
    )  # fmt: skip
    chi, km = array(d, c, 0.0, 1.0, max_size=2), array(d, c, 0.0, 0.5, max_size=2)
    c.args = (chi, km, real(d, c, 0.0, 3.0), turn(d, c))
    c.kwargs = {
        "rule": text_param(d, c, ("paper", "normal_force")),
        "n_scan": integer_param(
            d, c, (2, 10, 40), (1, -1, 2.5, True, None, 10**5 + 1, 10**9, 10**400, 2**64)
        ),
        "n_threads": threads(d, c),
    }
    c.info = {"chi": chi, "km": km, "points": ("chi", "km")}
    return c


def case_mu_s_min_path(d: Drawer) -> Case:
    c = Case(
        "mu_s_min_path", eccjump.mu_s_min_path,
        params=("alpha", "chi", "km", "n", "rule", "n_threads", "shapes"), check=check_mu_min,
    )  # fmt: skip
    alpha, chi = array(d, c, 0.0, HALF_PI, max_size=3), array(d, c, 0.0, 1.0, max_size=3)
    km = array(d, c, 0.0, 0.5, max_size=3)
    c.args = (alpha, chi, km, turn(d, c))
    c.kwargs = {"rule": text_param(d, c, ("paper", "normal_force")), "n_threads": threads(d, c)}
    c.info = {"alpha": alpha, "chi": chi, "km": km, "points": ("alpha", "chi", "km")}
    return c


def case_alpha_interval_around(d: Drawer) -> Case:
    c = Case(
        "alpha_interval_around", alpha_interval_around,
        params=("seed", "chi", "km", "mu_s", "n", "rule", "step", "n_threads", "shapes"),
        check=check_around,
    )  # fmt: skip
    c.args = (
        array(d, c, 0.0, HALF_PI, max_size=3),
        array(d, c, 0.0, 1.0, max_size=3),
        array(d, c, 0.0, 0.5, max_size=3),
        real(d, c, 0.0, 3.0),
        turn(d, c),
    )
    c.kwargs = {
        "rule": text_param(d, c, ("paper", "normal_force")),
        "step": real(d, c, 1e-6, 0.1),
        "n_threads": threads(d, c),
    }
    return c


#: closed_form functions: name -> (array inputs with ranges, takes n, takes theta0/omega0).
A = ("alpha", 0, HALF_PI)
CHI, KM, MU = ("chi", 0, 1), ("km", 0, 0.5), ("mu_s", 0, 3)
TH, TJ = ("theta", 0, 13), ("theta_J", 5, 6.3)
CLOSED_FORMS: dict[str, tuple[tuple[tuple[str, float, float], ...], str, bool]] = {
    "jump_forces": ((A, CHI, KM, TJ), "", False),
    "mu": ((CHI, KM, TJ), "", False),
    "green_turn": ((A, ("theta_J", 0, 13)), "", False),
    "in_green_interval": ((A, ("theta_J", 0, 13)), "optional", False),
    "mu_s_min": ((CHI, KM), "", False),
    "theta_J_range": ((CHI, KM, MU), "required", False),
    "alpha_min": ((CHI, KM, MU), "required", False),
    "gamma": ((CHI, KM), "", False),
    "J": ((TH, A, CHI, KM), "", False),
    "liftoff_function": ((TH, A, CHI, KM), "", True),
    "J_brackets": ((A, CHI, KM), "required", False),
    "theta_nJ": ((A, CHI, KM), "required", False),
    "path_forces": ((TH, A, CHI, KM), "", True),
}  # fmt: skip


def case_closed_form(d: Drawer) -> Case:
    name = d.choice(sorted(CLOSED_FORMS))
    inputs, n_kind, theta = CLOSED_FORMS[name]
    params = (*(i[0] for i in inputs), "n", "theta0", "omega0", "shapes")
    c = Case(
        f"closed_form.{name}", getattr(closed_form, name), params=params, check=check_pointwise
    )
    c.args = tuple(array(d, c, lo, hi) for _, lo, hi in inputs)
    if n_kind:
        n = turn(d, c, allow_none=True)
        if n is None and n_kind == "required":
            c.must_raise = True
        c.kwargs["n"] = n
    if theta:
        c.kwargs["theta0"] = real(d, c, -7.0, 7.0)
        c.kwargs["omega0"] = real(d, c, 0.0, 3.0)
    c.info = {
        **dict(zip((i[0] for i in inputs), c.args, strict=True)),
        "points": tuple(i[0] for i in inputs),
    }
    return c


def case_cylinder(d: Drawer) -> Case:
    k = d.integer(0, 2)
    if k == 0:
        c = Case("Cylinder", eccjump.Cylinder, params=("chi", "km"), check=check_cylinder)
        c.args = (real(d, c, 0.0, 1.0), real(d, c, 0.0, 1.0))
    elif k == 1:
        c = Case(
            "Cylinder.from_inertia", eccjump.Cylinder.from_inertia,
            params=("M", "R", "d", "I_C"), check=check_cylinder,
        )  # fmt: skip
        c.args = tuple(real(d, c, 0.0, 2.0) for _ in range(4))
    else:
        c = Case(
            "Cylinder.from_shell_and_line", eccjump.Cylinder.from_shell_and_line,
            params=("m_C", "m_P", "R", "d"), check=check_cylinder,
        )  # fmt: skip
        c.args = tuple(real(d, c, 0.0, 2.0) for _ in range(4))
    return c


def case_units(d: Drawer) -> Case:
    c = Case("Units", eccjump.Units, params=("g", "R", "M"), check=check_units)
    c.kwargs = {k: real(d, c, 1e-3, 1e3) for k in ("g", "R", "M")}
    return c


_TMP: list[Path] = []


def tmpdir() -> Path:
    if not _TMP:
        _TMP.append(Path(tempfile.mkdtemp(prefix="eccjump-fuzz-")))
        atexit.register(shutil.rmtree, _TMP[0], ignore_errors=True)
    return _TMP[0]


def case_store(d: Drawer) -> Case:
    where = tmpdir()
    if d.integer(0, 1):
        c = Case("store.save", store.save, params=("obj", "path", "attrs"), allow_oserror=True)
        reg = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.2], km_frac=[0.1])
        obj = d.choice((reg, reg, None, 3, "map"))
        path = d.choice(
            (
                where / "m.npz",
                str(where / "m.npz"),
                where / "m.txt",
                None,
                5,
                b"m.npz",
                where / "no" / "m.npz",
            )
        )
        attrs = d.choice((None, {"note": "x"}, 3))
        c.must_raise = obj is not reg or not isinstance(path, str | Path) or attrs == 3
        c.args, c.kwargs, c.check = (obj, path), {"attrs": attrs}, check_any
    else:
        name, load = d.choice(
            (("classification.load", load_region), ("load_map", eccjump.load_map))
        )
        c = Case(name, load, params=("path",), allow_oserror=True, check=check_region)
        good = where / "load.npz"
        if not good.exists():
            store.save(eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.2], km_frac=[0.1]), good)
        path = d.choice(
            (
                *(good, str(good), None, 7, b"x.npz", where / "missing.npz", where / "x.csv"),
                *damaged_maps(where),
            )
        )
        c.must_raise = path not in (good, str(good))
        c.args = (path,)
        if isinstance(path, str | Path):  # a damaged file's error names the file
            c.params = ("path", Path(path).name)
    return c


def case_results(d: Drawer) -> Case:
    """``eccjump.load`` of a saved result, a map, or a path that is none (a foreign or
    damaged file, a wrong suffix, a wrong type); ``save`` of a result to a good or bad path,
    over a file of the user's with and without ``overwrite``."""
    where = tmpdir()
    run = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    good = saved_results(where, run)
    if d.integer(0, 1):
        c = Case("RollResult.save", run.save, params=("path", "overwrite"), allow_oserror=True)
        user = where / "user.json"
        user.write_text("{}")
        path = d.choice((where / "r2.json", where / "r2.nc", user, where / "r.txt", None, 5))
        overwrite = d.choice((False, True, True, None, "yes"))
        c.args, c.kwargs, c.check = (path,), {"overwrite": overwrite}, check_any
        refused = path == user and not overwrite  # the user's file stays
        bad_path = not isinstance(path, Path) or path.suffix == ".txt"
        c.must_raise = bad_path or not isinstance(overwrite, bool) or refused
        return c
    c = Case("load", eccjump.load, params=("path",), allow_oserror=True, check=check_any)
    path = d.choice((*good, None, 7, b"r.json", where / "missing.json", where / "r.txt",
                     *spoilt_results(where)))  # fmt: skip
    c.must_raise = path not in good
    c.args = (path,)
    if isinstance(path, Path):  # an error about a file names the file
        c.params = ("path", path.name)
    return c


def saved_results(where: Path, run: Any) -> tuple[Path, ...]:
    """A roll saved as .json and .nc, a region as .npz (made once in ``where``)."""
    paths = (where / "r.json", where / "r.nc", where / "reg.npz")
    if not all(p.exists() for p in paths):
        run.save(paths[0], overwrite=True)
        run.save(paths[1], overwrite=True)
        eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.2], km_frac=[0.1]).save(paths[2])
    return paths


def spoilt_results(where: Path) -> tuple[Path, ...]:
    """JSON that is no result: not JSON, no type, an unknown type, a type that does not
    match the fields, an array reference that leads nowhere, truncated."""
    text = (where / "r.json").read_text()
    doc = json.loads(text)
    spoilt = {
        "text.json": "hello",
        "untyped.json": "{}",
        "list.json": "[1, 2]",
        "bogus.json": json.dumps({**doc, "eccjump_type": "bogus"}),
        "wrong.json": json.dumps({**doc, "eccjump_type": "motion"}),
        "lost.json": json.dumps({**doc, "arrays": {}}),
        "cut.json": text[: len(text) // 2],
    }
    for name, content in spoilt.items():
        (where / name).write_text(content)
    return tuple(where / n for n in spoilt)


def damaged_maps(where: Path) -> tuple[Path, ...]:
    """JARM maps damaged as in issue 46, 6 and 7 (made once in ``where``): a bit flipped in
    the data of theta_J (.npz, .zarr), a chunk of theta_J deleted (.zarr), an alpha of 10 rad
    and a theta_J of -inf written with the raw library (.npz). Each must be refused."""
    names = ("flip.npz", "flip.zarr", "lost.zarr", "alpha.npz", "inf.npz")
    paths = tuple(where / n for n in names)
    if all(p.exists() for p in paths):
        return paths
    reg = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.1, 0.2], km_frac=[0.01, 0.1])
    lay = reg.to_layout()
    store.save(reg, paths[0], overwrite=True)
    data = bytearray(paths[0].read_bytes())
    data[data.find(reg.result.theta_J.tobytes()) + 5] ^= 0x10
    paths[0].write_bytes(bytes(data))
    for path in paths[1:3]:
        store.save(reg, path)
    chunk = paths[1] / "theta_J" / "c" / "0" / "0" / "0"
    data = bytearray(chunk.read_bytes())
    data[len(data) // 2] ^= 0x01
    chunk.write_bytes(bytes(data))
    (paths[2] / "theta_J" / "c" / "0" / "0" / "0").unlink()
    alpha = (("alpha",), np.array([0.5, 10.0]), {})
    deg = (("alpha",), np.degrees(alpha[1]), {})
    store.save_npz({**lay, "coords": {**lay["coords"], "alpha": alpha, "alpha_deg": deg}}, paths[3])
    theta = (lay["data_vars"]["theta_J"][0], np.full(reg.shape, -math.inf), {})
    store.save_npz({**lay, "data_vars": {**lay["data_vars"], "theta_J": theta}}, paths[4])
    return paths


def check_drawn(res: Any, case: Case) -> None:
    """``.plot(ax=ax)`` returns that Axes, drawn on; otherwise a Figure (closed at once)."""
    from matplotlib.figure import Figure

    given = case.kwargs.get("ax")
    if given is not None:
        expect(res is given and res.has_data(), f"ax= returned {type(res).__name__}")
        return
    import matplotlib.pyplot as plt

    plt.close(res)
    expect(isinstance(res, Figure), f"returned {type(res).__name__}")


def case_plot_target(d: Drawer) -> Case:
    """A result's ``.plot`` given where to draw: an Axes, an empty or used Figure, both, or
    something else (a TypeError naming ``ax`` or ``fig``)."""
    from matplotlib.figure import Figure

    reg = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.2], km_frac=[0.1])
    c = Case("Region.plot", reg.plot, params=("ax", "fig", "km_frac"), check=check_drawn)
    used = Figure()  # not pyplot's: nothing is left open when the call raises
    ax = used.subplots()
    empty = Figure()
    wrong_ax, wrong_fig = ("axes", 3, used, [ax], None), ("fig", 2.5, ax, [empty], None)
    c.kwargs = {"ax": d.choice((ax, ax, *wrong_ax)), "fig": d.choice((None, empty, *wrong_fig))}
    if c.kwargs["ax"] is not None:
        c.kwargs["km_frac"] = real_or_none(d, c, 0.0, 1.0)
    bad = (c.kwargs["ax"] not in (ax, None)) or (c.kwargs["fig"] not in (empty, None))
    c.must_raise = c.must_raise or bad or (c.kwargs["ax"] is ax and c.kwargs["fig"] is empty)
    return c


def case_plot(d: Drawer) -> Case:
    from eccjump import plot

    k = d.integer(0, 3)
    if k == 3:
        return case_plot_target(d)
    if k == 2:
        c = Case(
            "plot.fraction_map",
            plot.fraction_map,
            params=("smap", "optimum"),
            check=check_figure,
        )
        smap = eccjump.start_map(1.0, [0.0, 4.7], [0.0, 1.0], grid=3)
        opt = eccjump.optimal_start(1.0, grid=2, lattice=(3, 2), max_evaluations=400)
        c.args = (d.choice((smap, smap, None, "map")),)
        c.kwargs = {"optimum": d.choice((None, opt, opt, 3))}
        c.must_raise = c.args[0] is not smap or c.kwargs["optimum"] == 3
        return c
    if k == 0:
        c = Case(
            "plot.trajectory",
            plot.trajectory,
            params=("result", "n_points", "ratio_max"),
            check=check_figure,
        )
        c.args = (d.choice((dense_run(), None, "run")),)
        c.kwargs = {"n_points": integer_param(d, c, (2, 50), (1, 0.5, True, None, 10**400, 10**9))}
        c.must_raise = c.must_raise or c.args[0] is not dense_run()
    else:
        c = Case(
            "plot.region_map", plot.region_map, params=("region", "panels"), check=check_figure
        )
        reg = eccjump.region(mu_s=1.0, alpha=[0.5, 0.7], chi=[0.2], km_frac=[0.1])
        c.args = (d.choice((reg, None, 3)),)
        c.kwargs = {"panels": integer_param(d, c, (1, 2), (0, 2.5, True, None, 10**400))}
        c.must_raise = c.must_raise or c.args[0] is not reg
    return c


# --- initial conditions (eccjump.classification.starts) -------------------------------------------

START_PARAMS = (
    "mu_s", "theta0", "omega0", "grid", "rule", "n_threads", "omega_max", "lattice", "n_starts",
    "max_evaluations", "progress",
)  # fmt: skip


def _grid(d: Drawer, c: Case, good: Sequence[int] = (2, 3, 5)) -> Any:
    return integer_param(d, c, good, (1, 0, -3, 129, 2.5, True, None, 10**400, 2**64))


def check_fraction(res: Any, case: Case) -> None:
    expect(isinstance(res, float), "not a float")
    expect(0.0 <= res <= 1.0, f"fraction {res} outside [0, 1]")


def check_shares(res: Any, case: Case) -> None:
    expect(isinstance(res, dict) and set(res) == set(eccjump.Reason), "not a share per reason")
    vals = np.array(list(res.values()))
    expect(bool(((vals >= 0) & (vals <= 1)).all()), "a share outside [0, 1]")
    expect(abs(vals.sum() - 1.0) <= 1e-12, f"shares sum to {vals.sum()}")


def check_start_map(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.StartMap), "not a StartMap")
    nt, no = res.theta0.size, res.omega0.size
    expect(res.shares.shape == (nt, no, N_REASONS), f"shares of shape {res.shares.shape}")
    expect(bool(((res.theta0 >= 0) & (res.theta0 < 2 * math.pi)).all()), "theta0 not in [0, 2pi)")
    expect(bool(np.allclose(res.shares.sum(axis=2), 1.0, rtol=0, atol=1e-12)), "shares sum")
    expect(bool((res.impossible == (res.fraction == 0)).all()), "impossible != fraction == 0")


def check_optimum(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.OptimalStart), "not an OptimalStart")
    expect(0.0 <= res.theta0 < 2 * math.pi, f"theta0 {res.theta0} not in [0, 2pi)")
    expect(0.0 <= res.omega0 <= res.omega_max, f"omega0 {res.omega0} out of [0, omega_max]")
    for k in ("fraction", "fraction_coarse", "fraction_at_rest"):
        expect(0.0 <= getattr(res, k) <= 1.0, f"{k} outside [0, 1]")
    for k in ("theta0_err", "omega0_err", "fraction_err", "step_theta0", "step_omega0"):
        v = getattr(res, k)
        expect(math.isfinite(v) and v >= 0, f"{k} = {v}")
    expect(res.fraction_err == abs(res.fraction - res.fraction_coarse), "fraction_err")
    expect(1 <= res.evaluations <= int(case.kwargs["max_evaluations"]), "evaluations")


def case_jarm_fraction(d: Drawer) -> Case:
    shares = d.integer(0, 1) == 1
    fn = eccjump.reason_shares if shares else eccjump.jarm_fraction
    c = Case(fn.__name__, fn, params=START_PARAMS,
             check=check_shares if shares else check_fraction)  # fmt: skip
    c.args = (
        real(d, c, 0.0, 3.0),
        d.pick(lambda: real(d, c, -7.0, 7.0), *(() if d.clean else (1e15, -1e300, 2 * math.pi))),
        d.pick(lambda: real(d, c, 0.0, 3.0), *(() if d.clean else (1e7, -1.0))),
    )
    c.kwargs = {
        "grid": _grid(d, c),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "n_threads": threads(d, c),
    }
    return c


def case_start_map(d: Drawer) -> Case:
    c = Case("start_map", eccjump.start_map, params=(*START_PARAMS, "shapes"),
             check=check_start_map)  # fmt: skip
    c.args = (
        real(d, c, 0.0, 3.0),
        array(d, c, -7.0, 7.0, max_size=3),
        array(d, c, 0.0, 3.0, max_size=3),
    )
    c.kwargs = {
        "grid": _grid(d, c, (2, 3)),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "n_threads": threads(d, c),
    }
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    if d.integer(0, 5) == 0 and not d.clean:
        c.args = (c.args[0], np.zeros(101), np.zeros(100))  # past the bound of starts
    return c


def case_optimal_start(d: Drawer) -> Case:
    c = Case("optimal_start", eccjump.optimal_start, params=START_PARAMS, check=check_optimum)
    c.args = (real(d, c, 0.0, 3.0),)
    lattice: Any = (
        integer_param(d, c, (2, 3, 4), (1, 1001, 2.5, True, None, 10**400)),
        integer_param(d, c, (2, 3), (1, 1001, 2.5, True, None)),
    )
    if d.integer(0, 6) == 0 and not d.clean:
        lattice = d.choice(((3,), "ab", None, 3, (2, 2, 2)))
        c.must_raise = True
    c.kwargs = {
        "grid": _grid(d, c, (2, 3)),
        "omega_max": real(d, c, 1e-3, 4.0),
        "lattice": lattice,
        "n_starts": integer_param(d, c, (1, 2), (0, 51, 2.5, True, None, 10**400)),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "n_threads": threads(d, c),
        "max_evaluations": integer_param(
            d, c, (1, 20, 400), (0, -1, 2.5, True, None, 10**5 + 1, 10**400)
        ),
    }
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    return c


DESIGN_PARAMS = (
    "alpha_range", "mu_s", "mu_s_err", "target", "body", "km_range", "rod_range", "radius",
    "mass", "g", "max_turns", "error", "grid", "min_apex", "tolerances", "maximise", "samples",
    "seed", "shapes", "progress", "p_target",
)  # fmt: skip


def check_design(res: Any, case: Case) -> None:
    import json

    expect(isinstance(res, eccjump.Design), "not a Design")
    lo, hi = (float(x) for x in case.info["alpha_range"])
    expect(lo - 1e-12 <= res.alpha <= hi + 1e-12, "alpha outside alpha_range")
    expect(res.score >= 0 and not math.isnan(res.score), f"score {res.score}")
    expect(all((m.margin >= 0 and m.lo < m.value < m.hi) or m.margin == 0 for m in res.margins),
           "a margin does not hold its value")  # fmt: skip
    target_ok = {"jarm": {"JARM"}, "slip": {"SLIP_BEFORE", "SLIP_AT_JUMP"}}[res.target]
    expect(set(res.reasons.values()) <= target_ok, f"verdict {res.reasons}")
    expect(isinstance(res.sheet(), str) and bool(res.sheet()), "no sheet")
    json.dumps(res.to_dict(), allow_nan=False)
    least = case.kwargs.get("min_apex", 0.0)
    if least > 0:  # the designed flights fly that high (in m with a radius, as min_apex)
        expect(min(f.apex for f in res.flights) >= least, f"apex below min_apex {least}")
    odds = res.p_success
    expect(
        (odds is None) == (case.kwargs.get("tolerances") is None), "p_success without tolerances"
    )
    if odds is not None:
        expect(0.0 <= odds.low <= odds.p <= odds.high <= 1.0, f"p_success {odds}")
    goal = case.kwargs.get("p_target")
    expect((res.p_jarm is None) == (goal is None), "p_jarm without p_target")
    if goal is not None:  # the design reaches its target by the Wilson lower bound
        expect(res.p_jarm.low >= float(goal), f"p_jarm {res.p_jarm} below p_target {goal}")


def _pair(d: Drawer, c: Case, lo: float, hi: float) -> Any:
    k = d.integer(0, 6)
    a, b = sorted((real(d, c, lo, hi, bad=False), real(d, c, lo, hi, bad=False)), key=_key)
    if k <= 3 or d.clean:
        x, y = sorted(lo + (hi - lo) * d.integer(0, 20) / 20 for _ in range(2))
        return (x, y) if k != 3 else np.array([x, y])
    if k == 4:
        return (b, a)
    if k == 5:
        return d.choice(((lo,), (lo, hi, hi), "ab", (lo, None), [[lo, hi]]))
    return wrong(d, c)


def _key(v: Any) -> float:
    try:
        return float(v)
    except (TypeError, ValueError, OverflowError):
        return math.nan


def case_design(d: Drawer) -> Case:
    c = Case("design", eccjump.design, params=DESIGN_PARAMS, check=check_design)
    alpha_range = _pair(d, c, 0.0, HALF_PI)
    c.args = (alpha_range, real(d, c, 0.05, 2.0), real(d, c, 0.0, 0.2))
    c.info["alpha_range"] = alpha_range if c.must_raise else (0.0, HALF_PI)
    if not c.must_raise:
        try:
            c.info["alpha_range"] = tuple(float(x) for x in alpha_range)
        except (TypeError, ValueError, OverflowError):
            pass
    c.kwargs = {
        "target": text_param(d, c, ("jarm", "slip")),
        "max_turns": integer_param(d, c, (1, 2, 3), (*INT_BAD, 1001)),
        "grid": integer_param(d, c, (4, 5), (*INT_BAD, 3, 65, 10**6)),
    }
    if d.integer(0, 2) == 0:
        was = c.must_raise
        c.kwargs["body"] = _body(d, c)
        if c.kwargs["body"] is None:  # design's default (search the body): not a wrong type
            c.must_raise = was
    else:
        c.kwargs["km_range"] = _pair(d, c, 0.0, 0.95)
        c.kwargs["rod_range"] = _pair(d, c, 0.0, 1.0)
    if d.integer(0, 2) == 0:
        c.kwargs["radius"] = real(d, c, 1e-3, 1.0)
        if d.integer(0, 4):
            c.kwargs["mass"] = real(d, c, 1e-3, 10.0)
    if d.integer(0, 3) == 0:
        c.kwargs["error"] = real(d, c, 0.0, 0.5)
    if d.integer(0, 4) == 0:
        c.kwargs["g"] = real(d, c, 1.0, 20.0)
    if d.integer(0, 4) == 0:
        c.kwargs["min_apex"] = real(d, c, 0.0, 0.02)
    if d.integer(0, 3) == 0:
        names = d.choice((("alpha",), ("chi", "km"), ("mu_s", "alpha")))
        c.kwargs["tolerances"] = {k: real(d, c, 0.0, 0.05) for k in names}
        c.kwargs["maximise"] = text_param(d, c, ("margin", "probability"))
        c.kwargs["samples"] = integer_param(d, c, (100, 300), (*INT_BAD, 99, 10**6 + 1))
        target = c.kwargs["target"]
        if d.integer(0, 1) and isinstance(target, str) and target == "jarm":  # a P(JARM)
            c.kwargs["p_target"] = real_or_none(d, c, 0.0, 1.0)
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    return c


def check_build(res: Any, case: Case) -> None:
    expect(isinstance(res, Build), "not a Build")
    expect(all(math.isfinite(x) and x >= 0 for x in res), f"non-finite or negative: {res}")
    body = case.args[0]
    expect(abs(res.d - body.chi * res.radius) <= 1e-12 * res.radius, "d != chi R")


def case_build(d: Drawer) -> Case:
    c = Case("build", eccjump.build, params=("body", "radius", "mass"), check=check_build)
    c.args = (_body(d, c),)
    c.kwargs = {k: real(d, c, 1e-3, 1e3) for k in ("radius", "mass") if d.integer(0, 1)}
    return c


# --- the explorer (eccjump.explore, and the requests of its page) ---------------------------

EXPLORE_PARAMS = (
    "alpha", "chi", "km", "mu_s", "mu_k", "restitution", "theta0", "omega0", "rule", "t_max",
)  # fmt: skip
#: The explorer's sliders in the Python API's units (radians).
EXPLORE_RANGES = (
    ("alpha", 0.0, HALF_PI), ("chi", 0.0, 1.0), ("km", 0.0, 1.0), ("mu_s", 0.0, 3.0),
    ("restitution", 0.0, 1.0), ("theta0", -math.pi, math.pi), ("omega0", 0.0, 3.0),
    ("t_max", 2.0, 60.0),
)  # fmt: skip


def _in_slider_ranges(values: dict[str, Any]) -> None:
    from eccjump.explorer import controls

    for c in controls.CONTROLS:
        if c.key in values:
            v = float(values[c.key])
            expect(c.lo <= v <= c.hi, f"{c.key} = {v} outside the slider [{c.lo}, {c.hi}]")


def check_explore(res: Any, case: Case) -> None:
    params = getattr(res, "params", None)
    expect(isinstance(params, dict), "not the explorer widget")
    expect(all(isinstance(v, str) for v in params.values()), "params are not strings")
    expect(params.get("rule") in ("paper", "normal_force"), f"rule {params.get('rule')}")
    expect(params.get("tie") == ("1" if case.kwargs.get("mu_k") is None else "0"), "tie")
    _in_slider_ranges(params)


def case_explore(d: Drawer) -> Case:
    c = Case("explore", eccjump.explore, params=EXPLORE_PARAMS, check=check_explore)
    c.kwargs = {k: real(d, c, lo, hi) for k, lo, hi in EXPLORE_RANGES if d.integer(0, 2)}
    if d.integer(0, 2) == 0:
        c.kwargs["mu_k"] = None if d.integer(0, 1) else real_or_none(d, c, 0.0, 3.0)
    if d.integer(0, 2) == 0:
        c.kwargs["rule"] = text_param(d, c, ("paper", "normal_force"))
    return c


#: What a message of the page's requests may name (the query's keys, and k_m in words).
EXPLORE_API_PARAMS = (*EXPLORE_PARAMS, "k_m", "tie", "request")


def check_explore_api(res: Any, case: Case) -> None:
    import json

    status, body = res
    json.dumps(body, allow_nan=False)
    expect(status in (200, 400, 404), f"status {status}")
    if status != 200:
        expect(set(body) == {"error"}, f"an error with more than its message: {set(body)}")
        msg = body["error"]
        expect(len(msg) <= MAX_MESSAGE, f"message of {len(msg)} characters")
        expect(message_names(msg, EXPLORE_API_PARAMS), f"message names nothing: {msg[:150]}")
        return
    endpoint = case.args[0]
    if endpoint == "region":
        expect(len(body["codes"]) == body["n"] ** 2, "region: not n x n codes")
        expect(0 <= body["jarm_fraction"] <= 1, "region: fraction")
        _in_slider_ranges(body["params"])
    elif endpoint == "motion":
        n = len(body["t"])
        for k in ("theta", "cx", "cy", "gx", "gy", "mode"):
            expect(len(body[k]) == n, f"motion: {k} has another length than t")
        expect(all(v is not None for k in ("theta", "cx", "cy") for v in body[k]), "NaN state")
        expect(set(body["mode"]) <= {0, 1, 2}, "motion: mode codes")
        p = body["params"]
        _in_slider_ranges(p)
        valid = p["mu_k"] <= p["mu_s"] and p["km"] <= 1 - p["chi"] + 1e-12
        expect(valid, "an impossible point ran")


def case_explore_api(d: Drawer) -> Case:
    from eccjump.explorer import api, controls

    c = Case("explorer.api.handle", api.handle, params=EXPLORE_API_PARAMS, check=check_explore_api)
    query: dict[str, str] = {}
    for ctl in controls.CONTROLS:
        if d.integer(0, 2):
            query[ctl.key] = cli_number(d, ctl.lo, ctl.hi)
    if d.integer(0, 2) == 0:
        query["rule"] = d.choice(("paper", "normal_force", "PAPER", ""))
    if d.integer(0, 2) == 0:
        query["tie"] = d.choice(("0", "1", "yes"))
    if d.integer(0, 5) == 0:
        query[d.choice(("zzz", "", "alpha "))] = "1"
    c.args = (d.choice(("motion", "motion", "region", "controls", "bogus")), query)
    return c


# --- the explorer's server (raw requests to 127.0.0.1, through a socket) --------------------

#: Statuses the explorer's server may answer: its routes (200, 400 a bad query, 404), the
#: refusal of another host (403), and the standard library's refusals of a bad request (400,
#: 414 too long a line, 431 too long or too many headers, 501 a method other than GET, 505 an
#: unknown HTTP version).
HTTP_STATUSES = {200, 400, 403, 404, 414, 431, 501, 505}
HTTP_TARGETS = (
    "/", "/index.html", "/explorer.js", "/explorer.css", "/api/controls", "/api/region",
    "/api/motion", "/api/motion", "/api/uncertainty", "/api/", "/api/nope", "/nope",
    "/../pyproject.toml", "/%2e%2e/%2e%2e/pyproject.toml", "/static/../server.py",
    "/api/..%2f..%2fcli",
    "//evil.example/api/controls", "http://evil.example/api/controls", "*", "/\x00", "/%ff",
)  # fmt: skip
#: Host headers: this server's names (PORT becomes the server's port), then other hosts.
LOCAL_HOSTS = ("127.0.0.1:PORT", "localhost:PORT", "[::1]:PORT", "LocalHost:PORT", "127.0.0.1")
FOREIGN_HOSTS = (
    "evil.example", "evil.example:PORT", "127.0.0.1:1", "127.0.0.1.evil.example:PORT",
    "localhost.:PORT", "0.0.0.0:PORT", "",
)  # fmt: skip


def http_exchange(port: int, request: bytes, timeout: float = 10.0) -> tuple[int, bytes]:
    """Send ``request`` (raw bytes) to 127.0.0.1:``port`` and read until the server closes:
    (status, body). Status 0: it closed without an answer; -1: no status line."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        try:
            s.sendall(request)
        except (BrokenPipeError, ConnectionResetError):
            pass  # refused before all of it was read: its answer may be waiting
        answer = b""
        try:
            while chunk := s.recv(65536):
                answer += chunk
        except ConnectionResetError:
            pass  # closed with bytes of ours unread (a body it does not read), after answering
    if not answer:
        return 0, b""
    head, _, body = answer.partition(b"\r\n\r\n")
    status = re.match(rb"HTTP/1\.[01] (\d{3}) ", head)
    return (int(status.group(1)) if status else -1), body


_HTTP: dict[str, Any] = {}


def explorer_server() -> tuple[int, list[Any]]:
    """A server of the explorer for this process, started on first use: (port, the errors
    it would print a traceback for: none is allowed)."""
    if not _HTTP:
        from eccjump.explorer.server import ExplorerServer

        srv = ExplorerServer(0).start()
        errors: list[Any] = []
        report = srv._httpd.handle_error

        def record(request: Any, address: Any) -> None:
            if not isinstance(sys.exc_info()[1], OSError):  # OSError: a client gone, quiet
                errors.append(sys.exc_info()[1])
            report(request, address)

        srv._httpd.handle_error = record  # type: ignore[method-assign]
        atexit.register(srv.stop)
        _HTTP.update(port=srv.port, errors=errors)
    return _HTTP["port"], _HTTP["errors"]


def explore_http(request: bytes) -> tuple[int, bytes, int]:
    """Send ``request`` to the explorer's server (PORT in it becomes the port): (status,
    body, the status of a plain request right after it)."""
    port, _ = explorer_server()
    status, body = http_exchange(port, request.replace(b"PORT", str(port).encode()))
    after = f"GET /api/controls HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode()
    return status, body, http_exchange(port, after)[0]


def check_explore_http(res: Any, case: Case) -> None:
    status, body, after = res
    expect(status in HTTP_STATUSES, f"status {status}: {body[:80]!r}")
    expect(after == 200, f"the next request got {after}")
    expect(not explorer_server()[1], f"the server failed: {explorer_server()[1][:1]}")
    if status != 200:
        expect(len(body) <= 300 and b"Traceback" not in body, f"error body {body[:80]!r}")
    if case.info["foreign"]:
        expect(status not in (200, 404, 501), f"another host got {status}: no route may run")
    elif status == 403:
        expect(case.info["origin"], f"this server's host was refused: {body[:80]!r}")


def case_explore_http(d: Drawer) -> Case:
    c = Case("explorer.server", explore_http, check=check_explore_http)
    target = d.choice(HTTP_TARGETS)
    if target.startswith("/api/") and d.integer(0, 1):
        values = (cli_number(d, -10, 100), "%ff", "%00", "9" * d.integer(1, 3000), "a&b=c")
        target += "?" + "&".join(f"{k}={d.choice(values)}" for k in ("alpha", "chi", "km"))
    method = d.choice(("GET",) * 6 + ("HEAD", "POST", "PUT", "G\x00T", "get"))
    version = d.choice(("HTTP/1.1",) * 4 + ("HTTP/1.0", "HTTP/9.9", "HTTP/1", "FTP/1.0", ""))
    hosts = [h for h in [d.choice(LOCAL_HOSTS * 2 + FOREIGN_HOSTS)] if h]
    if d.integer(0, 5) == 0:
        hosts.append(d.choice(LOCAL_HOSTS + FOREIGN_HOSTS))  # two Host headers
    lines = [f"{method} {target} {version}".rstrip(), *(f"Host: {h}" for h in hosts)]
    origin = d.choice((None,) * 4 + ("http://127.0.0.1:PORT", "http://evil.example", "null"))
    if origin is not None:
        lines.append(f"Origin: {origin}")
    if d.integer(0, 5) == 0:
        size = d.choice((1, 100, 70000))  # past 65536: too long a line; past 100: too many
        lines += [f"X-{i}: {'v' * size}" for i in range(d.integer(1, 120))]
    body = b""
    if d.integer(0, 5) == 0:
        body = d.choice((b"{bad json", b"\xff" * 5000, b"{}"))
        lines.append(f"Content-Length: {d.choice((len(body), 10**12, -1))}")
    c.args = ("\r\n".join(lines).encode("latin-1") + b"\r\n\r\n" + body,)
    c.info["foreign"] = len(hosts) != 1 or hosts[0] not in LOCAL_HOSTS
    c.info["origin"] = origin not in (None, "http://127.0.0.1:PORT")
    return c


# --- the command line ----------------------------------------------------------------------


def cli_number(d: Drawer, lo: float, hi: float) -> str:
    k = d.integer(0, 6)
    if k <= 3:
        return repr(lo + (hi - lo) * d.integer(0, 1000) / 1000)
    if k == 4:
        return d.choice(("nan", "inf", "-inf", "1e400", "-0", "5e-324", "1e300"))
    if k == 5:
        return d.choice(("abc", "", "0x10", "1,5", "True", "None", "1j"))
    return repr(d.choice((lo, hi)))


def cli_roll_argv(d: Drawer) -> list[str]:
    argv = ["roll", "--alpha", cli_number(d, 0, 90), "--chi", cli_number(d, 0, 1)]
    argv += ["--km", cli_number(d, 0, 0.5)]
    for opt, lo, hi in (
        ("--mu-s", 0, 3),
        ("--theta0", -360, 360),
        ("--omega0", 0, 3),
        ("--t-max", 0, 50),
        ("--rtol", 1e-12, 1e-3),
    ):
        if d.integer(0, 2) == 0:
            argv += [opt, cli_number(d, lo, hi)]
    cli_integrator(d, argv)
    if d.integer(0, 1):
        argv.append("--json")
    return argv


def cli_integrator(d: Drawer, argv: list[str]) -> None:
    """Sometimes ``--integrator``, a good or a bad pair."""
    if d.integer(0, 2) == 0:
        argv += ["--integrator", d.choice((*INTEGRATORS, *INTEGRATORS, "rk45", "", "RK4"))]


def cli_map_argv(d: Drawer) -> list[str]:
    out = tmpdir() / f"map{d.integer(0, 3)}{d.choice(('.npz', '.npz', '.txt'))}"
    argv = ["map", "--mu-s", cli_number(d, 0, 3), "-o", str(out), "--overwrite", "-q"]
    argv += ["--grid", d.choice(("2", "3", "0", "-1", "2.5", "x"))]
    for opt, lo, hi in (
        ("--alpha-min", 0, 45),
        ("--alpha-max", 45, 90),
        ("--chi-max", 0, 1),
        ("--theta0", -360, 360),
        ("--omega0", 0, 3),
    ):
        if d.integer(0, 2) == 0:
            argv += [opt, cli_number(d, lo, hi)]
    if d.integer(0, 2) == 0:
        argv += ["--n", d.choice(("1", "2", "0", "1.5", "99999999999"))]
    if d.integer(0, 2) == 0:
        argv += ["--threads", d.choice(("0", "1", "-1", "2.5", "99999999999999999999999"))]
    if d.integer(0, 2) == 0:
        argv += ["--max-turns", d.choice(("1", "5", "0", "4294967296", "1000001"))]
    if d.integer(0, 2) == 0:
        argv += ["--route", d.choice(("ode", "closed-form", "x"))]
    if d.integer(0, 4) == 0:
        argv += ["--stop-at-slip"]
    cli_integrator(d, argv)
    if d.integer(0, 2) == 0:  # the full motion, with its own options
        argv += ["--kind", d.choice(("motion", "motion", "x"))]
        for opt, lo, hi in (("--mu-k", 0, 3), ("--restitution", 0, 1), ("--t-max", 0, 30)):
            if d.integer(0, 2) == 0:
                argv += [opt, cli_number(d, lo, hi)]
        if d.integer(0, 2) == 0:
            argv += ["--max-transitions", d.choice(("1", "5", "0", "99999999999"))]
    return argv


#: The options of ``eccjump map`` that belong to one --kind (given with the other: exit 2).
MAP_KIND_OPTIONS = {
    "jarm": ("--n", "--route", "--max-turns", "--stop-at-slip"),
    "motion": ("--mu-k", "--restitution", "--t-max", "--max-transitions"),
}


def cli_uncertainty_argv(d: Drawer) -> list[str]:
    """A small study (64 samples), with bad spreads, confidences and outputs among them."""
    argv = ["uncertainty", "--chi", cli_number(d, 0, 1), "--km", "0.02", "--alpha", "40"]
    argv += ["--mu-s", cli_number(d, 0, 2), "-n", d.choice(("64", "64", "0")), "-q"]
    argv += ["--sd", d.choice(("chi", "alpha", "bogus")), d.choice(("0.01", "0.01", "1e300"))]
    if d.integer(0, 2) == 0:
        argv += ["--confidence", d.choice(("0.9", "1", "0.9999999999999999", "nan", "0"))]
    if d.integer(0, 3) == 0:
        argv += ["--question", "motion", "--t-max", d.choice(("5", "nan", "0"))]
    if d.integer(0, 2) == 0:
        name = d.choice(("u.csv", "u.nc", "x" * 300 + ".csv", "no/such/u.csv", "u.txt"))
        argv += ["-o", str(tmpdir() / name)]
        if d.integer(0, 1):
            argv.append("--overwrite")
    if d.integer(0, 1):
        argv.append("--json")
    if d.integer(0, 2) == 0:
        argv.append("--indices")
    return argv


def cli_starts_argv(d: Drawer) -> list[str]:
    argv = ["starts", "--mu-s", cli_number(d, 0, 3), "-q", "--lattice", "3", "2"]
    argv += ["--grid", d.choice(("2", "3", "0", "65", "x"))]
    argv += ["--map-grid", d.choice(("2", "3", "1")), "--map-size", "3", "2"]
    if d.integer(0, 2) == 0:
        argv += ["--omega-max", cli_number(d, 0, 3)]
    if d.integer(0, 3) == 0:
        argv.append("--no-map")
    if d.integer(0, 5) == 0:
        argv += ["-o", str(tmpdir() / d.choice(("x" * 300, "no/such")))]
    if d.integer(0, 1):
        argv.append("--json")
    return argv


def cli_design_argv(d: Drawer) -> list[str]:
    """A cheap design (grid 4, two turns, often a fixed body)."""
    argv = ["design", "--alpha-range", cli_number(d, 0, 45), cli_number(d, 45, 90)]
    argv += ["--mu-s", cli_number(d, 0, 2), "--grid", d.choice(("4", "4", "3", "x"))]
    argv += ["--max-turns", d.choice(("2", "2", "0"))]
    if d.integer(0, 1):
        argv += ["--chi", cli_number(d, 0, 1), "--km", cli_number(d, 0, 0.5)]
    for opt, lo, hi in (("--mu-s-err", 0, 0.3), ("--radius", 0, 1), ("--mass", 0, 2)):
        if d.integer(0, 3) == 0:
            argv += [opt, cli_number(d, lo, hi)]
    if d.integer(0, 2) == 0:
        argv += ["--target", d.choice(("jarm", "slip", "fly"))]
    if d.integer(0, 3) == 0:
        argv += ["--sd", d.choice(("chi", "alpha", "mu_k")), cli_number(d, 0, 0.05)]
        argv += ["--samples", d.choice(("100", "200", "99"))]
        argv += ["--maximise", d.choice(("margin", "probability", "odds"))]
        if d.integer(0, 1):  # the map's form of --sd, and a P(JARM) to reach
            argv += ["--sd", d.choice(("km=0.01", "alpha=0.25,chi=0.002", "chi=x", "mu_k=1"))]
            argv += ["--p-target", cli_number(d, 0, 1)]
    if d.integer(0, 1):
        argv.append("--json")
    return argv


#: The options each subcommand takes (what an error message must name).
CLI_PARAMS = (
    "alpha", "chi", "km", "mu", "mu_s", "mu-s", "theta0", "omega0", "t_max", "t-max", "rtol",
    "atol", "theta_max", "grid", "n", "threads", "n_threads", "max_turns", "max-turns",
    "output", "-o", "alpha-min", "alpha-max", "chi-max", "range", "rule", "shapes", "kind",
    "mu_k", "mu-k", "restitution", "max_transitions", "max-transitions", "route",
    "omega-max", "omega_max", "lattice", "map-grid", "map-size",
    "alpha_range", "alpha-range", "mu_s_err", "mu-s-err", "radius", "mass", "target",
    "body", "g", "error", "km_range", "rod_range", "integrator", "sd", "samples", "maximise",
    "tolerances", "stop-at-slip", "confidence", "output", "overwrite", "outdir", "question",
)  # fmt: skip


def check_cli(res: Any, case: Case) -> None:
    code, out, err = res
    expect("Traceback" not in err, "a traceback on stderr: " + err.strip()[-150:])
    expect(code in (0, 1, 2), f"exit status {code}")
    argv = case.info["argv"]
    if case.info["cmd"] == "map":  # one rule for the options of the other --kind
        kind = argv[argv.index("--kind") + 1] if "--kind" in argv else "jarm"
        other = {"jarm": "motion", "motion": "jarm"}.get(kind)
        crossed = other is not None and any(o in argv for o in MAP_KIND_OPTIONS[other])
        expect(not crossed or code == 2, f"an option of --kind {other} passed with --kind {kind}")
    if code == 0:
        expect(bool(out.strip()) or case.info["cmd"] == "map", "no output")
        if "--json" in case.info["argv"] and case.info["cmd"] in ("roll", "starts"):
            import json

            s = json.loads(out)
            if case.info["cmd"] == "starts":
                expect(all(0 <= r["fraction"] <= 1 for r in s), "fraction outside [0, 1]")
            else:
                expect(s["status"] in (-1, 0, 1), "status")
    else:
        last = err.strip().splitlines()[-1] if err.strip() else ""
        expect(len(last) <= MAX_MESSAGE, f"error line of {len(last)} characters")
        if code == 2:
            expect(message_names(last, CLI_PARAMS), f"error names no option: {last[:150]}")


def run_cli_inprocess(argv: list[str]) -> tuple[int, str, str]:
    import contextlib
    import io

    from eccjump.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as e:  # argparse
            code = e.code if isinstance(e.code, int) else 2
        except Exception:
            import traceback

            traceback.print_exc()
            code = 1
    return code, out.getvalue(), err.getvalue()


def case_cli(d: Drawer) -> Case:
    cmd = d.choice(("roll", "roll", "map", "roll", "map", "starts", "design", "uncertainty"))
    make = {
        "roll": cli_roll_argv,
        "map": cli_map_argv,
        "starts": cli_starts_argv,
        "design": cli_design_argv,
        "uncertainty": cli_uncertainty_argv,
    }
    argv = make[cmd](d)
    return Case(
        f"cli.{cmd}", run_cli_inprocess, args=(argv,), params=CLI_PARAMS, check=check_cli,
        info={"cmd": cmd, "argv": argv},
    )  # fmt: skip


# --- analyze: tracked experiments, good and bad ------------------------------------------

ANALYZE_PARAMS = (
    "track", "radius", "chi", "km", "alpha", "marker_angle", "marker_radius",
    "scale", "g", "rule", "window", "design", "profile_mu_k", "t", "xc", "yc", "xm", "ym",
    "mu_s", "mu_s_err",
)  # fmt: skip
_ROLLING_TRACK: list[Any] = []


def rolling_track() -> Any:
    """A short track of a body that rolls and never leaves the ramp (120 fps, 0.5 px)."""
    if not _ROLLING_TRACK:
        from eccjump.studies.experiment.synthetic import synthetic_track

        st = synthetic_track(eccjump.Cylinder(0.1, 0.3), 0.2, mu_s=1.0, fps=120.0,
                             duration=0.25, noise_px=0.5, seed=1)  # fmt: skip
        _ROLLING_TRACK.append(st.track)
    return _ROLLING_TRACK[0]


def check_analysis(res: Any, case: Case) -> None:
    import json

    from eccjump.studies.experiment import VERDICTS

    expect(isinstance(res, eccjump.Analysis), "not an Analysis")
    expect(res.verdict in VERDICTS, f"verdict {res.verdict}")
    expect(res.verdict != "undetermined" or bool(res.reason), "undetermined without a reason")
    json.dumps(res.to_dict(), allow_nan=False)
    expect(len(repr(res).splitlines()) <= 24, "repr longer than a screen")
    if case.info.get("never_leaves"):
        expect(res.verdict == "undetermined", f"a track that never leaves is {res.verdict}")


#: How a track file is spoilt (or written in another dialect that reads the same). The first
#: group must read as the good track; the rest must be refused (a FIFO without blocking).
TRACK_DIALECTS = ("good", "good", "semicolon", "quoted", "utf16", "bom", "tabs", "crlf")
TRACK_SPOILINGS = ("nan", "inf", "unsorted", "repeated", "missing", "few", "text", "empty",
                   "extra-cell", "short-row", "fifo", "device", "directory", "sparse",
                   "long-line", "many-frames", "pixels")  # fmt: skip


def _bad_track_file(d: Drawer, c: Case) -> Path:
    """A CSV of the rolling track, in another dialect, or spoilt one way."""
    tr = rolling_track()
    cols = {"t": tr.t.copy(), "xc": tr.c[:, 0].copy(), "yc": tr.c[:, 1].copy(),
            "xm": tr.m[:, 0].copy(), "ym": tr.m[:, 1].copy()}  # fmt: skip
    how = d.choice(TRACK_DIALECTS + TRACK_SPOILINGS)
    name = d.choice(list(cols))
    k = d.integer(1, tr.n - 2)
    if how in ("nan", "inf"):
        cols[name][k] = math.nan if how == "nan" else math.inf
    elif how == "unsorted":
        cols["t"][[k, k + 1]] = cols["t"][[k + 1, k]]
    elif how == "repeated":
        cols["t"][k + 1] = cols["t"][k]
    elif how == "few":
        keep = d.integer(0, 11)
        cols = {n: v[:keep] for n, v in cols.items()}
    elif how == "missing":
        del cols[name]
    elif how == "pixels":  # a track in pixels, analysed without scale
        cols = {n: v if n == "t" else v * 1230.5 for n, v in cols.items()}
    elif how == "many-frames":
        from eccjump.studies.experiment.track import MAX_FRAMES

        reps = MAX_FRAMES // tr.n + 1
        span = tr.t[-1] - tr.t[0] + tr.dt
        cols = {n: np.concatenate([v + (span * r if n == "t" else 0) for r in range(reps)])
                for n, v in cols.items()}  # fmt: skip
    c.info["never_leaves"] = how in TRACK_DIALECTS
    path = Path(tempfile.mkdtemp(dir=tmpdir())) / f"track-{how}.csv"  # new: a replay too
    special = _special_track_file(how, path)
    if special is not None:
        return special
    rows = [list(cols)] + [[repr(float(v[i])) for v in cols.values()]
                           for i in range(len(next(iter(cols.values()))))]  # fmt: skip
    if how == "text":
        rows[min(3, len(rows) - 1)] = ["0.1", "abc", "1", "2", "3"]
    elif how == "extra-cell":
        rows[min(k, len(rows) - 1)].append("1")
    elif how == "short-row":
        rows[min(k, len(rows) - 1)].pop()
    _write_dialect(path, rows, how)
    return path


def _special_track_file(how: str, path: Path) -> Path | None:
    """The path of a file that is no table: empty, a FIFO, a device, a directory, a sparse
    file past the size limit, a line past the length limit; None for a table."""
    if how == "empty":
        path.write_text("")
    elif how == "fifo":
        os.mkfifo(path)
    elif how == "device":
        return Path(os.devnull)
    elif how == "directory":
        path.mkdir()
    elif how == "sparse":
        path.write_bytes(b"t,xc,yc,xm,ym\n")
        os.truncate(path, 2**40)  # 1 TB, sparse
    elif how == "long-line":
        path.write_text("t,xc,yc,xm,ym\n" + "1," * 40_000 + "\n")
    else:
        return None
    return path


def _write_dialect(path: Path, rows: list[list[str]], how: str) -> None:
    """``rows`` as CSV in the dialect ``how`` names (commas otherwise)."""
    delimiter = {"semicolon": ";", "tabs": "\t"}.get(how, ",")
    if how == "semicolon":  # with decimal commas
        rows = [[cell.replace(".", ",") for cell in row] for row in rows]
    if how == "quoted":
        rows = [[f'"{cell}"' for cell in row] for row in rows]
    end = "\r\n" if how == "crlf" else "\n"
    text = end.join(delimiter.join(row) for row in rows) + end
    encoding = {"utf16": "utf-16", "bom": "utf-8-sig"}.get(how, "utf-8")
    path.write_bytes(text.encode(encoding))


def case_analyze(d: Drawer) -> Case:
    c = Case("analyze", eccjump.analyze, params=ANALYZE_PARAMS, check=check_analysis)
    c.args = (_bad_track_file(d, c) if d.integer(0, 3) else rolling_track(),)
    c.info.setdefault("never_leaves", True)
    c.kwargs = {
        "radius": 0.05 if d.integer(0, 2) else real(d, c, 1e-4, 10.0),
        "chi": 0.1 if d.integer(0, 2) else real(d, c, 0.0, 1.0),
        "km": 0.3 if d.integer(0, 2) else real(d, c, 0.0, 1.0),
        "alpha": d.pick(None, 0.2, lambda: real_or_none(d, c, 0.0, HALF_PI)),
        "marker_angle": 0.0 if d.integer(0, 2) else real(d, c, -2 * math.pi, 2 * math.pi),
        "profile_mu_k": False if d.integer(0, 5) else flag(d, c),
    }
    if d.integer(0, 4) == 0:
        c.kwargs["marker_radius"] = real_or_none(d, c, 0.0, 0.2)
    if d.integer(0, 5) == 0:
        c.kwargs["g"] = real(d, c, 0.01, 100.0)
    if d.integer(0, 5) == 0:
        c.kwargs["scale"] = real(d, c, 1.0, 1e9)
    if d.integer(0, 5) == 0:
        c.kwargs["window"] = integer_param(d, c, (7, 9, 11), (6, 8, 10**9, "7", 7.0, True))
    if d.integer(0, 5) == 0:
        c.kwargs["rule"] = text_param(d, c, ("paper", "normal_force"))
    if d.integer(0, 5) == 0:  # a measured friction: both or neither
        c.kwargs["mu_s"] = real_or_none(d, c, 1e-3, 10.0)
        c.kwargs["mu_s_err"] = real_or_none(d, c, 1e-4, 10.0)
        c.must_raise |= (c.kwargs["mu_s"] is None) != (c.kwargs["mu_s_err"] is None)
    kw = c.kwargs
    same = kw["radius"] == 0.05 and kw["chi"] == 0.1 and kw["km"] == 0.3
    if not (same and kw["alpha"] in (None, 0.2)):
        c.info["never_leaves"] = False  # another body or ramp may fit a flight in the noise
    return c


# --- track: videos, good and bad ---------------------------------------------------------

TRACK_PARAMS = ("video", "marker_radius", "scale", "axle_color", "marker_color", "alpha",
                "start", "end", "progress")  # fmt: skip
#: The bad videos (the issue's four -- no video, no frames, one dot, one colour -- and more)
#: and what the message of each must say besides the file's name.
BAD_VIDEOS = {
    "text.mp4": "is not a video",
    "random.mp4": "is not a video",
    "empty.mp4": "is not a video",
    "cut.mp4": "is not a video",
    "no-frames.mp4": "has no video frames",
    "audio.m4a": "has no video frames",
    "one-dot.mp4": "only one moving dot found",
    "one-colour.mp4": "both dots seem to have one colour",
}
#: The marker's distance from the axle in the rendered videos [m].
VIDEO_MARKER = 0.035
_VIDEOS: dict[str, Path] = {}


def videos() -> dict[str, Path]:
    """A good short video of the design's JARM body (384 x 216, 48 frames) and the bad ones
    of BAD_VIDEOS, made once per process."""
    if _VIDEOS:
        return _VIDEOS
    import av

    from eccjump.studies.experiment import render_video

    where = Path(tempfile.mkdtemp(dir=tmpdir()))
    body = eccjump.Cylinder(0.10927, 0.0777)
    for name, marker in (("good.mp4", "blue"), ("one-dot.mp4", None), ("one-colour.mp4", "red")):
        render_video(where / name, body, math.radians(66.087), mu_s=1.2, duration=0.2,
                     size=(384, 216), marker_radius=VIDEO_MARKER, dot_radius=0.2,
                     marker_color=marker)  # fmt: skip
    good = (where / "good.mp4").read_bytes()
    (where / "cut.mp4").write_bytes(good[: len(good) // 2])
    (where / "text.mp4").write_text("t,xc,yc,xm,ym\n0,0,0,1,1\n")
    (where / "random.mp4").write_bytes(random.Random(7).randbytes(4000))
    (where / "empty.mp4").write_bytes(b"")
    out = av.open(str(where / "no-frames.mp4"), "w")
    stream = out.add_stream("libx264", rate=240)
    stream.width, stream.height, stream.pix_fmt = 64, 64, "yuv420p"
    out.start_encoding()  # the header, and no frame
    out.close()
    with av.open(str(where / "audio.m4a"), "w") as out:
        sound = out.add_stream("aac", rate=8000)
        frame = av.AudioFrame.from_ndarray(np.zeros((1, 1024), np.float32), format="fltp",
                                           layout="mono")  # fmt: skip
        frame.sample_rate, frame.pts = 8000, 0
        out.mux(sound.encode(frame))
        out.mux(sound.encode())
    _VIDEOS.update({p.name: p for p in where.iterdir()})
    return _VIDEOS


def check_video_track(res: Any, case: Case) -> None:
    import json

    expect(isinstance(res, eccjump.VideoTrack), "not a VideoTrack")
    expect(res.n >= 12 and np.isfinite(res.c).all() and np.isfinite(res.m).all(), "bad track")
    expect(math.isfinite(res.scale) and res.scale > 0, f"scale {res.scale}")
    json.dumps(res.to_dict(), allow_nan=False)
    expect(len(repr(res)) < 1000, "repr longer than a screen")


COLOUR_VALUES = (None, None, "red", "blue", "BLUE", "#dc1e1e", (30, 70, 220), "green")
COLOUR_BAD = ("mauve", "#12345", "#gggggg", "grey", (128, 128, 128), (300, 0, 0), (1, 2),
              (1.0, 2.0, 3.0), (True, 0, 0), 5, b"red", ["r", "g", "b"])  # fmt: skip


def _colour(d: Drawer, c: Case) -> Any:
    if d.clean or d.integer(0, 3):
        return d.choice(COLOUR_VALUES)
    c.must_raise = True  # a wrong type or a colour that is none (grey: too pale)
    return d.choice(COLOUR_BAD)


def case_track(d: Drawer) -> Case:
    """``eccjump.track``: the good video with parameters good and bad, or a bad video or a
    path that is none (a FIFO, a directory, a device, a missing file, a wrong type)."""
    c = Case("track", eccjump.track, params=TRACK_PARAMS, check=check_video_track)
    files = videos()
    what = d.choice(("good.mp4",) * 6 + tuple(BAD_VIDEOS) + ("fifo", "dir", "device", "missing",
                                                             "int", "bytes"))  # fmt: skip
    if d.clean:
        what = "good.mp4"
    if what in files:
        c.args = (files[what],)
    else:
        c.args = (_not_a_video(what),)
    c.must_raise = what != "good.mp4"
    kw: dict[str, Any] = {"marker_radius": VIDEO_MARKER}
    if d.integer(0, 3) == 0:
        kw["marker_radius"] = real_or_none(d, c, 1e-3, 20.0)
    if d.integer(0, 4) == 0:
        kw["scale"] = real_or_none(d, c, 1.0, 1e9)
    if kw["marker_radius"] is None and kw.get("scale") is None:
        c.must_raise = True
    kw["axle_color"], kw["marker_color"] = _colour(d, c), _colour(d, c)
    if d.integer(0, 4) == 0:
        kw["alpha"] = real_or_none(d, c, 0.0, HALF_PI)
    if d.integer(0, 5) == 0:
        kw["start"], kw["end"] = real_or_none(d, c, -1.0, 1.0), real_or_none(d, c, -1.0, 1.0)
    if d.integer(0, 5) == 0:
        kw["progress"] = d.choice((_no_progress, None, 5))
        c.must_raise |= kw["progress"] == 5
    c.kwargs = kw
    return c


UNCERTAINTY_MAP_PARAMS = (
    "alpha", "chi", "km_frac", "mu_s", "km", "sd", "bounds", "n", "seed", "sampling",
    "question", "method", "invalid", "confidence", "rule", "chunks", "n_threads", "progress",
)  # fmt: skip


def check_uncertainty_map(res: Any, case: Case) -> None:
    expect(isinstance(res, eccjump.UncertaintyMap), "not an UncertaintyMap")
    f = res.fields
    if isinstance(res, eccjump.UncertaintyDeltaMap):  # no samples: an estimate or a status
        given = np.isin(f["delta_status"], (0, 6))  # an estimate, or a flagged one
        expect(bool(np.all(np.isnan(f["p_jarm"]) != given)), "p_jarm disagrees with its status")
        expect(bool(np.all((0 <= f["p_jarm"][given]) & (f["p_jarm"][given] <= 1))), "p_jarm")
        return
    has = f["n_valid"] > 0
    expect(bool(np.all(f["n_valid"] <= res.n)), "n_valid > n")
    p, lo, hi = f["p_jarm"][has], f["p_jarm_low"][has], f["p_jarm_high"][has]
    expect(bool(np.all((0 <= lo) & (lo <= p) & (p <= hi) & (hi <= 1))), "p_jarm outside its CI")
    expect(bool(np.isnan(f["p_jarm"][~has]).all()), "a share without a valid sample")
    if res.question == "motion":  # a JARM flies and did not slip first
        flies, slipped = f["p_flies"][has], f["p_slipped_first"][has]
        expect(bool(np.all((p <= flies) & (p + slipped <= 1 + 1e-12))), "P(JARM) > P(flies)")
        for q in ("liftoff_t", "flight_time", "distance"):
            lo, mid, hi = (f[f"{q}_{s}"] for s in ("q025", "median", "q975"))
            with np.errstate(invalid="ignore"):
                expect(not bool(np.any((lo > mid) | (mid > hi))), f"{q}'s quantiles disordered")
        return
    shares = p + sum(v[has] for k, v in f.items() if k.startswith("p_") and "jarm" not in k)
    expect(bool(np.all(np.abs(shares - 1) < 1e-9)), "the shares do not add up to 1")


def case_uncertainty_map(d: Drawer) -> Case:
    c = Case("uncertainty_map", eccjump.uncertainty_map, params=UNCERTAINTY_MAP_PARAMS,
             check=check_uncertainty_map)  # fmt: skip
    names = ("chi", "km", "alpha", "mu_s")
    axes = (_axis(d, c, 0.0, HALF_PI), _axis(d, c, 0.0, 1.0), _axis(d, c, 0.0, 1.0))
    c.args = (*axes, real(d, c, 0.0, 2.0))
    sd = _spread_dict(d, c, names, pair=False)
    bounds = _spread_dict(d, c, names, pair=True)
    if isinstance(sd, dict) and isinstance(bounds, dict):
        bounds = {k: v for k, v in bounds.items() if k not in sd or not d.clean}
    c.kwargs = {
        "sd": sd,
        "bounds": bounds,
        "question": text_param(d, c, ("jarm", "jarm", "motion")),
        "n": integer_param(d, c, (1, 7, 64), (*INT_BAD, 10**9)),
        "seed": integer_param(d, c, (0, 1, 12345), (-1, 2.5, None, "1", 2**64)),
        "sampling": text_param(d, c, ("random", "sobol")),
        "invalid": text_param(d, c, ("truncate", "count")),
        "confidence": d.choice((0.95, 0.5, *(() if d.clean else BAD_CONFIDENCE))),
        "rule": text_param(d, c, ("paper", "normal_force")),
        "n_threads": integer_param(d, c, (0, 1, 2), (*INT_BAD, 257)),
    }
    c.must_raise |= c.kwargs["confidence"] in BAD_CONFIDENCE
    if d.integer(0, 1) == 0 and c.kwargs["question"] == "jarm":
        c.kwargs["method"] = text_param(d, c, ("sampling", "delta"))
    if d.integer(0, 3) == 0:
        c.kwargs["progress"] = progress_param(d, c)
    if not d.clean and d.integer(0, 9) == 0:
        c.kwargs[d.choice(("km", "question"))] = d.choice((0.1, "flight"))
        c.must_raise = True
    return c


def _not_a_video(what: str) -> Any:
    """A path that names no video: a FIFO (refused without blocking), a directory, a device,
    a missing file; or a value of a wrong type."""
    where = Path(tempfile.mkdtemp(dir=tmpdir()))
    if what == "fifo":
        os.mkfifo(where / "fifo.mp4")
        return where / "fifo.mp4"
    return {"dir": where, "device": os.devnull, "missing": where / "missing.mp4", "int": 5,
            "bytes": b"clip.mp4"}[what]  # fmt: skip


#: Every generator, by entry point family.
GENERATORS: dict[str, Callable[[Drawer], Case]] = {
    "analyze": case_analyze,
    "track": case_track,
    "design": case_design,
    "build": case_build,
    "jarm": case_jarm,
    "region": case_region,
    "region_dataset": case_region_dataset,
    "roll": case_roll,
    "simulate": case_simulate,
    "motion_map": case_motion_map,
    "motion_points": case_motion_points,
    "motion_options": case_motion_options,
    "uncertainty": case_uncertainty,
    "uncertainty_map": case_uncertainty_map,
    "to_si": case_to_si,
    "sol": case_sol,
    "kinematics": case_kinematics,
    "alpha_intervals": case_alpha_intervals,
    "mu_s_min_path": case_mu_s_min_path,
    "alpha_interval_around": case_alpha_interval_around,
    "closed_form": case_closed_form,
    "cylinder": case_cylinder,
    "units": case_units,
    "store": case_store,
    "results": case_results,
    "plot": case_plot,
    "jarm_fraction": case_jarm_fraction,
    "start_map": case_start_map,
    "optimal_start": case_optimal_start,
    "explore": case_explore,
    "explore_api": case_explore_api,
    "explore_http": case_explore_http,
    "cli": case_cli,
}


# --- the contract -------------------------------------------------------------------------


@contextmanager
def alarm(seconds: int = 60) -> Iterator[None]:
    """Fail (TimeoutError) instead of hanging if the block runs longer than ``seconds``: a
    blocking read of a FIFO, say (in-process runs; the campaign's workers have their own
    time limit)."""

    def ring(signum: int, frame: Any) -> None:
        raise TimeoutError(f"no answer in {seconds} s: a hang")

    old = signal.signal(signal.SIGALRM, ring)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def message_names(message: str, params: Sequence[str]) -> bool:
    return any(
        re.search(rf"(?<![A-Za-z0-9_]){re.escape(p)}(?![A-Za-z0-9_])", message) for p in params
    )


@dataclass
class Outcome:
    """How a call went: ``kind`` is ``ok``, ``error`` (an allowed exception), or a violation:
    ``wrong-exception``, ``bad-message``, ``garbage``, ``accepted-wrong-type``."""

    kind: str
    detail: str = ""

    @property
    def violation(self) -> bool:
        return self.kind not in ("ok", "error")


ALLOWED = (ValueError, TypeError, MemoryError)


def make_case(family: str, d: Drawer) -> Case:
    """A case of ``family``: half of them clean (good types, values in range)."""
    d.clean = d.integer(0, 1) == 0
    case = GENERATORS[family](d)
    case.info["clean"] = d.clean
    return case


def outcome(case: Case) -> Outcome:
    """Run ``case`` and judge it against the contract."""
    allowed = (*ALLOWED, OSError) if case.allow_oserror else ALLOWED
    try:
        res = case.fn(*case.args, **case.kwargs)
    except KeyboardInterrupt:
        raise
    except allowed as err:
        msg = str(err)
        if isinstance(err, MemoryError) or (
            case.allow_oserror and type(err) is not ValueError and isinstance(err, OSError)
        ):
            return Outcome("error", type(err).__name__)
        if len(msg) > MAX_MESSAGE:
            return Outcome(
                "bad-message", f"{type(err).__name__} of {len(msg)} characters: {msg[:120]}"
            )
        if not message_names(msg, case.params):
            return Outcome("bad-message", f"{type(err).__name__} names no parameter: {msg[:150]}")
        return Outcome("error", type(err).__name__)
    except BaseException as err:  # the point of the fuzzing
        return Outcome("wrong-exception", f"{type(err).__name__}: {str(err)[:150]}")
    if case.must_raise:
        return Outcome("accepted-wrong-type", "returned a result")
    try:
        if case.check is not None:
            case.check(res, case)
    except ContractViolation as err:
        return Outcome("garbage", str(err)[:200])
    except Exception as err:  # a check that cannot look at the result
        return Outcome("garbage", f"unreadable result: {type(err).__name__}: {str(err)[:120]}")
    return Outcome("ok")
