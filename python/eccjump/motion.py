"""The full motion: :func:`simulate` follows the body through rolling, slipping, flight and
landing (``docs/motion.md`` is the model, ``docs/impact_law.md`` the impact law).

Units g = R = M = 1 unless converted with :meth:`MotionResult.to_si`; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._arrays import same_values
from eccjump._checks import Integrator, Rule, flag, integer, optional_real, real, real_array, text
from eccjump._html import card, deg, num, timeline
from eccjump.body import Cylinder
from eccjump.units import Units

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

#: Mode codes of :attr:`MotionResult.mode`, by index.
MODES = ("ROLL", "SLIP", "FLIGHT")
#: Why a mode began (``docs/motion.md``).
REASONS = (
    "start",
    "slip",
    "liftoff",
    "normal_force",
    "slip_inconsistent",
    "stick",
    "reverse",
    "impact",
    "settle",
)
#: The core's bounds on the work of a run (rust/eccjump-core/src/motion/options.rs and
#: modes/rolling/run.rs), checked here first so that the error states the true range.
MAX_TRANSITIONS = 10**6
MAX_STEPS = 10**7
#: How a run can end.
STATUSES = ("t_max", "l_max", "max_transitions", "painleve", "jam", "failed", "landed")


class Transition(NamedTuple):
    """A change of mode and the full state after it (after the impact, for a landing)."""

    t: float
    from_mode: str | None
    to_mode: str
    reason: str
    theta: float
    omega: float
    l: float  # noqa: E741 - the paper's name for the distance
    ldot: float
    b: float
    bdot: float


class FlightRecord(NamedTuple):
    """One flight: lift-off and landing (t_landing is NaN if the run ended in flight), the
    largest height of C above contact (apex = max(b - 1)) and the distance along the ramp."""

    t_liftoff: float
    t_landing: float
    theta_liftoff: float
    theta_landing: float
    apex: float
    distance: float


class ImpactRecord(NamedTuple):
    """One landing: the contact point's normal speed and slip velocity before it, the
    impulses, the kinetic energy it dissipated, whether the contact point stuck, and the
    mode after it."""

    t: float
    normal_speed: float
    slip_before: float
    pt: float
    pn: float
    energy_lost: float
    sticking: bool
    outcome: str


class Segment(NamedTuple):
    """A stretch of one mode: why it began, when, and the integrator's evaluations in it
    (0 in flight, which is exact)."""

    mode: str
    reason: str
    t_start: float
    t_end: float
    nfev: int


class MotionSolution:
    """Callable ``sol(t)``: (theta, omega, l, ldot, b, bdot) at times ``t`` across every
    segment (the interpolant in contact, the exact motion in flight; at an impact, the state
    after it). Scalar ``t`` gives shape (6,), an array of shape (n,) gives (6, n)."""

    def __init__(self, core: _core.MotionDense) -> None:
        self._core = core
        self.t_max = float(core.t_max)

    def __call__(self, t: ArrayLike) -> NDArray[np.float64]:
        tt = real_array("t", t)
        if tt.ndim > 1:
            raise ValueError(f"t must be a number or a 1-D array of times, got shape {tt.shape}")
        y = self._core.states(np.ascontiguousarray(np.atleast_1d(tt)))
        return y[:, 0] if tt.ndim == 0 else y


@dataclass(frozen=True, eq=False)
class MotionResult:
    """The outcome of :func:`simulate`.

    Arrays hold one row per accepted step (contact) or sample (flight), in time order; the
    boundary of two segments is recorded on both sides (the velocities jump at an impact).

    Attributes
    ----------
    t, theta, omega, l, ldot, b, bdot : time and state (l: C along the ramp from the start,
        b: height of C above the ramp, 1 in contact)
    Fx, Fy : contact force on the body [M g] (0 in flight)
    mode : int8 code per row, an index into :data:`MODES`
    energy : mechanical energy (kinetic + potential) [M g R]
    dissipated : energy dissipated so far by sliding and impacts; energy + dissipated is
        constant (``energy0``) to the integration tolerance
    transitions, flights, impacts, segments : see :class:`Transition`, :class:`FlightRecord`,
        :class:`ImpactRecord`, :class:`Segment`
    energy0, dissipated_slip, dissipated_impacts : the energy ledger
    status : one of :data:`STATUSES`; message : what happened, in words
    nfev : right-hand-side evaluations; sol : dense output or None
    """

    body: Cylinder
    alpha: float
    mu_s: float
    mu_k: float
    restitution: float
    rule: str
    t: NDArray[np.float64]
    theta: NDArray[np.float64]
    omega: NDArray[np.float64]
    l: NDArray[np.float64]  # noqa: E741
    ldot: NDArray[np.float64]
    b: NDArray[np.float64]
    bdot: NDArray[np.float64]
    Fx: NDArray[np.float64]
    Fy: NDArray[np.float64]
    energy: NDArray[np.float64]
    dissipated: NDArray[np.float64]
    mode: NDArray[np.int8]
    transitions: tuple[Transition, ...]
    flights: tuple[FlightRecord, ...]
    impacts: tuple[ImpactRecord, ...]
    segments: tuple[Segment, ...]
    energy0: float
    dissipated_slip: float
    dissipated_impacts: float
    status: str
    message: str
    nfev: int
    sol: MotionSolution | None
    units: Units | None = None

    @property
    def slip_velocity(self) -> NDArray[np.float64]:
        """The contact point's slip velocity ldot - omega (0 in pure rolling)."""
        return self.ldot - self.omega

    @property
    def height(self) -> NDArray[np.float64]:
        """The height of C above contact, b - 1 (0 in contact)."""
        return self.b - 1.0

    def mode_names(self) -> list[str]:
        """The modes in order of the transitions, e.g. ['ROLL', 'SLIP', 'FLIGHT', ...]."""
        return [tr.to_mode for tr in self.transitions]

    def __repr__(self) -> str:
        body = f"Cylinder(chi={self.body.chi!r}, km={self.body.km!r})"
        head = (
            f"MotionResult({body}, alpha={math.degrees(self.alpha):.6g} deg, "
            f"mu_s={self.mu_s:g}, mu_k={self.mu_k:g}, e={self.restitution:g}, rule={self.rule}"
            f"{', SI units' if self.units is not None else ''})"
        )
        seq = " -> ".join(self.mode_names()[:8]) + (" -> ..." if len(self.transitions) > 8 else "")
        end = float(self.t[-1]) if self.t.size else 0.0
        return (
            f"{head}\n  {seq}\n  {self.status} at t={end:.6g}: {len(self.transitions) - 1} "
            f"transitions, {len(self.flights)} flights, {len(self.impacts)} impacts, "
            f"nfev={self.nfev}"
        )

    def _repr_html_(self) -> str:
        si = self.units is not None
        time, length = (" s", " m") if si else (" sqrt(R/g)", " R")
        seq = " → ".join(self.mode_names()[:8]) + (" → …" if len(self.transitions) > 8 else "")
        end = float(self.t[-1]) if self.t.size else 0.0
        ledger = self.energy0 - (self.energy[-1] + self.dissipated[-1]) if self.t.size else 0.0
        rows = [
            ("body", f"chi = {num(self.body.chi)}, km = {num(self.body.km)}"),
            ("ramp", f"alpha = {deg(self.alpha)}"),
            ("friction", f"mu_s = {self.mu_s:g}, mu_k = {self.mu_k:g}; e = {self.restitution:g}"),
            ("rule", self.rule),
            ("modes", seq),
            ("ended", f"{self.status} at t = {num(end)}{time}"),
        ]
        for k, f in enumerate(self.flights[:3], start=1):
            rows.append(
                (
                    f"flight {k}",
                    f"from t = {num(f.t_liftoff)}{time} (theta = {deg(f.theta_liftoff)}): apex "
                    f"{num(f.apex)}{length}, distance {num(f.distance)}{length}",
                )
            )
        rows.append(("energy ledger", f"closes to {ledger:.2g} (energy0 = {num(self.energy0)})"))
        pic = timeline(self.t, self.mode, MODES)
        return card("MotionResult" + (" (SI units)" if si else ""), rows, pic)

    def plot(self, **kwargs: Any) -> Figure:
        """The run in six panels against time, the modes as coloured bands (``eccjump.plot.motion``;
        ``kwargs`` go to it). Needs ``pip install eccjump[plot]``."""
        from eccjump import plot  # figures: the layer on top of every result

        return plot.motion(self, **kwargs)

    def to_si(
        self, units: Units | None = None, *, g: float = 9.81, R: float = 1.0, M: float = 1.0
    ) -> MotionResult:
        """The same run in SI units (angles unchanged, times x sqrt(R/g), lengths x R, speeds
        x sqrt(gR), rates x sqrt(g/R), forces x M g, energies x M g R). ``sol`` is dropped."""
        if self.units is not None:
            raise ValueError("units: this result is already in SI units")
        if units is not None and not isinstance(units, Units):
            raise TypeError(f"units must be a Units or None, not {type(units).__name__}")
        u = units if units is not None else Units(g=g, R=R, M=M)
        speed, energy = u.length / u.time, u.force * u.length
        scale = {
            "t": u.time,
            "omega": u.rate,
            "l": u.length,
            "ldot": speed,
            "b": u.length,
            "bdot": speed,
        }
        with np.errstate(over="ignore"):
            return replace(
                self,
                **{k: getattr(self, k) * v for k, v in scale.items()},
                Fx=self.Fx * u.force,
                Fy=self.Fy * u.force,
                energy=self.energy * energy,
                dissipated=self.dissipated * energy,
                transitions=tuple(
                    tr._replace(
                        t=tr.t * u.time,
                        omega=tr.omega * u.rate,
                        l=tr.l * u.length,
                        ldot=tr.ldot * speed,
                        b=tr.b * u.length,
                        bdot=tr.bdot * speed,
                    )
                    for tr in self.transitions
                ),
                flights=tuple(
                    f._replace(
                        t_liftoff=f.t_liftoff * u.time,
                        t_landing=f.t_landing * u.time,
                        apex=f.apex * u.length,
                        distance=f.distance * u.length,
                    )
                    for f in self.flights
                ),
                impacts=tuple(
                    i._replace(
                        t=i.t * u.time,
                        normal_speed=i.normal_speed * speed,
                        slip_before=i.slip_before * speed,
                        pt=i.pt * u.M * speed,
                        pn=i.pn * u.M * speed,
                        energy_lost=i.energy_lost * energy,
                    )
                    for i in self.impacts
                ),
                segments=tuple(
                    s._replace(t_start=s.t_start * u.time, t_end=s.t_end * u.time)
                    for s in self.segments
                ),
                energy0=self.energy0 * energy,
                dissipated_slip=self.dissipated_slip * energy,
                dissipated_impacts=self.dissipated_impacts * energy,
                sol=None,
                units=u,
            )

    def __eq__(self, other: object) -> bool:
        """Field by field (arrays by values, NaN equal to NaN); ``sol`` by its states at the
        recorded times."""
        if type(other) is not type(self):
            return NotImplemented
        for f in fields(self):
            x, y = getattr(self, f.name), getattr(other, f.name)
            if f.name == "sol":
                if (x is None) != (y is None):
                    return False
                if x is not None and not np.array_equal(x(self.t), y(self.t), equal_nan=True):
                    return False
            elif not same_values(x, y):
                return False
        return True

    __hash__ = None  # type: ignore[assignment]


def simulate(
    body: Cylinder,
    alpha: float,
    *,
    mu_s: float,
    mu_k: float | None = None,
    restitution: float = 0.0,
    rule: Rule = "paper",
    theta0: float = 0.0,
    omega0: float = 0.0,
    slip0: float = 0.0,
    t_max: float = 100.0,
    l_max: float = math.inf,
    max_transitions: int = 100,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_steps: int = 1_000_000,
    dense_output: bool = False,
    integrator: Integrator = "RK45",
) -> MotionResult:
    """Follow ``body`` on a ramp of angle ``alpha`` through rolling, slipping, flight and
    landing, from (theta0, omega0) with slip velocity ``slip0`` (``docs/motion.md``).

    Parameters
    ----------
    body : Cylinder with km > 0 (km = 0 puts all the mass at the centre of mass; its spin in
        flight is undetermined).
    alpha : ramp angle [rad], in [0, pi/2] (0: flat ground).
    mu_s, mu_k : static and kinetic friction coefficients, 0 <= mu_k <= mu_s (default
        mu_k = mu_s).
    restitution : Stronge's energetic coefficient of restitution e in [0, 1].
    rule : lift-off from rolling: "paper" (chi theta'^2 cos theta = cos alpha) or
        "normal_force" (Fy = 0, or the friction cone left without a consistent slip).
    theta0, omega0, slip0 : initial angle [rad], angular velocity and slip velocity
        ldot - omega of the contact point.
    t_max : end time, in (0, 1e6]; l_max : distance along the ramp that ends the run.
    max_transitions : transitions after the start, 1 ... 10**6.
    rtol, atol : tolerances of the integrator; max_steps : accepted steps of the whole run,
        1 ... 10**7.
    integrator : ``"RK45"`` (Dormand–Prince 5(4), as scipy's ``RK45``; the default),
        ``"DOP853"`` (Dormand–Prince 8(5,3), as scipy's ``DOP853``), ``"Vern7"`` (Verner's
        7(6) pair) or ``"Vern9"`` (Verner's 9(8) pair). For speed pick ``"Vern9"`` (at the
        default rtol 1.5–1.9× faster than RK45 and about 15× more accurate); keep ``"RK45"``
        for step-for-step parity with scipy (``benches/bench_pairs.py``).
    dense_output : keep ``sol(t)`` across segments.

    Raises
    ------
    ValueError
        For any parameter outside its range; the message names it. Ctrl-C raises
        KeyboardInterrupt.
    """
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    # Plain floats, ints, a bool and strings, which the checks would return unchanged, skip
    # them after one test of their exact types (as in `roll`); anything else goes through
    # the checks, which alone define what is accepted, and comes back here plain.
    if not (
        type(alpha) is float
        and type(mu_s) is float
        and (mu_k is None or type(mu_k) is float)
        and type(restitution) is float
        and isinstance(rule, str)
        and type(theta0) is float
        and type(omega0) is float
        and type(slip0) is float
        and type(t_max) is float
        and type(l_max) is float
        and type(max_transitions) is int
        and 1 <= max_transitions <= MAX_TRANSITIONS
        and type(rtol) is float
        and type(atol) is float
        and type(max_steps) is int
        and 1 <= max_steps <= MAX_STEPS
        and type(dense_output) is bool
        and isinstance(integrator, str)
    ):
        # Checked in the signature's order: of several bad arguments the first is named.
        return simulate(
            body,
            real("alpha", alpha),
            mu_s=real("mu_s", mu_s),
            mu_k=optional_real("mu_k", mu_k),
            restitution=real("restitution", restitution),
            rule=text("rule", rule),  # type: ignore[arg-type]  # its values: the core's
            theta0=real("theta0", theta0),
            omega0=real("omega0", omega0),
            slip0=real("slip0", slip0),
            t_max=real("t_max", t_max),
            l_max=real("l_max", l_max),
            max_transitions=integer("max_transitions", max_transitions, 1, MAX_TRANSITIONS),
            rtol=real("rtol", rtol),
            atol=real("atol", atol),
            max_steps=integer("max_steps", max_steps, 1, MAX_STEPS),
            dense_output=flag("dense_output", dense_output),
            integrator=text("integrator", integrator),  # type: ignore[arg-type]
        )
    # The bridge builds the MotionResult itself (rust/eccjump-py/src/simulate.rs), as it
    # builds roll's RollResult.
    return _core.simulate(
        body,
        alpha,
        mu_s=mu_s,
        mu_k=mu_s if mu_k is None else mu_k,
        restitution=restitution,
        rule=rule,
        theta0=theta0,
        omega0=omega0,
        slip0=slip0,
        t_max=t_max,
        l_max=l_max,
        max_transitions=max_transitions,
        rtol=rtol,
        atol=atol,
        max_steps=max_steps,
        dense_output=dense_output,
        integrator=integrator,
    )
