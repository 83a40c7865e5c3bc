"""A static friction measured apart from the track (``analyze(mu_s=, mu_s_err=)``, ``eccjump
analyze --mu-s --mu-s-err``, or a design sheet's): it excludes the slip of one frame that a
rolling track alone cannot (``studies/experiment/friction.py``), and it never turns a slip
the track asks for into ``jarm``."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
import reference_tracks as rt
from hypothesis import given
from hypothesis import strategies as st

import eccjump
from eccjump.cli import main
from eccjump.studies.experiment import analyze, synthetic_track
from eccjump.studies.experiment.friction import MeasuredFriction, measured_friction

#: The design's JARM body (docs: "A walk through one track"), whose rolling needs mu_s of
#: about 0.27 and whose friction need peaks at the lift-off: at 240 fps and 0.5 px a slip of
#: one frame just before it costs the track's fit chi2 = 0.45 (9 needed).
BODY = eccjump.Cylinder(0.10927, 0.0777)
ALPHA = math.radians(66.087)
SETUP = {"radius": 0.05, "chi": BODY.chi, "km": BODY.km, "alpha": ALPHA,
         "marker_radius": 0.04, "profile_mu_k": False}  # fmt: skip
SHEET = {"body": {"chi": BODY.chi, "km": BODY.km}, "alpha_deg": 66.087}


@pytest.fixture(scope="module")
def design_track():
    made = synthetic_track(BODY, ALPHA, mu_s=1.2, mu_k=0.9, radius=0.05, fps=240.0,
                           noise_px=0.5, seed=0)  # fmt: skip
    return made.track


@pytest.fixture(scope="module")
def alone(design_track):
    return analyze(design_track, **SETUP)


def test_a_measured_mu_s_excludes_the_slip_a_rolling_track_cannot(design_track, alone):
    assert (alone.verdict, alone.reason) == ("undetermined", "frame_rate")
    sheet = SHEET | {"mu_s": 1.2, "mu_s_err": 0.1}  # the friction the body was designed for
    res = analyze(design_track, design=sheet, **SETUP)
    assert res.verdict == "jarm", res.evidence
    assert res.mu_s_measured == MeasuredFriction(1.2, 0.1, "design")
    assert "; measured 1.2 +- 0.1" in repr(res)
    assert any("the measured mu_s = 1.2 +- 0.1 (from the design sheet)" in e for e in res.evidence)
    measured = res.to_dict()["inputs"]["mu_s_measured"]
    assert measured == {"value": 1.2, "err": 0.1, "source": "design"}
    # the lift-off is the track's: the measured friction only rules out the slip
    assert abs(res.liftoff_t - alone.liftoff_t) < 0.5 * design_track.dt


def test_the_friction_an_undetermined_verdict_asks_for_settles_it(design_track, alone):
    """The track alone cannot exclude a slip of one frame, and its evidence says what
    measurement would: mu_s above what rolling to the lift-off needs by k standard
    deviations. A measurement 10 % beyond that gives jarm on the same track, one 20 % short
    of it does not (the printed figures are rounded to 2-3 digits)."""
    line = next(e for e in alone.evidence if e.startswith("what would settle it"))
    found = re.search(r"above ([0-9.]+), what rolling to the lift-off needs, by ([0-9.]+) of", line)
    assert found, line
    needs, k = float(found[1]), float(found[2])
    assert needs >= alone.mu_s_needed and 2.0 < k <= 3.0  # sqrt(9 - chi2) with chi2 in [0, 9)
    err = 0.05
    enough = analyze(design_track, mu_s=needs + 1.1 * k * err, mu_s_err=err, **SETUP)
    assert enough.verdict == "jarm", enough.evidence
    short = analyze(design_track, mu_s=needs + 0.8 * k * err, mu_s_err=err, **SETUP)
    assert (short.verdict, short.reason) == ("undetermined", "frame_rate"), short.evidence
    assert not any(e.startswith("what would settle it") for e in short.evidence)


def test_a_measured_mu_s_below_what_the_rolling_needs_is_no_jarm(design_track):
    """A friction too low for the fitted rolling (0.2 against 0.27) says the body should have
    slipped: it weighs for the slip, never for jarm."""
    res = analyze(design_track, mu_s=0.2, mu_s_err=0.02, **SETUP)
    assert res.verdict == "undetermined", res.evidence
    assert any("weighs chi2 = -" in e for e in res.evidence), res.evidence


def test_a_slip_the_track_asks_for_stays_slip_first_against_a_measured_mu_s():
    """The issue's stick-slip track (60 fps; slips 145.5-202.0 ms and again from 284.2 ms)
    with a friction measured far too high: the slip stands, and the evidence says to check
    the measurement."""
    case = rt.draw("stick_slip", 1, fps=60.0, noise=0.5)
    made = rt.film(case)
    res = analyze(made.track, radius=case.radius, chi=case.chi, km=case.km, alpha=case.alpha,
                  marker_angle=case.marker_angle, marker_radius=0.8 * case.radius,
                  profile_mu_k=False, mu_s=2.0, mu_s_err=0.05)  # fmt: skip
    assert res.verdict == "slip_first"
    assert any("check the friction measurement" in e for e in res.evidence), res.evidence


@pytest.mark.parametrize(
    ("mu_s", "mu_s_err", "error", "match"),
    [(1.0, None, ValueError, r"^mu_s_err is needed too"),
     (None, 0.1, ValueError, r"^mu_s is needed too"),
     (0.0, 0.1, ValueError, r"^mu_s = 0 is outside the allowed range \[0\.001, 10\]$"),
     (1.0, 0.0, ValueError, r"^mu_s_err = 0 is outside the allowed range \[0\.0001, 10\]$"),
     (math.nan, 0.1, ValueError, r"^mu_s = nan is outside"),
     ("1", 0.1, TypeError, r"^mu_s must be a real number")],
)  # fmt: skip
def test_a_measured_mu_s_comes_with_its_error(mu_s, mu_s_err, error, match):
    with pytest.raises(error, match=match) as err:
        analyze("never-read.csv", mu_s=mu_s, mu_s_err=mu_s_err, **SETUP)
    assert len(str(err.value)) < 200


def test_a_design_sheet_gives_its_friction_only_with_an_uncertainty():
    sheet = {"mu_s": 0.9, "mu_s_err": 0.05}
    from_sheet, notes = measured_friction(None, None, sheet)
    assert from_sheet == MeasuredFriction(0.9, 0.05, "design")
    assert notes == ("the design sheet's mu_s = 0.9 +- 0.05 is taken as the measured static "
                     "friction (give mu_s and mu_s_err to override it)",)  # fmt: skip
    none, notes = measured_friction(None, None, {"mu_s": 0.9, "mu_s_err": 0.0})
    assert none is None and "no uncertainty" in notes[0]
    assert measured_friction(None, None, {}) == (None, ())
    given_ = measured_friction(1.1, 0.2, sheet)[0]  # what is given wins over the sheet
    assert given_ == MeasuredFriction(1.1, 0.2, "given")
    percent, notes = measured_friction(0.8, 5.0, {})  # 5 %, given as 5
    assert percent == MeasuredFriction(0.8, 5.0, "given") and "not a percentage?" in notes[0]
    with pytest.raises(ValueError, match=r"^mu_s_err = 20 \(from design\) is outside"):
        measured_friction(None, None, {"mu_s": 0.9, "mu_s_err": 20.0})


@given(
    value=st.floats(0.01, 5.0),
    err=st.floats(0.001, 1.0),
    mu=st.floats(0.0, 6.0),
    shift=st.floats(0.0, 1.0),
)
def test_the_measurement_weighs_as_a_normal_chi_square(value, err, mu, shift):
    """((value - mu_slip)/err)^2 against a slip that needs mu_s <= mu_slip, zero where the
    measured value allows it; the same for a rolling that needs more than the value; each
    grows as the run asks for a friction further from the measurement."""
    m = MeasuredFriction(value, err, "given")
    slip, rolling = m.against_slip(mu), m.against_rolling(mu)
    assert slip == (0.0 if mu >= value else ((value - mu) / err) ** 2)
    assert rolling == (0.0 if mu <= value else ((mu - value) / err) ** 2)
    assert m.against_slip(mu - shift) >= slip and m.against_rolling(mu + shift) >= rolling
    assert m.against_rolling(math.inf) == math.inf


def test_the_command_line_takes_the_measured_friction(capsys, tmp_path: Path):
    """The README's track with the README's measurement (the design's mu_s = 1, to 5 %) is
    `jarm`, as the README and the page "Analysing an experiment" say (chi2 = 10.1: the
    track's 3.2 and the measurement's 6.9)."""
    data = Path(__file__).resolve().parent / "data" / "jarm_240fps.csv"
    argv = ["analyze", str(data), "--radius", "0.05", "--chi", "0.10927", "--km", "0.0777",
            "--alpha", "66.087", "--marker-radius", "0.04", "--marker-angle", "34.3775",
            "--scale", "1230.539145", "--mu-s", "1", "--mu-s-err", "0.05", "--json"]  # fmt: skip
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["inputs"]["mu_s_measured"] == {"value": 1.0, "err": 0.05, "source": "given"}
    assert report["verdict"] == "jarm", report["evidence"]
    assert main([*argv[:-5], "--mu-s", "1"]) == 2
    assert "error: --mu-s-err is needed too" in capsys.readouterr().err
