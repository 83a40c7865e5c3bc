"""What a run of the model says up to a time (all dimensionless): its key times, its slip
episodes and the friction its rolling needs.
"""

from __future__ import annotations

import math

import numpy as np

from eccjump.motion.simulation import MotionResult


def event_times(run: MotionResult, horizon: float) -> dict[str, float]:
    """Key times of a run (dimensionless): the first lift-off, the first landing, the
    onset and end of the first slip before that lift-off (NaN when absent), and the start
    and end of every slip episode k before it (``slip{k}_t1``, ``slip{k}_t2``)."""
    out = dict.fromkeys(("liftoff", "landing", "slip_onset", "slip_end"), math.nan)
    trs = [tr for tr in run.transitions[1:] if tr.t <= horizon]
    lift = next((tr.t for tr in trs if tr.to_mode == "FLIGHT"), math.nan)
    out["liftoff"] = lift
    if math.isfinite(lift):
        out["landing"] = next((tr.t for tr in trs if tr.from_mode == "FLIGHT"), math.nan)
    before = [tr for tr in trs if not tr.t > lift or math.isnan(lift)]
    onset = next((tr for tr in before if tr.to_mode == "SLIP"), None)
    if onset is not None:
        out["slip_onset"] = onset.t
        out["slip_end"] = next(
            (tr.t for tr in before if tr.t > onset.t and tr.from_mode == "SLIP"), lift
        )
    for k, (a, b) in enumerate(slip_intervals(run, lift if math.isfinite(lift) else horizon)):
        out[f"slip{k}_t1"], out[f"slip{k}_t2"] = a, b
    return out


def slip_intervals(run: MotionResult, until: float) -> list[tuple[float, float]]:
    """(start, end) of every slip of the run before ``until`` (dimensionless); a reversal
    continues the slip."""
    out: list[tuple[float, float]] = []
    for seg in run.segments:
        if seg.mode == "SLIP" and seg.t_start < until:
            end = min(seg.t_end, until)
            if out and seg.t_start <= out[-1][1]:
                out[-1] = (out[-1][0], end)
            else:
                out.append((seg.t_start, end))
    return out


def rolling_needs(run: MotionResult, until: float) -> float:
    """The largest friction ratio |F_x|/F_y of the run's rolling before ``until``: the
    lower bound on μ_s that the rolling implies (0 without rolling)."""
    rows = (np.asarray(run.mode) == 0) & (np.asarray(run.t) <= until) & (np.asarray(run.Fy) > 0)
    if not rows.any():
        return 0.0
    return float(np.max(np.abs(run.Fx[rows]) / run.Fy[rows]))
