"""``eccjump.analyze``: a tracked experiment in, a verdict with its evidence out.

The fit (``fit.py``) covers the track up to its second lift-off (bounces are left out: the
verdict is about the first lift-off) and carries the track's length scale as a nuisance
parameter (a scale from the dots' distance is off by parts in a thousand, which a rolling
body would read as a slip); errors correlated from frame to frame (a codec's) widen the
intervals and the slip test by ``fit.correlation_inflation``. The rules that turn the
fits into a verdict, its reason and its evidence are in ``verdict``.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, get_args

import numpy as np

from eccjump._base.body import Cylinder
from eccjump._base.canvas import Plottable
from eccjump._base.checks import Rule, flag, integer, optional_real, rule_name, short
from eccjump._base.docs import fill
from eccjump._base.html import card
from eccjump.maps.results import Result
from eccjump.studies.experiment import report
from eccjump.studies.experiment.events import Observed, Window, observe
from eccjump.studies.experiment.fit import (
    MU_MAX,
    UNITS,
    Fit,
    Setup,
    as_start,
    consistent_fits,
    fit,
    fitted_needs,
    flight_signal,
    horizon,
    misfit_p,
    slip_frames,
    until_liftoff,
)
from eccjump.studies.experiment.friction import MeasuredFriction, measured_friction, weigh
from eccjump.studies.experiment.geometry import path_angle
from eccjump.studies.experiment.inputs import MARKER_IN_R, in_range, marker_radius_in_range
from eccjump.studies.experiment.one_frame import one_frame_slip
from eccjump.studies.experiment.profiles import (
    mu_s_interval,
    profile,
    profile_interval,
    theta0_walk,
)
from eccjump.studies.experiment.reconstruction import MIN_WINDOW, Reconstruction, reconstruct
from eccjump.studies.experiment.release import REACH, release_frame
from eccjump.studies.experiment.runs import event_times, slip_intervals
from eccjump.studies.experiment.sheet import design_inputs
from eccjump.studies.experiment.times import time_errors
from eccjump.studies.experiment.track import (
    MAX_FRAMES,
    Track,
    first_frames,
    frames_from,
    load_track,
)
from eccjump.studies.experiment.verdict import (
    MISFIT_P,
    SIGNIFICANT,
    Verdict,
    decide,
    needs_sentence,
    unseen_hop,
)
from eccjump.studies.experiment.video import VideoTrack, is_video
from eccjump.studies.experiment.video import track as track_video

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

#: A given ramp angle further than this [rad] (and 4 standard errors) from the track's own
#: contact line gets a note: a rolled camera, a wrong alpha or a unit mistake.
ALPHA_TOLERANCE = math.radians(1.0)


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
class Analysis(Result, Plottable, kind="analysis"):
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
    #: mu_s's ~95 % interval: (lo, inf) a lower bound, (0, inf) not determined.
    mu_s_interval: tuple[float, float]
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
    #: The static friction measured apart from the track, if given (``friction``).
    mu_s_measured: MeasuredFriction | None = None

    @property
    def model_modes(self) -> list[str]:
        end = float(self.track.t[-1] - self.track.t[0]) / self.setup.time_unit
        return [tr.to_mode for tr in self.fit.run.transitions if tr.t <= end]

    def parameters(self) -> dict[str, dict[str, Any]]:
        """The fitted parameters (value, ~95 % interval, unit, ``status``), the ramp angle in
        radians. ``status`` is ``"value"``, ``"not_determined"`` (the track does not
        constrain it: its value is None, the interval the whole range; μ_k, μ_s and e
        whenever the reason is ``model``, since a model the track rejects fixes none of them)
        or, for μ_s, ``"lower_bound"`` (``mu_s_interval`` open above: a track that rolls,
        or slips only where its profile is flat; value None, hi inf)."""
        f, out = self.fit, {}
        rejected = self.reason == "model"  # the model does not describe the track
        for name in f.names:
            if name == "dmu":
                continue
            if name == "slip0" and f.jarm_only:  # a run that rolls from the start
                out[name] = {"value": 0.0, "lo": 0.0, "hi": 0.0, "unit": "m/s", "status": "value"}
                continue
            lo, hi = self.mu_k_interval if name == "mu_k" else f.interval(name)
            i = f.names.index(name)
            known = hi - lo < 0.9 * float(f.upper[i] - f.lower[i])
            if name == "e" and (rejected or not math.isfinite(self.times["landing"])):
                known = False  # a run that never lands says nothing of e; nor a rejected model
            out[name] = {
                "value": f.value(name) if known else math.nan,
                "lo": lo,
                "hi": hi,
                "unit": UNITS.get(name, ""),
                "status": "value" if known else "not_determined",
            }
        lo_s, hi_s = self.mu_s_interval
        status = "lower_bound" if math.isinf(hi_s) else "value"
        if rejected or (lo_s <= 0.0 and math.isinf(hi_s)):
            lo_s, status = 0.0, "not_determined"
        out["mu_s"] = {
            "value": f.value("mu_k") + f.value("dmu") if status == "value" else math.nan,
            "lo": lo_s,
            "hi": hi_s if status == "value" else math.inf,
            "unit": "",
            "rolling_needs": self.mu_s_needed,
            "status": status,
        }
        return out

    def parameter_lines(self) -> list[tuple[str, str]]:
        """(name, text) of μ_k, μ_s and e: a value with its interval, a bound, or "not
        determined"."""
        out = []
        for name, p in self.parameters().items():
            if name not in ("mu_k", "mu_s", "e"):
                continue
            if p["status"] == "lower_bound":
                text = (
                    f">= {p['lo']:.3f} (the track's 95 % bound; the fitted rolling needs "
                    f"{p['rolling_needs']:.3f})"
                )
            elif p["status"] == "not_determined":
                text = "not determined by this track"
                if self.reason == "model":
                    text = "not determined (the model does not fit this track)"
            else:
                text = f"{p['value']:.3f} in [{p['lo']:.3f}, {p['hi']:.3g}]"
            if name == "mu_s" and self.mu_s_measured is not None:
                text += f"; measured {self.mu_s_measured.shown}"
            out.append((name, text))
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
                "mu_s_measured": self.mu_s_measured.as_dict() if self.mu_s_measured else None,
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

    def _liftoff_text(self, pm: str) -> str:
        if math.isfinite(self.liftoff_err):
            return f"t = {self.liftoff_t:.5f} {pm} {self.liftoff_err:.1e} s"
        seen = self.liftoff_window
        shown = f"; the track shows [{seen.lo:.4f}, {seen.hi:.4f}] s" if seen else ""
        return f"t = {self.liftoff_t:.5f} s (the model's, not fixed by the track{shown})"

    def __repr__(self) -> str:
        head = f"Analysis: {self.verdict}" + (f" ({self.reason})" if self.reason else "")
        lines = [head]
        if math.isfinite(self.liftoff_t):
            lines.append(f"  lift-off    {self._liftoff_text('+-')}")
        for s in self.slips:
            lines.append(f"  slip        {s.t1:.5f} .. {s.t2:.5f} s ({s.frames:.1f} frames)")
        lines.extend(f"  {name:<11} {text}" for name, text in self.parameter_lines())
        lines.append(f"  observed    {' -> '.join(self.observed.sequence())}")
        lines.append(f"  model       {' -> '.join(self.model_modes[:8])}")
        lines.extend(f"  - {e}" for e in self.evidence[:6])
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        rows = [("verdict", self.verdict + (f" ({self.reason})" if self.reason else ""))]
        if math.isfinite(self.liftoff_t):
            rows.append(("lift-off", self._liftoff_text("±")))
        rows += [
            (f"slip {k + 1}", f"{s.t1:.5f} … {s.t2:.5f} s ({s.frames:.1f} frames)")
            for k, s in enumerate(self.slips)
        ]
        rows += self.parameter_lines()
        rows += [
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

    _plot_doc = """Data and model against time: θ, the slip velocity, the height of C,
    the modes as bands (``eccjump.studies.experiment.figure``). ``ax=``: only θ, drawn
    into this matplotlib Axes and returned, to compose figures; ``fig=``: the full figure
    in this empty Figure or SubFigure. Needs ``pip install eccjump[plot]``."""

    def to_xarray(self) -> xr.Dataset:
        """The track, its reconstruction and the fitted model along ``frame`` with units, the
        verdict as attributes (needs xarray; :mod:`eccjump.studies.experiment.report`)."""
        return report.analysis_dataset(self)


@fill
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
    mu_s: float | None = None,
    mu_s_err: float | None = None,
    g: float = 9.81,
    rule: Rule = "paper",
    window: int | None = None,
    profile_mu_k: bool = True,
) -> Analysis:
    """Analyse a tracked experiment: did the body jump straight out of pure rolling?

    Reads the track (axle C and a marker M in the lab frame), reconstructs θ, l, b and
    the slip velocity in the ramp frame with their errors from the data's noise, detects and
    times slips, lift-off, apex and landing, fits ``eccjump.simulate`` to the tracked points
    (the start, μ_k, μ_s, e, and α if not given) and gives the verdict with its
    evidence. The fit needs scipy (``pip install eccjump[analysis]``).

    Parameters
    ----------
    track : Track, str or path
        A :class:`Track`, or the path of a CSV (``t,xc,yc,xm,ym``; s, and m or px) or of
        Tracker's exported data table (``"-"``: the standard input); a regular file of at
        most 64 MiB and 10,000 frames (``read_track``). Or the path of a video (known by
        its suffix or first bytes): tracked first by :func:`eccjump.track` with
        ``marker_radius`` or ``scale`` (and ``alpha`` for the camera's roll); needs
        ``pip install eccjump[video]``.
    radius : float or None
        R [m], in [1e-4, 10]; or from ``design``.
    chi, km : float or None
        The body (χ in [0, 1], k_m in (0, 1 − χ]); or from ``design``. Explicit values win.
    alpha : float or None
        The ramp angle [rad], in [0, π/2]; None estimates it from the axle's path in
        contact, with its standard error.
    marker_angle : float, default 0.0
        The marker's angle from the direction axle -> centre of mass [rad], measured like
        θ (towards the direction of rolling), in [−2π, 2π].
    marker_radius : float or None
        The marker's distance from the axle [m], in [R/1000, 2 R]; None measures it from the
        track (which must put it there too: a track in pixels without ``scale`` does not).
    scale : float or None
        Pixels per metre, in [1, 1e9], when the file holds pixels.
    design : str, path, dict or None
        A sheet of ``eccjump design --json`` (its path or its dict) for the body, R and α,
        and the measured μ_s if the sheet gives it with an uncertainty above 0.
    mu_s, mu_s_err : float or None
        The static friction measured apart from the track (a tilt test) and its standard
        deviation, in [0.001, 10] and [0.0001, 10]; both or neither. A track that rolls up
        to its lift-off cannot exclude a slip of one frame just before it (that slip needs
        only a μ_s a little below the rolling's need, and barely moves the body); a
        measured μ_s can, and the verdict's evidence then says it rests on it
        (``friction``).
    g : float, default 9.81
        Gravity [m/s²], in [0.01, 100].
    rule : {"paper", "normal_force"}, default "paper"
        The lift-off rule of the model.
    window : int or None
        The smoothing window in frames (an odd int, at least 7, at most the frames); None
        chooses it from the frame rate.
    profile_mu_k : bool, default True
        Widen the intervals of μ_k and μ_s by their profiles (a few seconds; a local
        interval alone can miss a second minimum, or a slip's onset, a kink in μ_s). True
        or False, nothing else.

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
    %(type_error)s

    Examples
    --------
    >>> import math, eccjump
    >>> from eccjump.studies.experiment import synthetic_track
    >>> body = eccjump.Cylinder(0.10927, 0.0777)
    >>> alpha = math.radians(66.087)
    >>> made = synthetic_track(body, alpha, mu_s=1.2, mu_k=0.9, radius=0.05, fps=240.0,
    ...                        noise_px=0.05, seed=1)
    >>> res = eccjump.analyze(made.track, radius=0.05, chi=body.chi, km=body.km,
    ...                       alpha=alpha, marker_radius=0.04, profile_mu_k=False)
    >>> print(res.verdict, round(res.liftoff_t, 3))
    jarm 0.246
    """
    started = time.perf_counter()
    sheet = design_inputs(design) if design is not None else {}
    body, R, a_given = _inputs(radius, chi, km, alpha, sheet)
    friction, notes = measured_friction(mu_s, mu_s_err, sheet)
    beta = in_range("marker_angle", marker_angle)
    gg = in_range("g", g)
    px = None if scale is None else in_range("scale", scale)
    r_m = marker_radius_in_range(marker_radius, R)
    w = None if window is None else integer("window", window, MIN_WINDOW, MAX_FRAMES)
    profiled = flag("profile_mu_k", profile_mu_k)
    rule = _rule(rule)
    if is_video(track):  # tracked first, as eccjump.track does: in metres
        track = track_video(track, marker_radius=r_m, scale=px, alpha=a_given)  # type: ignore[arg-type]
        px = None
    elif not isinstance(track, Track):
        track = load_track(track, scale=px, fmt="auto", name="track")
    if not isinstance(track, VideoTrack):  # (a video's track is cut by the tracker)
        track, notes = _after_release(track, R, notes)
    _check_marker_distance(track, R, px)
    rec = reconstruct(
        track, radius=R, marker_angle=beta, marker_radius=r_m, alpha=a_given, window=w
    )
    observed = observe(rec)
    n = _before_bounces(track, observed, rec.window)
    if n < track.n:  # the verdict is about the first lift-off: not the bounces
        notes += (_bounces_note(track, n),)
        track = first_frames(track, n)
        rec = reconstruct(
            track, radius=R, marker_angle=beta, marker_radius=r_m, alpha=a_given, window=w
        )
        observed = observe(rec)
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
    setup, (best, jarm_fit) = _consistent_fits(setup, track, rec)
    one = None  # asked only where the verdict could be jarm: a slip under a frame
    if slip_frames(best, setup, track) < 1.0:
        one = one_frame_slip(jarm_fit or best, setup, track, rec)
        if one.refit is not None and one.refit.cost < best.cost:
            # a slip the free fit missed explains the track better: judge from it
            # (a descent from the capped fit's run: never worse than it)
            best, jarm_fit = fit(setup, track, rec, starts=[as_start(one.refit)]), jarm_fit or best
            one = None
    power = math.nan if one is None else one.cost
    weighed: tuple[str, ...] = ()
    if friction is not None:
        best, jarm_fit, power, weighed = weigh(
            friction, (best, jarm_fit), one, (setup, track, rec), SIGNIFICANT
        )
    off_path = _alpha_note(track, a_given, _contact_frames(track, best, setup))
    notes += off_path
    p = misfit_p(best, int(rec.line.contact.sum()))
    if p < MISFIT_P:
        notes += _angle_unit_note(track, setup, rec, best, w)
    if p < MISFIT_P or off_path:  # a model the track rejects fixes none of its parameters
        i = best.names.index("mu_k")
        intervals = ((float(best.lower[i]), float(best.upper[i])), (0.0, math.inf))
    else:  # (its profiles would be work for nothing)
        intervals = _friction_intervals(best, setup, track, rec, profiled)
    z, size = flight_signal(best, setup, rec)
    off = off_path[0] if off_path else ""
    needs = fitted_needs(jarm_fit or best, setup, track)  # the rolling the one-frame test tried
    verdict = Verdict(observed, best, jarm_fit, p, off, z, size, power, needs, weighed)
    return _judge(track, rec, verdict, setup, intervals, notes, started, friction)


def _consistent_fits(
    setup: Setup, track: Track, rec: Reconstruction
) -> tuple[Setup, tuple[Fit, Fit | None]]:
    """``fit.consistent_fits``, refitted from a deeper basin where the walk along a loose θ₀
    finds one (``profiles.theta0_walk``), screened again more widely where the pair fails
    the goodness-of-fit gate (a failed gate may be a local minimum: a long slip at 2 px stopped
    at chi2_red 31.7), and then fitted again with the slip velocity at the first frame free
    (``Setup.slip_at_start``: a track that starts mid-slip); the best pair and its setup."""
    fits = consistent_fits(setup, track, rec)
    deeper = theta0_walk(fits[0], setup, track, rec)
    if deeper is not None:
        walked = consistent_fits(setup, track, rec, start=deeper)
        if walked[0].cost < fits[0].cost:
            fits = walked
    if _passes(fits[0], rec):
        return setup, fits
    wider = consistent_fits(setup, track, rec, wide=True)
    if wider[0].cost < fits[0].cost:
        fits = wider
    if not _passes(fits[0], rec):
        sliding = replace(setup, slip_at_start=True)
        slid = consistent_fits(sliding, track, rec)
        if slid[0].cost < fits[0].cost:
            return sliding, slid
    return setup, fits


def _passes(f: Fit, rec: Reconstruction) -> bool:
    return misfit_p(f, int(rec.line.contact.sum())) >= MISFIT_P


def _friction_intervals(
    best: Fit, setup: Setup, track: Track, rec: Reconstruction, profiled: bool
) -> tuple[tuple[float, float], tuple[float, float]]:
    """μ_k's and μ_s's ~95 % intervals: local, widened by their profiles if ``profiled``.
    μ_s's local interval is a lower bound (what the rolling needs, to infinity) when the
    fitted run never slips or the fit does not constrain it."""
    mu_k_iv = best.interval("mu_k")
    lo_s, hi_s = mu_s_interval(best)
    if not math.isfinite(hi_s) or hi_s > 1.8 * MU_MAX or not _slips_in_track(best, setup, track):
        needs = fitted_needs(best, setup, track)  # inf where F_y -> 0 before a lift-off
        lo_s, hi_s = needs if needs <= MU_MAX else 0.0, math.inf
    if not profiled:
        return mu_k_iv, (lo_s, hi_s)
    i = best.names.index("mu_k")
    grid, costs = profile(best, setup, track, rec, "mu_k")
    mu_k_iv = profile_interval(
        grid, costs, best, mu_k_iv, (float(best.lower[i]), float(best.upper[i]))
    )
    grid, costs = profile(best, setup, track, rec, "mu_s")
    return mu_k_iv, profile_interval(grid, costs, best, (lo_s, hi_s), (0.0, math.inf))


def _judge(
    track: Track,
    rec: Reconstruction,
    v: Verdict,
    setup: Setup,
    intervals: tuple[tuple[float, float], tuple[float, float]],
    notes: tuple[str, ...],
    started: float,
    friction: MeasuredFriction | None,
) -> Analysis:
    best, observed = v.best, v.observed
    unit, t0, dt = setup.time_unit, float(track.t[0]), track.dt
    end = horizon(setup, track)
    times = event_times(best.run, end)
    errs = time_errors(best, setup, track, rec)
    lift = times["liftoff"]
    slips_dimless = slip_intervals(best.run, until_liftoff(best, setup, track))
    frames = sum(b - a for a, b in slips_dimless) * unit / dt  # fit.slip_frames, reused
    needs = fitted_needs(best, setup, track)
    delta = math.nan
    if v.jarm_fit is not None:
        delta = 2.0 * (v.jarm_fit.cost - best.cost) / best.variance_factor
    seen = observed.flights[0] if observed.flights else None
    # frames between the lift-off's 95 % interval and the track's end (NaN: no lift-off)
    after = ((end - lift) * unit - 1.96 * errs["liftoff"]) / dt
    verdict, reason, evidence = decide(v, seen, (lift, after), frames, delta, rec, t0, unit, dt)
    if reason == "model":  # a model the track rejects times nothing (liftoff_window does)
        errs = dict.fromkeys(errs, math.inf)
    elif unseen_hop(v, seen):  # nor the hop, and what ends with it, of one it does not
        errs = {k: math.inf if times.get(k, math.nan) >= lift else e for k, e in errs.items()}
    evidence.append(needs_sentence(needs))
    slips = tuple(
        SlipInterval(
            t0 + a * unit,
            t0 + b * unit,
            errs.get(f"slip{k}_t1", math.nan),
            errs.get(f"slip{k}_t2", math.nan),
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
        mu_k_interval=intervals[0],
        mu_s_interval=intervals[1],
        delta_chi2=delta,
        track=track,
        rec=rec,
        observed=observed,
        fit=best,
        fit_jarm=v.jarm_fit,
        setup=setup,
        times=times,
        time_errs=errs,
        mu_s_needed=needs,
        seconds=time.perf_counter() - started,
        notes=notes,
        mu_s_measured=friction,
    )


def _after_release(
    track: Track, radius: float, notes: tuple[str, ...]
) -> tuple[Track, tuple[str, ...]]:
    """The track from the first frame after a wait before the release
    (``release.release_frame``), with a note; else as it is."""
    begin = release_frame(track.t, track.c, REACH * radius)
    if begin == 0:
        return track, notes
    note = (
        f"the axle stays still for the first {begin} frames (a wait before the release): "
        f"the fit starts after the release, at t = {track.t[begin]:.4f} s"
    )
    return frames_from(track, begin), (*notes, note)


def _contact_frames(track: Track, best: Fit, setup: Setup) -> int:
    """The frames before the fitted model's first lift-off (all when it does not lift off,
    at least 8): a flight lower than the noise would bend the contact line."""
    lift = event_times(best.run, math.inf)["liftoff"]
    if not math.isfinite(lift):
        return track.n
    return max(int(np.searchsorted(track.t - track.t[0], lift * setup.time_unit)), 8)


def _alpha_note(track: Track, given: float | None, frames: int) -> tuple[str, ...]:
    """A note when the given ramp angle disagrees with the track's own contact line (over
    its first ``frames`` frames)."""
    if given is None:
        return ()
    seen, err = path_angle(track.c[:frames], given)
    tol = max(4 * err, ALPHA_TOLERANCE)
    if abs(seen - given) <= tol:
        return ()
    hint = ""
    if min(abs(math.degrees(given) - seen), abs(math.radians(given) - seen)) <= tol:
        hint = " (an angle in the wrong unit? the command line takes degrees, Python radians)"
    return (
        f"alpha: the axle's contact path runs at {math.degrees(seen):.4g} deg "
        f"(+- {math.degrees(err):.2g}), not the given {math.degrees(given):.4g} deg: a rolled "
        f"camera or a wrong alpha{hint}",
    )


def _angle_unit_note(
    track: Track, setup: Setup, rec: Reconstruction, best: Fit, window: int | None
) -> tuple[str, ...]:
    """When the fit fails: a note if the marker angle read in the other unit (degrees for
    radians, or the reverse) fits far better -- a unit mistake."""
    beta = setup.marker_angle
    for alt in (math.degrees(beta), math.radians(beta)):
        if alt == beta or not abs(alt) <= 2 * math.pi:
            continue
        rec2 = reconstruct(
            track,
            radius=setup.radius,
            marker_angle=alt,
            marker_radius=rec.marker_radius,
            alpha=None if setup.fit_alpha else setup.alpha,
            window=window,
        )
        other = fit(replace(setup, marker_angle=alt), track, rec2)
        if other.chi2_reduced < 0.25 * best.chi2_reduced:
            return (
                f"marker_angle: the fit is far better (reduced chi2 {other.chi2_reduced:.3g}, "
                f"not {best.chi2_reduced:.3g}) with {alt:.4g} rad ({math.degrees(alt):.4g} deg) "
                f"than with the {beta:.4g} rad ({math.degrees(beta):.4g} deg) given: an angle "
                "in the wrong unit? (the command line takes degrees, Python radians)",
            )
    return ()


def _inputs(
    radius: float | None,
    chi: float | None,
    km: float | None,
    alpha: float | None,
    sheet: dict[str, float],
) -> tuple[Cylinder, float, float | None]:
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
    return body, R, a


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


def _before_bounces(track: Track, observed: Observed, window: int) -> int:
    """The frames before the second lift-off the track shows (all when there is none, or
    when fewer than two smoothing windows would be left)."""
    if len(observed.flights) < 2:
        return track.n
    n = int(np.searchsorted(track.t, observed.flights[1].liftoff.lo))
    return n if n >= 2 * window else track.n


def _bounces_note(track: Track, n: int) -> str:
    return (
        f"the track is analysed up to its second lift-off, t = {track.t[n]:.4f} s: the "
        f"{track.n - n} frames after it (bounces, whose impacts the rigid model describes "
        "worst) are left out"
    )


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


def _slips_in_track(f: Fit, setup: Setup, track: Track) -> bool:
    """Whether the fitted run slips anywhere within the track (else μ_s is only bounded)."""
    end = horizon(setup, track)
    return any(seg.mode == "SLIP" and seg.t_start < end for seg in f.run.segments)


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
