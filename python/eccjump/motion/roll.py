"""Pure rolling: :func:`roll` integrates the rolling equation in the Rust core.

Equations (units g = R = M = 1; the user guide's "The paper's formulas" page lists how each
was checked):

* rolling equation (paper Eq. roll-eq):
  θ̈ (Ic + 1 + 2 χ cos θ) = χ θ̇² sin θ + χ sin(α + θ) + sin α
* contact force on the cylinder, x down the ramp, y normal to it (paper Eq. Njump):
  Fx = -sin α - χ θ̇² sin θ + (1 + χ cos θ) θ̈
  Fy =  cos α - χ θ̇² cos θ - χ θ̈ sin θ
* the paper's lift-off condition (Eq. jumpcondition): χ θ̇² cos θ - cos α = 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._base.arrays import frozen_result, records, same_values
from eccjump._base.body import Cylinder
from eccjump._base.canvas import Plottable
from eccjump._base.checks import (
    U64_MAX,
    Integrator,
    Rule,
    flag,
    integer,
    optional_real,
    real,
    rule_name,
    text,
)
from eccjump._base.docs import fill
from eccjump._base.html import card, deg, num
from eccjump._base.units import Units
from eccjump.maps import results
from eccjump.maps.results import Result
from eccjump.motion.dense import DenseSolution

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray as xr

EVENT_NAMES = ("liftoff", "normal_force_zero", "slip", "theta_limit")
"""The names of the events of :func:`roll`: the paper's lift-off condition (rising), the
normal force Fy reaching 0, the friction cone left (mu_s Fy = |Fx|), ``theta_max`` reached."""


class Event(NamedTuple):
    """An event met during a run of :func:`roll`: its name, time and state.

    Attributes
    ----------
    name : str
        One of :data:`EVENT_NAMES`.
    t : float
        Time [√(R/g)] (seconds after ``to_si``).
    theta : float
        Angle of the vector axis -> centre of mass from the ramp normal [rad].
    omega : float
        Angular velocity θ̇ [√(g/R) rad] (rad/s after ``to_si``).
    """

    name: str
    t: float
    theta: float
    omega: float


#: The series of a :class:`RollResult`: (long name, unit dimensionless, unit after ``to_si``).
SERIES = {
    "t": ("time", "sqrt(R/g)", "s"),
    "theta": ("angle of the vector axis -> centre of mass from the ramp normal", "rad", "rad"),
    "omega": ("angular velocity theta'", "sqrt(g/R) rad", "rad/s"),
    "omega_dot": ("angular acceleration theta''", "g/R rad", "rad/s2"),
    "Fx": ("friction force along the ramp, positive down the ramp", "M g", "N"),
    "Fy": ("normal force", "M g", "N"),
    "l": ("distance rolled along the ramp since the start", "R", "m"),
    "friction_ratio": ("|Fx|/Fy, the friction the rolling needs", "1", "1"),
}


@dataclass(frozen=True, eq=False)
class RollResult(Result, Plottable, kind="roll"):
    """The outcome of :func:`roll`, in the spirit of scipy's ``OdeResult``.

    Arrays hold the accepted steps (the initial point first, the terminal event last), in
    units g = R = M = 1 unless converted with :meth:`to_si` (then seconds, rad/s, rad/s²,
    newtons and metres).

    Attributes
    ----------
    body : Cylinder
        The body that rolled.
    alpha : float
        Ramp angle [rad].
    mu_s : float or None
        Static friction coefficient; None: enough friction (no slip event).
    rule : str
        Lift-off rule, ``"paper"`` or ``"normal_force"``.
    t : numpy.ndarray
        Time [√(R/g)].
    theta : numpy.ndarray
        Angle of the vector axis -> centre of mass from the ramp normal [rad].
    omega : numpy.ndarray
        Angular velocity θ̇ [√(g/R) rad].
    omega_dot : numpy.ndarray
        Angular acceleration θ̈ from the rolling equation [g/R rad].
    Fx : numpy.ndarray
        Friction force on the cylinder along the ramp, positive down the ramp [M g].
    Fy : numpy.ndarray
        Normal force on the cylinder [M g].
    l : numpy.ndarray
        Distance rolled along the ramp since the start, l - l0 [R].
    friction_ratio : numpy.ndarray
        |Fx|/Fy, the friction the rolling branch needs (inf where Fy ≤ 0).
    events : tuple of Event
        Every event met, in time order (names in :data:`EVENT_NAMES`).
    terminal_event : str or None
        Name of the event that ended the run, or None.
    status : int
        0 reached ``t_max``, 1 a terminal event, -1 the integrator failed.
    message : str
        What happened, in words.
    nfev : int
        Right-hand-side evaluations.
    sol : DenseSolution or None
        Dense output ``sol(t) -> (theta, omega)`` when asked for, else None.
    units : Units or None
        The scales of :meth:`to_si`, or None for a dimensionless result.

    Examples
    --------
    >>> import math
    >>> import eccjump
    >>> res = eccjump.roll(eccjump.Cylinder(chi=0.15, km=0.02), math.radians(40), mu_s=1.0)
    >>> res.terminal_event, res.status, res.success
    ('liftoff', 1, True)
    >>> print(f"t = {res.t[-1]:.6f}, Fy = {res.Fy[-1]:.5f} M g")
    t = 4.183024, Fy = 0.01543 M g
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

    def event(self, name: str) -> Event | None:
        """The first event called ``name``, or None if the run did not meet it.

        Parameters
        ----------
        name : str
            One of :data:`EVENT_NAMES`.

        Returns
        -------
        Event or None

        Raises
        ------
        ValueError
            If ``name`` is not one of :data:`EVENT_NAMES`.
        """
        if name not in EVENT_NAMES:
            raise ValueError(f"name = {name!r} is not one of {EVENT_NAMES}")
        return next((e for e in self.events if e.name == name), None)

    @fill
    def to_si(
        self, units: Units | None = None, *, g: float = 9.81, R: float = 1.0, M: float = 1.0
    ) -> RollResult:
        """The same run in SI units: angles unchanged, times × √(R/g), rates × √(g/R),
        angular accelerations × g/R, forces × M g, lengths × R.

        The dense output is dropped (it stays available on the dimensionless result).

        Parameters
        ----------
        units : Units, optional
            The scales; if given, ``g``, ``R`` and ``M`` are ignored.
        %(g)s
        R : float, default 1.0
            Radius [m], in [1e-50, 1e50].
        M : float, default 1.0
            Mass [kg], in [1e-50, 1e50].

        Returns
        -------
        RollResult
            A copy with ``units`` set and ``sol`` None.

        Raises
        ------
        ValueError
            If this result is already in SI units, a scale is out of range, or a value
            overflows float64 in SI units.
        TypeError
            If ``units`` is not a Units or None.

        Examples
        --------
        >>> import math
        >>> import eccjump
        >>> res = eccjump.roll(eccjump.Cylinder(chi=0.15, km=0.02), math.radians(40), mu_s=1.0)
        >>> si = res.to_si(g=9.81, R=0.2, M=1.5)
        >>> print(f"lift-off after {si.t[-1]:.4f} s, Fy = {si.Fy[-1]:.4f} N")
        lift-off after 0.5973 s, Fy = 0.2270 N
        """
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

    _plot_doc = """The run in four panels (``eccjump.plot.trajectory``): θ against t;
    θ̇, F_x, F_y and the friction ratio against θ. ``ax=``: only θ against t
    with its events, drawn into this matplotlib Axes and returned
    (``eccjump.plot.roll_panel``), to compose figures; ``fig=``: the full figure in this
    empty Figure or SubFigure. ``kwargs`` go to the function drawn. Needs
    ``pip install eccjump[plot]``."""

    # Taking the result elsewhere (save and eccjump.load: eccjump.maps.results).
    _unsaved = ("sol",)

    def _series_attrs(self, name: str) -> dict[str, str]:
        long_name, unit, si = SERIES[name]
        return {"long_name": long_name, "units": unit if self.units is None else si}

    def _column_attrs(self, name: str) -> dict[str, str]:
        return self._series_attrs(name) if name in SERIES else {}

    def to_xarray(self) -> xr.Dataset:
        """The run as an ``xarray.Dataset`` (needs xarray): the series along ``t`` with
        ``units`` and ``long_name``, the events along ``event``, the body, ramp, friction,
        rule and how the run ended as attributes."""
        values = {k: getattr(self, k) for k in SERIES if k != "t"}
        data = results.series("t", values, self._series_attrs)
        data |= results.records_of("event", self.events, Event._fields, self._column_attrs)
        attrs = {
            "chi": self.body.chi,
            "km": self.body.km,
            "alpha": self.alpha,
            "mu_s": self.mu_s,
            "rule": self.rule,
            "terminal_event": self.terminal_event,
            "status": self.status,
            "message": self.message,
            "nfev": self.nfev,
        }
        coords = {"t": ("t", self.t, self._series_attrs("t"))}
        return results.dataset(self, data, coords, attrs)

    def to_dataframe(self) -> pandas.DataFrame:
        """The series as a ``pandas.DataFrame`` indexed by ``t`` (needs xarray), their units
        in ``attrs["units"]``; the events: ``to_xarray()`` along ``event``."""
        return results.to_frame(self.to_xarray(), ("t",))


@fill
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

    The rolling equation (units g = R = M = 1)
    θ̈ (Ic + 1 + 2 χ cos θ) = χ θ̇² sin θ + χ sin(α + θ)
    + sin α, with the contact forces from Newton–Euler, integrated by an adaptive
    Runge–Kutta pair with events located on its dense output to near machine precision:
    ``liftoff`` (the paper's condition χ θ̇² cos θ = cos α, rising),
    ``normal_force_zero`` (Fy = 0), ``slip`` (μ_s Fy = |Fx|) and ``theta_limit``. A contact
    condition already violated at t = 0 ends the run at once.

    Parameters
    ----------
    %(body)s
    alpha : float
        Ramp angle [rad], in [0, π/2] (``math.radians`` for degrees).
    theta0 : float, default 0.0
        Initial angle of the vector axis -> centre of mass from the ramp normal [rad],
        |theta0| ≤ 2π 1e6.
    omega0 : float, default 0.0
        Initial angular velocity [√(g/R) rad], |omega0| ≤ 1e6.
    mu_s : float or None, default None
        Static friction coefficient, in [0, inf); None means enough friction (no slip event).
    t_max : float, default 1000.0
        Largest time [√(R/g)], > 0.
    theta_max : float, default inf
        The run ends when θ reaches this angle [rad] (event ``theta_limit``).
    rtol : float, default 1e-10
        Relative tolerance of the integrator (scipy's meaning), in [1e-15, 1e-3].
    atol : float, default 1e-12
        Absolute tolerance of the integrator, in [1e-300, 1e-3].
    dense_output : bool, default False
        Keep the interpolant, returned as ``sol``.
    max_steps : int, default 1_000_000
        Step limit, 1 ... 10**7; reaching it ends the run with status -1.
    rule : {"paper", "normal_force"}, default "paper"
        ``"paper"`` ends the run at the paper's lift-off condition; ``"normal_force"``
        keeps rolling until Fy = 0 or (with ``mu_s``) the friction cone is left, recording
        the paper's condition as an event.
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair. For speed pick ``"Vern9"`` (at the default rtol 1.5–1.9×
        faster than RK45 and about 15× more accurate); keep ``"RK45"`` for step-for-step
        parity with scipy. ``"RK45"``: Dormand–Prince 5(4), step for step as scipy's
        ``RK45``. ``"DOP853"``: Dormand–Prince 8(5,3) as scipy's ``DOP853``, about 3x fewer
        steps at the default tolerances and the same steps as scipy's (``nfev`` is lower: a
        step clear of events gets no dense output unless ``dense_output`` is asked for).
        ``"Vern9"``: Verner's 9(8) pair, the fastest.

    Returns
    -------
    RollResult
        The accepted steps, the events, how the run ended (``terminal_event``, ``status``,
        ``message``) and, with ``dense_output``, ``sol``.

    Raises
    ------
    ValueError
        For any parameter outside its range; the message names it, its range and unit.
    TypeError
        If ``body`` is not a Cylinder or a parameter has the wrong type.
    KeyboardInterrupt
        On Ctrl-C, within about a second (a run looks every 4096 steps).
    MemoryError
        If the record of the run cannot be allocated.

    See Also
    --------
    simulate : the full motion on through slipping, flight and landing.
    jarm : the same verdict for many points, by the paper's closed forms.

    Examples
    --------
    The paper's JARM point: it lifts off straight out of pure rolling.

    >>> import math
    >>> import eccjump
    >>> body = eccjump.Cylinder(chi=0.15, km=0.02)
    >>> res = eccjump.roll(body, math.radians(40), mu_s=1.0)
    >>> res.terminal_event
    'liftoff'
    >>> print(f"{math.degrees(res.theta[-1]):.6f} deg, Fy = {res.Fy[-1]:.5f} M g")
    334.343838 deg, Fy = 0.01543 M g

    The paper's Fig. 3b body needs more friction than μ_s = 1 before it lifts off:

    >>> res = eccjump.roll(eccjump.Cylinder(chi=0.5, km=0.4), math.radians(30), mu_s=1.0)
    >>> print(res.terminal_event, f"at {math.degrees(res.theta[-1]):.2f} deg")
    slip at 316.47 deg
    """
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    # The checks in their historical order (alpha, mu_s, rule, then the signature's): of
    # several bad arguments the same one is named.
    alpha = real("alpha", alpha)
    mu_s = optional_real("mu_s", mu_s)
    rule = rule_name(rule)
    raw = _core.roll(
        body.chi,
        body.km,
        alpha,
        theta0=real("theta0", theta0),
        omega0=real("omega0", omega0),
        mu_s=mu_s,
        t_max=real("t_max", t_max),
        theta_max=real("theta_max", theta_max),
        rtol=real("rtol", rtol),
        atol=real("atol", atol),
        max_steps=integer("max_steps", max_steps, 1, U64_MAX),
        dense_output=flag("dense_output", dense_output),
        rule=rule,
        integrator=text("integrator", integrator),
    )
    # The bridge gives the run by RollResult's field names; the call's values complete it.
    result: dict[str, Any] = raw  # type: ignore[assignment]  # a TypedDict, completed here
    result["events"] = records(Event, raw["events"])
    if raw["sol"] is not None:
        result["sol"] = DenseSolution(raw["sol"])
    result["body"], result["alpha"], result["mu_s"], result["rule"] = body, alpha, mu_s, rule
    result["units"] = None
    return frozen_result(RollResult, result)
