"""The standard errors of a fitted run's key times (the lift-off, the landing, every slip's
start and end), from their derivatives with respect to the parameters, taken across a
branch of the motion only where the track allows the other branch.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from eccjump.studies.experiment.fit import KINEMATIC, Fit, Model, Setup
from eccjump.studies.experiment.reconstruction import Reconstruction
from eccjump.studies.experiment.runs import event_times
from eccjump.studies.experiment.track import Track

#: The chi-square increase (in units of the reduced chi-square) beyond which the track
#: rejects a stepped run: the 95 % level of one parameter, as the profiles' intervals.
REJECTED = 3.84


def time_errors(
    model_fit: Fit, setup: Setup, track: Track, rec: Reconstruction
) -> dict[str, float]:
    """Standard errors [s] of the key times of the fitted run, from their derivatives with
    respect to the parameters and the covariance, plus the jump where a step crosses to
    another branch the track allows (:func:`branch_step`). A time that a start or frame
    parameter the track does not fix (an infinite variance) moves is not fixed either:
    infinite. (Not the friction: a rolling fit's μ_s is bounded from below only, and
    lowering it makes a slip the track rejects; nor a parameter at its bound, such as
    θ̇₀ = 0 from rest, whose column least squares returns as zero.)"""
    model = Model(setup, track, rec, jarm_only=model_fit.jarm_only)
    horizon = float(model.tau[-1])
    base = event_times(model_fit.run, horizon)
    grads = {k: np.zeros(model_fit.x.size) for k in base}
    jumps = dict.fromkeys(base, 0.0)
    unfixed: set[str] = set()
    for i, name in enumerate(model_fit.names):
        err = math.sqrt(model_fit.cov[i, i]) if math.isfinite(model_fit.cov[i, i]) else math.inf
        lo, hi = model_fit.lower[i], model_fit.upper[i]
        at_bound = min(model_fit.x[i] - lo, hi - model_fit.x[i]) <= 1e-9 * (hi - lo)
        if not err > 0 or (math.isinf(err) and (name not in KINEMATIC or at_bound)):
            continue  # (scipy's Jacobian has a zero column at an active bound: not lost)
        h = 0.1 * err if math.isfinite(err) else 1e-4 * (hi - lo)
        x_hi, x_lo = model_fit.x.copy(), model_fit.x.copy()
        x_hi[i], x_lo[i] = min(x_hi[i] + h, hi), max(x_lo[i] - h, lo)
        if x_hi[i] == x_lo[i]:
            continue
        try:
            up, dn = stepped(model, x_hi, horizon), stepped(model, x_lo, horizon)
        except ValueError:
            continue
        steps = (x_hi[i] - model_fit.x[i], x_lo[i] - model_fit.x[i])
        rise = 2.0 / model_fit.variance_factor  # what a cost difference is in chi-square
        allowed = (
            (up[1] - model_fit.cost) * rise <= REJECTED,
            (dn[1] - model_fit.cost) * rise <= REJECTED,
        )
        for k in base:
            grads[k][i], jump = branch_step(base, up[0], dn[0], k, steps, allowed, err)
            jumps[k] = max(jumps[k], jump)
            if math.isinf(err) and up[0].get(k) != dn[0].get(k):
                unfixed.add(k)
    cov = np.where(np.isfinite(model_fit.cov), model_fit.cov, 0.0)
    unit = setup.time_unit
    out = {}
    for k, g in grads.items():
        g = np.where(np.isfinite(g), g, 0.0)
        var = max(float(g @ cov @ g), 0.0) + jumps[k] ** 2
        out[k] = unit * math.sqrt(var) if math.isfinite(base[k]) else math.nan
        if k in unfixed and math.isfinite(base[k]):
            out[k] = math.inf
    return out


def stepped(model: Model, x: NDArray[np.float64], horizon: float) -> tuple[dict[str, float], float]:
    """The key times (:func:`event_times`) and the cost of the run at ``x``."""
    p = model.params(x)
    run = model.simulate(p)
    r = model.compare(p, model.states(run))
    return event_times(run, horizon), 0.5 * float(r @ r)


def branch(times: dict[str, float]) -> frozenset[str]:
    """Which of a run's key times (:func:`event_times`) exist: its branch (a slip before the
    lift-off or none, how many episodes, a lift-off and a landing or not)."""
    return frozenset(k for k, v in times.items() if math.isfinite(v))


def branch_step(
    base: dict[str, float],
    up: dict[str, float],
    dn: dict[str, float],
    key: str,
    steps: tuple[float, float],
    allowed: tuple[bool, bool] = (True, True),
    err: float = math.inf,
) -> tuple[float, float]:
    """The derivative of the time ``key`` (per unit of the parameter) from the runs stepped
    up and down by ``steps`` (above and below 0), and its jump, where a stepped run is on
    another branch (a slip that appears or goes within the step) or is one the track
    rejects (``allowed`` False: a slip that starts at another peak of the friction ratio,
    frames earlier). A central difference across such a switch is the jump over the step,
    a tenth of a standard error: lift-offs printed hundreds of times wider than their
    error. The derivative comes from the side that continues the fitted run (0 where that
    side is a bound); the jump is what the other side adds beyond it, where the track
    allows that side; NaN (no derivative) where the time is missing. Where the fitted side
    ends at a bound (its step the shorter) and the other is rejected, the parameter moves
    only toward a run the track rejects: over its standard error ``err`` the time moves no
    further than to that run (a μ at its bound with an error of 20 on a range of 3, whose
    one-sided slope over 4e-5 printed a lift-off ± 68 ms for an error of 77 µs). Where no
    side continues the fitted run on a run the track allows: the central difference where
    both are on the fitted branch (the track rejects a tenth of the error with the other
    parameters held, not as they move with it), else :func:`_within_rejected`."""
    b = base.get(key, math.nan)
    vu, vd = up.get(key, math.nan), dn.get(key, math.nan)
    same_up = branch(up) == branch(base) and allowed[0]
    same_dn = branch(dn) == branch(base) and allowed[1]
    central = (vu - vd) / (steps[0] - steps[1])
    if (same_up and same_dn) or not math.isfinite(b):
        return central, 0.0
    if not (same_up or same_dn):
        if all(allowed):  # the fitted run: a branch of its own
            mid = (vu + vd) / 2 - b
            return central, abs(mid) if math.isfinite(mid) else 0.0
        if branch(up) == branch(base) == branch(dn):  # both rejected, neither a switch
            return central, 0.0
        return _within_rejected(base, (up, dn), key, central, allowed, err)
    (v, s), (w, t, ok) = (
        ((vu, steps[0]), (vd, steps[1], allowed[1]))
        if same_up
        else ((vd, steps[1]), (vu, steps[0], allowed[0]))
    )
    g = (v - b) / s if s else 0.0
    if not ok and abs(s) < abs(t) and math.isfinite(w + err) and abs(g) * err > abs(w - b):
        g = math.copysign(abs(w - b) / err, g)
    return g, abs(w - b - g * t) if ok and math.isfinite(w) else 0.0


def _within_rejected(
    base: dict[str, float],
    sides: tuple[dict[str, float], dict[str, float]],
    key: str,
    central: float,
    allowed: tuple[bool, bool],
    err: float,
) -> tuple[float, float]:
    """:func:`branch_step` where neither side continues the fitted run on a run the track
    allows, some side is rejected and some side is on another branch (the central
    difference spans the switch): the parameter moves less than that step, so over its
    standard error ``err`` the time moves no further than the stepped runs on the fitted
    branch show (not at all where both are on other branches), and it may jump to an
    allowed side's. Differenced across the switch instead, a 59-frame slip at 60 fps whose
    step of a tenth of θ̇₀'s error made it lift off from rolling 0.85 s sooner printed its
    lift-off ± 7.6 s."""
    b = base[key]
    fitted = [abs(run.get(key, math.nan) - b) for run in sides if branch(run) == branch(base)]
    reach = max((d for d in fitted if math.isfinite(d)), default=0.0)
    g = central
    if math.isfinite(central) and abs(central) * err > reach:
        g = math.copysign(reach / err, central)
    others = [abs(run.get(key, math.nan) - b) for run, ok in zip(sides, allowed, strict=True) if ok]
    return g, max((d for d in others if math.isfinite(d)), default=0.0)
