"""The ramp frame and the marker: from lab positions to (θ, l, b) and back.

The ramp frame is the paper's: x down the ramp, y along its normal, away from it. In the lab
(x right, y up) a ramp of angle α that descends to the right (``side = +1``) has

    x_hat = (cos a, -sin a),   y_hat = (sin a, cos a);

one that descends to the left (``side = -1``) is its mirror image, x_hat = (-cos a, -sin a),
y_hat = (-sin a, cos a). The body's points are written in that frame, so the same formulas
hold on either side. The centre of mass sits at C + d (sin θ, cos θ) (the paper's
Eq. ddef: θ from the normal towards x_hat, growing as the body rolls down). A marker
fixed on the body at distance r_m from the axle, at angle beta from the direction C -> CM
(measured the same way), turns with the body:

    M = C + r_m (sin(θ + beta), cos(θ + beta))      (ramp frame),

so θ = atan2(u, v) - beta with (u, v) the ramp-frame components of M - C, unwrapped
(rolling down turns the body clockwise in a frame with x_hat to the right: a point at the
top, θ = 0, moves towards x_hat). l is the distance of C along x_hat from an origin on
C's contact line, b its height above the ramp: b = R in contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class RampFrame:
    """The ramp in the lab: angle ``alpha`` [rad], ``side`` (+1: descends to the right),
    ``origin`` (a lab point on the line of C in contact, where l = 0, b = R)."""

    alpha: float
    side: int
    origin: tuple[float, float]

    @property
    def axes(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """x_hat (down the ramp) and y_hat (the ramp's outward normal) in the lab."""
        ca, sa = math.cos(self.alpha), math.sin(self.alpha)
        return np.array([self.side * ca, -sa]), np.array([self.side * sa, ca])

    def to_ramp(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """Lab points (n, 2) as ramp-frame components (n, 2) relative to the origin."""
        x_hat, y_hat = self.axes
        q = p - np.asarray(self.origin)
        return np.column_stack([q @ x_hat, q @ y_hat])

    def to_lab(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """Ramp-frame components (n, 2) relative to the origin as lab points (n, 2)."""
        x_hat, y_hat = self.axes
        return np.asarray(self.origin) + np.outer(q[:, 0], x_hat) + np.outer(q[:, 1], y_hat)


def marker_offset(theta: NDArray[np.float64], r_m: float, beta: float) -> NDArray[np.float64]:
    """M - C in the ramp frame (n, 2) for body angles ``theta``."""
    phi = np.asarray(theta) + beta
    return r_m * np.column_stack([np.sin(phi), np.cos(phi)])


def theta_from_marker(offset: NDArray[np.float64], beta: float) -> NDArray[np.float64]:
    """The body angle from the ramp-frame marker offsets M - C (n, 2), unwrapped so that it
    is continuous (frames must be less than half a turn apart)."""
    return np.unwrap(np.arctan2(offset[:, 0], offset[:, 1])) - beta


def descent_side(c: NDArray[np.float64]) -> int:
    """+1 if the axle moves to the right over the track (the ramp descends to the right)."""
    return 1 if c[-1, 0] >= c[0, 0] else -1


@dataclass(frozen=True)
class ContactLine:
    """The line C follows in contact: the ramp frame, the ramp angle's standard error
    (0 when α was given), the per-coordinate noise ``sigma`` [m] of the tracked points
    (from the residuals about the line), and the frames used (in contact)."""

    frame: RampFrame
    alpha_err: float
    sigma: float
    contact: NDArray[np.bool_]


def fit_contact_line(
    c: NDArray[np.float64], alpha: float | None, *, lead: int = 8, rounds: int = 6
) -> ContactLine:
    """The line of C in contact, from the track itself: C is at height R above the ramp in
    every contact frame (rolling or slipping) and higher in flight. Starts from the first
    ``lead`` frames (the track must start on the ramp), then takes every frame within 4
    noise levels below or above the line, refits, and repeats. With ``alpha`` None the slope
    is fitted too (α and its standard error from the regression)."""
    side = descent_side(c)
    n = c.shape[0]
    use = np.zeros(n, dtype=bool)
    use[: max(lead, n // 4)] = True
    est = alpha if alpha is not None else _slope_angle(c[use], side)
    sigma = math.inf
    origin = c[0]
    alpha_err = 0.0
    for _ in range(rounds):
        frame = RampFrame(est, side, (float(origin[0]), float(origin[1])))
        q = frame.to_ramp(c)
        if alpha is None:
            slope, offset, alpha_err = _line(q[use, 0], q[use, 1])
            est = est - math.atan(slope)  # a residual slope turns x_hat towards y_hat
            frame = RampFrame(est, side, (float(origin[0]), float(origin[1])))
            q = frame.to_ramp(c)
        offset = float(np.median(q[use, 1]))
        resid = q[:, 1] - offset
        sigma = _robust_sigma(resid[use])
        x_hat, y_hat = frame.axes
        origin = np.asarray(frame.origin) + offset * y_hat + q[0, 0] * x_hat
        new = np.abs(resid) <= 4.0 * max(sigma, 1e-12 * (1.0 + float(np.abs(c).max())))
        new[:lead] = True  # the start is on the ramp by assumption
        if (new == use).all():
            break
        use = new
    frame = RampFrame(est, side, (float(origin[0]), float(origin[1])))
    return ContactLine(frame, alpha_err, sigma, use)


def path_angle(c: NDArray[np.float64], alpha: float) -> tuple[float, float]:
    """The angle [rad] of the straight line through the lab points ``c`` (all in contact)
    and its standard error: a regression of their height on their distance in the ramp
    frame of ``alpha`` (a near guess), every point weighed alike. Unlike
    :func:`fit_contact_line`, no point is left out: a start from rest crowds the first
    frames within a millimetre, and a line from them alone turns by degrees."""
    frame = RampFrame(alpha, descent_side(c), (float(c[0, 0]), float(c[0, 1])))
    q = frame.to_ramp(c)
    slope, _, err = _line(q[:, 0], q[:, 1])
    return alpha - math.atan(slope), err


def _slope_angle(c: NDArray[np.float64], side: int) -> float:
    """The ramp angle of the straight-line fit of lab points."""
    x, y = c[:, 0], c[:, 1]
    if np.ptp(x) == 0:
        return math.pi / 2
    slope = np.polyfit(x, y, 1)[0]
    return float(min(max(-side * math.atan(slope), 0.0), math.pi / 2))


def _line(s: NDArray[np.float64], h: NDArray[np.float64]) -> tuple[float, float, float]:
    """Least squares h = a s + b: (a, b, standard error of atan a)."""
    A = np.column_stack([s, np.ones_like(s)])
    coef, *_ = np.linalg.lstsq(A, h, rcond=None)
    resid = h - A @ coef
    dof = max(s.size - 2, 1)
    var = float(resid @ resid) / dof
    spread = float(((s - s.mean()) ** 2).sum())
    err = math.sqrt(var / spread) if spread > 0 else math.inf
    return float(coef[0]), float(coef[1]), err


def _robust_sigma(x: NDArray[np.float64]) -> float:
    """The standard deviation of Gaussian noise from the median absolute deviation."""
    return float(1.4826 * np.median(np.abs(x - np.median(x))))
