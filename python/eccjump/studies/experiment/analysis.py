"""``eccjump.analyze``: a tracked experiment in, a verdict with its evidence out.

Verdicts:

* ``jarm``: the body left the ramp straight from pure rolling -- the fitted model rolls up
  to its lift-off (or slips for less than one frame, and a fit that forbids any slip before
  the lift-off is as good), and the track shows the flight beyond its noise;
* ``slip_first``: it slipped from t1 to t2 before lifting off -- the fitted model slips for
  at least one frame before its lift-off, and the fit that forbids it is worse by a
  chi-square of at least :data:`SIGNIFICANT` (3 standard errors);
* ``undetermined``, with the reason: ``no_liftoff`` (the track never leaves the ramp),
  ``noise`` (the flight, or the slip, is within the noise), ``frame_rate`` (a slip shorter
  than :data:`MIN_SLIP_FRAMES` frames that the data cannot confirm), ``short_track`` (no
  rolling before the lift-off to judge it by) or ``model`` (the track flies where the fitted
  model does not: check the inputs).
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, get_args

import numpy as np

from eccjump._base.body import Cylinder
from eccjump._base.checks import Rule, flag, integer, optional_real, rule_name, short
from eccjump._base.html import card
from eccjump.studies.experiment import figure
from eccjump.studies.experiment.events import Observed, Window, observe
from eccjump.studies.experiment.fit import (
    UNITS,
    Fit,
    Setup,
    event_times,
    fit,
    profile,
    profile_interval,
    rolling_needs,
    slip_intervals,
    time_errors,
)
from eccjump.studies.experiment.inputs import MARKER_IN_R, in_range
from eccjump.studies.experiment.reconstruct import MIN_WINDOW, Reconstruction, reconstruct
from eccjump.studies.experiment.sheet import design_inputs
from eccjump.studies.experiment.track import MAX_FRAMES, Track, load_track

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

VERDICTS = ("jarm", "slip_first", "undetermined")
REASONS = ("", "no_liftoff", "noise", "frame_rate", "short_track", "model")
#: The chi-square by which forbidding the slip must worsen the fit for a slip_first verdict.
SIGNIFICANT = 9.0
#: A slip shorter than this (in frames) may be reported as undetermined.
MIN_SLIP_FRAMES = 3.0


@dataclass(frozen=True)
class SlipInterval:
    """A slip of the fitted model before the lift-off: from t1 to t2 [s] with standard
    errors, and its length in frames."""

    t1: float
    t2: float
    t1_err: float
    t2_err: float
    frames: float


@dataclass(frozen=True, eq=False)
class Analysis:
    """The outcome of :func:`analyze`: the verdict, its reason (for ``undetermined``) and
    evidence (sentences), the lift-off time [s] with its standard error (from the fitted
    model) and the observed window, the slips before it, the fits and what they rest on."""

    verdict: str
    reason: str
    evidence: tuple[str, ...]
    liftoff_t: float
    liftoff_err: float
    liftoff_window: Window | None
    slips: tuple[SlipInterval, ...]
    mu_k_interval: tuple[float, float]
    delta_chi2: float
    track: Track
    rec: Reconstruction
    observed: Observed
    fit: Fit
    fit_jarm: Fit | None
    setup: Setup
    times: dict[str, float]
    time_errs: dict[str, float]
    mu_s_needed: float
    seconds: float
    notes: tuple[str, ...] = field(default=())

    @property
    def model_modes(self) -> list[str]:
        end = float(self.track.t[-1] - self.track.t[0]) / self.setup.time_unit
        return [tr.to_mode for tr in self.fit.run.transitions if tr.t <= end]

    def parameters(self) -> dict[str, dict[str, Any]]:
        """The fitted parameters (value, ~95 % interval, unit), mu_s as a lower bound or a
        value, the ramp angle in degrees."""
        f, out = self.fit, {}
        for name in f.names:
            if name == "dmu":
                continue
            lo, hi = self.mu_k_interval if name == "mu_k" else f.interval(name)
            out[name] = {"value": f.value(name), "lo": lo, "hi": hi, "unit": UNITS.get(name, "")}
        mu_s = f.value("mu_k") + f.value("dmu")
        lo_s, hi_s = _mu_s_interval(f)
        out["mu_s"] = {
            "value": mu_s,
            "lo": lo_s,
            "hi": hi_s,
            "unit": "",
            "rolling_needs": self.mu_s_needed,
        }
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (NaN as None)."""
        t0 = float(self.track.t[0])
        obs = self.observed
        d: dict[str, Any] = {
            "verdict": self.verdict,
            "reason": self.reason or None,
            "evidence": list(self.evidence),
            "liftoff_t": self.liftoff_t,
            "liftoff_t_err": self.liftoff_err,
            "liftoff_window": _win(self.liftoff_window),
            "slip_intervals": [vars(s) for s in self.slips],
            "landing_t": _abs(self.times["landing"], t0, self.setup.time_unit),
            "landing_t_err": self.time_errs["landing"],
            "observed": {
                "modes": obs.sequence(),
                "flights": [
                    {
                        "liftoff": _win(f.liftoff),
                        "apex": _win(f.apex),
                        "apex_height": f.apex_height,
                        "apex_err": f.apex_err,
                        "landing": _win(f.landing),
                    }
                    for f in obs.flights
                ],
                "slips": [{"onset": _win(s.onset), "end": _win(s.end)} for s in obs.slips],
            },
            "model": {
                "modes": self.model_modes,
                "chi2_reduced": self.fit.chi2_reduced,
                "delta_chi2_no_slip": self.delta_chi2,
                "rule": self.setup.rule,
            },
            "parameters": self.parameters(),
            "inputs": {
                "chi": self.setup.body.chi,
                "km": self.setup.body.km,
                "radius": self.setup.radius,
                "alpha_deg": math.degrees(self.rec.line.frame.alpha),
                "alpha_err_deg": math.degrees(self.rec.line.alpha_err),
                "marker_radius": self.setup.marker_radius,
                "marker_angle_deg": math.degrees(self.setup.marker_angle),
                "g": self.setup.g,
            },
            "track": {
                "source": self.track.source,
                "frames": self.track.n,
                "fps": 1.0 / self.track.dt,
                "noise_m": self.rec.sigma,
                "window_frames": self.rec.window,
            },
            "notes": list(self.notes),
            "seconds": self.seconds,
        }
        return _clean(d)

    def __repr__(self) -> str:
        head = f"Analysis: {self.verdict}" + (f" ({self.reason})" if self.reason else "")
        lines = [head]
        if math.isfinite(self.liftoff_t):
            lines.append(f"  lift-off    t = {self.liftoff_t:.5f} +- {self.liftoff_err:.1e} s")
        for s in self.slips:
            lines.append(f"  slip        {s.t1:.5f} .. {s.t2:.5f} s ({s.frames:.1f} frames)")
        lo, hi = self.mu_k_interval
        lines.append(f"  mu_k        {self.fit.value('mu_k'):.3f} in [{lo:.3f}, {hi:.3f}]")
        mu_s = self.parameters()["mu_s"]
        lines.append(
            f"  mu_s        {mu_s['value']:.3f} in [{mu_s['lo']:.3f}, {mu_s['hi']:.3g}]; "
            f"the rolling needed >= {self.mu_s_needed:.3f}"
        )
        lines.append(f"  observed    {' -> '.join(self.observed.sequence())}")
        lines.append(f"  model       {' -> '.join(self.model_modes[:8])}")
        lines.extend(f"  - {e}" for e in self.evidence[:6])
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        lo, hi = self.mu_k_interval
        rows = [("verdict", self.verdict + (f" ({self.reason})" if self.reason else ""))]
        if math.isfinite(self.liftoff_t):
            rows.append(("lift-off", f"t = {self.liftoff_t:.5f} ± {self.liftoff_err:.1e} s"))
        rows += [
            (f"slip {k + 1}", f"{s.t1:.5f} … {s.t2:.5f} s ({s.frames:.1f} frames)")
            for k, s in enumerate(self.slips)
        ]
        rows += [
            ("mu_k", f"{self.fit.value('mu_k'):.3f} in [{lo:.3f}, {hi:.3f}]"),
            ("mu_s", f">= {self.mu_s_needed:.3f} (what the observed rolling needed)"),
            ("observed", " → ".join(self.observed.sequence())),
            ("model", " → ".join(self.model_modes[:8])),
            (
                "track",
                f"{self.track.n} frames at {1 / self.track.dt:.4g} fps, noise "
                f"{self.rec.sigma * 1e3:.3g} mm",
            ),
        ]
        rows += [("evidence", e) for e in self.evidence]
        return card("Analysis of a tracked experiment", rows)

    def plot(self, **kwargs: Any) -> Figure:
        """Data and model: theta, the slip velocity, the height of C, the modes as bands
        (``eccjump.studies.experiment.figure``; needs ``pip install eccjump[plot]``)."""
        return figure.analysis_figure(self, **kwargs)


def analyze(
    track: Track | str | os.PathLike[str],
    *,
    radius: float | None = None,
    chi: float | None = None,
    km: float | None = None,
    alpha: float | None = None,
    marker_angle: float = 0.0,
    marker_radius: float | None = None,
    scale: float | None = None,
    design: str | os.PathLike[str] | dict[str, Any] | None = None,
    g: float = 9.81,
    rule: Rule = "paper",
    window: int | None = None,
    profile_mu_k: bool = True,
) -> Analysis:
    """Analyse a tracked experiment: did the body jump straight out of pure rolling?

    Reads the track (axle C and a marker M in the lab frame), reconstructs theta, l, b and
    the slip velocity in the ramp frame with their errors from the data's noise, detects and
    times slips, lift-off, apex and landing, fits ``eccjump.simulate`` to the tracked points
    (the start, mu_k, mu_s, e, and alpha if not given) and gives the verdict with its
    evidence. The fit needs scipy (``pip install eccjump[analysis]``).

    Parameters
    ----------
    track : Track, str or path
        A :class:`Track`, or the path of a CSV (``t,xc,yc,xm,ym``; s, and m or px) or of
        Tracker's exported data table (``"-"``: the standard input); a regular file of at
        most 64 MiB and 10,000 frames (``read_track``).
    radius : float or None
        R [m], in [1e-4, 10]; or from ``design``.
    chi, km : float or None
        The body (chi in [0, 1], km in (0, 1 - chi]); or from ``design``. Explicit values win.
    alpha : float or None
        The ramp angle [rad], in [0, pi/2]; None estimates it from the axle's path in
        contact, with its standard error.
    marker_angle : float, default 0.0
        The marker's angle from the direction axle -> centre of mass [rad], measured like
        theta (towards the direction of rolling), in [-2 pi, 2 pi].
    marker_radius : float or None
        The marker's distance from the axle [m], in [R/1000, 2 R]; None measures it from the
        track (which must put it there too: a track in pixels without ``scale`` does not).
    scale : float or None
        Pixels per metre, in [1, 1e9], when the file holds pixels.
    design : str, path, dict or None
        A sheet of ``eccjump design --json`` (its path or its dict) for the body, R and alpha.
    g : float, default 9.81
        Gravity [m/s^2], in [0.01, 100].
    rule : {"paper", "normal_force"}, default "paper"
        The lift-off rule of the model.
    window : int or None
        The smoothing window in frames (an odd int, at least 7, at most the frames); None
        chooses it from the frame rate.
    profile_mu_k : bool, default True
        Widen mu_k's interval by its profile (a few seconds; the local interval alone can
        miss a second minimum). True or False, nothing else.

    Returns
    -------
    Analysis
        ``verdict`` (``"jarm"``, ``"slip_first"`` or ``"undetermined"``) with its
        ``reason`` and ``evidence``, ``liftoff_t`` [s] and ``liftoff_err``, ``slips``, the
        fitted parameters and their intervals (``mu_k_interval``), ``to_dict()`` for the
        JSON report and ``plot()`` for the figure.

    Raises
    ------
    ValueError
        For a bad track (a file that is not a regular file or is too large, a row whose
        cells do not match the header, NaN, unsorted or repeated times, missing columns, too
        few or too many frames) or a parameter outside its range; the message names it.
    TypeError
        For an argument of the wrong type.

    Examples
    --------
    >>> import math, eccjump
    >>> from eccjump.studies.experiment import synthetic_track
    >>> body = eccjump.Cylinder(0.10927, 0.0777)
    >>> alpha = math.radians(66.087)
    >>> made = synthetic_track(body, alpha, mu_s=1.2, mu_k=0.9, radius=0.05, fps=240.0,
    ...                        noise_px=0.5, seed=1)
    >>> res = eccjump.analyze(made.track, radius=0.05, chi=body.chi, km=body.km,
    ...                       alpha=alpha, marker_radius=0.04, profile_mu_k=False)
    >>> print(res.verdict, round(res.liftoff_t, 3))
    jarm 0.246
    """
    started = time.perf_counter()
    body, R, a_given, notes = _inputs(radius, chi, km, alpha, design)
    beta = in_range("marker_angle", marker_angle)
    gg = in_range("g", g)
    px = None if scale is None else in_range("scale", scale)
    r_m = _marker_radius(marker_radius, R)
    w = None if window is None else integer("window", window, MIN_WINDOW, MAX_FRAMES)
    profiled = flag("profile_mu_k", profile_mu_k)
    rule = _rule(rule)
    if not isinstance(track, Track):
        track = load_track(track, scale=px, fmt="auto", name="track")
    _check_marker_distance(track, R, px)
    rec = reconstruct(
        track, radius=R, marker_angle=beta, marker_radius=r_m, alpha=a_given, window=w
    )
    notes += _marker_note(rec, r_m)
    setup = Setup(
        body,
        rec.line.frame.alpha,
        R,
        gg,
        rec.marker_radius,
        beta,
        rule,
        fit_alpha=a_given is None,
    )
    observed = observe(rec)
    best = fit(setup, track, rec)
    mu_k_iv = best.interval("mu_k")
    if profiled:
        grid, costs = profile(best, setup, track, rec)
        mu_k_iv = profile_interval(grid, costs, best)
    return _judge(track, rec, observed, best, setup, mu_k_iv, notes, started)


def _judge(
    track: Track,
    rec: Reconstruction,
    observed: Observed,
    best: Fit,
    setup: Setup,
    mu_k_iv: tuple[float, float],
    notes: tuple[str, ...],
    started: float,
) -> Analysis:
    unit, t0, dt = setup.time_unit, float(track.t[0]), track.dt
    horizon = float(track.t[-1] - t0) / unit
    times = event_times(best.run, horizon)
    errs = time_errors(best, setup, track, rec)
    lift = times["liftoff"]
    slips_dimless = slip_intervals(best.run, lift if math.isfinite(lift) else horizon)
    slip_frames = sum(b - a for a, b in slips_dimless) * unit / dt
    needs = rolling_needs(best.run, lift if math.isfinite(lift) else horizon)
    evidence: list[str] = []
    verdict, reason, delta, jarm_fit = "undetermined", "", math.nan, None
    seen = observed.flights[0] if observed.flights else None
    if seen is None and not math.isfinite(lift):
        reason = "no_liftoff"
        evidence.append(
            "the track never leaves the ramp: the axle stays on its contact line "
            f"within {3 * rec.sigma * 1e3:.2g} mm (3 sigma), and so does the model"
        )
    elif seen is None:
        reason = "noise"
        evidence.append(
            f"the model lifts off at t = {t0 + lift * unit:.4f} s, but its flight "
            f"stays within 3 sigma = {3 * rec.sigma * 1e3:.2g} mm of the ramp"
        )
    elif not math.isfinite(lift):
        reason = "model"
        evidence.append(
            f"the track flies ({seen.apex_height * 1e3:.3g} mm above the ramp) but "
            "the fitted model does not leave it: check chi, km, alpha, R"
        )
    elif (lift * unit) < 4 * dt:
        reason = "short_track"
        evidence.append(
            "the lift-off comes within 4 frames of the track's start: no rolling to judge it by"
        )
    else:
        evidence.append(
            f"the axle rises {seen.apex_height * 1e3:.3g} mm above the ramp "
            f"({observed.peak_snr:.0f} sigma); lift-off seen in "
            f"[{seen.liftoff.lo:.4f}, {seen.liftoff.hi:.4f}] s"
        )
        if slip_frames <= 0:
            verdict = "jarm"
            evidence.append(
                f"the fitted model rolls without slipping from the first frame to "
                f"its lift-off at t = {t0 + lift * unit:.5f} s"
            )
        else:
            jarm_fit = fit(setup, track, rec, jarm_only=True, starts=[_as_start(best)])
            delta = 2.0 * (jarm_fit.cost - best.cost) / max(best.chi2_reduced, 1e-12)
            verdict, reason = _slip_verdict(slip_frames, delta)
            evidence.append(
                f"the fitted model slips for {slip_frames:.1f} frames before its "
                f"lift-off; forbidding that slip worsens the fit by chi2 = "
                f"{delta:.3g} (significant above {SIGNIFICANT:g})"
            )
    evidence.append(
        f"the rolling before it needs mu_s >= {needs:.3f} (the model's friction ratio |F_x|/F_y)"
    )
    slips = tuple(
        SlipInterval(
            t0 + a * unit,
            t0 + b * unit,
            errs["slip_onset"] if k == 0 else math.nan,
            errs["slip_end"] if k == len(slips_dimless) - 1 else math.nan,
            (b - a) * unit / dt,
        )
        for k, (a, b) in enumerate(slips_dimless)
    )
    if verdict == "jarm":
        slips = ()
    return Analysis(
        verdict=verdict,
        reason=reason,
        evidence=tuple(evidence),
        liftoff_t=_abs(lift, t0, unit),
        liftoff_err=errs["liftoff"],
        liftoff_window=seen.liftoff if seen else None,
        slips=slips,
        mu_k_interval=mu_k_iv,
        delta_chi2=delta,
        track=track,
        rec=rec,
        observed=observed,
        fit=best,
        fit_jarm=jarm_fit,
        setup=setup,
        times=times,
        time_errs=errs,
        mu_s_needed=needs,
        seconds=time.perf_counter() - started,
        notes=notes,
    )


def _slip_verdict(frames: float, delta: float) -> tuple[str, str]:
    if delta >= SIGNIFICANT and frames >= 1.0:
        return "slip_first", ""
    if frames < 1.0:
        return "jarm", ""  # a slip shorter than a frame that the data do not ask for
    return "undetermined", "frame_rate" if frames < MIN_SLIP_FRAMES else "noise"


def _as_start(f: Fit) -> dict[str, float]:
    start = {n: f.value(n) for n in f.names}
    start["omega0"] = max(start["omega0"], 0.0)
    return start


def _inputs(
    radius: float | None,
    chi: float | None,
    km: float | None,
    alpha: float | None,
    design: str | os.PathLike[str] | dict[str, Any] | None,
) -> tuple[Cylinder, float, float | None, tuple[str, ...]]:
    sheet = design_inputs(design) if design is not None else {}
    notes: tuple[str, ...] = ()
    given = {"radius": radius, "chi": chi, "km": km, "alpha": alpha}
    for name, v in given.items():
        optional_real(name, v)  # the type first, as given
    R, c, k, a = (v if v is not None else sheet.get(name) for name, v in given.items())
    for name, v in (("radius", R), ("chi", c), ("km", k)):
        if v is None:
            raise ValueError(f"{name} is needed (give it, or a design sheet that holds it)")
    assert R is not None and c is not None and k is not None
    R = in_range("radius", R, "" if radius is not None else " (from design)")
    if a is not None:
        a = in_range("alpha", a, "" if alpha is not None else " (from design)")
    body = Cylinder(chi=c, km=k)
    if not body.km > 0:
        raise ValueError("km must be > 0: the model's spin in flight is undetermined at km = 0")
    return body, R, a, notes


def _marker_radius(value: object, radius: float) -> float | None:
    """marker_radius [m] within MARKER_IN_R times R, or None."""
    r = optional_real("marker_radius", value)
    lo, hi = MARKER_IN_R
    if r is not None and not lo * radius <= r <= hi * radius:
        raise ValueError(
            f"marker_radius = {short(r)} m is outside the allowed range [R/{1 / lo:g}, "
            f"{hi:g} R] = [{lo * radius:.4g}, {hi * radius:.4g}] m"
        )
    return r


def _check_marker_distance(track: Track, radius: float, scale: float | None) -> None:
    """The tracked marker must be a point of the body (within 2 R of the axle, as
    marker_radius): a track in pixels without ``scale`` has it tens of "metres" away."""
    d = float(np.median(np.hypot(*(track.m - track.c).T)))
    lo, hi = MARKER_IN_R
    if d > hi * radius:
        why = "a track in pixels needs it [px/m]" if scale is None else "check it and the radius"
        raise ValueError(
            f"scale: the tracked marker is {d:.4g} m from the axle, more than {hi:g} R = "
            f"{hi * radius:.4g} m: {why}"
        )
    if d < lo * radius:
        raise ValueError(
            f"xm, ym: the tracked marker is {d:.3g} m from the axle, less than R/{1 / lo:g}: "
            "track a point away from the axle (or check scale)"
        )


def _rule(value: object) -> Rule:
    name = rule_name(value)
    if name not in get_args(Rule):
        raise ValueError(f"rule must be 'paper' or 'normal_force', got {short(name)}")
    return name


def _marker_note(rec: Reconstruction, given: float | None) -> tuple[str, ...]:
    measured = rec.marker_measured
    if given is None:
        return (f"marker_radius measured from the track: {measured * 1e3:.4g} mm",)
    if abs(measured - given) < 0.1 * given + 3 * rec.sigma:
        return ()
    return (
        f"the tracked marker is {measured * 1e3:.4g} mm from the axle, not the "
        f"{given * 1e3:.4g} mm given as marker_radius",
    )


def _mu_s_interval(f: Fit) -> tuple[float, float]:
    i, j = f.names.index("mu_k"), f.names.index("dmu")
    var = f.cov[i, i] + f.cov[j, j] + 2 * f.cov[i, j]
    v = f.value("mu_k") + f.value("dmu")
    if not math.isfinite(var):
        return f.value("mu_k"), math.inf
    e = 1.96 * math.sqrt(max(var, 0.0))
    return max(v - e, 0.0), v + e


def _abs(t: float, t0: float, unit: float) -> float:
    return t0 + t * unit if math.isfinite(t) else math.nan


def _win(w: Window | None) -> dict[str, float] | None:
    return None if w is None else w.as_dict()


def _clean(x: Any) -> Any:
    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_clean(v) for v in x]
    if isinstance(x, float | np.floating):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, np.integer):
        return int(x)
    return x
