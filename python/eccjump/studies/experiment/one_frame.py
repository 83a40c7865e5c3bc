"""Whether a track that rolls to its lift-off could hide a slip of one frame just before it:
the largest μ_s at which the fitted run slips that long, what that slip costs the fit, and
the refit that slips that long with everything else free.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump.studies.experiment.fit import (
    MAX_NFEV,
    Fit,
    Model,
    Setup,
    fitted,
    slip_frames,
    solve,
    start_guess,
)
from eccjump.studies.experiment.inputs import BOUNDS
from eccjump.studies.experiment.reconstruction import Reconstruction
from eccjump.studies.experiment.runs import event_times, slip_intervals
from eccjump.studies.experiment.track import Track

#: The largest measured mu_s that :func:`slipping_mu_s` compares with.
MU_MEASURED_MAX = BOUNDS["mu_s"].hi


class OneFrameSlip(NamedTuple):
    """What :func:`one_frame_slip` found: the χ² ``cost``, the ``refit`` that slips
    (or None) and ``mu_s``, the largest μ_s at which the run slips a frame (NaN: none)."""

    cost: float
    refit: Fit | None
    mu_s: float


def one_frame_slip(f: Fit, setup: Setup, track: Track, rec: Reconstruction) -> OneFrameSlip:
    """How much worse (a χ², scaled like the slip test's) the rolling fit ``f``
    becomes when its body slips for one frame in all before the lift-off, and the refit
    that slips that long (None if it does not). The slip: μ_s lowered below what the
    rolling needs (bisection) until ``f``'s run slips one frame, with μ_k = μ_s (the
    gentlest slip: a rolling track does not fix μ_k, and a lower one shows more). Taken
    as it is, that run overstates what the track can tell (a slip elsewhere, or with
    another start, may fit better); so the other parameters are refitted with μ_s kept at
    most there, and the better of the two runs that slip a frame or more is the
    alternative. A refit better than ``f`` itself means ``f`` was a local minimum. Below
    the slip test's threshold a one-frame slip is not excluded. NaN (and None) when no
    lowered μ_s gives a run that lifts off after a frame's slip."""
    model = Model(setup, track, rec, jarm_only=False)
    p = model.params(f.x)
    found = _one_frame_mu_s(model, p, f.mu_s_bound, track.dt / setup.time_unit)
    if found is None:
        return OneFrameSlip(math.nan, None, math.nan)
    mu_s, res = found
    cost = 0.5 * float(res @ res)
    refit = _capped_fit(f, setup, track, rec, mu_s)
    if slip_frames(refit, setup, track) < 1.0:  # back to rolling: no alternative
        return OneFrameSlip(2.0 * (cost - f.cost) / f.variance_factor, None, mu_s)
    return OneFrameSlip(2.0 * (min(cost, refit.cost) - f.cost) / f.variance_factor, refit, mu_s)


def slipping_mu_s(f: Fit, setup: Setup, track: Track, rec: Reconstruction) -> float:
    """The largest μ_s (with μ_k = μ_s, the gentlest slip) at which ``f``'s run slips a
    frame or more before it lifts off; NaN if none up to what its rolling needs (or
    MU_MEASURED_MAX, where that is unbounded). A measured μ_s above it weighs against
    ``f``'s slip (``friction``)."""
    model = Model(setup, track, rec, jarm_only=False)
    bound = min(f.mu_s_bound, MU_MEASURED_MAX) if f.mu_s_bound > 0 else MU_MEASURED_MAX
    found = _one_frame_mu_s(model, model.params(f.x), bound, track.dt / setup.time_unit)
    return math.nan if found is None else found[0]


def _one_frame_mu_s(
    model: Model, p: dict[str, float], mu_bound: float, frame: float
) -> tuple[float, NDArray[np.float64]] | None:
    """The largest μ_s (to 1e-4 of ``mu_bound``) at which the run of ``p`` lifts off after
    slipping for at least ``frame`` in all, and that run's residuals."""
    horizon = float(model.tau[-1])
    lo, hi = 0.0, mu_bound
    found = None
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        try:
            run = model.simulate(p | {"mu_k": mid}, mu_s=mid)
        except ValueError:
            lo = mid
            continue
        lift = event_times(run, horizon)["liftoff"]
        if not math.isfinite(lift):
            lo = mid
            continue
        if sum(b - a for a, b in slip_intervals(run, lift)) >= frame:
            lo, found = mid, (mid, model.compare(p, model.states(run)))
        else:
            hi = mid
        if hi - lo < 1e-4 * mu_bound:
            break
    return found


def _capped_fit(f: Fit, setup: Setup, track: Track, rec: Reconstruction, mu_s: float) -> Fit:
    """``f`` refitted with its runs' μ_s at most ``mu_s`` (from ``f``, μ_s set there);
    its μ_k and Δμ are those its run used (a start for a free fit that gives that run)."""
    model = Model(setup, track, rec, jarm_only=False, mu_s_range=(0.0, mu_s))
    lo, hi = model.bounds(start_guess(setup, rec))
    capped = fitted(model, solve(model, _with_mu_s(f.x, f.names, mu_s), lo, hi, MAX_NFEV), lo, hi)
    used = min(capped.value("mu_k") + capped.value("dmu"), mu_s)
    return replace(capped, x=_with_mu_s(capped.x, capped.names, used))


def _with_mu_s(x: NDArray[np.float64], names: tuple[str, ...], mu_s: float) -> NDArray[np.float64]:
    """``x`` with μ_s = μ_k + Δμ set to ``mu_s`` (μ_k lowered to it where above)."""
    y = x.copy()
    mu_k = min(float(x[names.index("mu_k")]), mu_s)
    y[names.index("mu_k")], y[names.index("dmu")] = mu_k, mu_s - mu_k
    return y
