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
from eccjump._base.checks import integer
from eccjump.motion.options import MotionOptions
from eccjump.motion.simulation import MODES, MotionResult, simulate
from eccjump.studies.experiment.geometry import RampFrame, marker_offset
from eccjump.studies.experiment.inputs import between, in_range, marker_radius_in_range
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
    """The track an ideal experiment would give: a simulated run, filmed with pixel noise.

    Simulates ``body`` on a ramp of angle ``alpha`` from (theta0, omega0) and films it: the
    axle C and the marker M in the lab frame at ``fps`` from t = 0, in a field of view
    ``field_px`` pixels across the whole track, with Gaussian noise of ``noise_px`` pixels on
    each coordinate. The track is in metres (the pixels divided by the scale), given with
    the truth at its frames.

    Parameters
    ----------
    body : Cylinder
        The body, with km > 0 (as :func:`eccjump.simulate` takes it).
    alpha : float
        The ramp angle [rad], in [0, π/2].
    mu_s : float
        Static friction coefficient, in [0, inf).
    mu_k : float or None, default None
        Kinetic friction coefficient, in [0, μ_s]; None: μ_k = μ_s.
    restitution : float, default 0.0
        Stronge's energetic coefficient of restitution e, in [0, 1].
    theta0 : float, default 0.0
        Initial angle [rad], |theta0| ≤ 2π 1e6.
    omega0 : float, default 0.0
        Initial angular velocity [√(g/R) rad], |omega0| ≤ 1e6.
    radius : float, default 0.05
        R [m], the body's radius, in [1e-4, 10].
    g : float, default 9.81
        Gravity [m/s²], in [0.01, 100].
    fps : float, default 240.0
        The frame rate [1/s], in [1, 1e5].
    duration : float or None, default None
        The track's length [s] (its frames are the ones before it); None: to the first
        landing and half a flight more, or 3 s without a flight. The run it needs,
        ``duration`` / √(R/g) + 2, must be in (0, 1e6] (``simulate``'s ``t_max``).
    marker_radius : float or None, default None
        The marker's distance from the axle [m], in [R/1000, 2 R]; None: 0.8 R.
    marker_angle : float, default 0.0
        The marker's angle from the direction C -> CM [rad], measured like θ (towards the
        direction of rolling), in [−2π, 2π].
    noise_px : float, default 0.5
        The standard deviation of the Gaussian noise on each coordinate of each point [px],
        in [0, 100].
    field_px : float, default 1000.0
        The field of view [px]: 1.1 times the larger span of C's and M's paths (x or y) is
        ``field_px`` pixels, in [10, 1e6]; it sets the ``scale`` [px/m], and so the noise in
        metres.
    side : int, default 1
        The ramp's direction in the lab: 1 descends to the right, -1 to the left.
    seed : int, default 0
        The seed of the noise (``numpy.random.default_rng``), an int ≥ 0.

    Returns
    -------
    SyntheticTrack
        ``track`` (a :class:`Track` in metres, t [s] from 0), the ``scale`` it was drawn at
        [px/m], the truth at its frames (``theta`` [rad], ``l`` and ``b`` [m], ``mode``), the
        simulated run (``motion``, dimensionless, with its ``time_unit`` [s]) and
        ``transitions_si()``.

    Raises
    ------
    ValueError
        For a parameter outside its range (above; a body with km = 0); the message names
        it.
    TypeError
        If ``body`` is not a Cylinder or a parameter has the wrong type.
    """
    radius, g, r_m, marker_angle = scene_inputs(radius, g, marker_radius, marker_angle)
    fps = between("fps", fps, 1.0, MAX_FPS, "1/s")
    noise_px = between("noise_px", noise_px, 0.0, 100.0, "px")
    field_px = between("field_px", field_px, 10.0, 1e6, "px")
    if side not in (1, -1):
        raise ValueError(f"side must be 1 (the ramp descends to the right) or -1, not {side!r}")
    rng = np.random.default_rng(integer("seed", seed))
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
    c, m, (theta, l, b) = lab_points(run, tau, alpha, side, radius, r_m, marker_angle)  # noqa: E741
    pts = np.vstack([c, m])
    extent = 1.1 * float(max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1])))
    scale = field_px / extent
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


#: The highest frame rate of a synthetic track or video [1/s].
MAX_FPS = 1e5


def scene_inputs(
    radius: object, g: object, marker_radius: object, marker_angle: object
) -> tuple[float, float, float, float]:
    """R [m], g [m/s²], the marker's distance from the axle [m] (None: 0.8 R) and its angle
    [rad], each in the range ``analyze`` takes (``inputs``): ValueError or TypeError naming
    it (a radius of 0 divided by zero, one below 0 gave "math domain error")."""
    r = in_range("radius", radius)
    r_m = marker_radius_in_range(marker_radius, r)
    return (
        r,
        in_range("g", g),
        0.8 * r if r_m is None else r_m,
        in_range("marker_angle", marker_angle),
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
