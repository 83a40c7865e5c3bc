"""The model fitted to the track: ``eccjump.simulate`` from an unknown start, with unknown
friction and restitution, by least squares on the tracked points (scipy's
``least_squares``).

Parameters (:data:`NAMES`): the start θ₀ (``theta0``) [rad] and θ̇₀ (``omega0``) [rad/s] at
the first frame (and its slip velocity ``slip0`` [m/s] where a rolling start fails: see
:class:`Setup`), μ_k (``mu_k``), Δμ = μ_s − μ_k ≥ 0 (``dmu``, so μ_k ≤ μ_s always holds), the
restitution e, and two offsets of the ramp frame, l0 and n0 [m] (where the axle starts
along the ramp, and the contact line's height: nuisance parameters); ``alpha`` too when the
ramp angle was not given. Residuals: the model's C and M minus the tracked ones, both
coordinates, divided by the noise level σ, so the cost is half a χ² and the covariance of
the parameters is (JᵀJ)⁻¹ s² at the optimum (s² the reduced χ² where it exceeds 1: a misfit
widens every interval; 1 below). A direction the track does not constrain (μ_s above what
the observed rolling needed, e when nothing lands) has a vanishing singular value: its
interval is the parameter's whole range ("not identified").

``jarm_only=True`` fits under the constraint that the body does not slip before its first
lift-off: μ_s is raised to the largest friction ratio |F_x|/F_y the rolling from the fitted
start needs up to the lift-off (``eccjump.jarm``'s max_ratio), the bound on μ_s that an
observed rolling implies. Comparing the two fits tests a slip before the lift-off;
:func:`consistent_fits` makes the pair consistent (the free fit never worse than the
constrained one) and :func:`misfit_p` tests the goodness of fit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump.classification.classify import jarm
from eccjump.motion.simulation import MotionResult, simulate
from eccjump.studies.experiment.geometry import RampFrame, marker_offset
from eccjump.studies.experiment.reconstruction import Reconstruction, derivative_weights
from eccjump.studies.experiment.runs import event_times, rolling_needs, slip_intervals
from eccjump.studies.experiment.track import Track, first_frames

NAMES = ("theta0", "omega0", "slip0", "mu_k", "dmu", "e", "l0", "n0", "length_scale", "alpha")
#: The parameters of the start and of the frame (not the friction or e).
KINEMATIC = ("theta0", "omega0", "slip0", "l0", "n0", "length_scale", "alpha")
UNITS = {"theta0": "rad", "omega0": "rad/s", "slip0": "m/s", "l0": "m", "n0": "m", "alpha": "rad"}
#: How far the track's length scale may be from the stated one (a ratio): a scale from the
#: dots' distance or a ruler is good to a few parts in a thousand; a larger error (a
#: misstated radius, a ruler out of the face's plane) is for the goodness of fit to catch,
#: and a wider range lets a long slip trade its distance against the scale.
SCALE_RANGE = (0.97, 1.03)
#: The friction coefficients searched are below this.
MU_MAX = 3.0
#: Most transitions a fitted run may take (bounces after a landing).
MAX_TRANSITIONS = 60
#: The largest slip velocity at the first frame that a fit tries [√(gR)]: released from rest
#: and cut a few frames late, a body slips at most g Δt (0.1 m/s after 10 ms: 0.3 √(gR) at
#: R = 1 cm).
SLIP0_MAX = 2.0
#: Evaluations of one least-squares run, and of one point of a profile.
MAX_NFEV, PROFILE_NFEV = 250, 60
#: Iterations of a screening fit, and the screened starts fitted in full.
SCREEN_NFEV, KEEP = 20, 3


@dataclass(frozen=True)
class Setup:
    """What the fit knows: the body, the ramp (``alpha`` fixed unless ``fit_alpha``), the
    radius R [m], g [m/s²], the marker, the lift-off rule; and whether the free fit also
    fits the slip velocity at the first frame, slip0, and lets θ̇₀ be negative
    (``slip_at_start``): for a track whose fit from a rolling start fails the gate (the
    analysis' ``_consistent_fits``). A track cut after a wait before the release starts
    late (the cut errs late, ``release.release_frame``), and a body that slips from its
    release is slipping, turning backwards, at the first frame: rolling from there cannot
    describe it (χ²_red 160-250 at 240 and 1000 fps). Not for every track: on a rolling
    body's video the freedom fitted the codec's errors as a slip of a frame (Δχ² 12)."""

    body: Cylinder
    alpha: float
    radius: float
    g: float
    marker_radius: float
    marker_angle: float
    rule: str
    fit_alpha: bool
    slip_at_start: bool = False

    @property
    def time_unit(self) -> float:
        return math.sqrt(self.radius / self.g)


@dataclass(frozen=True, eq=False)
class Fit:
    """One least-squares fit: the parameters (SI, :data:`NAMES` order, those fitted), their
    covariance, the cost (half the sum of squared normalised residuals), the degrees of
    freedom, the fitted run (dimensionless, time 0 at the first frame) and its states at the
    frames, and whether it was constrained to roll up to the lift-off."""

    names: tuple[str, ...]
    x: NDArray[np.float64]
    cov: NDArray[np.float64]
    lower: NDArray[np.float64]
    upper: NDArray[np.float64]
    cost: float
    dof: int
    run: MotionResult
    states: NDArray[np.float64]
    jarm_only: bool
    mu_s_bound: float
    nfev: int
    #: The variance inflation of slow signals by the residuals' correlation from frame to
    #: frame (:func:`correlation_inflation`): 1 for independent errors.
    correlation: float = 1.0

    def value(self, name: str) -> float:
        return float(self.x[self.names.index(name)])

    def error(self, name: str) -> float:
        i = self.names.index(name)
        return float(math.sqrt(max(self.cov[i, i], 0.0)))

    def interval(self, name: str, z: float = 1.96) -> tuple[float, float]:
        """The ~95 % interval of a parameter, within its range (the whole range when the
        track does not constrain it)."""
        i = self.names.index(name)
        v, e = self.x[i], self.error(name)
        if not math.isfinite(e) or e > self.upper[i] - self.lower[i]:
            return float(self.lower[i]), float(self.upper[i])
        return float(max(v - z * e, self.lower[i])), float(min(v + z * e, self.upper[i]))

    @property
    def chi2_reduced(self) -> float:
        return 2.0 * self.cost / max(self.dof, 1)

    @property
    def variance_factor(self) -> float:
        """What the parameters' variances and a χ² difference are scaled by: the
        reduced χ² where above 1 (a misfit widens), times :attr:`correlation`'s."""
        return max(self.chi2_reduced, 1.0) * self.correlation


class Model:
    """The residuals of a parameter vector against one reconstructed track."""

    def __init__(
        self,
        setup: Setup,
        track: Track,
        rec: Reconstruction,
        *,
        jarm_only: bool,
        mu_s_range: tuple[float, float] = (0.0, math.inf),
    ):
        self.setup, self.track, self.rec = setup, track, rec
        self.jarm_only = jarm_only
        self.mu_s_range = mu_s_range  # the runs' mu_s kept within (mu_k at most mu_s)
        self.names = tuple(n for n in NAMES if n not in self._fixed())
        self.tau = (track.t - track.t[0]) / setup.time_unit
        self.sigma = max(rec.sigma, 1e-12 * setup.radius)
        frame = rec.line.frame
        self.side, self.origin = frame.side, frame.origin
        self.nfev = 0
        self._bounds: dict[tuple[float, float, float], float] = {}

    def _fixed(self) -> tuple[str, ...]:
        """The parameters held: α where given, slip0 (at 0) unless the setup frees it.
        Every model of one setup has the same parameters: a fit that rolls to its lift-off
        keeps slip0 but runs with 0 (a slip at the start is a slip before the lift-off)."""
        slip0 = () if self.setup.slip_at_start else ("slip0",)
        return slip0 + (() if self.setup.fit_alpha else ("alpha",))

    def _slips_at_start(self) -> bool:
        return self.setup.slip_at_start and not self.jarm_only

    def frame(self, alpha: float) -> RampFrame:
        return RampFrame(alpha, self.side, self.origin)

    def params(self, x: NDArray[np.float64]) -> dict[str, float]:
        p = dict(zip(self.names, (float(v) for v in x), strict=True))
        p.setdefault("alpha", self.setup.alpha)
        p.setdefault("slip0", 0.0)
        return p

    def simulate(self, p: dict[str, float], mu_s: float | None = None) -> MotionResult:
        """The run of ``p`` over the track (dimensionless, dense)."""
        s = self.setup
        mu_s = p["mu_k"] + p["dmu"] if mu_s is None else mu_s
        mu_s = min(max(mu_s, self.mu_s_range[0]), self.mu_s_range[1])
        mu_k = min(p["mu_k"], mu_s)
        if self.jarm_only:
            mu_s = max(mu_s, self.mu_bound(p) * (1 + 1e-9))
        self.nfev += 1
        return simulate(
            s.body,
            p["alpha"],
            mu_s=mu_s,
            mu_k=mu_k,
            restitution=p["e"],
            rule=s.rule,  # type: ignore[arg-type]
            theta0=p["theta0"],
            omega0=p["omega0"] * s.time_unit,
            slip0=0.0 if self.jarm_only else p["slip0"] * s.time_unit / s.radius,
            t_max=float(self.tau[-1]) + 1e-9,
            max_transitions=MAX_TRANSITIONS,
            dense_output=True,
        )

    def mu_bound(self, p: dict[str, float]) -> float:
        """The friction the rolling from the start needs up to its lift-off (0 if none).
        Remembered by the start and the ramp, all it depends on: the columns of a
        finite-difference Jacobian that vary the friction, e or the offsets reuse it."""
        key = (p["alpha"], p["theta0"], p["omega0"])
        if key not in self._bounds:
            if len(self._bounds) > 4096:
                self._bounds.clear()
            self._bounds[key] = self._rolling_bound(p)
        return self._bounds[key]

    def _rolling_bound(self, p: dict[str, float]) -> float:
        res = jarm(
            p["alpha"],
            self.setup.body.chi,
            self.setup.body.km,
            1e6,
            rule=self.setup.rule,  # type: ignore[arg-type]
            theta0=p["theta0"],
            omega0=max(p["omega0"] * self.setup.time_unit, 0.0),
            refine_extrema=True,
            max_turns=20,
            n_threads=1,
        )
        bound = float(np.asarray(res.max_ratio).reshape(-1)[0])
        return bound if math.isfinite(bound) and bound > 0 else 0.0

    def states(self, run: MotionResult) -> NDArray[np.float64]:
        """(6, n) states at the frames; frames past the run's end hold its last state."""
        assert run.sol is not None
        return run.sol(np.minimum(self.tau, run.sol.t_max))

    def residuals(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        p = self.params(x)
        try:
            y = self.states(self.simulate(p))
        except ValueError:  # a start the model refuses: far from the data
            return np.full(4 * self.tau.size, 1e6)
        return self.compare(p, y)

    def compare(self, p: dict[str, float], y: NDArray[np.float64]) -> NDArray[np.float64]:
        s = self.setup
        frame = self.frame(p["alpha"])
        qc_obs, qm_obs = frame.to_ramp(self.track.c), frame.to_ramp(self.track.m)
        k = p["length_scale"] * s.radius  # the model's lengths in the track's metres
        qc = np.column_stack([p["l0"] + k * y[2], p["n0"] + k * (y[4] - 1.0)])
        qm = qc + marker_offset(y[0], p["length_scale"] * s.marker_radius, s.marker_angle)
        return np.concatenate([(qc - qc_obs).ravel(), (qm - qm_obs).ravel()]) / self.sigma

    def bounds(
        self, guess: dict[str, float], *, roomy: bool = False
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The range of each parameter around the smoothed start ``guess``; ``roomy``: l0
        out to four noise levels where that is more than R (:func:`fit`)."""
        r, th, om, al = self.setup.radius, guess["theta0"], guess["omega0"], guess["alpha"]
        reach = theta0_reach(self.rec)
        # slip0 held near 0 where the run rolls from the start (its x then says what it ran)
        slip0 = SLIP0_MAX * r / self.setup.time_unit * (1.0 if self._slips_at_start() else 1e-12)
        l0 = max(r, 4.0 * self.rec.sigma) if roomy else r
        lo = {
            "theta0": th - reach,
            # a body that slips from its release may turn backwards as it slides
            "omega0": -SLIP0_MAX / self.setup.time_unit if self._slips_at_start() else 0.0,
            "slip0": -slip0,
            "mu_k": 0.0,
            "dmu": 0.0,
            "e": 0.0,
            "l0": -l0,
            "n0": -0.5 * r,
            "length_scale": SCALE_RANGE[0],
            "alpha": max(al - 0.2, 0.0),
        }
        hi = {
            "theta0": th + reach,
            "omega0": max(3 * om, 50.0 / self.setup.time_unit),
            "slip0": slip0,
            "mu_k": MU_MAX,
            "dmu": MU_MAX,
            "e": 1.0,
            "l0": l0,
            "n0": 0.5 * r,
            "length_scale": SCALE_RANGE[1],
            "alpha": min(al + 0.2, math.pi / 2),
        }
        return np.array([lo[n] for n in self.names]), np.array([hi[n] for n in self.names])


def start_guess(setup: Setup, rec: Reconstruction) -> dict[str, float]:
    """θ₀, θ̇₀ (≥ 0 unless the setup frees slip0), slip0 (l̇ - R θ̇,
    within its range) and l0 from the smoothed track at its first frame."""
    idx, w0 = derivative_weights(rec.t, rec.window, deriv=0)
    _, w1 = derivative_weights(rec.t, rec.window, deriv=1)
    omega = float(w1[0] @ rec.theta[idx[0]])
    slip = float(w1[0] @ rec.l[idx[0]]) - setup.radius * omega
    most = 0.5 * SLIP0_MAX * setup.radius / setup.time_unit
    return {
        "theta0": float(w0[0] @ rec.theta[idx[0]]),
        "omega0": omega if setup.slip_at_start else max(omega, 0.0),
        "slip0": min(max(slip, -most), most),
        "l0": float(w0[0] @ rec.l[idx[0]]),
        "n0": 0.0,
        "length_scale": 1.0,
        "alpha": setup.alpha,
    }


#: θ₀'s range around the smoothed start [rad], at least; the screen's step in θ₀ [rad].
THETA0_RANGE, THETA0_STEP = 1.5, 0.5


def theta0_error(rec: Reconstruction) -> float:
    """The standard error [rad] of the smoothed θ at the first frame, the start's θ₀."""
    first = rec.t[: rec.window]  # that frame's window alone: every frame's weights cost
    # 23 ms on a track of 1200 frames, and each fit's ranges ask for this
    _, w0 = derivative_weights(first, rec.window, deriv=0)
    return float(np.sqrt(w0[0] ** 2 @ rec.theta_err[: rec.window] ** 2))


def theta0_reach(rec: Reconstruction) -> float:
    """How far [rad] a fit's θ₀ may go from the smoothed start: :data:`THETA0_RANGE`, or
    three standard errors of the start, up to π (the cost has period 2π in θ₀)."""
    return min(max(THETA0_RANGE, 3.0 * theta0_error(rec)), math.pi)


def theta0_offsets(rec: Reconstruction) -> list[float]:
    """The offsets [rad] from the smoothed θ₀ that the screen tries: 0, and steps of
    :data:`THETA0_STEP` out to two standard errors of the start. Where the marker is a
    few pixels from the axle, a frame's θ is nearly noise (an error of 1.3 rad at 2 px
    with the marker 2.8 px out): the smoothed start is then a guess, and a fit from it
    stopped in a local minimum worse by Δχ² 166 than the truth."""
    k = int(min(2.0 * theta0_error(rec), math.pi) / THETA0_STEP)
    return [THETA0_STEP * i for i in range(-k, k + 1)]


def theta0_is_loose(rec: Reconstruction) -> bool:
    """Whether the smoothed θ₀ is only a guess: the screen then spreads its starts in θ₀
    (:func:`theta0_offsets` gives more than 0)."""
    return len(theta0_offsets(rec)) > 1


def mean_rate(rec: Reconstruction) -> float:
    """θ's mean rate [rad/s] over the first two smoothing windows (≥ 0): a start for
    θ̇₀ where the smoothed derivative at the track's edge is off (a slip, a kick)."""
    k = min(2 * rec.window, rec.t.size - 1)
    return float(max((rec.theta[k] - rec.theta[0]) / (rec.t[k] - rec.t[0]), 0.0))


def fit(
    setup: Setup,
    track: Track,
    rec: Reconstruction,
    *,
    jarm_only: bool = False,
    starts: list[dict[str, float]] | None = None,
    wide: bool = False,
    grow: bool = True,
) -> Fit:
    """The best of several least-squares fits. Without ``starts``: a screen of short fits
    (:data:`SCREEN_NFEV` iterations) from the smoothed start with the friction guesses of
    :func:`friction_guesses`, each with the smoothed θ̇₀, θ's mean rate
    (:func:`mean_rate`) and 0 (the edge of the smoothing window makes θ̇₀ noisy), and
    θ₀ at :func:`theta0_offsets` from the smoothed one, then full fits from the
    :data:`KEEP` best (the cost has many local minima: a slip, a bounce and a shifted start
    trade off), and with ``grow`` one more from :func:`grown_start`. ``wide`` screens
    more: μ_k / μ_s of 0.5, 0.75 and 0.95 and e of 0.05 and 0.5, and keeps twice as many
    (for a fit that failed its goodness-of-fit test). With ``starts`` (each a dict of some
    of :data:`NAMES`, on top of that guess): a full fit from each. The best is fitted
    again with room where it is held at l0's bound (:func:`with_room`)."""
    model = Model(setup, track, rec, jarm_only=jarm_only)
    guess = start_guess(setup, rec)
    lo, hi = model.bounds(guess)
    if starts is None:
        omegas = sorted({guess["omega0"], 0.0, mean_rate(rec)})
        ratios, bounces = ((0.5, 0.75, 0.95), (0.05, 0.5)) if wide else ((0.75,), (0.05,))
        offsets = theta0_offsets(rec)
        screen = [
            {"mu_k": q * m, "dmu": (1 - q) * m, "e": e, "omega0": w, "theta0": guess["theta0"] + d}
            for m in friction_guesses(model.mu_bound(guess))
            for w in omegas
            for q in ratios
            for e in bounces
            for d in offsets
        ]
        tried = sorted((solve(model, guess | s, lo, hi, SCREEN_NFEV) for s in screen), key=_cost)
        x0s = [r.x for r in tried[: KEEP * (2 if wide else 1)]]
        if grow and track.n >= 2 * GROW_SHORT:
            start = grown_start(setup, track, rec, jarm_only=jarm_only, wide=wide)
            x0s.append(np.array([(guess | start)[n] for n in model.names], dtype=float))
    else:
        x0s = [np.array([(guess | s)[n] for n in model.names], dtype=float) for s in starts]
    res = min((solve(model, x0, lo, hi, MAX_NFEV) for x0 in x0s), key=_cost)
    return fitted(model, *with_room(model, guess, res, lo, hi))


def with_room(
    model: Model,
    guess: dict[str, float],
    res: Any,
    lo: NDArray[np.float64],
    hi: NDArray[np.float64],
) -> tuple[Any, NDArray[np.float64], NDArray[np.float64]]:
    """``res`` and its ranges, or, where it is held at l0's bound and four noise levels
    are more than R, the better of it and a fit from it with l0 that far (and those
    ranges). l is counted from the first frame's axle, off by that frame's noise: beyond R
    on a track of a few pixels per radius (σ 53 mm at R = 50 mm held l0 at -R and μ_k's
    interval off the truth). Only a fit held there gets the room: given from the start,
    it led another long slip's fit to a minimum worse by Δχ² 220."""
    j = model.names.index("l0")
    if min(res.x[j] - lo[j], hi[j] - res.x[j]) > 1e-9 * (hi[j] - lo[j]):
        return res, lo, hi
    roomy_lo, roomy_hi = model.bounds(guess, roomy=True)
    if not roomy_hi[j] > hi[j]:
        return res, lo, hi
    roomy = solve(model, res.x, roomy_lo, roomy_hi, MAX_NFEV)
    return min((res, roomy), key=_cost), roomy_lo, roomy_hi


#: The frames of the first window of :func:`grown_start` (at least; an eighth of the track).
GROW_FIRST = 16
#: The first window of a track shorter than twice :data:`GROW_FIRST` (one shorter than twice
#: this is not grown).
GROW_SHORT = 8


def grown_start(
    setup: Setup, track: Track, rec: Reconstruction, *, jarm_only: bool, wide: bool
) -> dict[str, float]:
    """A start for the whole track from fits of its first frames, the window doubled from
    an eighth of it (at least :data:`GROW_FIRST` frames; :data:`GROW_SHORT` on a short
    track), each window's fit started from the last one's. Over a long track the cost has
    a local minimum for every turn the marker's phase can slip by (a start that is a
    little off in θ₀ or θ̇₀ ends turns away after a slip of a hundred frames, in a
    basin of its own); a short window has few turns, and each doubling moves the phase by
    less than one. A short track gains too: at 60 fps a slip, the flight and the landing
    come within 30 frames, and a screen of the whole track went from a start 10 % off in
    θ̇₀ to a body that barely turns and bounces (chi2_red 163); grown from its first 8
    frames it fits (chi2_red 0.75; from 15, it did not)."""
    k = max(GROW_FIRST, track.n // 8) if track.n >= 2 * GROW_FIRST else GROW_SHORT
    f = fit(setup, first_frames(track, k), rec, jarm_only=jarm_only, wide=wide, grow=False)
    while 2 * k < track.n:
        k *= 2
        f = fit(setup, first_frames(track, k), rec, jarm_only=jarm_only, starts=[as_start(f)])
    return as_start(f)


#: Rounds of refitting the free and the slip-forbidden fit from the better of the two.
ROUNDS = 3


def consistent_fits(
    setup: Setup,
    track: Track,
    rec: Reconstruction,
    *,
    wide: bool = False,
    start: dict[str, float] | None = None,
) -> tuple[Fit, Fit | None]:
    """The free fit (screened, or from ``start`` alone) and, when it slips before its
    lift-off, the fit that forbids that slip (else None: the free fit is slip-free
    itself). The free fit can never be worse than the constrained one; if it is, the
    optimiser stopped in a local minimum: the free fit is redone from the better solution
    (and its own), up to :data:`ROUNDS` times; if the pair is still inconsistent, the
    better one is returned as the free fit."""
    free = fit(setup, track, rec, wide=wide, starts=None if start is None else [start])
    constrained: Fit | None = None
    for _ in range(ROUNDS):
        if not slips_before_liftoff(free):
            return free, None
        starts = [as_start(free)] + ([as_start(constrained)] if constrained else [])
        constrained = fit(setup, track, rec, jarm_only=True, starts=starts)
        if free.cost <= constrained.cost * (1 + 1e-9):
            return free, constrained
        free = fit(setup, track, rec, starts=[as_start(constrained), as_start(free)])
    assert constrained is not None
    if constrained.cost < free.cost:
        return constrained, None
    return free, constrained


def slips_before_liftoff(f: Fit) -> bool:
    """Whether the fitted run slips before its first lift-off (or its end)."""
    horizon = float(f.run.t[-1])
    lift = event_times(f.run, horizon)["liftoff"]
    return bool(slip_intervals(f.run, lift if math.isfinite(lift) else horizon))


def as_start(f: Fit) -> dict[str, float]:
    """A start for another fit from ``f``'s parameters (μ_s raised to what ``f``'s run
    used when it was constrained to roll)."""
    start = {n: f.value(n) for n in f.names}  # (clipped to the next fit's bounds there)
    if f.jarm_only:
        mu_s = max(start["mu_k"] + start["dmu"], f.mu_s_bound * (1 + 1e-6))
        start["dmu"] = min(mu_s - start["mu_k"], MU_MAX)
    return start


def misfit_p(f: Fit, noise_frames: int) -> float:
    """The probability of a reduced χ² at least ``f``'s if the model held: the F
    distribution with (the fit's degrees of freedom, those of the noise level), since
    σ is itself estimated from the spread of ``noise_frames`` contact frames (a robust
    spread: about 0.37 degrees of freedom per frame)."""
    from scipy.stats import f as f_dist

    nu = max(0.37 * noise_frames, 2.0)
    return float(f_dist.sf(f.chi2_reduced, f.dof, nu))


def friction_guesses(bound: float) -> list[float]:
    """The μ_s of the starts: 1.1 and 0.6 times the friction the rolling from the smoothed
    start needs up to its lift-off (no slip, a slip), and a fixed spread."""
    return sorted({round(m, 3) for m in (1.1 * bound, 0.6 * bound, 0.3, 0.5, 0.8, 1.2)
                   if 0.02 < m < MU_MAX})  # fmt: skip


def _cost(res: Any) -> float:
    return float(res.cost)


def solve(
    model: Model,
    x0: dict[str, float] | NDArray[np.float64],
    lo: NDArray[np.float64],
    hi: NDArray[np.float64],
    nfev: int,
) -> Any:
    """scipy's least squares of ``model`` from ``x0`` (clipped into [``lo``, ``hi``]) with at
    most ``nfev`` evaluations: its result object."""
    from scipy.optimize import least_squares  # the optional extra 'analysis'

    if isinstance(x0, dict):
        x0 = np.array([x0[n] for n in model.names], dtype=float)
    return least_squares(
        model.residuals,
        np.clip(x0, lo, hi),
        bounds=(lo, hi),
        x_scale="jac",
        diff_step=1e-6,
        max_nfev=nfev,
        method="trf",
    )


#: The largest variance inflation :func:`correlation_inflation` gives (rho = 0.82).
MAX_INFLATION = 10.0


def correlation_inflation(residuals: NDArray[np.float64], frames: int) -> float:
    """(1 + ρ) / (1 - ρ) for the residuals' lag-1 autocorrelation ρ over the frames,
    pooled over the four coordinate series (C and M, along and across the ramp); 1 for
    ρ ≤ 0. Errors correlated from frame to frame (a video codec's, a tracker's smoothing,
    a slow misfit) carry less information on slow signals -- a slip, a start -- than
    independent ones: for AR(1) errors the variance of a mean over many frames grows by
    this factor, and so must the parameters' covariance and a χ² difference."""
    r = residuals.reshape(2, frames, 2).transpose(0, 2, 1).reshape(4, frames)
    den = float(np.sum(r * r))
    if frames < 3 or not den > 0:
        return 1.0
    rho = float(np.sum(r[:, 1:] * r[:, :-1])) / den
    return float(min(max((1 + rho) / (1 - rho), 1.0), MAX_INFLATION)) if rho < 1 else MAX_INFLATION


def covariance(jac: NDArray[np.float64], scale: float) -> NDArray[np.float64]:
    """The parameters' covariance ``scale`` (J^T J)^+ from the Jacobian ``jac`` (its
    singular values above 1e-8 of the largest). A parameter with weight in the directions
    no singular value is left for (its projection on them longer than 0.1) has an infinite
    variance: the track does not fix it. The projection, not its parts: a weight spread
    over several such directions is lost as much as one in one."""
    _, sv, vt = np.linalg.svd(jac, full_matrices=False)
    keep = sv > sv[0] * 1e-8 if sv.size and sv[0] > 0 else np.zeros_like(sv, dtype=bool)
    inv = np.where(keep, 1.0 / np.where(keep, sv, 1.0) ** 2, 0.0)
    cov = (vt.T * inv) @ vt * scale
    lost = (vt[~keep] ** 2).sum(axis=0) > 0.01
    cov[lost, lost] = np.inf
    return cov


#: The step of :func:`coarse_jacobian`, a fraction of each parameter's range.
COARSE_STEP = 1e-3
#: How much longer than at the coarse step a column may be at least squares' own step
#: before the cost counts as rough (:func:`rough`).
ROUGH = 10.0


def coarse_jacobian(
    model: Model, x: NDArray[np.float64], lo: NDArray[np.float64], hi: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The residuals' Jacobian at ``x`` by central differences over :data:`COARSE_STEP` of
    each parameter's range (one-sided at a bound)."""
    cols = []
    for i in range(x.size):
        h = COARSE_STEP * (hi[i] - lo[i])
        up, dn = x.copy(), x.copy()
        up[i], dn[i] = min(x[i] + h, hi[i]), max(x[i] - h, lo[i])
        cols.append((model.residuals(up) - model.residuals(dn)) / (up[i] - dn[i]))
    return np.column_stack(cols)


def rough(fine: NDArray[np.float64], coarse: NDArray[np.float64]) -> bool:
    """Whether the cost is rough where it was fitted: a column of least squares' Jacobian
    (a step of 1e-6) :data:`ROUGH` times longer than the coarse one. A run that chatters
    through bounces inside the track moves its residuals by sigmas for the smallest step,
    so that Jacobian grows like 1/step and its covariance shrinks to nothing (a lift-off
    timed to 4 us, seconds from the truth). The coarse one measures the cost's curvature
    on the scale a parameter can move, but across a kink (a slip that starts or ends within
    its step) it can be the longer one: a rough fit's covariance is the sum of both."""
    f, c = np.linalg.norm(fine, axis=0), np.linalg.norm(coarse, axis=0)
    return bool(np.any((f > ROUGH * c) & (f > 1e-6 * f.max(initial=0.0))))


def fitted(model: Model, res: Any, lo: NDArray[np.float64], hi: NDArray[np.float64]) -> Fit:
    """The :class:`Fit` of ``model`` from least squares' result ``res`` within [``lo``,
    ``hi``]: its covariance, goodness of fit and run."""
    m = res.fun.size
    dof = max(m - res.x.size, 1)
    inflation = correlation_inflation(res.fun, model.tau.size)
    # widened by a misfit, never narrowed below the noise; and by correlated errors
    s2 = max(2.0 * res.cost / dof, 1.0) * inflation
    cov = covariance(res.jac, s2)
    coarse = coarse_jacobian(model, res.x, lo, hi)
    if rough(res.jac, coarse):  # neither Jacobian alone: the sum is wider than both
        cov = cov + covariance(coarse, s2)
    p = model.params(res.x)
    run = model.simulate(p)
    bound = model.mu_bound(p)
    return Fit(
        names=model.names,
        x=res.x,
        cov=cov,
        lower=lo,
        upper=hi,
        cost=float(res.cost),
        dof=dof,
        run=run,
        states=model.states(run),
        jarm_only=model.jarm_only,
        mu_s_bound=bound,
        nfev=model.nfev,
        correlation=inflation,
    )


def horizon(setup: Setup, track: Track) -> float:
    """The track's length in the model's time (dimensionless)."""
    return float(track.t[-1] - track.t[0]) / setup.time_unit


def until_liftoff(f: Fit, setup: Setup, track: Track) -> float:
    """The fitted run's first lift-off within the track, or the track's end (dimensionless)."""
    end = horizon(setup, track)
    lift = event_times(f.run, end)["liftoff"]
    return lift if math.isfinite(lift) else end


def fitted_needs(f: Fit, setup: Setup, track: Track) -> float:
    """The largest friction ratio |F_x|/F_y of the fitted run's rolling before its first
    lift-off (or the track's end): what μ_s must be for that rolling."""
    return rolling_needs(f.run, until_liftoff(f, setup, track))


def slip_frames(f: Fit, setup: Setup, track: Track) -> float:
    """The frames the fitted run slips for in all before its first lift-off (or the end)."""
    slips = slip_intervals(f.run, until_liftoff(f, setup, track))
    return sum(b - a for a, b in slips) * setup.time_unit / track.dt


def flight_signal(f: Fit, setup: Setup, rec: Reconstruction) -> tuple[float, float]:
    """How clearly the track shows the fitted model's flights, in standard errors: the
    matched filter of the model's heights above the ramp h_m on the track's heights h,
    sum(h h_m) / (σ |h_m|), widened by the errors' correlation; and what the filter
    gives on the model's own heights, |h_m| / σ (its expected value where the model is
    right). Frame by frame a flight of a few σ is lost in the noise (``events.observe``
    asks for 3 σ in 3 frames in a row); summed along the model's parabola it is not.
    (0, 0) when the model never flies."""
    h_model = f.value("length_scale") * setup.radius * (f.states[4] - 1.0)
    up = h_model > 1e-9 * setup.radius
    norm = float(np.sqrt(h_model[up] @ h_model[up]))
    if not norm > 0:
        return 0.0, 0.0
    scale = rec.sigma * math.sqrt(f.correlation)
    return float(rec.height[up] @ h_model[up]) / (scale * norm), norm / scale
