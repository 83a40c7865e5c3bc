"""A wait before the release: where a body held still on the ramp is let go.

The model starts at the track's first frame with θ̇₀ ≥ 0 and cannot hold still: a track that
waits before the release fails the fit (χ²_red 34 after a 0.57 s wait). The frames before
the release are left out, and the cut errs late, never early: a start a few frames into the
motion costs the fit nothing (θ₀ and θ̇₀ are fitted), a still frame left in costs it the
whole wait.

Released from rest, the axle's displacement along its path grows from the release t_r as
s(t) = v τ + a τ²/2 + j τ³/6 with τ = max(t − t_r, 0) (a push, the acceleration, its slow
change; v and a ≥ 0), and stays at its place before it. :func:`release_frame` fits that to
the frames up to where the axle has moved a fifth of the radius, with t_r on a grid, and
cuts at the first frame after the latest t_r the frames allow (Δχ² = 9, 3 standard errors,
in the fit's own noise and widened by the residuals' correlation).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

#: The fewest still frames before the release taken as a wait (a body released at its first
#: frames loses nothing).
MIN_REST_FRAMES = 8
#: How far from its place (a fraction of the radius) the fit of the release follows the
#: axle: a cubic in time holds there.
REACH = 0.2
#: The χ² (in units of the residuals' own variance, widened by their correlation) by which
#: a release time may worsen the fit and still be allowed (3 standard errors): the cut
#: comes after the latest such time.
RELEASE_CHI2 = 9.0
#: The most frames before the axle has moved ``reach`` that the fit of the release looks at,
#: and the steps per frame interval where the release time is refined.
_WINDOW, _PER_FRAME = 1000, 10


def release_frame(t: NDArray[np.float64], c: NDArray[np.float64], reach: float) -> int:
    """The first frame to keep: the first one after the release (the module docstring), if
    the frames show a wait (a release at the first frame is excluded, Δχ² > 9) of
    :data:`MIN_REST_FRAMES` frames or more before it; else 0. The
    fit looks at the frames up to where the axle ``c`` has moved ``reach`` from its first
    place (a fifth of the radius: the cubic holds there), or 10 times its noise if that is
    farther (three frames in a row: not a spike); the χ² is in the fit's own noise.
    Frames where ``c`` is NaN (a dot lost) are skipped."""
    found = np.flatnonzero(np.isfinite(c[:, 0]))
    if found.size < 2 * MIN_REST_FRAMES:
        return 0
    tt, cc = t[found], c[found]
    place = np.median(cc[:MIN_REST_FRAMES], axis=0)
    reach = max(reach, 10.0 * still_noise(cc[: 2 * MIN_REST_FRAMES]))
    beyond = np.hypot(*(cc - place).T) > reach
    far = np.flatnonzero(beyond[:-2] & beyond[1:-1] & beyond[2:])  # not a noise spike
    if far.size == 0 or far[0] < MIN_REST_FRAMES + 4:
        return 0
    lo, end = max(int(far[0]) + 1 - _WINDOW, 0), int(far[0]) + 1
    way = cc[end - 1] - place
    ts, s = tt[lo:end], (cc[lo:end] - place) @ (way / np.hypot(*way))
    rss = np.array([_rss(ts, s, t_r) for t_r in ts])
    i = int(np.argmin(rss))
    fine = _steps(ts, max(i - 1, 0), min(i + 1, ts.size - 1))
    best = min(fine, key=lambda t_r: _rss(ts, s, t_r))
    r = _residuals(ts, s, best)
    least = float(r @ r)
    rho = min(float(r[1:] @ r[:-1]) / least, 0.9) if least > 0 else 0.0
    unit = least / max(ts.size - 5, 1) * max((1 + rho) / (1 - rho), 1.0)
    if not unit > 0:
        return 0
    chi2 = (rss - least) / unit
    if chi2[0] <= RELEASE_CHI2 or np.count_nonzero(tt < best) < MIN_REST_FRAMES:
        return 0  # no wait shown: the motion may start at the first frame
    allowed = np.flatnonzero(chi2 <= RELEASE_CHI2)
    k = max(allowed[-1] if allowed.size else 0, np.searchsorted(ts, best, side="right") - 1)
    edge = _steps(ts, int(k), min(int(k) + 1, ts.size - 1))
    latest = max(best, *(t_r for t_r in edge if (_rss(ts, s, t_r) - least) / unit <= RELEASE_CHI2))
    return int(found[np.searchsorted(tt, latest, side="right")])


def _residuals(t: NDArray[np.float64], s: NDArray[np.float64], t_r: float) -> NDArray[np.float64]:
    """The residuals of s = b + v τ + a τ²/2 + j τ³/6, τ = max(t - t_r, 0), fitted by least
    squares in (b, v, a, j) for the release ``t_r``, with v ≥ 0 and a ≥ 0: the body leaves
    its place along its path (unbounded, a polynomial bent back before a late release fits
    the still frames' noise and excludes the true release). The bounded least squares is
    the best of the fits with v, a or both held at 0 that keep the bounds."""
    tau = np.maximum(t - t_r, 0.0)
    basis = np.column_stack([np.ones_like(tau), tau, tau**2, tau**3])
    best: NDArray[np.float64] | None = None
    for cols in ([0, 1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 3]):
        coef, *_ = np.linalg.lstsq(basis[:, cols], s, rcond=None)
        if all(c >= 0 for k, c in zip(cols, coef, strict=True) if k in (1, 2)):
            r = s - basis[:, cols] @ coef
            if best is None or r @ r < best @ best:
                best = r
    assert best is not None  # v = a = 0 keeps the bounds
    return best


def _rss(t: NDArray[np.float64], s: NDArray[np.float64], t_r: float) -> float:
    r = _residuals(t, s, t_r)
    return float(r @ r)


def _steps(t: NDArray[np.float64], i: int, j: int) -> NDArray[np.float64]:
    """Release times from frame ``i`` to frame ``j``, :data:`_PER_FRAME` per interval."""
    return np.linspace(t[i], t[j], (j - i) * _PER_FRAME + 1)


def still_noise(c: NDArray[np.float64]) -> float:
    """The per-coordinate noise of the points ``c`` (their unit), from the spread of each
    coordinate's second differences about their median (a steady acceleration's second
    differences are a constant the median takes out): 1.4826 MAD / √6."""
    d2 = np.diff(c[np.isfinite(c[:, 0])], n=2, axis=0)
    if d2.shape[0] == 0:
        return 0.0
    mad = np.median(np.abs(d2 - np.median(d2, axis=0)), axis=0)  # each coordinate's own
    return float(1.4826 * math.sqrt(float(np.mean(mad**2))) / math.sqrt(6.0))
