"""Tracks filmed from the independent model (``reference_motion.py``, scipy, not ``simulate``):
the held-out check of ``eccjump.analyze`` (issue 48). Shared by the tests and the campaign
(``pytest -m campaign tests/test_analysis_verdict.py``).

The reference gives the transitions (times and states); between two of them the mode's
equations of the reference (``newton_euler``, the free flight) are integrated again from the
transition's state to the frame times, so the frames carry the reference's motion to its
tolerance. Frames: from t = 0 at ``fps``, to the first landing and half a flight more.
Camera: a field of ``field_px`` pixels across the whole track, Gaussian noise of ``noise_px``
per coordinate, a camera rolled by ``roll_deg`` (the lab frame turned), positions in metres.

:func:`draw` makes a seeded case of a family: ``jarm`` (rolls to its lift-off), ``slip``
(slips for ``frames`` frames in all before its lift-off, by bisection on mu_s), ``long_slip``
(10 to 200 frames), ``stick_slip`` (the issue's body, which slips, sticks and slips again).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from reference_motion import FLIGHT, ROLL, SLIP, Body, newton_euler, simulate_reference
from scipy.integrate import solve_ivp

from eccjump.studies.experiment.track import Track

G = 9.81


@dataclass(frozen=True)
class Case:
    """A body on a ramp with its friction, start and camera (angles in radians)."""

    chi: float
    km: float
    alpha: float
    mu_s: float
    mu_k: float
    theta0: float
    omega0: float  # dimensionless (per sqrt(R/g))
    restitution: float = 0.0
    radius: float = 0.05
    fps: float = 240.0
    noise_px: float = 0.5
    marker_angle: float = 0.6
    marker_in_r: float = 0.8
    roll_deg: float = 0.0
    seed: int = 0
    family: str = ""


@dataclass(frozen=True, eq=False)
class RefTrack:
    """The track (metres) and the truth: the first lift-off [s] (NaN if none), the slips
    before it [(t1, t2) s] (a reversal continues a slip), their total in frames."""

    case: Case
    track: Track
    liftoff: float
    slips: list[tuple[float, float]] = field(default_factory=list)

    @property
    def slip_frames(self) -> float:
        return sum(b - a for a, b in self.slips) * self.case.fps


def _mode_runs(res: dict, horizon: float) -> list[tuple[float, float, str, tuple[float, ...]]]:
    """(t_start, t_end, mode, start state (th, om, l, ld, b, bd)) of every segment."""
    trs = res["transitions"]
    out = []
    for k, tr in enumerate(trs):
        t, mode, state = tr[0], tr[2], tuple(tr[4:10])
        end = trs[k + 1][0] if k + 1 < len(trs) else horizon
        if mode is not None and t < horizon:
            out.append((t, min(end, horizon), mode, state))
    return out


def _sigma(body: Body, mode_prev: str | None, sig_prev: float, state: tuple) -> float:
    """The sign of the friction of a slip that starts at ``state`` (as the reference's
    ``decide``): against the slip velocity; at v = 0 a reversal (after a slip) or the
    direction the rolling branch needs."""
    th, om, _, ld, _, _ = state
    v = ld - om
    if abs(v) > 1e-9:
        return -math.copysign(1.0, v)
    if mode_prev == SLIP:
        return -sig_prev
    return 1.0 if newton_euler(body, ROLL, th, om)[3] >= 0 else -1.0


def _sample(body: Body, mu_k: float, runs: list, tau: np.ndarray) -> np.ndarray:
    """(n, 3) theta, l, b (dimensionless) at the times ``tau``."""
    out = np.full((tau.size, 3), np.nan)
    prev, sig = None, 0.0
    for t0, t1, mode, st in runs:
        th, om, x, ld, b, bd = st
        sig = _sigma(body, prev, sig, st) if mode == SLIP else 0.0
        prev = mode
        idx = np.flatnonzero((tau >= t0) & (tau < t1) if t1 > t0 else tau == t0)
        if not idx.size:
            continue
        te = tau[idx]
        if mode == ROLL:

            def rhs(_t, y):
                return [y[1], newton_euler(body, ROLL, y[0], y[1])[0]]

            y0 = [th, om]
        elif mode == SLIP:

            def rhs(_t, y, sg=sig):
                z = newton_euler(body, SLIP, y[0], y[1], sg, mu_k)
                return [y[1], z[0], y[3], z[1]]

            y0 = [th, om, x, ld]
        else:

            def rhs(_t, y, w=om):
                return [w, 0.0, y[3], body.chi * w * w * math.sin(y[0]) + body.sa, y[5],
                        body.chi * w * w * math.cos(y[0]) - body.ca]  # fmt: skip

            y0 = [th, om, x, ld, b, bd]
        sol = solve_ivp(rhs, (t0, float(te[-1]) + 1e-12), y0, t_eval=te, rtol=1e-10,
                        atol=1e-12, method="DOP853")  # fmt: skip
        y = sol.y
        if mode == ROLL:
            out[idx] = np.column_stack([y[0], x + (y[0] - th), np.ones(te.size)])
        elif mode == SLIP:
            out[idx] = np.column_stack([y[0], y[2], np.ones(te.size)])
        else:
            out[idx] = np.column_stack([y[0], y[2], y[4]])
    return out


def _truth(res: dict, horizon: float) -> tuple[float, list[tuple[float, float]]]:
    """The first lift-off and the slips before it (dimensionless)."""
    runs = _mode_runs(res, horizon)
    lift = next((t0 for t0, _, mode, _ in runs if mode == FLIGHT), math.nan)
    slips: list[tuple[float, float]] = []
    for t0, t1, mode, _ in runs:
        if mode == SLIP and (math.isnan(lift) or t0 < lift):
            end = t1 if math.isnan(lift) else min(t1, lift)
            if slips and t0 <= slips[-1][1]:
                slips[-1] = (slips[-1][0], end)
            else:
                slips.append((t0, end))
    return lift, slips


def _simulate(c: Case, t_max: float) -> dict:
    return simulate_reference(c.chi, c.km, c.alpha, mu_s=c.mu_s, mu_k=c.mu_k,
                              restitution=c.restitution, theta0=c.theta0, omega0=c.omega0,
                              t_max=t_max, max_transitions=30, rtol=1e-10, atol=1e-12)  # fmt: skip


def film(c: Case) -> RefTrack:
    """The track of case ``c`` (module docstring)."""
    unit = math.sqrt(c.radius / G)
    res = _simulate(c, 3.0 / unit)
    trs = res["transitions"]
    lift = next((tr[0] for tr in trs if tr[2] == FLIGHT), math.nan)
    land = next((tr[0] for tr in trs if tr[1] == FLIGHT), math.nan)
    horizon = res["end"][0]
    if math.isfinite(land):
        horizon = min(horizon, land + 0.5 * (land - lift))
    tau = np.arange(0.0, horizon, 1.0 / (c.fps * unit))
    body = Body(c.chi, c.km, c.alpha)
    th, x, b = _sample(body, c.mu_k, _mode_runs(res, horizon + 1e-9), tau).T
    ca, sa = math.cos(c.alpha), math.sin(c.alpha)
    x_hat, y_hat = np.array([ca, -sa]), np.array([sa, ca])
    qc = np.column_stack([c.radius * x, c.radius * (b - 1.0)])
    r_m, phi = c.marker_in_r * c.radius, th + c.marker_angle
    qm = qc + r_m * np.column_stack([np.sin(phi), np.cos(phi)])
    lab_c, lab_m = qc @ np.vstack([x_hat, y_hat]), qm @ np.vstack([x_hat, y_hat])
    rot = math.radians(c.roll_deg)
    turn = np.array([[math.cos(rot), math.sin(rot)], [-math.sin(rot), math.cos(rot)]])
    lab_c, lab_m = lab_c @ turn, lab_m @ turn
    pts = np.vstack([lab_c, lab_m])
    extent = 1.1 * float(max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1])))
    noise = c.noise_px * extent / 1000.0
    rng = np.random.default_rng(c.seed)
    lab_c = lab_c + rng.normal(0.0, noise, lab_c.shape)
    lab_m = lab_m + rng.normal(0.0, noise, lab_m.shape)
    track = Track(t=tau * unit, c=lab_c, m=lab_m, source="reference")
    lift_t, slips = _truth(res, horizon)
    return RefTrack(c, track, lift_t * unit, [(a * unit, b_ * unit) for a, b_ in slips])


# --- families --------------------------------------------------------------------------------


def rolling_needs(c: Case) -> tuple[float, float]:
    """(the largest |F_x|/F_y of the pure rolling up to its lift-off, the lift-off time
    [dimensionless]; NaN if it does not lift off within 3 s)."""
    unit = math.sqrt(c.radius / G)
    res = simulate_reference(c.chi, c.km, c.alpha, mu_s=1e3, mu_k=1e3, theta0=c.theta0,
                             omega0=c.omega0, t_max=3.0 / unit, max_transitions=2)  # fmt: skip
    trs = res["transitions"]
    if len(trs) < 2 or trs[1][2] != FLIGHT:
        return math.nan, math.nan
    lift = trs[1][0]
    body = Body(c.chi, c.km, c.alpha)
    tau = np.linspace(0.0, lift, 400)
    th = _sample(body, 0.0, _mode_runs(res, lift + 1e-9), tau)[:, 0]
    om = np.gradient(th, tau)
    ratio = 0.0
    for a, w in zip(th, om, strict=True):
        z = newton_euler(body, ROLL, a, w)
        if z[4] > 0:
            ratio = max(ratio, abs(z[3]) / z[4])
    return ratio, lift


def _slip_frames(c: Case) -> float:
    unit = math.sqrt(c.radius / G)
    res = _simulate(c, 3.0 / unit)
    lift, slips = _truth(res, res["end"][0])
    if math.isnan(lift):
        return math.nan
    return sum(b - a for a, b in slips) * unit * c.fps


def _body(rng: np.random.Generator, fps: float, noise: float, seed: int, family: str) -> Case:
    chi = rng.uniform(0.1, 0.6)
    km = rng.uniform(0.05, 0.6) * (1 - chi)
    return Case(chi=chi, km=km, alpha=rng.uniform(0.4, 1.25), mu_s=1e3, mu_k=1e3,
                theta0=rng.uniform(-math.pi, math.pi), omega0=rng.uniform(0.0, 2.0),
                fps=fps, noise_px=noise, marker_angle=rng.uniform(-math.pi, math.pi),
                seed=seed, family=family)  # fmt: skip


def _lifts_visibly(c: Case) -> tuple[float, float]:
    """The rolling's need and lift-off, if it lifts off between 0.1 and 1 s."""
    need, lift = rolling_needs(c)
    unit = math.sqrt(c.radius / G)
    if not (math.isfinite(lift) and 0.1 < lift * unit < 1.0 and 0.05 < need < 2.0):
        return math.nan, math.nan
    return need, lift


def draw(family: str, seed: int, fps: float = 240.0, noise: float = 0.5) -> Case:
    """A seeded case of ``family`` (module docstring); ``slip`` aims at 1 to 10 frames."""
    rng = np.random.default_rng(48_000 + seed)
    if family == "stick_slip":  # the body: slips, sticks, slips again, lifts off
        base = Case(chi=0.2596466707595845, km=0.32057066331201517,
                    alpha=0.9014599094096946, mu_s=0.73965, mu_k=0.62730, theta0=0.0,
                    omega0=0.0, fps=fps, noise_px=noise, seed=seed, family=family)  # fmt: skip
        return base
    for _ in range(200):
        c = _body(rng, fps, noise, seed, family)
        need, _ = _lifts_visibly(c)
        if not math.isfinite(need):
            continue
        if family == "jarm":
            mu_s = need * rng.uniform(1.03, 1.5)
            return _with(c, mu_s, rng)
        lo_f, hi_f = (1.0, 10.0) if family == "slip" else (10.0, 200.0)
        target = rng.uniform(lo_f, hi_f)
        got = _bisect(c, need, target, rng)
        if got is not None:
            return got
    raise RuntimeError(f"no {family} case found for seed {seed}")


def _with(c: Case, mu_s: float, rng: np.random.Generator) -> Case:
    return Case(**{**c.__dict__, "mu_s": mu_s, "mu_k": mu_s * rng.uniform(0.6, 0.95)})


def _bisect(c: Case, need: float, target: float, rng: np.random.Generator) -> Case | None:
    """mu_s below ``need`` such that the slip before the lift-off lasts about ``target``
    frames (within 30 %), or None."""
    ratio = rng.uniform(0.6, 0.95)
    lo, hi = 0.3 * need, need
    for _ in range(14):
        mid = 0.5 * (lo + hi)
        trial = Case(**{**c.__dict__, "mu_s": mid, "mu_k": mid * ratio})
        try:
            frames = _slip_frames(trial)
        except (RuntimeError, np.linalg.LinAlgError, ValueError):
            return None
        if not math.isfinite(frames):
            lo = mid  # no lift-off: too little friction
            continue
        if abs(frames - target) < 0.3 * target and frames >= 1.0:
            return trial
        if frames > target:
            lo = mid
        else:
            hi = mid
    return None


def systematic(c: Case, kind: str, sign: int) -> tuple[Case, dict]:
    """A misstatement of case ``c``: the camera rolled (``roll``: 3 deg), or the analysis
    told a wrong radius (``radius``: 10 %) -- the case and the analyze keywords to use."""
    if kind == "roll":
        return Case(**{**c.__dict__, "roll_deg": 3.0 * sign}), {}
    return c, {"radius": c.radius * (1 + 0.1 * sign)}
