"""Reading a track and reconstructing theta, l, b from it (eccjump.experiment: track,
geometry, reconstruct). The round trip: tracks filmed from `simulate` come back to the
simulated angles and distances within the noise."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import eccjump
from eccjump.experiment.geometry import RampFrame, marker_offset, theta_from_marker
from eccjump.experiment.reconstruct import derivative_weights, reconstruct
from eccjump.experiment.synthetic import synthetic_track
from eccjump.experiment.track import MIN_FRAMES, read_track, track_from_arrays, write_csv

DATA = Path(__file__).parent / "data"
JARM_BODY = eccjump.Cylinder(chi=0.10927, km=0.0777)  # eccjump design --min-apex, 66.087 deg
JARM_ALPHA = math.radians(66.087)


def _columns(n=20):
    t = np.arange(n) / 240.0
    return t, t * 0.5, 1 - t, t * 0.5 + 0.01, 1 - t


def test_the_marker_formula_inverts_for_every_side_and_angle():
    theta = np.linspace(-1.0, 12.0, 200)
    for beta in (0.0, 0.7, -2.5):
        back = theta_from_marker(marker_offset(theta, 0.03, beta), beta)
        turns = (back - theta) / (2 * math.pi)  # the same angle up to whole turns
        assert np.allclose(turns, np.round(turns[0]), atol=1e-12)


def test_the_ramp_frame_is_the_papers():
    """Down the ramp is +x; the normal points away from it; the body at theta = 0 has its
    centre of mass straight above C, and a quarter turn later ahead of it (down the ramp)."""
    for side in (1, -1):
        f = RampFrame(math.radians(30), side, (0.0, 0.0))
        x_hat, y_hat = f.axes
        assert x_hat[1] < 0 and side * x_hat[0] > 0  # down and away to that side
        assert y_hat[1] > 0  # the outward normal points up
        q = np.array([[1.0, 2.0], [-0.5, 0.3]])
        assert np.allclose(f.to_ramp(f.to_lab(q)), q)
        ahead = marker_offset(np.array([math.pi / 2]), 1.0, 0.0)
        assert np.allclose(ahead, [[1.0, 0.0]])


@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("given_alpha", [True, False])
def test_round_trip_from_simulate_to_the_reconstruction(side, given_alpha):
    st = synthetic_track(JARM_BODY, JARM_ALPHA, mu_s=1.0, mu_k=0.8, fps=240, noise_px=0.5,
                         side=side, marker_angle=0.7, seed=3)  # fmt: skip
    r = reconstruct(st.track, radius=0.05, marker_angle=0.7,
                    alpha=JARM_ALPHA if given_alpha else None)  # fmt: skip
    px = 1 / st.scale
    assert 0.35 < r.sigma / px < 0.65  # the noise level is found from the data
    l_shift = np.mean(r.l - st.l)  # l's origin is the first frame's (noisy) axle
    assert abs(l_shift) < 4 * r.sigma
    pairs = ((r.theta, st.theta, r.theta_err), (r.l - l_shift, st.l, r.sigma), (r.b, st.b, r.sigma))
    for got, true, err in pairs:
        z = (got - true) / err
        assert abs(np.mean(z)) < 1.0 and 0.6 < np.std(z) < 1.5
    if not given_alpha:
        assert abs(r.line.frame.alpha - JARM_ALPHA) < 5 * r.line.alpha_err + math.radians(0.1)


def test_rates_are_exact_for_a_cubic_and_their_errors_follow_the_weights():
    t = np.sort(np.random.default_rng(0).uniform(0, 1, 40))
    idx, w = derivative_weights(t, 9)
    y = 2 - t + 3 * t**2 - t**3
    assert np.allclose((w * y[idx]).sum(axis=1), -1 + 6 * t - 3 * t**2)


def test_csv_round_trip_in_pixels(tmp_path):
    st = synthetic_track(JARM_BODY, JARM_ALPHA, mu_s=1.0, fps=120, noise_px=0.5, seed=1)
    p = tmp_path / "track.csv"
    p.write_text(write_csv(st.track, scale=st.scale))
    tr = read_track(p, scale=st.scale)
    assert tr.n == st.track.n and np.allclose(tr.c, st.track.c, atol=0.01 / st.scale)


def test_tracker_export_reads(tmp_path):
    tr = read_track(DATA / "tracker_sample.txt")
    assert tr.n >= MIN_FRAMES and tr.source == "tracker_sample.txt"
    assert np.isfinite(tr.c).all() and np.isfinite(tr.m).all()


@pytest.mark.parametrize(
    ("change", "name"),
    [
        (lambda c: c.__setitem__(1, c[1].copy() * np.nan), "xc"),
        (lambda c: c.__setitem__(0, c[0][::-1].copy()), "t"),
        (lambda c: c.__setitem__(0, np.r_[c[0][:5], c[0][4], c[0][6:]]), "t"),
        (lambda c: [c.__setitem__(i, c[i][:5]) for i in range(5)], "t"),
    ],
    ids=["nan", "unsorted", "repeated", "too-few"],
)
def test_bad_tracks_are_errors_naming_the_column(change, name):
    cols = list(_columns())
    change(cols)
    with pytest.raises(ValueError, match=rf"^{name}\b") as err:
        track_from_arrays(*cols)
    assert len(str(err.value)) < 200


def test_a_csv_without_a_column_is_an_error_naming_it(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("t,xc,yc,xm\n0,1,2,3\n")
    with pytest.raises(ValueError, match=r"missing column.*ym"):
        read_track(p)
