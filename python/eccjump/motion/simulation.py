"""The full motion: :func:`simulate` follows the body through rolling, slipping, flight and
landing (the user guide's pages "The full motion" and "The impact law" give the model and
the impact law).

Units g = R = M = 1 unless converted with :meth:`MotionResult.to_si`; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.arrays import frozen_result, records, same_values
from eccjump._base.body import Cylinder
from eccjump._base.canvas import Plottable
from eccjump._base.checks import (
    Integrator,
    Rule,
    flag,
    optional_real,
    real,
    real_array,
    rule_name,
)
from eccjump._base.docs import fill
from eccjump._base.html import card, deg, num, timeline
from eccjump._base.units import Units
from eccjump.maps import results
from eccjump.maps.results import Result

# The bounds live with the options; still named here, where they were.
from eccjump.motion.options import MAX_STEPS as MAX_STEPS
from eccjump.motion.options import MAX_TRANSITIONS as MAX_TRANSITIONS
from eccjump.motion.options import MotionOptions

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray as xr

#: Mode codes of :attr:`MotionResult.mode`, by index.
MODES = ("ROLL", "SLIP", "FLIGHT")

#: The parameters of :attr:`MotionResult.d_transitions`, in the order of its last axis.
SENSITIVITY_PARAMETERS: tuple[str, ...] = tuple(_core.MOTION_PARAMETERS)
#: Why a mode began (the user guide's "The full motion", Transitions).
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
#: How a run can end.
STATUSES = ("t_max", "l_max", "max_transitions", "painleve", "jam", "failed", "landed")

# The names above, by code, are the core's (written out to be read here): a build whose
# codes moved would mislabel every record, so it is refused at import, as for ``Reason``.
if (
    list(enumerate(MODES)) != _core.mode_codes()
    or list(enumerate(REASONS)) != _core.transition_reason_codes()
    or list(enumerate(STATUSES)) != _core.status_codes()
):
    raise ImportError(
        "eccjump.motion's MODES, REASONS or STATUSES differ from the core's: rebuild eccjump"
    )


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
    """Callable ``sol(t)``: (θ, θ̇, l, l̇, b, ḃ) at times ``t`` across every
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


_TIME, _ANGLE, _LENGTH = ("sqrt(R/g)", "s"), ("rad", "rad"), ("R", "m")
_SPEED, _ENERGY, _IMPULSE = ("sqrt(g R)", "m/s"), ("M g R", "J"), ("M sqrt(g R)", "N s")

#: The units (dimensionless, after ``to_si``) of the columns of a :class:`MotionResult`,
#: its series and its records alike, by name.
UNITS = {
    **dict.fromkeys(("t", "t_liftoff", "t_landing", "t_start", "t_end"), _TIME),
    **dict.fromkeys(("theta", "theta_liftoff", "theta_landing"), _ANGLE),
    **dict.fromkeys(("l", "b", "apex", "distance"), _LENGTH),
    **dict.fromkeys(("ldot", "bdot", "normal_speed", "slip_before"), _SPEED),
    **dict.fromkeys(("energy", "dissipated", "energy_lost"), _ENERGY),
    **dict.fromkeys(("pt", "pn"), _IMPULSE),
    "omega": ("sqrt(g/R) rad", "rad/s"),
    **dict.fromkeys(("Fx", "Fy"), ("M g", "N")),
}
#: The long names of the series of a :class:`MotionResult`.
SERIES = {
    "t": "time",
    "theta": "angle of the vector C -> centre of mass from the ramp normal",
    "omega": "angular velocity theta'",
    "l": "position of C along the ramp from the start",
    "ldot": "speed of C along the ramp",
    "b": "height of C above the ramp",
    "bdot": "rate of b",
    "Fx": "friction force along the ramp, positive down the ramp",
    "Fy": "normal force",
    "energy": "mechanical energy, kinetic + potential",
    "dissipated": "energy dissipated so far by sliding and impacts",
    "mode": "mode (ROLL, SLIP, FLIGHT)",
}
#: The records of a :class:`MotionResult`: its field, its dimension, its named tuple.
RECORDS = (
    ("transitions", "transition", Transition),
    ("flights", "flight", FlightRecord),
    ("impacts", "impact", ImpactRecord),
    ("segments", "segment", Segment),
)


@dataclass(frozen=True, eq=False)
class MotionResult(Result, Plottable, kind="motion"):
    """The outcome of :func:`simulate`.

    Arrays hold one row per accepted step (contact) or sample (flight), in time order; the
    boundary of two segments is recorded on both sides (the velocities jump at an impact).

    Units g = R = M = 1 unless converted with :meth:`to_si` (then seconds, metres, m/s,
    rad/s, newtons and joules); angles in radians.

    Attributes
    ----------
    body : Cylinder
        The body.
    alpha : float
        Ramp angle [rad].
    mu_s : float
        Static friction coefficient.
    mu_k : float
        Kinetic friction coefficient.
    restitution : float
        Stronge's energetic coefficient of restitution e.
    rule : str
        Lift-off rule from rolling, ``"paper"`` or ``"normal_force"``.
    t : numpy.ndarray
        Time [√(R/g)].
    theta : numpy.ndarray
        Angle of the vector C -> centre of mass from the ramp normal [rad].
    omega : numpy.ndarray
        Angular velocity θ̇ [√(g/R) rad].
    l : numpy.ndarray
        Position of the centre C along the ramp from the start [R].
    ldot : numpy.ndarray
        Speed of C along the ramp [√(gR)].
    b : numpy.ndarray
        Height of C above the ramp [R] (1 in contact).
    bdot : numpy.ndarray
        Rate of b [√(gR)].
    Fx : numpy.ndarray
        Friction force on the body along the ramp, positive down the ramp [M g] (0 in
        flight).
    Fy : numpy.ndarray
        Normal force on the body [M g] (0 in flight).
    energy : numpy.ndarray
        Mechanical energy, kinetic + potential [M g R].
    dissipated : numpy.ndarray
        Energy dissipated so far by sliding and impacts [M g R]; energy + dissipated is
        constant (``energy0``) to the integration tolerance.
    mode : numpy.ndarray of int8
        Mode code per row, an index into ``MODES`` = ("ROLL", "SLIP", "FLIGHT").
    transitions : tuple of Transition
        Every change of mode (the start first): time, modes, reason, full state after it.
    flights : tuple of FlightRecord
        Every flight: lift-off and landing times and angles, apex of C above contact [R],
        distance along the ramp [R].
    impacts : tuple of ImpactRecord
        Every landing: normal speed, slip velocity before it, impulses, energy lost, whether
        the contact point stuck, the mode after it.
    segments : tuple of Segment
        Every stretch of one mode, with the integrator's evaluations in it.
    energy0 : float
        Mechanical energy at the start [M g R].
    dissipated_slip : float
        Energy dissipated by sliding over the run [M g R].
    dissipated_impacts : float
        Energy dissipated by the impacts over the run [M g R].
    status : str
        How the run ended: ``"t_max"``, ``"l_max"``, ``"max_transitions"``,
        ``"painleve"`` (an impulsive jam: the normal impulse of a slip grows without
        bound), ``"jam"`` or ``"failed"``.
    message : str
        What happened, in words.
    nfev : int
        Right-hand-side evaluations.
    sol : MotionSolution or None
        Dense output ``sol(t) -> (theta, omega, l, ldot, b, bdot)`` across segments, when
        asked for.
    d_transitions : numpy.ndarray or None
        With ``sensitivities=True``, shape (len(transitions), 2, 8): the derivatives of
        each transition's time ``[:, 0]`` and angle ``[:, 1]`` with respect to
        :data:`SENSITIVITY_PARAMETERS` (α, χ, km, μ_s, μ_k, restitution, theta0,
        omega0), in the units of the time and angle per unit of each parameter. NaN where
        ``d_singular``.
    d_singular : numpy.ndarray of bool or None
        With ``sensitivities=True``: the transition is not differentiable (a grazing
        event, two events at once, a landing whose outcome switches, a slip that went on in
        the normal impulse) or follows one that is not.
    units : Units or None
        The scales of :meth:`to_si`, or None for a dimensionless result.

    Examples
    --------
    >>> import math
    >>> import eccjump
    >>> body = eccjump.Cylinder(chi=0.5, km=0.4)
    >>> res = eccjump.simulate(body, math.radians(30), mu_s=1.0, t_max=9.0)
    >>> res.mode_names()
    ['ROLL', 'SLIP', 'FLIGHT', 'SLIP', 'ROLL', 'SLIP', 'FLIGHT']
    >>> f = res.flights[0]
    >>> print(f"apex {f.apex:.6f} R, distance {f.distance:.5f} R")
    apex 0.074954 R, distance 3.49484 R
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
    d_transitions: NDArray[np.float64] | None = None
    d_singular: NDArray[np.bool_] | None = None
    units: Units | None = None

    @property
    def slip_velocity(self) -> NDArray[np.float64]:
        """The contact point's slip velocity ldot - omega [√(gR)] (0 in pure rolling)."""
        return self.ldot - self.omega

    @property
    def height(self) -> NDArray[np.float64]:
        """The height of C above contact, b - 1 [R] (0 in contact)."""
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

    @fill
    def to_si(
        self, units: Units | None = None, *, g: float = 9.81, R: float = 1.0, M: float = 1.0
    ) -> MotionResult:
        """The same run in SI units: angles unchanged, times × √(R/g), lengths × R,
        speeds × √(gR), rates × √(g/R), forces × M g, energies × M g R.

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
        MotionResult
            A copy with ``units`` set and ``sol`` None (the dense output is dropped).

        Raises
        ------
        ValueError
            If this result is already in SI units, a scale is out of range, or a value
            overflows float64 in SI units.
        TypeError
            If ``units`` is not a Units or None.
        """
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
                d_transitions=_sensitivities_si(self.d_transitions, u),
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

    _plot_doc = """The run in six panels against time, the modes as coloured bands
    (``eccjump.plot.motion``). ``ax=``: only θ̇ against t with the modes and impacts,
    drawn into this matplotlib Axes and returned (``eccjump.plot.motion_panel``), to
    compose figures; ``fig=``: the full figure in this empty Figure or SubFigure.
    ``kwargs`` go to the function drawn. Needs ``pip install eccjump[plot]``."""

    # Taking the result elsewhere (save and eccjump.load: eccjump.maps.results).
    _unsaved = ("sol",)

    def _attrs(self, name: str) -> dict[str, Any]:
        """The ``units`` (and ``long_name``, codes) of a series or record column."""
        out: dict[str, Any] = {"long_name": SERIES[name]} if name in SERIES else {}
        if name in UNITS:
            out["units"] = UNITS[name][self.units is not None]
        if name == "mode":
            out |= {
                "units": "1",
                "flag_values": np.arange(len(MODES), dtype=np.int8),
                "flag_meanings": " ".join(MODES),
            }
        return out

    def to_xarray(self) -> xr.Dataset:
        """The run as an ``xarray.Dataset`` (needs xarray): the series along ``step`` (the
        time ``t`` a coordinate on it: a segment boundary is recorded twice), each record
        table along its own dimension (``transition``, ``flight``, ``impact``, ``segment``;
        columns named ``<dimension>_<field>``), the sensitivities (if any) along
        ``transition`` x ``quantity`` x ``parameter``, the scalar facts as attributes."""
        values = {k: getattr(self, k) for k in SERIES if k != "t"}
        data = results.series("step", values, self._attrs)
        for name, dim, record in RECORDS:
            data |= results.records_of(dim, getattr(self, name), record._fields, self._attrs)
        data |= self._sensitivity_vars()
        coords = {"t": ("step", self.t, self._attrs("t"))}
        names = ("mu_s", "mu_k", "restitution", "rule", "energy0", "dissipated_slip")
        attrs = {k: getattr(self, k) for k in (*names, "dissipated_impacts", "status", "nfev")}
        attrs |= {"chi": self.body.chi, "km": self.body.km, "alpha": self.alpha}
        return results.dataset(self, data, coords, {**attrs, "message": self.message})

    def _sensitivity_vars(self) -> dict[str, Any]:
        if self.d_transitions is None or self.d_singular is None:
            return {}
        dims = ("transition", "quantity", "parameter")
        return {
            "d_transitions": (dims, self.d_transitions, {"long_name": "d(t, theta)/d parameter"}),
            "d_singular": (("transition",), self.d_singular, {"long_name": "not differentiable"}),
            "quantity": (("quantity",), np.array(["t", "theta"])),
            "parameter": (("parameter",), np.array(SENSITIVITY_PARAMETERS)),
        }

    def to_dataframe(self, table: str = "series") -> pandas.DataFrame:
        """A table of the run as a ``pandas.DataFrame`` (needs xarray), the units of its
        columns in ``attrs["units"]``.

        Parameters
        ----------
        table : str, default "series"
            ``"series"`` (one row per step, indexed by ``step``, ``t`` a column),
            ``"transitions"``, ``"flights"``, ``"impacts"`` or ``"segments"`` (one row per
            record).
        """
        dims = {"series": "step", **{name: dim for name, dim, _ in RECORDS}}
        if table not in dims:
            raise ValueError(f"table must be one of {', '.join(dims)}, not {table!r}"[:200])
        return results.to_frame(self.to_xarray(), (dims[table],))


def _sensitivities_si(d: NDArray[np.float64] | None, u: Units) -> NDArray[np.float64] | None:
    """d(t, θ)/dp in SI units: times × √(R/g), and per rad/s of omega0 (a rate x
    √(g/R)) rather than per dimensionless rate; the other parameters are dimensionless
    or angles."""
    if d is None:
        return None
    out = d * np.array([u.time, 1.0])[:, None]
    out[..., SENSITIVITY_PARAMETERS.index("omega0")] /= u.rate
    return out


@fill
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
    sensitivities: bool = False,
) -> MotionResult:
    """Follow ``body`` on a ramp of angle ``alpha`` through rolling, slipping, flight and
    landing, from (theta0, omega0) with slip velocity ``slip0``.

    One segment at a time: rolling and slipping are integrated with events, flight is exact,
    every landing goes through the impact law (Routh's method with Coulomb friction and
    Stronge's energetic restitution), and after every event the consistent contact mode is
    chosen again. The run ends at ``t_max``, ``l_max`` or ``max_transitions``, or where the
    rigid model cannot continue (Painlevé, a jam): that is a ``status``, not an error.

    Where the sliding normal force grows large (above 1e3 M g: D = I_CM + χ K sin θ
    falls towards 0, the Painlevé singularity) the slip goes on against the normal impulse, in
    which nothing diverges, until it stops, lifts off, or the force falls back below 1e2 M g;
    only a slip whose normal force grows without bound at a finite impulse ends the run
    (status ``"painleve"``). Each step of rolling or slipping
    turns the body by at most 0.5 rad, so that the record is fine enough to plot.

    Parameters
    ----------
    body : Cylinder
        The body, with km > 0 (km = 0 puts all the mass at the centre of mass: its spin in
        flight is undetermined).
    alpha : float
        Ramp angle [rad], in [0, π/2] (0: flat ground).
    %(mu_s)s
    mu_k : float or None, default None
        Kinetic friction coefficient, in [0, μ_s]; None: μ_k = μ_s.
    restitution : float, default 0.0
        Stronge's energetic coefficient of restitution e, in [0, 1].
    rule : {"paper", "normal_force"}, default "paper"
        Lift-off from rolling: ``"paper"`` (χ θ̇² cos θ = cos α) or
        ``"normal_force"`` (Fy = 0, or the friction cone left without a consistent slip).
    %(theta0)s
    omega0 : float, default 0.0
        Initial angular velocity [√(g/R) rad], |omega0| ≤ 1e6.
    slip0 : float, default 0.0
        Initial slip velocity l̇ - θ̇ of the contact point [√(gR)], |slip0| ≤ 1e6.
    t_max : float, default 100.0
        End time [√(R/g)], in (0, 1e6].
    l_max : float, default inf
        Distance of C along the ramp that ends the run [R], in (0, inf]; inf disables it.
    max_transitions : int, default 100
        Transitions after the start, 1 ... 10**6.
    rtol : float, default 1e-10
        Relative tolerance of the integrator, in [1e-15, 1e-6] (looser, the energy ledger
        no longer closes: the user guide's "Limits" page).
    atol : float, default 1e-12
        Absolute tolerance of the integrator, in [1e-300, 1e-6].
    max_steps : int, default 1_000_000
        Accepted steps of the whole run (rolling and slipping together), 1 ... 10**7.
    dense_output : bool, default False
        Keep ``sol(t)`` across segments.
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair: ``"RK45"`` (Dormand–Prince 5(4), as scipy's ``RK45``),
        ``"DOP853"`` (Dormand–Prince 8(5,3), as scipy's ``DOP853``) or ``"Vern9"``
        (Verner's 9(8) pair). For speed pick
        ``"Vern9"`` (at the default rtol 1.5–1.9× faster than RK45 and about 15× more
        accurate); keep ``"RK45"`` for step-for-step parity with scipy.
    sensitivities : bool, default False
        Also give ``d_transitions``, the exact derivatives of every transition's time and
        angle with respect to (α, χ, km, μ_s, μ_k, restitution, theta0, omega0):
        the variational equations along each segment, each event's time correction and the
        landing's Jacobian (the user guide's "The full motion", Sensitivities). About ten
        times the run's cost (2.5 ms for the paper's body over 19 transitions).

    Returns
    -------
    MotionResult
        The recorded motion, its transitions, flights, impacts and segments, the energy
        ledger, the ``status`` and, with ``dense_output``, ``sol``.

    Raises
    ------
    ValueError
        For any parameter outside its range; the message names it, its range and unit.
    TypeError
        If ``body`` is not a Cylinder or a parameter has the wrong type.
    %(keyboard_interrupt)s
    MemoryError
        If the record of the run cannot be allocated.

    See Also
    --------
    roll : pure rolling to its first event.
    motion_map : the same run, to its first landing, at every point of a grid.

    Examples
    --------
    The paper's Fig. 3b body slips first, then flies 3.5 R down the ramp:

    >>> import math
    >>> import eccjump
    >>> body = eccjump.Cylinder(chi=0.5, km=0.4)
    >>> res = eccjump.simulate(body, math.radians(30), mu_s=1.0, t_max=9.0)
    >>> [tr.reason for tr in res.transitions[1:]]
    ['slip', 'normal_force', 'impact', 'stick', 'slip', 'normal_force']
    >>> f = res.flights[0]
    >>> print(f"lift-off t = {f.t_liftoff:.6f}, landing t = {f.t_landing:.6f}")
    lift-off t = 5.370832, landing t = 7.090869
    >>> print(f"dissipated: slip {res.dissipated_slip:.6f}, impacts {res.dissipated_impacts:.6f}")
    dissipated: slip 0.806067, impacts 0.293353
    >>> res.status
    't_max'
    """
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    # Checked in the signature's order: of several bad arguments the first is named.
    alpha = real("alpha", alpha)
    mu_s = real("mu_s", mu_s)
    mu_k = optional_real("mu_k", mu_k)
    mu_k = mu_s if mu_k is None else mu_k
    restitution = real("restitution", restitution)
    rule = rule_name(rule)
    theta0, omega0, slip0 = real("theta0", theta0), real("omega0", omega0), real("slip0", slip0)
    run = MotionOptions(
        rule=rule,
        t_max=t_max,
        max_transitions=max_transitions,
        rtol=rtol,
        atol=atol,
        max_steps=max_steps,
        integrator=integrator,
    )
    raw = _core.simulate(
        body.chi,
        body.km,
        alpha,
        mu_s=mu_s,
        mu_k=mu_k,
        restitution=restitution,
        theta0=theta0,
        omega0=omega0,
        slip0=slip0,
        l_max=real("l_max", l_max),
        **run.keywords(),
        dense_output=flag("dense_output", dense_output),
        sensitivities=flag("sensitivities", sensitivities),
    )
    # The bridge gives the run by MotionResult's field names; the call's values complete it.
    result: dict[str, Any] = raw  # type: ignore[assignment]  # a TypedDict, completed here
    result["transitions"] = records(Transition, raw["transitions"])
    result["flights"] = records(FlightRecord, raw["flights"])
    result["impacts"] = records(ImpactRecord, raw["impacts"])
    result["segments"] = records(Segment, raw["segments"])
    if raw["sol"] is not None:
        result["sol"] = MotionSolution(raw["sol"])
    result["body"], result["alpha"], result["rule"], result["units"] = body, alpha, rule, None
    result["mu_s"], result["mu_k"], result["restitution"] = mu_s, mu_k, restitution
    return frozen_result(MotionResult, result)
