"""From a track to θ(t), l(t), b(t) in the ramp frame, their rates and the slip, each with
its standard error.

Noise: the tracked points carry independent noise of one level sigma per coordinate (pixel
noise of the tracking), estimated from the data: C lies on a straight line in every contact
frame, so the spread of its distance to that line is sigma (``geometry.fit_contact_line``).
Per frame: l and b carry sigma; θ = atan2 of M - C carries sigma √(2) / r_m; the slip
displacement s = l - R (θ - theta_0) carries sigma² (1 + 2k cos phi + 2k²), k = R / r_m,
phi = θ + beta (C's noise enters both l and θ: the cross term).

Rates: local cubic least squares over a window of frames around each frame (Savitzky-Golay
on the actual frame times, so dropped frames are allowed). Why this method: it is a linear
filter with known weights, so the standard error of every rate follows exactly from the
per-frame errors (sum of weight² x variance), and it is local, so a landing blurs the rates
only within one window. A smoothing spline would need its smoothing parameter chosen
from the same noise estimate and gives no simpler error formula. The window (odd, at least 7
frames; by default about 25 ms) trades noise against the blurring of a transition.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from eccjump.studies.experiment.geometry import ContactLine, fit_contact_line, theta_from_marker
from eccjump.studies.experiment.track import Track

#: The default span of the smoothing window [s] and its bounds in frames.
WINDOW_SECONDS = 0.025
MIN_WINDOW, MAX_WINDOW = 7, 41
#: The polynomial degree of the local fits.
DEGREE = 3


@dataclass(frozen=True, eq=False)
class Reconstruction:
    """θ [rad], l [m] (C along the ramp, from its first frame), b [m] (C above the
    ramp; R in contact), the slip displacement s = l - R (θ - θ[0]) [m] per frame
    with their standard errors, and the smoothed rates omega [rad/s], ldot, bdot and the
    slip velocity v = l̇ - R θ̇ [m/s] with theirs; the contact line (frame, α,
    noise), the smoothing window (frames), the marker's distance used and the one measured."""

    t: NDArray[np.float64]
    theta: NDArray[np.float64]
    l: NDArray[np.float64]  # noqa: E741 - the paper's name
    b: NDArray[np.float64]
    s: NDArray[np.float64]
    theta_err: NDArray[np.float64]
    s_err: NDArray[np.float64]
    omega: NDArray[np.float64]
    omega_err: NDArray[np.float64]
    ldot: NDArray[np.float64]
    ldot_err: NDArray[np.float64]
    bdot: NDArray[np.float64]
    bdot_err: NDArray[np.float64]
    slip: NDArray[np.float64]
    slip_err: NDArray[np.float64]
    line: ContactLine
    radius: float
    marker_radius: float
    marker_angle: float
    window: int
    marker_measured: float

    @property
    def sigma(self) -> float:
        """The noise level of a tracked coordinate [m] (the standard error of l and b)."""
        return self.line.sigma

    @property
    def dt(self) -> float:
        """The median frame interval [s]."""
        return float(np.median(np.diff(self.t)))

    @property
    def height(self) -> NDArray[np.float64]:
        """b - R [m]: 0 in contact."""
        return self.b - self.radius


def default_window(dt: float) -> int:
    """About :data:`WINDOW_SECONDS` of frames, odd, within [MIN_WINDOW, MAX_WINDOW]."""
    w = round(WINDOW_SECONDS / dt)
    w = min(max(w, MIN_WINDOW), MAX_WINDOW)
    return w if w % 2 else w + 1


def reconstruct(
    track: Track,
    *,
    radius: float,
    marker_angle: float,
    marker_radius: float | None = None,
    alpha: float | None = None,
    window: int | None = None,
) -> Reconstruction:
    """θ, l, b, the rates and the slip of ``track`` (module docstring for the method)."""
    line = fit_contact_line(track.c, alpha)
    frame = line.frame
    qc, qm = frame.to_ramp(track.c), frame.to_ramp(track.m)
    offset = qm - qc
    measured = float(np.median(np.hypot(offset[:, 0], offset[:, 1])))
    if not measured > 0:
        raise ValueError("xm, ym: the marker coincides with the axle (it must be off the axle)")
    r_m = marker_radius if marker_radius is not None else measured
    theta = theta_from_marker(offset, marker_angle)
    l, b = qc[:, 0], qc[:, 1] + radius  # noqa: E741
    sigma = max(line.sigma, 1e-12 * radius)  # a noise-free track: errors at rounding level
    k = radius / r_m
    phi = theta + marker_angle
    theta_err = np.full(track.n, sigma * math.sqrt(2.0) / r_m)
    s_var = sigma**2 * (1.0 + 2.0 * k * np.cos(phi) + 2.0 * k * k)
    s = l - radius * (theta - theta[0])
    w = window if window is not None else default_window(track.dt)
    if w < MIN_WINDOW or w % 2 == 0 or w > track.n:
        raise ValueError(
            f"window must be an odd number of frames in [{MIN_WINDOW}, {track.n}], got {w}"
        )
    idx, weights = derivative_weights(track.t, w)
    flat = np.full(track.n, sigma**2)
    omega, omega_var = _apply(idx, weights, theta, theta_err**2)
    ldot, ldot_var = _apply(idx, weights, l, flat)
    bdot, bdot_var = _apply(idx, weights, b, flat)
    slip, slip_var = _apply(idx, weights, s, s_var)
    return Reconstruction(
        t=track.t,
        theta=theta,
        l=l,
        b=b,
        s=s,
        theta_err=theta_err,
        s_err=np.sqrt(s_var),
        omega=omega,
        omega_err=np.sqrt(omega_var),
        ldot=ldot,
        ldot_err=np.sqrt(ldot_var),
        bdot=bdot,
        bdot_err=np.sqrt(bdot_var),
        slip=slip,
        slip_err=np.sqrt(slip_var),
        line=line,
        radius=radius,
        marker_radius=r_m,
        marker_angle=marker_angle,
        window=w,
        marker_measured=measured,
    )


def derivative_weights(
    t: NDArray[np.float64], window: int, deriv: int = 1
) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """For each frame the indices of its window (shifted inwards at the ends) and the
    weights whose sum over the window gives the ``deriv``-th derivative of the local cubic
    least-squares fit at that frame."""
    n, half = t.size, window // 2
    start = np.clip(np.arange(n) - half, 0, n - window)
    idx = start[:, None] + np.arange(window)[None, :]
    tau = t[idx] - t[:, None]
    scale = np.abs(tau).max(axis=1, keepdims=True)
    x = tau / scale  # conditioning: local time in [-1, 1]
    V = x[:, :, None] ** np.arange(DEGREE + 1)[None, None, :]
    pinv = np.linalg.pinv(V)  # (n, degree + 1, window)
    weights = pinv[:, deriv, :] * math.factorial(deriv) / scale**deriv
    return idx, weights


def _apply(
    idx: NDArray[np.intp],
    weights: NDArray[np.float64],
    y: NDArray[np.float64],
    var: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return (weights * y[idx]).sum(axis=1), (weights**2 * var[idx]).sum(axis=1)
