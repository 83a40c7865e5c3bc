"""Synthetic tracks made by :func:`eccjump.simulate`: the video an ideal experiment would give,
sampled at a frame rate and blurred by Gaussian pixel noise. The analysis is validated on
them (``tests/test_analysis.py``, ``scripts/make_tracks.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump.motion.options import MotionOptions
from eccjump.motion.simulation import MODES, MotionResult, simulate
from eccjump.studies.experiment.geometry import RampFrame, marker_offset
from eccjump.studies.experiment.track import Track


@dataclass(frozen=True, eq=False)
class SyntheticTrack:
    """A track (metres), the pixel scale it was drawn at [px/m] and the truth at its frames:
    θ [rad], l and b [m] (l from the first frame), the mode of each frame, and the
    simulated run (dimensionless, its time 0 at the first frame)."""

    track: Track
    scale: float
    theta: NDArray[np.float64]
    l: NDArray[np.float64]  # noqa: E741
    b: NDArray[np.float64]
    mode: NDArray[np.int8]
    motion: MotionResult
    time_unit: float

    def transitions_si(self) -> list[tuple[float, str, str]]:
        """(t [s], to_mode, reason) of every transition within the track."""
        end = float(self.track.t[-1])
        return [
            (tr.t * self.time_unit, tr.to_mode, tr.reason)
            for tr in self.motion.transitions[1:]
            if tr.t * self.time_unit <= end
        ]


def synthetic_track(
    body: Cylinder,
    alpha: float,
    *,
    mu_s: float,
    mu_k: float | None = None,
    restitution: float = 0.0,
    theta0: float = 0.0,
    omega0: float = 0.0,
    radius: float = 0.05,
    g: float = 9.81,
    fps: float = 240.0,
    duration: float | None = None,
    marker_radius: float | None = None,
    marker_angle: float = 0.0,
    noise_px: float = 0.5,
    field_px: float = 1000.0,
    side: int = 1,
    seed: int = 0,
) -> SyntheticTrack:
    """Simulate ``body`` from (theta0, omega0) and film it: frames at ``fps`` from t = 0
    for ``duration`` seconds (default: to the first landing and half a flight more, or 3
    s without a flight), the marker at ``marker_radius`` (default 0.8 R) and
    ``marker_angle`` from C -> CM, a field of view ``field_px`` pixels across the whole
    track, Gaussian noise of ``noise_px`` pixels on each coordinate."""
    run, unit, horizon = simulated_run(
        body,
        alpha,
        mu_s=mu_s,
        mu_k=mu_k,
        restitution=restitution,
        theta0=theta0,
        omega0=omega0,
        radius=radius,
        g=g,
        duration=duration,
    )
    tau = np.arange(0.0, horizon, 1.0 / (fps * unit))
    mode = np.asarray(run.mode)[np.clip(np.searchsorted(run.t, tau, side="right") - 1, 0, None)]
    r_m = 0.8 * radius if marker_radius is None else marker_radius
    c, m, (theta, l, b) = lab_points(run, tau, alpha, side, radius, r_m, marker_angle)  # noqa: E741
    pts = np.vstack([c, m])
    extent = 1.1 * float(max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1])))
    scale = field_px / extent
    rng = np.random.default_rng(seed)
    c_px = (c - pts.min(axis=0)) * scale + rng.normal(0.0, noise_px, c.shape)
    m_px = (m - pts.min(axis=0)) * scale + rng.normal(0.0, noise_px, m.shape)
    track = Track(t=tau * unit, c=c_px / scale, m=m_px / scale, source="synthetic")
    return SyntheticTrack(
        track=track,
        scale=scale,
        theta=theta,
        l=l,
        b=b,
        mode=mode.astype(np.int8),
        motion=run,
        time_unit=unit,
    )


def simulated_run(
    body: Cylinder,
    alpha: float,
    *,
    mu_s: float,
    mu_k: float | None,
    restitution: float,
    theta0: float,
    omega0: float,
    radius: float,
    g: float,
    duration: float | None,
) -> tuple[MotionResult, float, float]:
    """The run that a synthetic track or video films: ``simulate`` with dense output, the time
    unit √(R/g) [s] and the horizon (dimensionless): ``duration`` seconds, or by default to
    the first landing and half a flight more (3 s without a flight)."""
    unit = math.sqrt(radius / g)
    horizon = 3.0 / unit if duration is None else duration / unit
    # Past the frames' end, with room for the stick-slip chatter of a long track.
    options = MotionOptions(t_max=horizon + 2.0, max_transitions=200)
    run = simulate(
        body,
        alpha,
        mu_s=mu_s,
        mu_k=mu_k,
        restitution=restitution,
        theta0=theta0,
        omega0=omega0,
        **options.keywords(),
        dense_output=True,
    )
    if duration is None and run.flights and math.isfinite(run.flights[0].t_landing):
        f = run.flights[0]
        horizon = f.t_landing + 0.5 * (f.t_landing - f.t_liftoff)
    assert run.sol is not None
    return run, unit, min(horizon, run.sol.t_max)


def lab_points(
    run: MotionResult,
    tau: NDArray[np.float64],
    alpha: float,
    side: int,
    radius: float,
    r_m: float,
    beta: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64], tuple[NDArray[np.float64], ...]]:
    """The axle C and the marker M (each (n, 2), lab metres, C's contact line through the
    origin) at the dimensionless times ``tau``, and (θ [rad], l [m], b [m]) there."""
    assert run.sol is not None
    theta, _, l, _, b, _ = run.sol(tau)  # noqa: E741
    frame = RampFrame(alpha, side, (0.0, 0.0))
    qc = np.column_stack([radius * l, radius * (b - 1.0)])
    c = frame.to_lab(qc)
    m = frame.to_lab(qc + marker_offset(theta, r_m, beta))
    return c, m, (theta, radius * l, radius * b)


__all__ = ["MODES", "SyntheticTrack", "synthetic_track"]
