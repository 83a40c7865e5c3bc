"""A verdict you can trust (issue 48): eccjump.analyze on tracks of the independent model
(``reference_tracks.py``: scipy's full motion, not ``simulate``) and on the stored track with
a wrong unit. Fast: the issue's two reproducers, the goodness-of-fit gate, the slip rule,
slips that come and go, bounds printed as bounds. The campaign (``pytest -m campaign``,
about 15 minutes): the seeded sweep of ``verdict_campaign.py`` against the targets."""

from __future__ import annotations

import functools
import json
import math
import re
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import reference_tracks as rt
import verdict_campaign as vc
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from eccjump.cli import main
from eccjump.studies.experiment import analysis, analyze
from eccjump.studies.experiment import fit as fitmod
from eccjump.studies.experiment.events import observe
from eccjump.studies.experiment.fit import (
    ROUGH,
    Model,
    coarse_jacobian,
    correlation_inflation,
    covariance,
    fit,
    flight_signal,
    rough,
)
from eccjump.studies.experiment.friction import MeasuredFriction
from eccjump.studies.experiment.profiles import profile_interval
from eccjump.studies.experiment.times import (
    branch_step,
    time_errors,
)
from eccjump.studies.experiment.track import first_frames
from eccjump.studies.experiment.verdict import (
    SIGNIFICANT,
    Verdict,
    decide,
    needs_sentence,
    settle,
    slip_verdict,
)
from eccjump.studies.experiment.video import VideoTrack

DATA = Path(__file__).resolve().parent / "data"
#: The stored JARM track (tests/data/jarm_240fps.csv, pixels) and the README's options.
README = ["analyze", str(DATA / "jarm_240fps.csv"), "--radius", "0.05", "--chi", "0.10927",
          "--km", "0.0777", "--alpha", "66.087", "--marker-radius", "0.04",
          "--scale", "1230.539145", "--json"]  # fmt: skip


def _analyze(case: rt.Case, **kwargs):
    made = rt.film(case)
    args = {"radius": case.radius, "chi": case.chi, "km": case.km, "alpha": case.alpha,
            "marker_angle": case.marker_angle, "marker_radius": 0.8 * case.radius,
            "profile_mu_k": False} | kwargs  # fmt: skip
    return made, analyze(made.track, **args)


def _spy_fit_inputs(monkeypatch) -> list[tuple]:
    """The (setup, track, rec) that each analyze call fits, as they come (the setup its fits
    were made with)."""
    inputs: list[tuple] = []
    real = analysis._consistent_fits

    def spy(setup, track, rec):
        used, fits = real(setup, track, rec)
        inputs.append((used, track, rec))
        return used, fits

    monkeypatch.setattr(analysis, "_consistent_fits", spy)
    return inputs


def test_a_slip_that_comes_and_goes_is_slip_first_with_every_episode():
    """The issue's first reproducer, made by the independent model: 60 fps, slips 145.5-202.0
    ms, sticks, slips again from 284.2 ms, lifts off from SLIP at 289.3 ms. It was `jarm`
    with chi2 = 20.7 for forbidding the slip, and the first slip missing from observed."""
    case = rt.draw("stick_slip", 1, fps=60.0, noise=0.5)
    made, res = _analyze(case)
    assert [round(a, 4) for a, _ in made.slips] == [0.1455, 0.2842]
    assert res.verdict == "slip_first" and res.delta_chi2 >= SIGNIFICANT
    assert len(res.slips) == 2
    (t1, t2), first = made.slips[0], res.slips[0]
    assert abs(first.t1 - t1) < 1 / 60 and abs(first.t2 - t2) < 1 / 60
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err
    seen = res.observed.slips
    assert any(s.onset.lo - 1 / 60 <= t1 and s.end.hi + 1 / 60 >= t2 for s in seen), seen
    assert res.fit_jarm is not None and res.fit.cost <= res.fit_jarm.cost


def test_a_gentle_slip_that_sticks_again_is_not_jarm():
    """Independent model, 60 fps, 2 px: the body slips 34.7-91.4 ms (3.4 frames) with mu_k
    near mu_s, sticks, and lifts off from rolling at 102.9 ms. The free fit rolled (chi2_red
    0.58) and a one-frame slip with the rolling fit's own mu_k (a slip with a 12 % drop of
    friction) cost chi2 = 182: it was `jarm`. The gentlest slip (mu_k = mu_s) is the one to
    exclude, and the refit from it explains the track better than rolling."""
    case = rt.Case(chi=0.5346883126741298, km=0.03476102940999703, alpha=1.147337101693883,
                   mu_s=0.5873991231989188, mu_k=0.5192114130748546, theta0=-2.93335204228217,
                   omega0=1.600312165917336, fps=60.0, noise_px=2.0,
                   marker_angle=-0.9740196422725806, seed=1005, family="slip")  # fmt: skip
    made, res = _analyze(case)
    assert made.slip_frames > 3
    assert res.verdict != "jarm", (res.verdict, res.evidence)
    assert res.fit_jarm is None or res.fit.cost <= res.fit_jarm.cost


def test_a_flight_within_the_noise_follows_from_the_rolling_inside_the_track():
    """Independent model, 60 fps, 0.5 px: a JARM body whose flight rises 0.21 mm (1.5 sigma
    along the whole parabola) was `undetermined (noise)`. A rigid body whose fitted rolling
    loses its normal force leaves the ramp there: with that inside the track (and a one-frame
    slip excluded) it is `jarm`. Cut one frame after the lift-off, the track no longer fixes
    it: `undetermined (noise)`, saying why."""
    case = rt.draw("jarm", 2001, fps=60.0, noise=0.5)
    made, res = _analyze(case)
    assert not res.observed.flights  # no frame shows the flight
    assert res.verdict == "jarm", res.evidence
    assert "loses its normal force" in res.evidence[0]
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err
    n = int(np.searchsorted(made.track.t, made.liftoff)) + 1
    args = {"radius": case.radius, "chi": case.chi, "km": case.km, "alpha": case.alpha,
            "marker_angle": case.marker_angle, "marker_radius": 0.8 * case.radius,
            "profile_mu_k": False}  # fmt: skip
    cut = analyze(first_frames(made.track, n), **args)
    assert (cut.verdict, cut.reason) == ("undetermined", "noise"), cut.evidence
    assert "before the track does" in cut.evidence[0]


@pytest.mark.slow
def test_a_fit_stuck_in_a_local_minimum_is_refitted():
    """The issue's second reproducer (independent model, 1000 fps): chi2_red 1.25e4 and a
    slip-forbidden fit better by 1318 came back `undetermined (noise)`, the lift-off 9.7
    frames late. Now the screened starts find the slip: slip_first, the lift-off within its
    interval, the free fit no worse than the constrained one."""
    case = rt.Case(chi=0.5552372066470188, km=0.3117790815485588, alpha=1.0242279446056208,
                   mu_s=0.6665, mu_k=0.4522, theta0=0.0, omega0=0.0, fps=1000.0,
                   noise_px=0.5, seed=1)  # fmt: skip
    made, res = _analyze(case)
    assert made.slip_frames > 200
    assert res.verdict == "slip_first", res
    assert res.fit.chi2_reduced < 1.5
    assert res.fit_jarm is not None and res.fit.cost <= res.fit_jarm.cost
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err + 1e-4
    lo, hi = res.mu_k_interval
    assert lo - 0.002 <= case.mu_k <= hi + 0.002


def test_an_angle_in_the_wrong_unit_fails_the_gate_with_a_note(capsys):
    """--marker-angle 0.6 (radians typed where degrees are expected): chi2_red 60.5 was
    `jarm` with no note. Now `undetermined (model)`, naming the likely causes, and a note
    that 0.6 rad fits; the README's 34.3775 deg gives the right fit."""
    assert main([*README, "--marker-angle", "0.6"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert (report["verdict"], report["reason"]) == ("undetermined", "model")
    assert "rolled camera" in report["evidence"][0] and "wrong unit" in report["evidence"][0]
    assert any(n.startswith("marker_angle: the fit is far better") for n in report["notes"])
    assert report["model"]["chi2_reduced"] > 10
    assert main([*README, "--marker-angle", "34.3775"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert (report["verdict"], report["reason"]) == ("undetermined", "frame_rate")
    assert [n for n in report["notes"] if not n.startswith("the track is analysed up to")] == []
    assert report["model"]["chi2_reduced"] < 1.5


def test_a_rolled_camera_is_named_and_never_confidently_wrong():
    """A camera rolled by 3 degrees: the contact path disagrees with alpha (a note), and the
    verdict is `undetermined (model)` (the campaign's seed 0 had one such slip called `jarm`
    with chi2_red 1.08 before the contact path was part of the gate), and the model's
    frictions and times are not printed as values (their intervals missed the truth)."""
    base = rt.draw("slip", 3, fps=240.0, noise=0.5)
    case, _ = rt.systematic(base, "roll", 1)
    made, res = _analyze(case)
    assert any(n.startswith("alpha: the axle's contact path runs at") for n in res.notes)
    assert made.slip_frames >= 1
    assert (res.verdict, res.reason) == ("undetermined", "model")
    assert res.evidence[0].startswith("alpha: the axle's contact path runs at")
    # fitted in a frame the track contradicts: no friction printed as a value
    params = res.parameters()
    assert {params[n]["status"] for n in ("mu_k", "mu_s", "e")} == {"not_determined"}
    assert res.mu_k_interval == (0.0, 3.0)
    assert "mu_k        not determined (the model does not fit this track)" in repr(res)
    # nor its times (the misstated setups' lift-offs were 4-5 standard errors off)
    assert res.liftoff_err == math.inf and "not fixed by the track" in repr(res)


def test_a_step_across_a_branch_is_a_jump_not_a_slope():
    """A run stepped down by 0.01 slips before its lift-off, which comes 0.05 later; stepped
    up, it rolls like the fitted run. The derivative is the rolling side's (0.1), the jump
    what the slip adds beyond it (where the track allows that run); the central difference
    would have been 2.55."""
    base = {"liftoff": 1.0, "slip_onset": math.nan}
    up = {"liftoff": 1.001, "slip_onset": math.nan}
    dn = {"liftoff": 1.05, "slip_onset": 1.04, "slip0_t1": 1.04, "slip0_t2": 1.05}
    g, jump = branch_step(base, up, dn, "liftoff", (0.01, -0.01))
    assert g == pytest.approx(0.1) and jump == pytest.approx(0.051)
    assert branch_step(base, up, up, "liftoff", (0.01, -0.01)) == (0.0, 0.0)
    g, jump = branch_step(base, up, base, "liftoff", (0.01, -0.01))
    assert g == pytest.approx(0.05) and jump == 0.0  # one branch: central
    g, jump = branch_step(base, dn, base, "liftoff", (0.01, 0.0))  # at a bound, then a slip
    assert g == 0.0 and jump == pytest.approx(0.05)
    g, jump = branch_step(base, dn, dn, "liftoff", (0.01, -0.01))  # a branch of its own
    assert g == 0.0 and jump == pytest.approx(0.05)
    # a run on the same branch that the track rejects (a slip from an earlier peak of the
    # friction ratio): the other side's slope, and no jump
    far = {"liftoff": 1.3, "slip_onset": math.nan}
    assert branch_step(base, far, up, "liftoff", (0.01, -0.01))[0] == pytest.approx(14.95)
    g, jump = branch_step(base, far, up, "liftoff", (0.01, -0.01), (False, True))
    assert g == pytest.approx(-0.1) and jump == 0.0
    g, jump = branch_step(base, up, dn, "liftoff", (0.01, -0.01), (True, False))
    assert g == pytest.approx(0.1) and jump == 0.0
    # at a bound, toward a rejected run: the time moves no further than to that run
    # over the standard error (20), whatever the slope over the bound's short step
    near = {"liftoff": 1.0001, "slip_onset": math.nan}
    g, jump = branch_step(base, far, near, "liftoff", (2.0, -1e-4), (False, True), 20.0)
    assert g == pytest.approx(-0.3 / 20.0) and jump == 0.0
    g, jump = branch_step(base, far, near, "liftoff", (2.0, -1e-4), (False, True))
    assert g == pytest.approx(-1.0)  # (an error unknown: the slope)
    # no side continues the fitted run where the track allows: one side starts a slip, the
    # other stays on the fitted branch but is rejected; over the error (0.1, ten steps)
    # the time moves no further than that rejected run (0.3), not the slope across (12.5)
    g, jump = branch_step(base, far, dn, "liftoff", (0.01, -0.01), (False, False), 0.1)
    assert g == pytest.approx(3.0) and jump == 0.0
    g, jump = branch_step(base, far, dn, "liftoff", (0.01, -0.01), (False, True), 0.1)
    assert g == pytest.approx(3.0) and jump == pytest.approx(0.05)  # the slip allowed: a jump
    # both sides on the fitted branch, both rejected with the other parameters held: the
    # slope (a 10.7-frame slip at 60 fps lost its lift-off at 8.7 errors when bounded)
    g, jump = branch_step(base, far, up, "liftoff", (0.01, -0.01), (False, False), 0.1)
    assert g == pytest.approx(14.95) and jump == 0.0
    later = dn | {"liftoff": 1.2}
    g, jump = branch_step(base, later, dn, "liftoff", (0.01, -0.01), (False, False), 0.1)
    assert g == 0.0 and jump == 0.0  # both sides on other branches the track rejects


def test_a_lift_off_on_the_edge_of_a_slip_is_timed_from_the_fitted_side():
    """Independent model, a JARM body at 240 fps and 0.2 px. Its rolling fit sits where a
    step of a tenth of a standard error in θ₀, θ̇₀ or μ_k starts a slip a fraction of a
    frame before the lift-off, which then comes 0.9 ms later. Differenced across that
    switch, the lift-off printed ± 11 ms for an error of 8 µs. That slip is a run the track
    rejects: the lift-off is timed from the rolling side (tens of µs), the truth inside."""
    case = rt.Case(chi=0.5148544751270913, km=0.16702607048477652, alpha=1.1759328953619526,
                   mu_s=1.1026692398407802, mu_k=0.7288040418825077, theta0=-1.8878380530244832,
                   omega0=0.22702892288570298, restitution=0.0, radius=0.05, fps=240.0,
                   noise_px=0.2, marker_angle=-0.25830006248049386, marker_in_r=0.8,
                   roll_deg=0.0, seed=4012, family="jarm")  # fmt: skip
    made, res = _analyze(case)
    assert res.verdict == "jarm"
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err < 3e-4


def test_a_marker_a_few_pixels_from_the_axle_is_fitted_from_a_walk_along_theta0():
    """Independent model, 60 fps, 2 px with R only 3.4 px: a slip of 59 frames from the
    release. A frame's θ is uncertain by 1.3 rad and the smoothed θ₀ by 1.25, so the fit
    from it stopped Δχ² 166 above the truth and saw no lift-off (`undetermined`). Screened
    with θ₀ spread, it found a basin at the truth's cost but μ_k 0.316 ± 0.005 (the truth
    0.382), and its lift-off, differenced across a switch to rolling, printed ± 7.6 s. The
    walk along θ₀ finds the deeper basin (Δχ² 59 lower); a step the track rejects bounds
    the lift-off's error."""
    case = rt.Case(chi=0.5821308597718936, km=0.22716469362763725, alpha=1.2364671772472517,
                   mu_s=0.5696185492449404, mu_k=0.38240657248548016, theta0=-2.114789013012084,
                   omega0=0.5491227579176716, restitution=0.0, radius=0.05, fps=60.0,
                   noise_px=2.0, marker_angle=0.39968330731283386, marker_in_r=0.8,
                   roll_deg=0.0, seed=1008, family="long_slip")  # fmt: skip
    made, res = _analyze(case, profile_mu_k=True)
    assert made.slip_frames > 50 and res.verdict == "slip_first"
    lo, hi = res.mu_k_interval
    assert lo <= case.mu_k <= hi and hi - lo < 0.1
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err < 0.5


def test_a_lift_off_moved_by_a_start_the_track_does_not_fix_is_not_timed(monkeypatch):
    """Independent model, 60 fps, 2 px (a field of metres: the noise is 9 mm), a slip of 32
    frames. Its fit stopped in a minimum whose start (θ₀, θ̇₀) had an infinite variance, and
    its lift-off, which the start moves, was printed with an error of 0 (0.279 s against
    the true 0.533 s) until such a time was made infinite. The start grown from the track's
    first frames now finds the true minimum (the start fixed, the lift-off covered); the
    rule is checked on that fit with θ₀'s variance made infinite."""
    inputs = _spy_fit_inputs(monkeypatch)
    made, res = _analyze(rt.draw("long_slip", 2008, fps=60.0, noise=2.0))
    assert made.slip_frames > 30 and math.isfinite(res.fit.error("theta0"))
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err
    cov = res.fit.cov.copy()
    cov[0, :] = cov[:, 0] = 0.0
    cov[0, 0] = math.inf
    assert time_errors(replace(res.fit, cov=cov), *inputs[0])["liftoff"] == math.inf
    # a start from rest (the body at 240 fps) has θ̇₀ at its bound, where least
    # squares returns a zero column: an infinite variance, but not a start the track
    # leaves open; its lift-off stays timed (and covered)
    made, res = _analyze(rt.draw("stick_slip", 2021, fps=240.0, noise=0.2))
    assert res.fit.value("omega0") < 1e-9 and not math.isfinite(res.fit.error("omega0"))
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err < 1e-3


def test_a_start_from_rest_does_not_turn_the_contact_path():
    """Independent model, 240 fps, 0.5 px: a long slip from nearly at rest (travel 12 mm in
    its first 13 frames, 146 mm before the lift-off). The contact path's angle came from a
    line that had kept 12 of the 52 contact frames (its first-quarter start turned it by
    degrees, its spread shrank to 0.06 mm): 58.64 +- 0.45 deg against the true 60.65, a
    false note and `undetermined (model)` on a fit at chi2_red 1.3. Every contact frame
    weighs in now: no note, `slip_first`."""
    case = rt.Case(chi=0.41873672909488113, km=0.20709115686339175, alpha=1.058489594330454,
                   mu_s=0.6574902491251782, mu_k=0.4983894566941508, theta0=2.8786626922206384,
                   omega0=0.025541959224031574, fps=240.0, noise_px=0.5,
                   marker_angle=-1.9406165704324552, seed=1019, family="long_slip")  # fmt: skip
    made, res = _analyze(case)
    assert not [n for n in res.notes if n.startswith("alpha:")], res.notes
    assert res.verdict == "slip_first", (res.reason, res.evidence)
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err


def test_a_fit_that_fails_the_gate_is_screened_again_more_widely():
    """Independent model, 240 fps, 2 px: a slip of 90 frames from the start. The screen's
    starts ended in a minimum at chi2_red 31.7 (`undetermined (model)`); where the gate
    fails, the fit is screened again with more frictions and bounces, and the better pair
    is judged: slip_first, the slip's length within a frame."""
    case = rt.Case(chi=0.5584107791417636, km=0.09753424940769792, alpha=1.0177015323189604,
                   mu_s=0.6572072248899836, mu_k=0.3964395555116616,
                   theta0=-2.4162846534304463, omega0=0.9399856427485693, fps=240.0,
                   noise_px=2.0, marker_angle=1.3329427160646903, seed=1020,
                   family="long_slip")  # fmt: skip
    made, res = _analyze(case)
    assert res.fit.chi2_reduced < 2.0
    assert res.verdict == "slip_first", (res.reason, res.evidence)
    assert abs(sum(s.frames for s in res.slips) - made.slip_frames) < 1.0


def test_a_long_track_is_fitted_in_growing_windows(monkeypatch):
    """Independent model, 60 fps, 0.2 px, a slip of 98 frames over 20 m of ramp (about 38
    turns). Every screened start, and the wide screen, ended turns away in a minimum at
    chi2_red 35 that never lifts off (`undetermined (model)`); the start grown from the
    track's first frames finds the slip: slip_first, the lift-off covered. Without it (the
    screen alone) the fit is worse by a chi-square of thousands."""
    inputs = _spy_fit_inputs(monkeypatch)
    made, res = _analyze(rt.draw("long_slip", 3009, fps=60.0, noise=0.2))
    assert made.slip_frames > 90
    assert res.fit.chi2_reduced < 1.5, res.fit.chi2_reduced
    assert res.verdict == "slip_first", (res.reason, res.evidence)
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err
    screened = fit(*inputs[0], grow=False)
    assert screened.cost > res.fit.cost + 1000.0


def test_a_short_track_is_grown_from_its_first_frames():
    """Independent model, 60 fps, 0.5 px, a slip of 5.7 frames and a lift-off at 0.21 s: 30
    frames to the landing and half a flight more. Screened over the whole track (scipy 1.17)
    every start went to a body that barely turns and bounces, `undetermined (model)` at
    chi2_red 163; grown from its first 8 frames the fit describes the track."""
    made, res = _analyze(rt.draw("slip", 2004, fps=60.0, noise=0.5))
    assert made.track.n == 30 and made.slip_frames > 5
    assert res.fit.chi2_reduced < 1.5, res.fit.chi2_reduced
    assert res.verdict == "slip_first", (res.reason, res.evidence)
    assert abs(res.liftoff_t - made.liftoff) < 1.96 * res.liftoff_err


def test_a_hop_the_heights_contradict_is_not_timed(monkeypatch):
    """Independent model, 60 fps, 2 px (noise of 13 mm), a slip of 124 frames and a
    lift-off at 2.07 s that no frame shows. The fit (χ²_red 1.5) hops at 0.77 s and
    chatters through bounces: its residuals jump by sigmas for the smallest step, least
    squares' Jacobian grew like 1/step, and the hop was timed to 4 µs. The Jacobian at a
    coarse step says the cost is rough and widens the covariance; and since the heights
    contradict the model's flight (they follow it at -0.2 sigma where its own would give
    6.4), its lift-off is not fixed by the track. The slip stays `slip_first`. That fit came
    from the smoothed θ₀ alone; with R at 2 px θ₀ is loose, and the full search (θ₀ spread
    and walked, l0 given room) finds a better fit (χ²_red 1.17) that does not lift off
    inside the track, nor does the track show one: `undetermined (no_liftoff)`, μ_k
    covered. The rules are checked on the fit from the smoothed θ₀."""
    made = rt.film(rt.draw("long_slip", 3008, fps=60.0, noise=2.0))
    args = {"radius": made.case.radius, "chi": made.case.chi, "km": made.case.km,
            "alpha": made.case.alpha, "marker_angle": made.case.marker_angle,
            "marker_radius": 0.8 * made.case.radius}  # fmt: skip
    searched = analyze(made.track, **args)
    assert searched.verdict == "undetermined" and searched.reason == "no_liftoff"
    lo, hi = searched.mu_k_interval
    assert lo <= made.case.mu_k <= hi
    monkeypatch.setattr(fitmod, "theta0_offsets", lambda rec: [0.0])  # (and no walk)
    monkeypatch.setattr(fitmod, "theta0_reach", lambda rec: fitmod.THETA0_RANGE)
    monkeypatch.setattr(fitmod, "with_room", lambda model, guess, res, lo, hi: (res, lo, hi))
    inputs = _spy_fit_inputs(monkeypatch)
    res = analyze(made.track, **args, profile_mu_k=False)
    assert res.fit.cost > searched.fit.cost
    assert made.slip_frames > 100 and not res.observed.flights
    assert res.verdict == "slip_first", (res.reason, res.evidence)
    assert res.liftoff_err == math.inf and "not fixed by the track" in repr(res)
    assert any("the heights contradict it" in e for e in res.evidence), res.evidence
    assert res.slips[-1].t2_err == math.inf and math.isfinite(res.slips[0].t1_err)
    model = Model(*inputs[0], jarm_only=res.fit.jarm_only)
    lo, hi = res.fit.lower, res.fit.upper
    coarse = coarse_jacobian(model, res.fit.x, lo, hi)
    monkeypatch.setattr(fitmod, "COARSE_STEP", 1e-7)
    assert rough(coarse_jacobian(model, res.fit.x, lo, hi), coarse)


def test_a_smooth_cost_keeps_least_squares_covariance(monkeypatch):
    """On a clean JARM track the Jacobians at the fine and the coarse step agree: no
    rough cost, the covariance is least squares' own."""
    inputs = _spy_fit_inputs(monkeypatch)
    _, res = _analyze(rt.draw("jarm", 1, fps=240.0, noise=0.2))
    model = Model(*inputs[0], jarm_only=res.fit.jarm_only)
    lo, hi = res.fit.lower, res.fit.upper
    coarse = coarse_jacobian(model, res.fit.x, lo, hi)
    monkeypatch.setattr(fitmod, "COARSE_STEP", 1e-7)
    assert not rough(coarse_jacobian(model, res.fit.x, lo, hi), coarse)


@given(
    st.lists(st.floats(0.2, 5.0), min_size=1, max_size=9),
    st.floats(ROUGH * 1.01, 1e6),
    st.integers(0, 2**32 - 1),
)
def test_a_column_rough_only_when_much_longer_at_the_fine_step(scales, jump, seed):
    coarse = np.random.default_rng(seed).normal(size=(40, len(scales)))
    coarse[:, 0] = 0.0  # a parameter with no effect: zero at either step, not rough
    assert not rough(coarse * np.array(scales), coarse)
    fine = coarse.copy()
    k = len(scales) - 1
    fine[:, k] = coarse[:, k] * jump if k else 1.0
    assert rough(fine, coarse)


def test_parameters_the_track_does_not_determine_print_as_bounds(capsys):
    """The README's JARM track printed "mu_k 3.000 in [0, 3]", "mu_s 6.000 in [3, inf]".
    mu_s is a lower bound from its profile: a body with mu_s down to 0.3 slips only in the
    last frames, with forces near zero, and fits this track as well (chi2 0.64 more), so
    the bound is far below the 0.868 the fitted rolling needs (and the verdict says the
    frame rate cannot exclude a slip)."""
    assert main([*README[:-1], "--marker-angle", "34.3775"]) == 0
    out = capsys.readouterr().out
    assert "mu_k        not determined by this track" in out
    assert re.search(
        r"mu_s        >= 0\.[0-9]{3} \(the track's 95 % bound; "
        r"the fitted rolling needs 0\.86[89]\)",
        out,
    )
    assert "3.000" not in out and "6.000" not in out
    assert main([*README, "--marker-angle", "34.3775"]) == 0
    params = json.loads(capsys.readouterr().out)["parameters"]
    assert params["mu_k"]["status"] == "not_determined" and params["mu_k"]["value"] is None
    assert params["mu_s"]["status"] == "lower_bound" and params["mu_s"]["value"] is None
    assert params["mu_s"]["rolling_needs"] == pytest.approx(0.8685, abs=1e-3)
    assert 0.0 < params["mu_s"]["lo"] < params["mu_s"]["rolling_needs"]
    assert params["theta0"]["status"] == "value"


@given(st.floats(0.0, 1e3), st.floats(-1e3, 1e3))
def test_a_slip_the_data_ask_for_is_never_jarm(frames, delta):
    verdict, reason = slip_verdict(frames, delta)
    if delta >= SIGNIFICANT:
        assert verdict != "jarm"
    if verdict == "slip_first":
        assert delta >= SIGNIFICANT and frames >= 1
    assert (verdict == "undetermined") == (reason != "")


def _rolling_verdict(one: float, needs: float, friction: tuple[str, ...] = ()) -> tuple:
    """decide() on a track whose fitted model rolls to a lift-off seen in the track, fits
    it, and leaves a slip of one frame costing ``one``."""
    seen = SimpleNamespace(apex_height=8e-3, liftoff=SimpleNamespace(lo=0.23, hi=0.24))
    observed = SimpleNamespace(peak_snr=20.0, flights=(seen,))
    v = Verdict(observed, None, None, 0.5, "", 20.0, 20.0, one, needs, friction)  # type: ignore[arg-type]
    rec = SimpleNamespace(sigma=4e-4)
    return decide(v, seen, (10.0, 30.0), 0.0, math.nan, rec, 0.0, 0.02, 1 / 240)  # type: ignore[arg-type]


@given(st.floats(-20.0, 8.99), st.floats(0.05, 2.9))
def test_an_undetermined_one_frame_test_says_what_settles_it(one, needs):
    """Below SIGNIFICANT the verdict is frame_rate, and the evidence names the measured mu_s
    that would settle it: the measurement's chi-square at the printed mu_s
    (``MeasuredFriction.against_slip``, the route ``friction.weigh`` takes) plus the
    track's reaches SIGNIFICANT (the figures are rounded up, never short of it)."""
    verdict, reason, evidence = _rolling_verdict(one, needs)
    assert (verdict, reason) == ("undetermined", "frame_rate")
    assert evidence[-1] == settle(one, needs)[0]
    found = re.search(r"above ([0-9.]+), .* by ([0-9.]+) of its standard deviations", evidence[-1])
    mu = float(found[1]) + float(found[2]) * 0.1  # as printed
    against = MeasuredFriction(mu, 0.1, "given").against_slip(needs)
    total = against + max(one, 0.0)
    assert SIGNIFICANT - 1e-9 <= total <= SIGNIFICANT + 0.2  # the figures are rounded up
    assert _rolling_verdict(9.0, needs)[0] == "jarm"
    assert not any("settle" in e for e in _rolling_verdict(one, needs, ("weighed",))[2])


def test_evidence_without_a_number_to_give_says_so():
    """No one-frame slip could be made (NaN), a rolling that needs no finite mu_s, a run
    with no rolling: the evidence says what is missing, never 'chi2 nan' or '>= 0.000'."""
    verdict, reason, evidence = _rolling_verdict(math.nan, 0.5)
    assert (verdict, reason) == ("undetermined", "frame_rate")
    assert "could be tried" in evidence[-1] and "nan" not in " ".join(evidence)
    assert settle(3.0, math.inf) == settle(3.0, 0.0)
    assert "mu_s" not in settle(3.0, math.inf)[0]
    assert "no rolling" in needs_sentence(0.0) and "0.000" not in needs_sentence(0.0)
    assert "without bound" in needs_sentence(math.inf)
    assert needs_sentence(0.8685).startswith("the rolling before it needs mu_s >= 0.869")


# --- the campaign ------------------------------------------------------------------------


@functools.cache
def campaign_rows() -> list[dict]:
    """The seeded sweep (seed 0), judged once for both campaign tests."""
    rows = [vc.judge(case, kwargs) for case, kwargs in vc.cases(seed=0)]
    print(vc.summary(rows))
    return rows


@pytest.mark.campaign
def test_never_confidently_wrong():
    """No `jarm` for a track that slips, no `slip_first` for one that never slips."""
    rows = campaign_rows()
    assert not [r for r in rows if r["wrong"]]
    assert all(math.isfinite(r["chi2"]) for r in rows)


@pytest.mark.campaign
def test_the_held_out_intervals_cover():
    """The 95 % intervals of the lift-off, mu_k and mu_s (a value or a bound) cover the
    truth in >= 90 % of the tracks."""
    rows = campaign_rows()
    for key in ("lift_ok", "mu_k_ok", "mu_s_ok"):
        assert sum(r[key] for r in rows) >= 0.9 * len(rows), key


@pytest.mark.campaign
@pytest.mark.xfail(
    reason="issue 48 open: from the track alone, JARM tracks called jarm in 6-11 of 12 per "
    "seed (with a measured mu_s: 10-12, test_with_a_measured_friction_...), slips >= 3 "
    "frames in 84-100 % per seed, 64 of 71 over seeds 0-3 (a one-frame slip before the "
    "lift-off would not show at 1000 fps, a slip inside 2 px of noise); the misses are "
    "`undetermined`",
    strict=False,
)
def test_the_held_out_verdicts():
    """Slips >= 3 frames slip_first in >= 90 %, JARM jarm in >= 90 %."""
    rows = campaign_rows()
    clean = [r for r in rows if "/" not in r["family"]]
    ge3 = [r for r in clean if r["frames"] >= 3]
    jarm = [r for r in clean if r["frames"] == 0]
    assert sum(r["verdict"] == "slip_first" for r in ge3) >= 0.9 * len(ge3)
    assert sum(r["verdict"] == "jarm" for r in jarm) >= 0.9 * len(jarm)


@functools.cache
def measured_rows() -> list[dict]:
    """Seed 0's sweep and the JARM tracks of seeds 1-3, with mu_s measured apart from each
    track to 5 % (``judge``)."""
    picked = vc.cases(seed=0) + [
        (case, kwargs)
        for seed in (1, 2, 3)
        for case, kwargs in vc.cases(seed=seed)
        if case.family == "jarm" and not kwargs and not case.roll_deg
    ]
    rows = [vc.judge(case, kwargs, measured=0.05) for case, kwargs in picked]
    print(vc.summary(rows))
    return rows


@pytest.mark.campaign
def test_with_a_measured_friction_jarm_is_called_and_never_wrong():
    """What the track alone cannot exclude (a slip of one frame at the lift-off) a measured
    mu_s can: the JARM tracks of seeds 0-3 are `jarm` in 43 of 48 (35 of 48 from the tracks
    alone; 45 of 48 with another draw of the measurement errors: where the need comes within
    the measurement's 3 sigma it depends on the draw), and still no confidently wrong
    verdict. The bar is 85 %: the issue's 90 % is for the track alone."""
    rows = measured_rows()
    assert not [r for r in rows if r["wrong"]]
    jarm = [r for r in rows if r["frames"] == 0 and "/" not in r["family"]]
    assert len(jarm) == 48
    assert sum(r["verdict"] == "jarm" for r in jarm) >= 0.85 * len(jarm)


# --- the track's own length scale, correlated errors, bounces --------------------------------


def test_a_scale_off_by_a_part_in_a_thousand_is_not_a_slip():
    """A scale from the dots' distance is off by 5e-4 to 1e-3 on a video (the marker's dot is
    blurred along its arc): every length of the track is, and a rolling body seems to slip
    by that share of its travel. The fit carries the track's length scale as a nuisance
    parameter: the JARM track stays jarm, and the scale is recovered."""
    case = rt.draw("jarm", 1, 240.0, 0.2)
    made = rt.film(case)
    k = 1.001
    stretched = replace(made.track, c=made.track.c * k, m=made.track.m * k)
    res = analyze(stretched, radius=case.radius, chi=case.chi, km=case.km, alpha=case.alpha,
                  marker_angle=case.marker_angle, marker_radius=0.8 * case.radius * k,
                  profile_mu_k=False)  # fmt: skip
    assert res.verdict == "jarm", (res.verdict, res.reason, res.evidence)
    assert res.fit.value("length_scale") == pytest.approx(k, abs=3 * res.fit.error("length_scale"))


@given(st.floats(-0.8, 0.8), st.integers(0, 2**32 - 1))
@settings(max_examples=20, deadline=None)
def test_the_correlation_inflation_of_ar1_errors(rho, seed):
    """AR(1) residuals with lag-1 correlation rho: the inflation is (1 + rho) / (1 - rho) for
    rho > 0 (the variance of a long mean grows by it), 1 for rho <= 0."""
    rng = np.random.default_rng(seed)
    n = 4000
    e = rng.standard_normal((4, n))
    r = np.empty_like(e)
    r[:, 0] = e[:, 0]
    for i in range(1, n):
        r[:, i] = rho * r[:, i - 1] + math.sqrt(1 - rho**2) * e[:, i]
    residuals = r.reshape(2, 2, n).transpose(0, 2, 1).ravel()  # C then M, (frames, 2) each
    got = correlation_inflation(residuals, n)
    want = max((1 + rho) / (1 - rho), 1.0)
    assert got == pytest.approx(want, rel=0.15, abs=0.15)


@given(st.floats(0.5, 8.0), st.floats(1.0, 4.0), st.integers(0, 2**32 - 1))
@settings(max_examples=15, deadline=None)
def test_the_flight_signal_is_the_matched_filter_in_standard_errors(z, inflation, seed):
    """A parabolic flight of |h| = z sigma (its norm over the frames) in white noise: the
    matched filter sum(h_obs h) / (sigma |h|) is normal with mean z / sqrt(inflation) and
    standard deviation 1 / sqrt(inflation), checked over 400 noise draws, and z /
    sqrt(inflation) as the flight's own size; contact frames (h = 0) add nothing. A model
    that never flies gives (0, 0)."""
    rng = np.random.default_rng(seed)
    radius, sigma, n = 0.05, 1e-3, 120
    tau = np.linspace(-1.0, 1.0, 80)
    y = np.ones((6, n))  # the model's states: y[4] = 1 + h / R on the 80 flight frames
    shape = 1.0 - tau**2
    h = shape * z * sigma / float(np.linalg.norm(shape))
    y[4, 20:100] += h / radius
    fit = SimpleNamespace(value=lambda name: 1.0, states=y, correlation=inflation)
    setup = SimpleNamespace(radius=radius)
    heights = (y[4] - 1.0) * radius + sigma * rng.standard_normal((400, n))
    got = np.array([flight_signal(fit, setup, SimpleNamespace(height=hh, sigma=sigma))
                    for hh in heights])  # fmt: skip
    scale = 1.0 / math.sqrt(inflation)
    assert got[:, 0].mean() == pytest.approx(z * scale, abs=4 * scale / 20)
    assert got[:, 0].std() == pytest.approx(scale, rel=0.2)
    assert got[:, 1] == pytest.approx(z * scale)  # the filter on the model's own heights
    fit.states = np.ones((6, n))
    assert flight_signal(fit, setup, SimpleNamespace(height=heights[0], sigma=sigma)) == (0, 0)


@given(st.integers(0, 2**32 - 1), st.floats(0.0, 0.3))
@settings(max_examples=60, deadline=None)
@example(0, 0.13)
def test_a_parameter_the_jacobian_does_not_fix_has_an_infinite_variance(seed, weight):
    """A Jacobian of rank 4 in 6 parameters whose two unresolved directions carry parameter
    5 with weight w/√2 each (a projection of length w) and parameter 0 not at all: the
    variance is infinite exactly where w > 0.1 (judged by the largest single part, w = 0.13
    was lost in neither direction and its variance came out near 0), finite elsewhere."""
    assume(abs(weight - 0.1) > 1e-6)  # (the boundary itself: rounding decides)
    rng = np.random.default_rng(seed)
    a, a_perp = np.linalg.qr(rng.standard_normal((4, 2)))[0].T  # in parameters 1-4
    c2 = 1.0 - weight**2 / 2.0
    beta = -(weight**2 / 2.0) / c2  # makes the two directions orthogonal
    b = beta * a + math.sqrt(1.0 - beta**2) * a_perp
    null = np.array([[0.0, *(math.sqrt(c2) * v), weight / math.sqrt(2.0)] for v in (a, b)]).T
    resolved = np.linalg.svd(np.eye(6) - null @ null.T)[0][:, :4]
    jac = rng.standard_normal((40, 4)) @ resolved.T * 10.0
    cov = covariance(jac, 1.0)
    assert math.isfinite(cov[0, 0])  # parameter 0: resolved
    assert (not math.isfinite(cov[5, 5])) == (weight > 0.1)


def test_a_profile_flat_to_the_grids_end_leaves_mu_k_open_above():
    """A JARM track at 2 px (independent model, mu_k 1.99): the profile of mu_k was within
    the level from 0.45 to the grid's end, 1.5, and the interval stopped at 1.65; a flat
    profile says nothing past its grid: up to the bound. A profile that rises again keeps
    its end (one grid step past the last accepted value)."""
    grid = np.linspace(0.0, 1.5, 11)
    best = SimpleNamespace(names=("mu_k",), lower=np.array([0.0]), upper=np.array([3.0]),
                           cost=10.0, variance_factor=1.0)  # fmt: skip
    flat = np.where(grid < 0.4, 500.0, 10.5)
    assert profile_interval(grid, flat, best, (0.5, 0.7), (0.0, 3.0)) == pytest.approx((0.3, 3.0))
    rising = flat + np.where(grid > 1.0, 100.0, 0.0)
    lo, hi = profile_interval(grid, rising, best, (0.5, 0.7), (0.0, 3.0))
    assert (lo, hi) == pytest.approx((0.3, 0.9 + 0.15))


def test_a_second_flights_liftoff_comes_after_the_first_landing():
    """The lift-off of a bounce was looked for 50 ms back, inside the first flight: the
    analysis then cut the track mid-flight. A flight's lift-off is after the previous one's
    last frame."""
    t = np.arange(200) / 240.0
    h = np.zeros_like(t)
    h[50:90] = 0.005 * np.sin(np.linspace(0, math.pi, 40))
    h[100:140] = 0.004 * np.sin(np.linspace(0, math.pi, 40))
    rec = SimpleNamespace(t=t, height=h, sigma=1e-4, window=9, dt=t[1],
                          slip=np.zeros_like(t), slip_err=np.ones_like(t),
                          s=np.zeros_like(t), s_err=np.ones_like(t))  # fmt: skip
    flights = observe(rec).flights  # type: ignore[arg-type]
    assert len(flights) == 2
    assert flights[1].liftoff.lo > flights[0].landing.hi


def test_first_frames_cuts_every_per_frame_array():
    made = rt.film(rt.draw("jarm", 2, 240.0, 0.5))
    video = VideoTrack(t=made.track.t, c=made.track.c, m=made.track.m,
                       c_err=np.ones_like(made.track.c), frame_t=made.track.t.copy(),
                       scale=1000.0)  # fmt: skip
    cut = first_frames(video, 10)
    assert isinstance(cut, VideoTrack) and cut.n == 10 and cut.scale == 1000.0
    assert cut.c_err.shape == (10, 2) and cut.frame_t.shape == (10,)
    assert cut.m_err.shape == video.m_err.shape  # not per frame: kept
