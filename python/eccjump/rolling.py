"""Pure rolling: :func:`roll` integrates the rolling equation in the Rust core.

Equations (units g = R = M = 1; ``docs/paper_formulas.md`` lists how each was checked):

* rolling equation (paper Eq. roll-eq):
  theta'' (Ic + 1 + 2 chi cos theta) = chi theta'^2 sin theta + chi sin(alpha + theta) + sin alpha
* contact force on the cylinder, x down the ramp, y normal to it (paper Eq. Njump):
  Fx = -sin alpha - chi theta'^2 sin theta + (1 + chi cos theta) theta''
  Fy =  cos alpha - chi theta'^2 cos theta - chi theta'' sin theta
* the paper's lift-off condition (Eq. jumpcondition): chi theta'^2 cos theta - cos alpha = 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._arrays import same_values
from eccjump._checks import U64_MAX, Integrator, Rule, flag, integer, optional_real, real, text
from eccjump._html import card, deg, num
from eccjump.body import Cylinder
from eccjump.dense import DenseSolution
from eccjump.units import Units

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

EVENT_NAMES = ("liftoff", "normal_force_zero", "slip", "theta_limit")


class Event(NamedTuple):
    """An event met during a run: its name, time and state (dimensionless units)."""

    name: str
    t: float
    theta: float
    omega: float


@dataclass(frozen=True, eq=False)
class RollResult:
    """The outcome of :func:`roll`, in the spirit of scipy's ``OdeResult``.

    Arrays hold the accepted steps (the initial point first, the terminal event last), in
    units g = R = M = 1 unless converted with :meth:`to_si`.

    Attributes
    ----------
    t : time [sqrt(R/g)]
    theta : angle of the vector C -> CM from the ramp normal [rad]
    omega : angular velocity theta' [sqrt(g/R) rad]
    omega_dot : angular acceleration theta'' from the rolling equation [g/R rad]
    Fx : friction force on the cylinder along the ramp, positive down the ramp [M g]
    Fy : normal force on the cylinder [M g]
    l : distance rolled along the ramp since the start, l - l0 [R] (from the core)
    friction_ratio : |Fx|/Fy, the friction the rolling branch needs (inf where Fy <= 0)
    events : every event met, in time order (see :data:`EVENT_NAMES`)
    terminal_event : name of the event that ended the run, or None
    status : 0 reached t_max, 1 a terminal event, -1 the integrator failed
    message : what happened, in words
    nfev : right-hand-side evaluations
    sol : dense output ``sol(t) -> (theta, omega)`` when asked for, else None
    """

    body: Cylinder
    alpha: float
    mu_s: float | None
    rule: str
    t: NDArray[np.float64]
    theta: NDArray[np.float64]
    omega: NDArray[np.float64]
    omega_dot: NDArray[np.float64]
    Fx: NDArray[np.float64]
    Fy: NDArray[np.float64]
    l: NDArray[np.float64]  # noqa: E741 - the paper's name for the distance
    friction_ratio: NDArray[np.float64]
    events: tuple[Event, ...]
    terminal_event: str | None
    status: int
    message: str
    nfev: int
    sol: DenseSolution | None
    units: Units | None = None

    @property
    def success(self) -> bool:
        """True unless the integrator failed."""
        return self.status >= 0

    def _outcome(self) -> str:
        """How the run ended, in a few words."""
        if self.terminal_event is not None:
            return self.terminal_event
        return "t_max reached" if self.status == 0 else f"failed ({self.message})"

    def __repr__(self) -> str:
        """A short summary: how the run ended, the end state, steps and evaluations (the
        arrays themselves are not shown)."""
        outcome = self._outcome()
        si = self.units is not None
        mu = "enough friction" if self.mu_s is None else f"mu_s={self.mu_s:g}"
        body = f"Cylinder(chi={self.body.chi!r}, km={self.body.km!r})"
        alpha = f"alpha={math.degrees(self.alpha):.6g} deg"
        head = f"RollResult({body}, {alpha}, {mu}, rule={self.rule}{', SI units' if si else ''})"
        k = len(self.events)
        counts = f"nfev={self.nfev}, {k} event{'' if k == 1 else 's'}"
        if self.t.size == 0:
            return f"{head}\n  {outcome}; no steps, {counts}"
        t, theta, omega = float(self.t[-1]), float(self.theta[-1]), float(self.omega[-1])
        return (
            f"{head}\n  {outcome} at t={t:.6g}{' s' if si else ''}, "
            f"theta={math.degrees(theta):.6g} deg, omega={omega:.6g}{' rad/s' if si else ''}; "
            f"{self.t.size - 1} steps, {counts}"
        )

    def _repr_html_(self) -> str:
        si = self.units is not None
        time, rate = (" s", " rad/s") if si else (" sqrt(R/g)", " sqrt(g/R)")
        rows = [
            ("body", f"chi = {num(self.body.chi)}, km = {num(self.body.km)}"),
            ("ramp", f"alpha = {deg(self.alpha)}"),
            (
                "friction",
                "enough (no slip event)" if self.mu_s is None else f"mu_s = {self.mu_s:g}",
            ),
            ("rule", self.rule),
            ("ended by", self._outcome()),
        ]
        if self.t.size:
            t, theta, omega = float(self.t[-1]), float(self.theta[-1]), float(self.omega[-1])
            end = f"t = {num(t)}{time}, theta = {deg(theta)}, omega = {num(omega)}{rate}"
            rows.append(("end state", end))
        for e in self.events[:4]:
            rows.append((f"event {e.name}", f"t = {num(e.t)}{time}, theta = {deg(e.theta)}"))
        rows.append(("steps, nfev", f"{max(self.t.size - 1, 0)}, {self.nfev}"))
        return card("RollResult" + (" (SI units)" if si else ""), rows)

    def plot(self, **kwargs: Any) -> Figure:
        """The run in four panels: theta against t; omega, F_x, F_y and the friction ratio against
        theta (``eccjump.plot.trajectory``; ``kwargs`` go to it). Needs ``pip install
        eccjump[plot]``."""
        from eccjump import plot  # figures: the layer on top of every result

        return plot.trajectory(self, **kwargs)

    def event(self, name: str) -> Event | None:
        """The first event called ``name``, or None."""
        if name not in EVENT_NAMES:
            raise ValueError(f"name = {name!r} is not one of {EVENT_NAMES}")
        return next((e for e in self.events if e.name == name), None)

    def to_si(
        self, units: Units | None = None, *, g: float = 9.81, R: float = 1.0, M: float = 1.0
    ) -> RollResult:
        """The same run in SI units for gravity ``g`` [m/s²], radius ``R`` [m], mass ``M``
        [kg]: angles unchanged, times x sqrt(R/g), rates x sqrt(g/R), forces x M g.
        The dense output is dropped (it stays available on the dimensionless result)."""
        if self.units is not None:
            raise ValueError("units: this result is already in SI units")
        if units is not None and not isinstance(units, Units):
            raise TypeError(f"units must be a Units or None, not {type(units).__name__}")
        u = units if units is not None else Units(g=g, R=R, M=M)
        with np.errstate(over="ignore"):
            out = replace(
                self,
                t=self.t * u.time,
                omega=self.omega * u.rate,
                omega_dot=self.omega_dot * u.acceleration,
                Fx=self.Fx * u.force,
                Fy=self.Fy * u.force,
                l=self.l * u.length,
                events=tuple(
                    Event(e.name, e.t * u.time, e.theta, e.omega * u.rate) for e in self.events
                ),
                sol=None,
                units=u,
            )
        for name in ("t", "omega", "omega_dot", "Fx", "Fy", "l"):
            before, after = getattr(self, name), getattr(out, name)
            if not np.array_equal(np.isfinite(before), np.isfinite(after)):
                raise ValueError(
                    f"units: {name} in SI units overflows float64 (g = {u.g:g}, R = {u.R:g}, "
                    f"M = {u.M:g})"
                )
        return out

    def __eq__(self, other: object) -> bool:
        """Field by field: arrays by shape, dtype and values (NaN equal to NaN); the dense
        output ``sol`` by :meth:`DenseSolution.same_as` at the step times ``t``."""
        if type(other) is not type(self):
            return NotImplemented
        for f in fields(self):
            x, y = getattr(self, f.name), getattr(other, f.name)
            if f.name == "sol":
                if (x is None) != (y is None) or (x is not None and not x.same_as(y, self.t)):
                    return False
            elif not same_values(x, y):
                return False
        return True

    __hash__ = None  # type: ignore[assignment]  # mutable numpy arrays inside


def roll(
    body: Cylinder,
    alpha: float,
    *,
    theta0: float = 0.0,
    omega0: float = 0.0,
    mu_s: float | None = None,
    t_max: float = 1000.0,
    theta_max: float = math.inf,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    dense_output: bool = False,
    max_steps: int = 1_000_000,
    rule: Rule = "paper",
    integrator: Integrator = "RK45",
) -> RollResult:
    """Integrate pure rolling of ``body`` on a ramp of angle ``alpha`` until an event ends it.

    Parameters
    ----------
    body : Cylinder
    alpha : ramp angle [rad], in [0, pi/2].
    theta0, omega0 : initial angle [rad], |theta0| <= 2 pi 1e6, and angular velocity,
        |omega0| <= 1e6 [sqrt(g/R) rad].
    mu_s : static friction coefficient, >= 0; None means enough friction (no slip event).
    t_max : largest time [sqrt(R/g)], > 0.
    theta_max : the run ends when theta reaches this angle [rad] (event ``theta_limit``).
    rtol, atol : tolerances of the integrator (scipy's meaning).
    dense_output : keep the interpolant, returned as ``sol``.
    max_steps : step limit (1 ... 10**7); reaching it ends the run with status -1. A run
        honours Ctrl-C (KeyboardInterrupt); bounds: ``docs/limits.md``.
    rule : ``"paper"`` ends the run at the paper's lift-off condition
        chi theta'^2 cos theta = cos alpha; ``"normal_force"`` keeps rolling until Fy = 0 or
        (with ``mu_s``) the friction cone is left, recording the paper's condition as an event.
    integrator : for speed pick ``"Vern9"`` (at the default rtol 1.5–1.9× faster than RK45
        and about 15× more accurate); keep ``"RK45"`` for step-for-step parity with scipy
        (``benches/bench_pairs.py``). The pairs: ``"RK45"`` (Dormand–Prince 5(4), step for
        step as scipy's ``RK45``; the default),
        ``"DOP853"`` (Dormand–Prince 8(5,3) as scipy's ``DOP853``: about 3x fewer steps at
        the default tolerances, and faster; the same steps as scipy's, but ``nfev`` is lower:
        a step whose ends clear it of events is not given the dense output's 3 extra
        evaluations unless ``dense_output`` is asked for), ``"Vern7"`` (Verner's 7(6) pair,
        10 evaluations per step and 5 more for an interpolant, which events need only
        rarely; scipy's step control with a safety factor of 0.75 and a first step probed
        up to three times: at equal accuracy mostly the fastest over a few turns) or
        ``"Vern9"`` (Verner's 9(8) pair, 16 evaluations per step and 4 more for an
        interpolant, the same step control: the fastest over long runs and at tight
        tolerances; ``benches/README.md``).

    Events (located on the dense output to near machine precision): ``liftoff`` (paper's
    condition, rising), ``normal_force_zero`` (Fy = 0), ``slip`` (mu_s Fy = |Fx|),
    ``theta_limit``. A contact condition already violated at t = 0 ends the run at once.

    Raises
    ------
    ValueError
        For any parameter outside its range; the message names it.
    """
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    # The bridge builds the RollResult itself (rust/eccjump-py/src/roll.rs): in Python its
    # 19-entry dict alone cost as much as a tenth of a short run. The arguments go in this
    # signature's order, positionally (the bridge's order: tested). Most calls pass plain
    # floats, an int, a bool and strings, which the checks would return unchanged; the
    # bridge runs on those at once and returns None if any argument has another type.
    run = _core.roll(
        body,
        alpha,
        theta0,
        omega0,
        mu_s,
        t_max,
        theta_max,
        rtol,
        atol,
        dense_output,
        max_steps,
        rule,
        integrator,
    )
    if run is not None:
        return run
    # Then the checks, which alone define what is accepted, name a bad argument or make it
    # plain, in their historical order (alpha, mu_s, rule, then the signature's): of several
    # bad arguments the same one is named.
    return roll(
        body,
        real("alpha", alpha),
        mu_s=optional_real("mu_s", mu_s),
        rule=text("rule", rule),  # type: ignore[arg-type]  # its values: the core's
        theta0=real("theta0", theta0),
        omega0=real("omega0", omega0),
        t_max=real("t_max", t_max),
        theta_max=real("theta_max", theta_max),
        rtol=real("rtol", rtol),
        atol=real("atol", atol),
        max_steps=integer("max_steps", max_steps, 1, U64_MAX),
        dense_output=flag("dense_output", dense_output),
        integrator=text("integrator", integrator),  # type: ignore[arg-type]
    )
