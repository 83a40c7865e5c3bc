"""Hypothesis strategies of valid eccjump inputs, for property-based tests of code built on it.

Each strategy draws only values that eccjump accepts (no ``ValueError``) and reaches the
edges of the valid ranges, where bugs live: χ = 0 and 1, k_m = 0 and 1 − χ, α = 0 and π/2,
μ_k = 0 and μ_k = μ_s, e = 0 and 1, the start from rest. Keyword arguments narrow a
strategy to the part of the space a test is about; they are checked when the strategy is
made (``ValueError`` naming the keyword). Units: g = R = M = 1, angles in radians.

========================  ====================================================================
:func:`bodies`            :class:`~eccjump.Cylinder` (χ ∈ [0, 1], k_m ∈ [0, 1 − χ])
:func:`ramps`             α ∈ [0, π/2] (rad)
:func:`frictions`         :class:`Friction` (μ_s ≥ 0, 0 ≤ μ_k ≤ μ_s)
:func:`starts`            :class:`Start` (θ0, θ̇0, and a slip velocity for ``simulate``)
:func:`motion_inputs`     :class:`MotionInput`, everything :func:`eccjump.simulate` takes
:func:`tracks`            :class:`TrackInput`, a filmed run and what :func:`eccjump.analyze` needs
========================  ====================================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, NamedTuple

from hypothesis import assume
from hypothesis import strategies as st

from eccjump import Cylinder
from eccjump._base.checks import short
from eccjump.studies.experiment import SyntheticTrack, Track, synthetic_track
from eccjump.studies.experiment.track import MIN_FRAMES

#: The smallest k_m that :func:`eccjump.simulate`, :func:`eccjump.motion_points`,
#: :func:`eccjump.motion_map` and :func:`eccjump.analyze` take with every χ. They need
#: Ĩ_CM = k_m (1 − k_m + χ²)/(1 − k_m) ≥ 1e-10 (the impact law divides by Ĩ_CM), and
#: Ĩ_CM ≥ k_m, also as rounded. The default of :func:`motion_inputs` and :func:`tracks`.
MOTION_MIN_KM = 1e-10

HALF_PI = math.pi / 2


def _range(name_lo: str, lo: float, name_hi: str, hi: float, bounds: tuple[float, float]) -> None:
    """lo ≤ hi, both finite and within ``bounds``; else ValueError naming the keywords."""
    a, b = bounds
    for name, v in ((name_lo, lo), (name_hi, hi)):
        if not (isinstance(v, int | float) and a <= v <= b):
            raise ValueError(f"{name} = {short(v)} is outside the allowed range [{a:g}, {b:g}]")
    if lo > hi:
        raise ValueError(f"{name_lo} = {short(lo)} is above {name_hi} = {short(hi)}")


def _floats(lo: float, hi: float) -> st.SearchStrategy[float]:
    """Floats in [lo, hi]: the bounds themselves are drawn often."""
    return st.floats(lo, max(lo, hi), allow_nan=False, allow_infinity=False)


def bodies(
    *,
    chi: float | None = None,
    km: float | None = None,
    min_chi: float = 0.0,
    max_chi: float = 1.0,
    min_km: float = 0.0,
    max_km: float = 1.0,
) -> st.SearchStrategy[Cylinder]:
    """Valid bodies: χ ∈ [min_chi, max_chi], then k_m ∈ [min_km, min(max_km, 1 − χ)].

    Parameters
    ----------
    chi, km : float, optional
        Fix χ or k_m (the other is drawn within its range for that value).
    min_chi, max_chi : float
        The range of χ = d/R, within [0, 1] (dimensionless).
    min_km, max_km : float
        The range of the shell mass fraction k_m, within [0, 1] (dimensionless); k_m never
        passes 1 − χ. ``min_km=MOTION_MIN_KM`` (or more) for :func:`eccjump.simulate`,
        which refuses Ĩ_CM < 1e-10 (k_m = 0 is a point mass).

    Returns
    -------
    hypothesis.strategies.SearchStrategy of eccjump.Cylinder
        Reaches χ = 0 and χ = max(χ), k_m = min_km and k_m = 1 − χ (the rod at the rim).

    Raises
    ------
    ValueError
        If a range is empty or outside [0, 1], or no body has it (min_chi + min_km > 1).

    Examples
    --------
    >>> from hypothesis import given
    >>> from eccjump.testing import strategies
    >>> @given(strategies.bodies(max_chi=0.5))
    ... def test_the_inertia_about_the_cm_is_at_most_the_one_about_the_axis(body):
    ...     assert 0.0 <= body.Icm <= body.Ic <= 1.0
    >>> test_the_inertia_about_the_cm_is_at_most_the_one_about_the_axis()
    """
    if chi is not None:
        min_chi = max_chi = chi
    if km is not None:
        min_km = max_km = km
    _range("min_chi", min_chi, "max_chi", max_chi, (0.0, 1.0))
    _range("min_km", min_km, "max_km", max_km, (0.0, 1.0))
    if min_chi + min_km > 1.0:
        raise ValueError(
            f"min_km = {short(min_km)} is above 1 - min_chi = {short(1.0 - min_chi)}: "
            "no body has km > 1 - chi"
        )
    return _bodies(min_chi, min(max_chi, 1.0 - min_km), min_km, max_km)


@st.composite
def _bodies(draw: st.DrawFn, chi_lo: float, chi_hi: float, km_lo: float, km_hi: float) -> Cylinder:
    chi = draw(_floats(chi_lo, chi_hi))
    # 1 - chi may round an ulp below km_lo: the core allows 4 ulps above 1 - chi
    return Cylinder(chi, draw(_floats(km_lo, min(km_hi, 1.0 - chi))))


def ramps(*, min_alpha: float = 0.0, max_alpha: float = HALF_PI) -> st.SearchStrategy[float]:
    """Ramp angles α [rad] in [min_alpha, max_alpha] ⊂ [0, π/2] (0: flat ground, π/2: a wall).

    Parameters
    ----------
    min_alpha, max_alpha : float
        The range [rad], within [0, π/2] (``math.radians`` for degrees).

    Returns
    -------
    hypothesis.strategies.SearchStrategy of float
        Reaches both ends.

    Raises
    ------
    ValueError
        If the range is empty or outside [0, π/2].

    Examples
    --------
    >>> import math
    >>> from hypothesis import given
    >>> from eccjump.testing import strategies
    >>> @given(strategies.ramps(min_alpha=math.radians(10)))
    ... def test_in_range(alpha):
    ...     assert math.radians(10) <= alpha <= math.pi / 2
    >>> test_in_range()
    """
    _range("min_alpha", min_alpha, "max_alpha", max_alpha, (0.0, HALF_PI))
    return _floats(min_alpha, max_alpha)


class Friction(NamedTuple):
    """Coulomb friction: static ``mu_s`` and kinetic ``mu_k`` ≤ μ_s (dimensionless)."""

    mu_s: float
    mu_k: float


def frictions(
    *, min_mu_s: float = 0.0, max_mu_s: float = 2.0, min_ratio: float = 0.0
) -> st.SearchStrategy[Friction]:
    """Friction coefficients: μ_s ∈ [min_mu_s, max_mu_s], μ_k = r μ_s with r ∈ [min_ratio, 1].

    Parameters
    ----------
    min_mu_s, max_mu_s : float
        The range of μ_s (dimensionless), finite and ≥ 0 (the core takes any).
    min_ratio : float
        The smallest μ_k/μ_s, in [0, 1]; 1 draws μ_k = μ_s only.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Friction
        ``(mu_s, mu_k)``; reaches μ_s = min_mu_s and max_mu_s, μ_k = μ_s and μ_k = min_ratio μ_s.

    Raises
    ------
    ValueError
        If a range is empty, negative or not finite.

    Examples
    --------
    >>> from hypothesis import given
    >>> from eccjump.testing import strategies
    >>> @given(strategies.frictions(min_mu_s=0.5))
    ... def test_kinetic_at_most_static(f):
    ...     assert 0.0 <= f.mu_k <= f.mu_s and f.mu_s >= 0.5
    >>> test_kinetic_at_most_static()
    """
    _range("min_mu_s", min_mu_s, "max_mu_s", max_mu_s, (0.0, 1e300))
    _range("min_ratio", min_ratio, "1", 1.0, (0.0, 1.0))
    pairs = st.tuples(_floats(min_mu_s, max_mu_s), _floats(min_ratio, 1.0))
    return pairs.map(lambda p: Friction(p[0], p[0] * p[1]))  # r <= 1: mu_k <= mu_s, rounded too


class Start(NamedTuple):
    """A start: angle ``theta0`` [rad], angular velocity ``omega0`` [√(g/R)] and the slip
    velocity ``slip0`` = l̇0 − θ̇0 [√(g R)] (``simulate`` only; 0 is rolling)."""

    theta0: float
    omega0: float
    slip0: float


def starts(
    *,
    min_theta0: float = 0.0,
    max_theta0: float = 2 * math.pi,
    min_omega0: float = 0.0,
    max_omega0: float = 2.0,
    max_slip0: float = 0.0,
) -> st.SearchStrategy[Start]:
    """Starts: θ0 ∈ [min_theta0, max_theta0], θ̇0 ∈ [min_omega0, max_omega0], |slip0| ≤ max_slip0.

    :func:`eccjump.jarm`, :func:`eccjump.region` and the maps take θ̇0 ≥ 0 only, and no slip;
    :func:`eccjump.roll` and :func:`eccjump.simulate` take θ̇0 < 0 too (``min_omega0 < 0``),
    ``simulate`` a slip (``max_slip0 > 0``).

    Parameters
    ----------
    min_theta0, max_theta0 : float
        The range of θ0 [rad], within ±2π·10⁶.
    min_omega0, max_omega0 : float
        The range of θ̇0 [√(g/R)], within ±10⁶.
    max_slip0 : float
        The largest |slip0| [√(g R)], in [0, 10⁶]; 0 (default): every start rolls.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Start
        Reaches the ends of each range, and the paper's start from rest (θ0 = θ̇0 = 0) with
        the default ranges.

    Raises
    ------
    ValueError
        If a range is empty or outside its bounds.

    Examples
    --------
    >>> from hypothesis import given
    >>> from eccjump.testing import strategies
    >>> @given(strategies.starts(max_omega0=1.0))
    ... def test_a_rolling_start(start):
    ...     assert start.slip0 == 0.0 and 0.0 <= start.omega0 <= 1.0
    >>> test_a_rolling_start()
    """
    turns = 2 * math.pi * 1e6
    _range("min_theta0", min_theta0, "max_theta0", max_theta0, (-turns, turns))
    _range("min_omega0", min_omega0, "max_omega0", max_omega0, (-1e6, 1e6))
    _range("0", 0.0, "max_slip0", max_slip0, (0.0, 1e6))
    slip = _floats(-max_slip0, max_slip0) if max_slip0 > 0 else st.just(0.0)
    return st.builds(Start, _floats(min_theta0, max_theta0), _floats(min_omega0, max_omega0), slip)


@dataclass(frozen=True)
class MotionInput:
    """Everything :func:`eccjump.simulate` takes about the physics: the body, the ramp angle
    ``alpha`` [rad], friction, restitution and start.
    ``simulate(m.body, m.alpha, **m.keywords())`` runs it (add the options: ``t_max``,
    ``rule``, ...)."""

    body: Cylinder
    alpha: float
    mu_s: float
    mu_k: float
    restitution: float
    theta0: float
    omega0: float
    slip0: float

    def keywords(self) -> dict[str, float]:
        """The keyword arguments of :func:`eccjump.simulate` after the body and ``alpha``."""
        return {
            "mu_s": self.mu_s,
            "mu_k": self.mu_k,
            "restitution": self.restitution,
            "theta0": self.theta0,
            "omega0": self.omega0,
            "slip0": self.slip0,
        }


def motion_inputs(
    *,
    body: st.SearchStrategy[Cylinder] | None = None,
    alpha: st.SearchStrategy[float] | None = None,
    friction: st.SearchStrategy[Friction] | None = None,
    start: st.SearchStrategy[Start] | None = None,
    min_restitution: float = 0.0,
    max_restitution: float = 1.0,
) -> st.SearchStrategy[MotionInput]:
    """Inputs of a full motion (:func:`eccjump.simulate`), from the strategies above.

    Parameters
    ----------
    body : SearchStrategy of Cylinder, optional
        Default ``bodies(min_km=MOTION_MIN_KM)``: a narrower one must keep k_m ≥ it.
    alpha : SearchStrategy of float, optional
        Default :func:`ramps`.
    friction : SearchStrategy of Friction, optional
        Default :func:`frictions`.
    start : SearchStrategy of Start, optional
        Default ``starts(min_omega0=-2.0, max_slip0=1.0)``: turned, spinning either way,
        sliding either way, and at rest.
    min_restitution, max_restitution : float
        The range of Stronge's coefficient e, within [0, 1].

    Returns
    -------
    hypothesis.strategies.SearchStrategy of MotionInput
        Reaches the edges of each part, e = 0 and e = 1 among them.

    Raises
    ------
    ValueError
        If the range of e is empty or outside [0, 1].

    Examples
    --------
    >>> import eccjump
    >>> from hypothesis import given, settings
    >>> from eccjump.testing import strategies
    >>> @settings(max_examples=10, deadline=None)
    ... @given(strategies.motion_inputs())
    ... def test_no_run_gains_energy(m):
    ...     r = eccjump.simulate(m.body, m.alpha, **m.keywords(), t_max=5.0)
    ...     assert r.dissipated[-1] >= -1e-9
    >>> test_no_run_gains_energy()
    """
    _range("min_restitution", min_restitution, "max_restitution", max_restitution, (0.0, 1.0))
    part = st.tuples(
        bodies(min_km=MOTION_MIN_KM) if body is None else body,
        ramps() if alpha is None else alpha,
        frictions() if friction is None else friction,
        _floats(min_restitution, max_restitution),
        starts(min_omega0=-2.0, max_slip0=1.0) if start is None else start,
    )
    return part.map(lambda p: MotionInput(p[0], p[1], *p[2], p[3], *p[4]))


@dataclass(frozen=True, eq=False)
class TrackInput:
    """A filmed run and what :func:`eccjump.analyze` needs to read it:
    ``analyze(t.track, **t.keywords())``. ``truth`` is the synthetic track with the simulated
    run (``truth.motion``) and the true θ, l, b and mode at each frame; ``inputs`` the run's
    physics."""

    track: Track
    radius: float
    marker_angle: float
    marker_radius: float
    inputs: MotionInput
    truth: SyntheticTrack

    def keywords(self) -> dict[str, Any]:
        """The keyword arguments of :func:`eccjump.analyze` after the track: the body, the ramp
        and the marker, as the experimenter knows them."""
        return {
            "radius": self.radius,
            "chi": self.inputs.body.chi,
            "km": self.inputs.body.km,
            "alpha": self.inputs.alpha,
            "marker_angle": self.marker_angle,
            "marker_radius": self.marker_radius,
        }


def tracks(
    *,
    inputs: st.SearchStrategy[MotionInput] | None = None,
    fps: st.SearchStrategy[float] | None = None,
    max_frames: int = 60,
    max_noise_px: float = 1.0,
) -> st.SearchStrategy[TrackInput]:
    """Tracks of simulated runs, filmed as :func:`eccjump.studies.experiment.synthetic_track`
    does (the axle and a marker, Gaussian pixel noise), short enough to analyse in seconds.

    Each track runs to the first landing and half a flight more (3 s without a flight), cut
    to ``max_frames`` frames and made at least 12 (the fewest :func:`eccjump.analyze` takes)
    by its duration.

    Parameters
    ----------
    inputs : SearchStrategy of MotionInput, optional
        The runs: default ``motion_inputs(start=starts(max_omega0=1.0))`` (rolling starts:
        what a lab releases). k_m ≥ MOTION_MIN_KM, as ``analyze`` needs.
    fps : SearchStrategy of float, optional
        The frame rate [1/s]: default 60, 120 or 240.
    max_frames : int
        The most frames of a track, 12 or more.
    max_noise_px : float
        The largest pixel noise (its standard deviation) of a track 1000 px across, ≥ 0.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of TrackInput
        Radius 1 to 10 cm, g = 9.81 m/s², the marker at 0.3 to 1 R, any angle from C → CM.

    Raises
    ------
    ValueError
        If max_frames < 12 or max_noise_px < 0.

    Examples
    --------
    >>> import eccjump
    >>> from hypothesis import given, settings
    >>> from eccjump.testing import strategies
    >>> @settings(max_examples=2, deadline=None)
    ... @given(strategies.tracks(max_frames=30))
    ... def test_a_verdict_for_every_track(t):
    ...     result = eccjump.analyze(t.track, **t.keywords(), profile_mu_k=False)
    ...     assert result.verdict in ("jarm", "slip_first", "undetermined")
    >>> test_a_verdict_for_every_track()
    """
    if not (isinstance(max_frames, int) and MIN_FRAMES <= max_frames <= 10_000):
        raise ValueError(
            f"max_frames = {short(max_frames)} is outside the allowed range [12, 10000]"
        )
    _range("0", 0.0, "max_noise_px", max_noise_px, (0.0, 100.0))
    return _tracks(
        motion_inputs(start=starts(max_omega0=1.0)) if inputs is None else inputs,
        st.sampled_from([60.0, 120.0, 240.0]) if fps is None else fps,
        max_frames,
        max_noise_px,
    )


@st.composite
def _tracks(
    draw: st.DrawFn,
    inputs: st.SearchStrategy[MotionInput],
    fps: st.SearchStrategy[float],
    max_frames: int,
    max_noise_px: float,
) -> TrackInput:
    m = replace(draw(inputs), slip0=0.0)  # a filmed run starts rolling (synthetic_track)
    rate = draw(fps)
    radius = draw(_floats(0.01, 0.1))
    angle = draw(_floats(-math.pi, math.pi))
    marker = radius * draw(_floats(0.3, 1.0))
    noise, seed = draw(_floats(0.0, max_noise_px)), draw(st.integers(0, 2**32 - 1))

    def film(duration: float | None) -> SyntheticTrack:
        return synthetic_track(
            m.body, m.alpha, mu_s=m.mu_s, mu_k=m.mu_k, restitution=m.restitution,
            theta0=m.theta0, omega0=m.omega0, radius=radius, fps=rate, duration=duration,
            marker_radius=marker, marker_angle=angle, noise_px=noise, seed=seed,
        )  # fmt: skip

    truth = film(None)
    if not MIN_FRAMES <= truth.track.n <= max_frames:  # film again, as long as allowed
        truth = film((min(max(truth.track.n, MIN_FRAMES), max_frames) - 0.5) / rate)
    assume(truth.track.n >= MIN_FRAMES)  # a run that ended early (a jam) films too few
    return TrackInput(truth.track, radius, angle, marker, m, truth)
