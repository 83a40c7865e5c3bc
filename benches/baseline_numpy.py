"""The straightforward numpy/scipy JARM classification, as a user would write it by hand.

Same problem as ``eccjump.jarm(..., rule="paper")`` with the default start (rest at θ0 = 0)
and automatic n (first-jump semantics), units g = R = M = 1, angles in radians:

- pure rolling from rest: θ̇²(θ) = 2E/Ĩ_P by energy, with E = θ sin α + χ(cos α − cos(α + θ))
  and Ĩ_P = Ĩ_C + 1 + 2χ cos θ; θ̈ from the rolling equation; F_x, F_y from physics.md;
- the paper's lift-off function L = χθ̇² cos θ − cos α (lift-off at its first rising zero);
- the path is watched for F_y ≤ 0, slip margin μ_s F_y − |F_x| < 0 and L ≥ 0, up to 2πn* with
  n* = min{n ≥ 1 : n tan α > γ}, γ = (Ĩ_C + 1 + 2χ)/(4πχ); the first event decides;
- a lift-off counts as a JARM iff it lies in a green window 2πn − α < θ_J < 2πn with
  F_y,J > 0 (Eq. Njumpfn) and μ(θ_J) ≤ μ_s (Eq. ineq2, signed: −F_x,J/F_y,J).

Two routes:

``classify_closed_form``: vectorised numpy on a sampled θ grid (``samples_per_turn`` per turn,
scanned in blocks of turns), first violating sample, then ``scipy.optimize.brentq`` in that cell.
Like any sampled scan it can miss a violation narrower than one cell (a thin dip of F_y or of
the slip margin, or an L that only just touches 0); eccjump's scan locates interior minima
with derivative roots instead.

``classify_ode``: ``scipy.integrate.solve_ivp`` (RK45, rtol 1e-10, atol 1e-12) with terminal
events (L rising, F_y falling, slip margin falling, θ = 2πn*). scipy only compares event signs
at step ends, so it shares the same blind spot for violations narrower than a step.

Both return the reason code of ``eccjump.Reason`` (0 JARM, 1 NO_ROOT, 2 LIFTOFF_EARLIER,
3 NORMAL_FORCE_LOST, 4 SLIP_BEFORE, 5 SLIP_AT_JUMP, 7 TURN_LIMIT, 8 INVALID_PARAMS) and θ_J
(NaN unless a lift-off was found: JARM, LIFTOFF_EARLIER, SLIP_AT_JUMP).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

TAU = 2.0 * math.pi

JARM, NO_ROOT, LIFTOFF_EARLIER, NORMAL_FORCE_LOST = 0, 1, 2, 3
SLIP_BEFORE, SLIP_AT_JUMP, TURN_LIMIT, INVALID_PARAMS = 4, 5, 7, 8


class Verdict(NamedTuple):
    reason: int
    theta_J: float  # lift-off angle [rad] or NaN
    theta_event: float  # where the deciding event happened [rad] or NaN


class Point:
    """One parameter point: the rolling path from rest at θ0 = 0 as functions of θ."""

    def __init__(self, alpha: float, chi: float, km: float, mu_s: float) -> None:
        self.alpha, self.chi, self.km, self.mu_s = alpha, chi, km, mu_s
        self.sa = math.sin(alpha)
        self.ca = 0.0 if alpha == math.pi / 2 else math.cos(alpha)  # exact 0 on the vertical
        self.ic = km + chi * chi / (1.0 - km) if km < 1.0 else km  # Ĩ_C (χ = 0 allows k_m = 1)
        self.icm = km * (1.0 - km + chi * chi) / (1.0 - km) if km < 1.0 else 0.0

    # --- the rolling path, vectorised over θ -------------------------------------------
    def forces(self, th):
        """θ̇², θ̈, F_x, F_y, L along pure rolling from rest at 0 (arrays or floats)."""
        chi, sa, ca = self.chi, self.sa, self.ca
        s, c = np.sin(th), np.cos(th)
        ip = self.ic + 1.0 + 2.0 * chi * c
        energy = th * sa + 2.0 * chi * np.sin(self.alpha + 0.5 * th) * np.sin(0.5 * th)
        w2 = 2.0 * energy / ip
        wdd = (chi * w2 * s + chi * (sa * c + ca * s) + sa) / ip
        fx = -sa - chi * w2 * s + (1.0 + chi * c) * wdd
        fy = ca - chi * w2 * c - chi * wdd * s
        lift = chi * w2 * c - ca
        return w2, wdd, fx, fy, lift

    def fy(self, th):
        return self.forces(th)[3]

    def margin(self, th):
        _, _, fx, fy, _ = self.forces(th)
        return self.mu_s * fy - np.abs(fx)

    def lift(self, th):
        return self.forces(th)[4]

    # --- the jump point (paper Sec. 3.1) ------------------------------------------------
    def mu(self, th: float) -> float:
        """Eq. ineq2, signed: −F_x,J/F_y,J."""
        chi, s, c = self.chi, math.sin(th), math.cos(th)
        return -(self.icm + chi * chi * s * s) / (chi * s * (1.0 + chi * c))

    def fy_jump(self, th: float) -> float:
        """Eq. Njumpfn."""
        chi, s, c = self.chi, math.sin(th), math.cos(th)
        ip = self.ic + 1.0 + 2.0 * chi * c
        return -chi * (1.0 + chi * c) * (s / c) * math.sin(self.alpha + th) / ip

    def in_green_window(self, th: float) -> bool:
        n = math.ceil(th / TAU)
        return n >= 1 and TAU * n - self.alpha < th < TAU * n

    def judge_liftoff(self, th: float) -> Verdict:
        """Verdict for a first lift-off at θ = th (paper's rule)."""
        if th <= 0.0:
            return Verdict(LIFTOFF_EARLIER, th, th)
        if not self.in_green_window(th) or self.fy_jump(th) <= 0.0:
            return Verdict(NORMAL_FORCE_LOST, math.nan, th)
        if self.mu(th) > self.mu_s:
            return Verdict(SLIP_AT_JUMP, th, th)
        return Verdict(JARM, th, math.nan)

    def judge_slip(self, th: float, next_liftoff: float) -> Verdict:
        """Slip at th; SLIP_AT_JUMP if the paper's lift-off that follows fails ineq2 in the
        green window (the jump-point test alone would reject the point), else SLIP_BEFORE."""
        tl = next_liftoff
        if math.isfinite(tl) and self.in_green_window(tl) and self.mu(tl) > self.mu_s:
            return Verdict(SLIP_AT_JUMP, tl, th)
        return Verdict(SLIP_BEFORE, math.nan, th)


def _special(alpha: float, chi: float, km: float, mu_s: float, max_turns: int):
    """Invalid parameters and the trivial cases; else (Point, n*)."""
    ok = (
        all(math.isfinite(v) for v in (alpha, chi, km, mu_s))
        and 0.0 <= alpha <= math.pi / 2
        and 0.0 <= chi <= 1.0
        and 0.0 <= km <= 1.0 - chi + 1e-15
        and mu_s >= 0.0
    )
    if not ok:
        return Verdict(INVALID_PARAMS, math.nan, math.nan)
    p = Point(alpha, chi, min(km, 1.0 - chi), mu_s)
    if alpha == 0.0:  # equilibrium at rest
        return Verdict(NO_ROOT, math.nan, math.nan)
    if chi == 0.0:  # centred: no lift-off; slips at once if friction cannot hold
        if p.margin(0.0) < 0.0:
            return Verdict(SLIP_BEFORE, math.nan, 0.0)
        return Verdict(NO_ROOT, math.nan, math.nan)
    gamma = (p.ic + 1.0 + 2.0 * chi) / (4.0 * math.pi * chi)
    t = math.tan(alpha)
    n_star = math.floor(gamma / t) + 1 if gamma / t < 1e15 else max_turns + 1
    while (n_star - 1) >= 1 and (n_star - 1) * t > gamma:
        n_star -= 1
    while n_star * t <= gamma:
        n_star += 1
    return p, n_star


# ------------------------------------------------------------------------------------------
# (a) closed form on a sampled θ grid
# ------------------------------------------------------------------------------------------
def classify_closed_form(
    alpha: float,
    chi: float,
    km: float,
    mu_s: float,
    *,
    samples_per_turn: int = 200,
    block_turns: int = 8,
    max_turns: int = 10_000,
) -> Verdict:
    """Classify one point by scanning the closed-form path on a θ grid; brentq refines."""
    sp = _special(alpha, chi, km, mu_s, max_turns)
    if isinstance(sp, Verdict):
        return sp
    p, n_star = sp
    turns = min(n_star, max_turns)
    end = TAU * turns

    # θ = 0: the start itself (e.g. α = π/2: L(0) = F_y(0) = 0).
    _, _, fx0, fy0, l0 = p.forces(0.0)
    if l0 >= 0.0:
        return p.judge_liftoff(0.0)
    if fy0 <= 0.0:
        return Verdict(NORMAL_FORCE_LOST, math.nan, 0.0)
    if mu_s * fy0 - abs(fx0) < 0.0:
        return p.judge_slip(0.0, _next_liftoff(p, 0.0, end, samples_per_turn, block_turns))

    h = TAU / samples_per_turn
    start = 0.0
    while start < end:
        stop = min(start + TAU * block_turns, end)
        k = max(1, math.ceil((stop - start) / h))
        th = np.linspace(start, stop, k + 1)
        _, _, fx, fy, lift = p.forces(th)
        bad = (fy <= 0.0) | (mu_s * fy - np.abs(fx) < 0.0) | (lift >= 0.0)
        bad[0] = False  # checked as the previous block's last sample (or at θ = 0)
        hits = np.flatnonzero(bad)
        if hits.size:
            i = hits[0]
            a, b = th[i - 1], th[i]
            cands = []  # (θ, kind), in the order that wins near-ties
            if lift[i] >= 0.0:
                cands.append((_root(p.lift, a, b), "lift"))
            if fy[i] <= 0.0:
                cands.append((_root(p.fy, a, b), "fy"))
            if mu_s * fy[i] - abs(fx[i]) < 0.0:
                cands.append((_root(p.margin, a, b), "slip"))
            t_ev, kind = _first(cands, 1e-12)
            if kind == "lift":
                return p.judge_liftoff(t_ev)
            if kind == "fy":
                return Verdict(NORMAL_FORCE_LOST, math.nan, t_ev)
            return p.judge_slip(t_ev, _next_liftoff(p, t_ev, end, samples_per_turn, block_turns))
        start = stop
    return Verdict(TURN_LIMIT if n_star > max_turns else NO_ROOT, math.nan, math.nan)


def _first(cands, rel: float):
    """The earliest (θ, kind); near-ties (within rel (1 + θ)) go to the earlier entry: at
    Ĩ_CM = 0 the slip margin vanishes together with F_y, and that is a loss of normal force."""
    best = None
    for t, kind in cands:
        if best is None or t < best[0] - rel * (1.0 + abs(best[0])):
            best = (t, kind)
    return best


def _root(f, a: float, b: float) -> float:
    fa, fb = float(f(a)), float(f(b))
    if fa == 0.0:
        return a
    if fa * fb > 0.0:  # grid sign test came from the inequality's edge (exact zero)
        return b
    return brentq(f, a, b, xtol=1e-14, rtol=1e-15)


def _next_liftoff(p: Point, t0: float, end: float, spt: int, block_turns: int) -> float:
    """First θ > t0 with L ≥ 0 along the rolling branch (NaN if none before `end`)."""
    h = TAU / spt
    start = t0
    while start < end:
        stop = min(start + TAU * block_turns, end)
        k = max(1, math.ceil((stop - start) / h))
        th = np.linspace(start, stop, k + 1)
        lift = p.lift(th)
        hits = np.flatnonzero(lift[1:] >= 0.0)
        if hits.size:
            i = hits[0] + 1
            return _root(p.lift, th[i - 1], th[i])
        start = stop
    return math.nan


# ------------------------------------------------------------------------------------------
# (b) ODE route: solve_ivp with terminal events
# ------------------------------------------------------------------------------------------
def classify_ode(
    alpha: float,
    chi: float,
    km: float,
    mu_s: float,
    *,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
) -> Verdict:
    """Classify one point by integrating the rolling equation with scipy's RK45 and events."""
    sp = _special(alpha, chi, km, mu_s, max_turns)
    if isinstance(sp, Verdict):
        return sp
    p, n_star = sp
    end = TAU * min(n_star, max_turns)
    sa, ca, ic = p.sa, p.ca, p.ic

    def state(y):
        th, w = y
        s, c = math.sin(th), math.cos(th)
        wdd = (chi * w * w * s + chi * (sa * c + ca * s) + sa) / (ic + 1.0 + 2.0 * chi * c)
        fx = -sa - chi * w * w * s + (1.0 + chi * c) * wdd
        fy = ca - chi * w * w * c - chi * wdd * s
        return wdd, fx, fy, chi * w * w * c - ca

    def rhs(_t, y):
        return [y[1], state(y)[0]]

    def ev_lift(_t, y):
        return state(y)[3]

    def ev_fy(_t, y):
        return state(y)[2]

    def ev_slip(_t, y):
        _, fx, fy, _ = state(y)
        return mu_s * fy - abs(fx)

    def ev_end(_t, y):
        return y[0] - end

    ev_lift.terminal, ev_lift.direction = True, 1
    ev_fy.terminal, ev_fy.direction = True, -1
    ev_slip.terminal, ev_slip.direction = True, -1
    ev_end.terminal, ev_end.direction = True, 1

    # θ = 0 itself
    _, fx0, fy0, l0 = state((0.0, 0.0))
    if l0 >= 0.0:
        return p.judge_liftoff(0.0)
    if fy0 <= 0.0:
        return Verdict(NORMAL_FORCE_LOST, math.nan, 0.0)
    if mu_s * fy0 - abs(fx0) < 0.0:
        return p.judge_slip(0.0, _ode_liftoff(rhs, ev_lift, ev_end, [0.0, 0.0], rtol, atol))

    t_max = 1e9
    sol = solve_ivp(
        rhs,
        (0.0, t_max),
        [0.0, 0.0],
        method="RK45",
        rtol=rtol,
        atol=atol,
        events=[ev_lift, ev_fy, ev_slip, ev_end],
    )
    hit = [(ys[0][0], i) for i, ys in enumerate(sol.y_events) if len(ys)]
    if not hit:
        return Verdict(NO_ROOT, math.nan, math.nan)
    t_ev, kind = _first(hit, 1e-9)
    y_ev = sol.y_events[kind][0]
    # scipy drops the events after the first terminal one in a step: resolve near-ties by the
    # values at the event (at Ĩ_CM = 0 the slip margin vanishes together with F_y).
    _, _, fy_ev, l_ev = state(y_ev)
    if kind > 0 and l_ev >= -1e-9:
        kind = 0
    elif kind > 1 and fy_ev <= 1e-9:
        kind = 1
    if kind == 0:
        return p.judge_liftoff(t_ev)
    if kind == 1:
        return Verdict(NORMAL_FORCE_LOST, math.nan, t_ev)
    if kind == 2:
        tl = _ode_liftoff(rhs, ev_lift, ev_end, y_ev, rtol, atol)
        return p.judge_slip(t_ev, tl)
    return Verdict(TURN_LIMIT if n_star > max_turns else NO_ROOT, math.nan, math.nan)


def _ode_liftoff(rhs, ev_lift, ev_end, y0, rtol: float, atol: float) -> float:
    """Continue along rolling from y0 to the next rising zero of L (NaN if none)."""
    sol = solve_ivp(
        rhs,
        (0.0, 1e9),
        list(y0),
        method="RK45",
        rtol=rtol,
        atol=atol,
        events=[ev_lift, ev_end],
    )
    if len(sol.y_events[0]):
        return float(sol.y_events[0][0][0])
    return math.nan


def classify_many(alpha, chi, km, mu_s: float, method: str = "closed_form") -> np.ndarray:
    """Reason codes and θ_J for arrays of points (a plain Python loop over points)."""
    fn = classify_closed_form if method == "closed_form" else classify_ode
    a, c, k = np.broadcast_arrays(np.asarray(alpha, float), np.asarray(chi, float), km)
    out = np.empty((a.size, 2))
    for i, (ai, ci, ki) in enumerate(zip(a.ravel(), c.ravel(), np.ravel(k), strict=True)):
        v = fn(float(ai), float(ci), float(ki), mu_s)
        out[i] = v.reason, v.theta_J
    return out.reshape((*a.shape, 2))
