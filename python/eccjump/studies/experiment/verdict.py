"""The rules that turn the fits of a track into a verdict, its reason and its evidence
(``analysis.analyze`` fits; this module judges).

First the goodness of fit: a reduced χ² improbable under the model (p below
:data:`MISFIT_P` by ``fit.misfit_p``), or a given α that the axle's contact path
before the model's lift-off contradicts (``analysis.ALPHA_TOLERANCE``), gives ``undetermined``
(``model``) whatever else the track shows. Then the verdicts:

* ``jarm``: the body left the ramp straight from pure rolling -- the fitted model rolls up
  to its lift-off (or slips for less than one frame, and a fit that forbids any slip before
  the lift-off is as good), a slip of one frame before the lift-off would have shown
  (``one_frame.one_frame_slip`` at least :data:`SIGNIFICANT`; with a friction measured apart
  from the track, what the measurement says against that slip is added: ``friction``),
  and the track shows the flight beyond its noise (frame by frame, or along the model's
  parabola: ``fit.flight_signal`` at least :data:`FLIGHT_Z`) or the lift-off follows from
  the rolling (a rigid body whose fitted rolling loses its normal force leaves the ramp:
  inside the track, by :data:`FRAMES_AFTER` frames, and with heights that do not
  contradict the flight);
* ``slip_first``: it slipped before lifting off -- the fitted model slips for at least one
  frame in all (every episode: slip, stick, slip again, reversals), and the fit that
  forbids it is worse by a χ² of at least :data:`SIGNIFICANT` (3 standard errors);
  a slip the data ask for is never ``jarm``, and is ``slip_first`` even where the flight
  after it is within the noise;
* ``undetermined``, with the reason: ``model`` (the gate, or the track flies where the
  fitted model does not), ``no_liftoff`` (no lift-off shows, in the track or in the model
  fitted to it), ``noise`` (the flight is within the noise and the rolling does not fix
  the lift-off, or a slip of 3 frames or more is within the noise), ``frame_rate`` (a slip
  shorter than :data:`MIN_SLIP_FRAMES` frames that the data cannot confirm, one they ask
  for that is shorter than a frame, or a rolling fit that a one-frame slip would not have
  changed visibly: the evidence then says what would settle it, :func:`settle`) or
  ``short_track`` (no rolling before the lift-off).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from eccjump.studies.experiment.events import Flight, Observed
from eccjump.studies.experiment.fit import MU_MAX, Fit
from eccjump.studies.experiment.reconstruction import Reconstruction

VERDICTS = ("jarm", "slip_first", "undetermined")
REASONS = ("", "no_liftoff", "noise", "frame_rate", "short_track", "model")
#: The chi-square by which forbidding the slip must worsen the fit for a slip_first verdict.
SIGNIFICANT = 9.0
#: The matched-filter z (``fit.flight_signal``) at which the track shows the model's flight
#: when no frame clears the per-frame threshold of ``events``.
FLIGHT_Z = 5.0
#: Where the flight is within the noise, the lift-off follows from the rolling only if the
#: track runs on at least this many frames after the lift-off's 95 % interval.
FRAMES_AFTER = 2.0
#: A slip shorter than this (in frames) may be reported as undetermined.
MIN_SLIP_FRAMES = 3.0
#: The goodness-of-fit gate: a reduced chi-square this improbable under the model (the F
#: distribution of ``fit.misfit_p``) means the model does not describe the track.
MISFIT_P = 1e-3


@dataclass(frozen=True, eq=False)
class Verdict:
    """What the verdict rests on: the observed events, the consistent pair of fits (free,
    slip-forbidden or None) and the goodness of fit (``fit.misfit_p``)."""

    observed: Observed
    best: Fit
    jarm_fit: Fit | None
    misfit_p: float
    off_path: str  # the given alpha contradicted by the track's contact path (or "")
    flight_z: float  # how clearly the heights show the model's flight (fit.flight_signal)
    flight_size: float  # what they would show on the model's own heights (ditto)
    one_frame: float  # what a one-frame slip would cost the rolling fit (one_frame.one_frame_slip)
    needs: float  # what the rolling the one-frame test tried needs (fit.fitted_needs)
    friction: tuple[str, ...] = ()  # what the measured mu_s adds (friction.weigh)


def decide(
    v: Verdict,
    seen: Flight | None,
    lift_after: tuple[float, float],
    slip_frames: float,
    delta: float,
    rec: Reconstruction,
    t0: float,
    unit: float,
    dt: float,
) -> tuple[str, str, list[str]]:
    """The verdict, its reason and the evidence (the module docstring's rules, in order:
    the goodness of fit first, then what the track shows, then the slip test).
    ``lift_after``: the model's lift-off and how many frames the track runs on after its
    95 % interval."""
    lift, after = lift_after
    sigma3 = f"{3 * rec.sigma * 1e3:.2g} mm"
    if v.misfit_p < MISFIT_P:
        return "undetermined", "model", [_misfit_sentence(v.best, v.misfit_p)]
    if v.off_path:  # the model was fitted in a frame the track contradicts
        return "undetermined", "model", [v.off_path]
    if seen is None and not math.isfinite(lift):
        return (
            "undetermined",
            "no_liftoff",
            [
                f"no lift-off shows: the axle never clears its contact line by 3 sigma = "
                f"{sigma3} three frames in a row, and the fitted model does not lift off "
                "inside the track"
            ],
        )
    if (
        seen is None
        and v.flight_z < FLIGHT_Z
        and slip_verdict(slip_frames, delta)[0] != "slip_first"
        and not _liftoff_follows(v, after)
    ):
        return (
            "undetermined",
            "noise",
            [
                f"the model lifts off at t = {t0 + lift * unit:.4f} s, but its flight "
                f"stays within 3 sigma = {sigma3} of the ramp (the heights follow it at "
                f"{v.flight_z:.2g} sigma, {FLIGHT_Z:g} needed), and the rolling does not "
                f"fix the lift-off either ({_unfixed(v, after)})"
            ],
        )
    if not math.isfinite(lift):
        assert seen is not None
        return (
            "undetermined",
            "model",
            [
                f"the track flies ({seen.apex_height * 1e3:.3g} mm above the ramp) but "
                "the fitted model does not leave it: check chi, km, alpha, R"
            ],
        )
    if (lift * unit) < 4 * dt:
        return (
            "undetermined",
            "short_track",
            ["the lift-off comes within 4 frames of the track's start: no rolling to judge it by"],
        )
    evidence = [_flight_sentence(v, seen, sigma3, after)]
    if slip_frames <= 0:
        evidence.append(
            f"the fitted model rolls without slipping from the first frame to "
            f"its lift-off at t = {t0 + lift * unit:.5f} s"
        )
        evidence += v.friction
        return _jarm_if_shown(v, evidence)
    verdict, reason = slip_verdict(slip_frames, delta)
    evidence.append(
        f"the fitted model slips for {slip_frames:.1f} frames in all before its "
        f"lift-off; forbidding that slip worsens the fit by chi2 = "
        f"{delta:.3g} (significant above {SIGNIFICANT:g})"
    )
    evidence += v.friction
    if verdict == "jarm":
        return _jarm_if_shown(v, evidence)
    return verdict, reason, evidence


def _liftoff_follows(v: Verdict, after: float) -> bool:
    """Whether the lift-off follows from the rolling where the flight is within the noise:
    a rigid body whose fitted rolling loses its normal force must leave the ramp there, if
    that comes inside the track (its 95 % interval ends :data:`FRAMES_AFTER` frames before
    the track does) and the heights do not contradict the model's flight (they follow it
    within 3 standard errors of what its own heights would give, ``fit.flight_signal``)."""
    return after >= FRAMES_AFTER and not _heights_contradict(v)


def _heights_contradict(v: Verdict) -> bool:
    """Whether the heights fall 3 standard errors or more short of what the model's own
    flight would give them (``fit.flight_signal``): a flight the track does not have."""
    return v.flight_z < v.flight_size - 3.0


def unseen_hop(v: Verdict, seen: Flight | None) -> bool:
    """Whether the model's lift-off is a hop the track does not show and its heights
    contradict: then its time is the model's guess, fixed by nothing in the track."""
    return seen is None and v.flight_z < FLIGHT_Z and _heights_contradict(v)


def _unfixed(v: Verdict, after: float) -> str:
    """Why ``_liftoff_follows`` is false, for the evidence."""
    if not after >= FRAMES_AFTER:
        return (
            f"its 95 % interval ends {after:.1f} frames before the track does, "
            f"{FRAMES_AFTER:g} needed"
        )
    return f"the heights give {v.flight_z:.2g} sigma where its flight gives {v.flight_size:.2g}"


def _flight_sentence(v: Verdict, seen: Flight | None, sigma3: str, after: float) -> str:
    """What the track shows of the flight: seen frame by frame, along the model's parabola
    (``fit.flight_signal``), or not at all (then a slip_first rests on the slip alone, and
    a jarm on the lift-off that the rolling implies, ``_liftoff_follows``)."""
    if seen is not None:
        return (
            f"the axle rises {seen.apex_height * 1e3:.3g} mm above the ramp "
            f"({v.observed.peak_snr:.0f} sigma); lift-off seen in "
            f"[{seen.liftoff.lo:.4f}, {seen.liftoff.hi:.4f}] s"
        )
    if v.flight_z >= FLIGHT_Z:
        return (
            f"the axle's heights follow the fitted model's flight at {v.flight_z:.3g} sigma "
            f"(no frame clears 3 sigma = {sigma3} three times in a row)"
        )
    if _liftoff_follows(v, after):
        return (
            f"the model's flight stays within the noise (the heights follow it at "
            f"{v.flight_z:.2g} sigma, its own heights would give {v.flight_size:.2g}): the "
            "lift-off is where the fitted rolling loses its normal force, inside the track "
            f"({after:.0f} frames before its end beyond the lift-off's 95 % interval)"
        )
    if _heights_contradict(v):
        return (
            f"the model's flight stays within the noise and the heights contradict it "
            f"(they follow it at {v.flight_z:.2g} sigma, its own heights would give "
            f"{v.flight_size:.2g}): its lift-off is not fixed by the track, and the "
            "verdict rests on the slip before it"
        )
    return (
        f"the model's flight stays within the noise (the heights follow it at "
        f"{v.flight_z:.2g} sigma): the verdict rests on the slip before it"
    )


def _jarm_if_shown(v: Verdict, evidence: list[str]) -> tuple[str, str, list[str]]:
    """jarm if a slip of one frame before the lift-off would have shown (``v.one_frame``,
    what it costs the fit -- with the measured μ_s if one was weighed -- at least
    SIGNIFICANT), else undetermined (frame_rate) with what would settle it
    (:func:`settle`)."""
    weighed, one = bool(v.friction), v.one_frame
    fit_ = "the fit and the measured mu_s together" if weighed else "the fit"
    if one >= SIGNIFICANT:
        evidence.append(f"a slip of one frame before it would worsen {fit_} by chi2 = {one:.3g}")
        return "jarm", "", evidence
    if math.isnan(one):
        evidence.append(
            "no slip of one frame before the lift-off could be tried (no lowered mu_s gives "
            "the fitted rolling one and a lift-off after it): the track cannot exclude it"
        )
        return "undetermined", "frame_rate", evidence
    cost = (
        f"would worsen {fit_} by only chi2 = {one:.2g}"
        if one > 0
        else f"fits as well (chi2 {one:.2g})"
    )
    cannot = "the frame rate and the noise" + (", and the measured mu_s," if weighed else "")
    evidence.append(
        f"but a slip of one frame before the lift-off {cost} (it takes {SIGNIFICANT:g} to "
        f"show): {cannot} cannot exclude it"
    )
    if not weighed:
        evidence += settle(one, v.needs)
    return "undetermined", "frame_rate", evidence


def settle(one: float, needs: float) -> list[str]:
    """What would settle a one-frame slip that the track alone cannot exclude (it costs the
    rolling fit ``one``, a χ² below SIGNIFICANT): a static friction measured apart
    above ``needs`` (what rolling to the lift-off needs), since such a slip needs μ_s below
    it and a measurement μ ± s adds ((μ − needs)/s)² against it
    (``friction.MeasuredFriction.against_slip``): μ − needs ≥ s √(SIGNIFICANT − one)
    settles it, on this track. Less tracking noise settles it too, but by how much the track
    cannot say: the nearest slip moves with the fit (the site's page "Analysing an
    experiment", "Ninth round")."""
    if not 0 < needs <= MU_MAX:
        return ["what would settle it: less tracking noise (larger dots, a sharper image)"]
    above = math.sqrt(SIGNIFICANT - max(one, 0.0))
    # both rounded up: a measurement that follows the printed figures settles it
    return [
        f"what would settle it: a static friction measured apart (a tilt test; mu_s and "
        f"mu_s_err) above {math.ceil(needs * 1e3) / 1e3:.3f}, what rolling to the lift-off "
        f"needs, by {math.ceil(above * 100) / 100:.2f} of its standard deviations, or less "
        "tracking noise (larger dots, a sharper image)"
    ]


def needs_sentence(needs: float) -> str:
    """What the fitted rolling before the lift-off says of μ_s (``fit.fitted_needs``; 0
    where the fitted run does not roll, inf where F_y → 0 while it rolls)."""
    if needs == 0.0:
        return "the fitted model does not roll before its lift-off: no rolling bounds mu_s"
    if needs <= MU_MAX:
        return (
            f"the rolling before it needs mu_s >= {needs:.3f} (the model's friction ratio "
            "|F_x|/F_y)"
        )
    return (
        "the fitted rolling's friction ratio |F_x|/F_y grows without bound (F_y -> 0 "
        "before the lift-off): it bounds mu_s by nothing the fit can search"
    )


def slip_verdict(frames: float, delta: float) -> tuple[str, str]:
    """A slip the data ask for (Δχ² ≥ SIGNIFICANT) is never jarm: slip_first from a frame
    on, below it undetermined (frame_rate). A slip they do not ask for is jarm below a
    frame, undetermined (frame_rate, then noise) above."""
    if delta >= SIGNIFICANT:
        return ("slip_first", "") if frames >= 1.0 else ("undetermined", "frame_rate")
    if frames < 1.0:
        return "jarm", ""  # a slip shorter than a frame that the data do not ask for
    return "undetermined", "frame_rate" if frames < MIN_SLIP_FRAMES else "noise"


def _misfit_sentence(f: Fit, p: float) -> str:
    return (
        f"the model does not describe the track: reduced chi2 = {f.chi2_reduced:.3g} for "
        f"{f.dof} degrees of freedom (p = {p:.1g}, the gate {MISFIT_P:g}); likely causes: "
        "the radius, the marker's radius or angle, a rolled camera, alpha, an angle or "
        "length in the wrong unit, or physics outside the rigid model (rolling resistance)"
    )
