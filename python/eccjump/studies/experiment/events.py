"""What the track itself shows, without the model: flights (the axle above its contact line
beyond the noise), their lift-off, apex and landing, and slips (the slip velocity beyond its
error in contact), each timed with a window.

Thresholds: a frame is off the ramp when b - R > 3 sigma, and a flight is a run of at least
:data:`MIN_RUN` such frames (a false alarm needs three 3-sigma excursions in a row, about
1 in 4e8 per frame). At a lift-off from contact the normal velocity and acceleration of C are
both 0 (the lift-off conditions), so the gap grows like (t - t_L)³ and stays inside the
noise for several frames: the lift-off is timed by fitting c tau³ (tau = t - t_L > 0, c ≥ 0)
 to the gap over the start of the flight, profiling t_L; its window is where the sum of
squares is within sigma² of its least value (one standard error). A slip is a run of at
least :data:`MIN_RUN` contact frames whose slip velocity exceeds 3 standard errors, or where
the slip displacement's mean over the next 4 frames differs from that over the previous 4
by more than 3 standard errors (a slip shorter than the smoothing window, which the
smoothed velocity averages away, moves s from one level to another); frames
within half a smoothing window of a lift-off window are not judged (the rates there mix
contact and flight).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from eccjump.studies.experiment.reconstruction import Reconstruction

#: Consecutive frames beyond the threshold that make a flight or a slip.
MIN_RUN = 3
#: The threshold, in standard errors.
Z = 3.0
#: The frames on either side of a level shift of the slip displacement (``_steps``).
STEP_FRAMES = 4
#: Mode codes (as eccjump.motion.MODES).
ROLL, SLIP, FLIGHT = 0, 1, 2


@dataclass(frozen=True)
class Window:
    """A time [s] and its window [lo, hi]."""

    t: float
    lo: float
    hi: float

    def as_dict(self) -> dict[str, float]:
        return {"t": self.t, "lo": self.lo, "hi": self.hi}


@dataclass(frozen=True)
class Flight:
    """A flight seen in the track: lift-off, apex (with its height above contact [m] and
    its error) and landing (None if the track ends in flight)."""

    liftoff: Window
    apex: Window
    apex_height: float
    apex_err: float
    landing: Window | None


@dataclass(frozen=True)
class Slip:
    """A slip seen in the track: its onset and its end (a stick, or a lift-off)."""

    onset: Window
    end: Window


@dataclass(frozen=True, eq=False)
class Observed:
    """The observed mode of every frame (0 ROLL, 1 SLIP, 2 FLIGHT), the flights and slips,
    and the flight's signal: the largest gap over its error (0 without a flight)."""

    mode: NDArray[np.int8]
    flights: tuple[Flight, ...]
    slips: tuple[Slip, ...]
    peak_snr: float

    def sequence(self) -> list[str]:
        names = ("ROLL", "SLIP", "FLIGHT")
        keep = np.r_[True, np.diff(self.mode) != 0]
        return [names[int(m)] for m in self.mode[keep]]


def runs(flag: NDArray[np.bool_], min_run: int = MIN_RUN) -> list[tuple[int, int]]:
    """(first, last) index of each run of True at least ``min_run`` long."""
    padded = np.r_[False, flag, False].astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    pairs = zip(edges[::2], edges[1::2] - 1, strict=True)
    return [(int(a), int(b)) for a, b in pairs if b - a + 1 >= min_run]


def observe(rec: Reconstruction) -> Observed:
    """Flights and slips of ``rec`` (module docstring for the rules)."""
    t, h, sigma = rec.t, rec.height, rec.sigma
    mode = np.zeros(t.size, dtype=np.int8)
    flights: list[Flight] = []
    blocked = np.zeros(t.size, dtype=bool)  # frames not judged for slip
    half = rec.window // 2
    floor = 0  # a lift-off is looked for after the previous flight's last frame
    for a, b in runs(h > Z * sigma):
        lift = _liftoff(t, h, sigma, a, b, floor)
        floor = b + 1
        land = _landing(t, h, b)
        top = a + int(np.argmax(h[a : b + 1]))
        near = np.flatnonzero(h[a : b + 1] >= h[top] - sigma) + a
        apex = Window(float(t[top]), float(t[near[0]]), float(t[near[-1]]))
        flights.append(Flight(lift, apex, float(h[top]), sigma, land))
        end = land.t if land is not None else math.inf
        mode[(t >= lift.t) & (t < end)] = FLIGHT
        blocked |= (t >= lift.lo - half * rec.dt) & (t < end + half * rec.dt)
    moving = (np.abs(rec.slip) > Z * rec.slip_err) | _steps(rec.s, rec.s_err)
    slips = [_slip(rec, a, b) for a, b in runs(moving & ~blocked & (mode != FLIGHT), MIN_RUN)]
    for s in slips:
        mode[(t >= s.onset.t) & (t < s.end.t) & (mode != FLIGHT)] = SLIP
    snr = float(max((f.apex_height / sigma for f in flights), default=0.0))
    return Observed(mode, tuple(flights), tuple(slips), snr)


def _steps(s: NDArray[np.float64], err: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Frames k where the slip displacement's mean over the :data:`STEP_FRAMES` frames from k
    differs from its mean over those before k by more than Z standard errors: a slip
    shorter than the smoothing window (a few frames at a low frame rate), which the smoothed
    slip velocity averages away, shifts s from one level to another."""
    n, w = s.size, STEP_FRAMES
    out = np.zeros(n, dtype=bool)
    if n < 2 * w:
        return out
    csum, vsum = np.r_[0.0, np.cumsum(s)], np.r_[0.0, np.cumsum(err**2)]
    k = np.arange(w, n - w + 1)
    shift = (csum[k + w] - csum[k]) / w - (csum[k] - csum[k - w]) / w
    spread = np.sqrt(vsum[k + w] - vsum[k - w]) / w
    out[k] = np.abs(shift) > Z * spread
    return out


def _liftoff(
    t: NDArray[np.float64], h: NDArray[np.float64], sigma: float, a: int, b: int, floor: int
) -> Window:
    """Profile fit of h = c tau³ (tau > 0, c ≥ 0) from 20 frames (at least 50 ms) before
    the run, but not before frame ``floor`` (the previous flight's landing), to where the
    gap first reaches 8 sigma (the series holds near the lift-off only)."""
    back = max(20, int(0.05 / float(np.median(np.diff(t)))))
    lo = max(a - back, floor, 0)
    top = a + int(np.argmax(h[a : b + 1] >= min(8 * sigma, h[a : b + 1].max())))
    hi = max(top, min(a + 2, b))
    tt, hh = t[lo : hi + 1], h[lo : hi + 1]
    grid = np.linspace(t[lo], t[a], 20 * (a - lo) + 1)
    sse = np.array([_onset_sse(tt, hh, t0) for t0 in grid])
    best = int(np.argmin(sse))
    inside = grid[sse <= sse[best] + sigma**2]
    return Window(float(grid[best]), float(inside.min()), float(inside.max()))


def _onset_sse(t: NDArray[np.float64], h: NDArray[np.float64], t0: float) -> float:
    """The least sum of squares of h - c tau³ over c ≥ 0."""
    cube = np.clip(t - t0, 0.0, None) ** 3
    norm = float(cube @ cube)
    c = max(float(cube @ h) / norm, 0.0) if norm > 0 else 0.0
    r = h - c * cube
    return float(r @ r)


def _landing(t: NDArray[np.float64], h: NDArray[np.float64], b: int) -> Window | None:
    """Between the last frame off the ramp and the next one; the estimate where the line
    through the last two flight frames meets the ramp."""
    if b + 1 >= t.size:
        return None
    t1, t2 = t[b], t[b + 1]
    guess = t1
    if b >= 1 and h[b - 1] > h[b] > 0:
        guess = t[b] + h[b] * (t[b] - t[b - 1]) / (h[b - 1] - h[b])
    return Window(float(min(max(guess, t1), t2)), float(t1), float(t2))


def _slip(rec: Reconstruction, a: int, b: int) -> Slip:
    """A slip over frames a..b: onset and end where the slip velocity, extrapolated linearly
    from the run's first (last) frames, crosses 0, within the frames where it is
    indistinguishable from 0 (below 1 standard error) next to the run."""
    t, v, err = rec.t, rec.slip, rec.slip_err
    quiet = np.abs(v) < err
    before = np.flatnonzero(quiet[:a])
    after = np.flatnonzero(quiet[b + 1 :]) + b + 1
    lo = float(t[before[-1]]) if before.size else float(t[a])
    hi = float(t[after[0]]) if after.size else float(t[b])
    onset = _zero_crossing(t[a : min(a + 5, b + 1)], v[a : min(a + 5, b + 1)], lo, float(t[a]))
    end = _zero_crossing(t[max(b - 4, a) : b + 1], v[max(b - 4, a) : b + 1], float(t[b]), hi)
    return Slip(Window(onset, lo, float(t[a])), Window(end, float(t[b]), hi))


def _zero_crossing(t: NDArray[np.float64], v: NDArray[np.float64], lo: float, hi: float) -> float:
    if t.size >= 2:
        slope, icpt = np.polyfit(t, v, 1)
        if slope != 0:
            return float(min(max(-icpt / slope, lo), hi))
    return lo
