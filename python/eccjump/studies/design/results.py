"""What a design returns: its margins, sensitivity, flight and the lab sheet."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any, NamedTuple

from eccjump._base.body import Cylinder
from eccjump._base.canvas import Plottable
from eccjump._base.checks import short
from eccjump._base.html import card, deg, num
from eccjump.maps import results
from eccjump.maps.results import Result
from eccjump.studies.design.physical import Build

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


@dataclass(frozen=True)
class Margin:
    """The distance of one input from the nearest boundary of the verdict's region.

    ``lo``/``hi``: the boundaries below and above ``value`` (-inf/inf: none in the input's
    whole range); ``margin``: the distance to the nearer one (for μ_s: beyond the stated
    uncertainty); ``relative``: margin / value, the fractional error that changes the verdict.
    """

    name: str
    value: float
    lo: float
    hi: float
    margin: float
    relative: float


@dataclass(frozen=True)
class Sensitivity:
    """One input moved by -error and +error (the others nominal, μ_s at its worst case):
    the verdict under both rules (``"kept"`` or the reasons) and the angle of the deciding
    event under the paper's rule (lift-off for a JARM, slip for a slip) [deg]."""

    input: str
    unit: str
    nominal: float
    minus: str
    plus: str
    theta_minus_deg: float
    theta_plus_deg: float


@dataclass(frozen=True)
class Flight:
    """The full motion at the design point under one rule (nominal μ_s, restitution 0):
    the first modes, and the first flight (NaN if none): lift-off angle [deg], apex of the
    axis above contact, distance along the ramp and duration (SI if the design has units:
    m and s; else R and √(R/g))."""

    rule: str
    modes: tuple[str, ...]
    theta_liftoff_deg: float
    apex: float
    distance: float
    duration: float


def _names(cls: type) -> tuple[str, ...]:
    return tuple(f.name for f in fields(cls))


def _margin_attrs(name: str) -> dict[str, str]:
    if name in ("value", "lo", "hi", "margin"):
        return {"units": "rad for alpha, else 1"}
    return {}


class Success(NamedTuple):
    """The probability that a body built to a design keeps its verdict under the lab's
    tolerances: the share ``p`` of the ``n_valid`` samples, and its 95 % Wilson interval."""

    p: float
    low: float
    high: float
    n_valid: int


class PJarm(NamedTuple):
    """A design's P(JARM) under the lab's tolerances (``design(..., p_target=)``): as
    :func:`eccjump.uncertainty` computes it, under the lift-off ``rule`` that gives the
    lower value; ``p`` of the ``n_valid`` samples, with its 95 % Wilson interval."""

    p: float
    low: float
    high: float
    n_valid: int
    rule: str


@dataclass(frozen=True)
class Design(Result, Plottable, kind="design"):
    """A lab design (:func:`design`): print it (``str(d)`` or :meth:`sheet`) for the lab
    sheet, :meth:`to_dict` for JSON. Angles in radians except the ``*_deg`` fields.

    Attributes
    ----------
    target : str
        ``"jarm"`` or ``"slip"``.
    body : Cylinder
        The chosen body.
    alpha : float
        The chosen ramp angle [rad].
    mu_s : float
        The nominal static friction coefficient.
    mu_s_err : float
        Its uncertainty.
    mu_s_worst : float
        The end of [μ_s - mu_s_err, μ_s + mu_s_err] where the verdict is weakest.
    build : Build
        The body as a shell plus a rod, in SI units or in R and M.
    si : bool
        Whether the sheet is in SI units (``radius`` and ``mass`` given).
    g : float
        Gravitational acceleration [m/s²].
    margins : tuple of Margin
        The margins in ``"alpha"`` [rad], ``"mu_s"`` and ``"rod"`` (r/R).
    score : float
        The smallest relative margin: the robustness.
    theta_deg : dict of str to float
        The deciding angle under each rule [deg] (lift-off for a JARM, slip for a slip).
    turn : int
        The turn of the deciding event.
    max_turns : int
        The turns the ramp allows.
    reasons : dict of str to str
        The verdict under each rule (a :class:`~eccjump.Reason` name).
    flights : tuple of Flight
        The full motion at the design under each rule: its first modes and first flight.
    sensitivity : tuple of Sensitivity
        Each input moved by -error and +error.
    error : float
        The fractional error of the sensitivity table.
    evaluations : int
        Classifications made by the search.
    notes : tuple of str
        Warnings for the lab.
    tolerances : dict of str to float or None
        The tolerances (normal standard deviations by name) ``p_success`` is for.
    p_success : Success or None
        The probability of the verdict under ``tolerances`` (None without them).
    p_target : float or None
        The P(JARM) the design was asked to reach (None: no target).
    p_jarm : PJarm or None
        Its P(JARM) under ``tolerances``, the lower rule's, whose Wilson lower bound reaches
        ``p_target`` (None without a target).
    """

    target: str
    body: Cylinder
    alpha: float
    mu_s: float
    mu_s_err: float
    mu_s_worst: float
    build: Build
    si: bool
    g: float
    margins: tuple[Margin, ...]
    score: float
    theta_deg: dict[str, float]
    turn: int
    max_turns: int
    reasons: dict[str, str]
    flights: tuple[Flight, ...]
    sensitivity: tuple[Sensitivity, ...]
    error: float
    evaluations: int
    notes: tuple[str, ...] = field(default=())
    tolerances: dict[str, float] | None = None
    p_success: Success | None = None
    p_target: float | None = None
    p_jarm: PJarm | None = None

    @property
    def rod_position(self) -> float:
        """ρ = r/R."""
        return self.build.rod_position / self.build.radius

    def margin(self, name: str) -> Margin:
        """The margin of one input.

        Parameters
        ----------
        name : {"alpha", "mu_s", "rod"}
            The input.

        Returns
        -------
        Margin
            ``value``, the boundaries ``lo`` and ``hi``, the ``margin`` and its
            ``relative`` size.

        Raises
        ------
        ValueError
            For another name.
        """
        for m in self.margins:
            if m.name == name:
                return m
        raise ValueError(f"name = {short(name)}; use 'alpha', 'mu_s' or 'rod'")

    def to_dict(self) -> dict[str, Any]:
        """Everything on the sheet as JSON-ready data.

        Returns
        -------
        dict of str to object
            Angles in degrees; NaN and infinities as None.
        """
        b = self.build
        return {
            "target": self.target,
            "units": _unit_names(self.si),
            "body": {
                "chi": self.body.chi,
                "km": self.body.km,
                "Ic": self.body.Ic,
                "rod_position_over_R": self.rod_position,
                **{k: _num(v) for k, v in b._asdict().items()},
            },
            "alpha_deg": math.degrees(self.alpha),
            "mu_s": self.mu_s,
            "mu_s_err": self.mu_s_err,
            "mu_s_worst": self.mu_s_worst,
            "theta_deg": {k: _num(v) for k, v in self.theta_deg.items()},
            "turn": self.turn,
            "max_turns": self.max_turns,
            "reasons": dict(self.reasons),
            "margins": [
                {
                    "name": m.name,
                    "unit": "deg" if m.name == "alpha" else "1",
                    **{
                        k: _num(math.degrees(v) if m.name == "alpha" and k != "relative" else v)
                        for k, v in (
                            ("value", m.value),
                            ("lo", m.lo),
                            ("hi", m.hi),
                            ("margin", m.margin),
                            ("relative", m.relative),
                        )
                    },
                }
                for m in self.margins
            ],
            "score": _num(self.score),
            "flights": [
                {k: (_num(v) if isinstance(v, float) else v) for k, v in f.__dict__.items()}
                | {"modes": list(f.modes)}
                for f in self.flights
            ],
            "error": self.error,
            "sensitivity": [
                {k: (_num(v) if isinstance(v, float) else v) for k, v in s.__dict__.items()}
                for s in self.sensitivity
            ],
            "evaluations": self.evaluations,
            "notes": list(self.notes),
            "tolerances": self.tolerances,
            "p_success": None if self.p_success is None else self.p_success._asdict(),
            "p_target": self.p_target,
            "p_jarm": None if self.p_jarm is None else self.p_jarm._asdict(),
        }

    # Taking the result elsewhere (save and eccjump.load: eccjump.maps.results; a design is
    # small: save it as .json).
    def to_xarray(self) -> xr.Dataset:
        """The design as an ``xarray.Dataset`` (needs xarray): the margins along ``margin``,
        the sensitivity table along ``input``, the flights along ``rule`` (their modes
        joined by " -> "), the scalar facts as attributes (angles in radians, build in
        the sheet's units, the tolerances as JSON text)."""
        rows = {
            "margin": [tuple(vars(m).values()) for m in self.margins],
            "input": [tuple(vars(x).values()) for x in self.sensitivity],
            "rule": [(*vars(f).values(),) for f in self.flights],
        }
        rows["rule"] = [(r[0], " -> ".join(r[1]), *r[2:]) for r in rows["rule"]]
        data = results.records_of("margin", rows["margin"], _names(Margin), _margin_attrs)
        data |= results.records_of("input", rows["input"], _names(Sensitivity))
        data |= results.records_of("rule", rows["rule"], _names(Flight))
        return results.dataset(self, data, attrs=self._attrs())

    def _attrs(self) -> dict[str, Any]:
        names = ("target", "alpha", "mu_s", "mu_s_err", "mu_s_worst", "si", "g", "score")
        out = {k: getattr(self, k) for k in (*names, "turn", "max_turns", "error")}
        out |= {"evaluations": self.evaluations, "chi": self.body.chi, "km": self.body.km}
        out |= {f"build_{k}": v for k, v in self.build._asdict().items()}
        out |= {f"theta_deg_{k}": v for k, v in self.theta_deg.items()}
        out |= {f"reason_{k}": v for k, v in self.reasons.items()}
        out["notes"] = "\n".join(self.notes)
        out["tolerances"] = json.dumps(self.tolerances)
        if self.p_success is not None:
            out |= {f"p_success_{k}": v for k, v in self.p_success._asdict().items()}
        if self.p_jarm is not None:
            out |= {"p_target": self.p_target}
            out |= {f"p_jarm_{k}": v for k, v in self.p_jarm._asdict().items()}
        return out

    def sheet(self) -> str:
        """The lab sheet, as text.

        Returns
        -------
        str
        """
        return _sheet(self)

    def __str__(self) -> str:
        return self.sheet()

    def __repr__(self) -> str:
        """One screen at most: the design and its verdict (``print`` it for the lab sheet)."""
        return (
            f"Design(target={self.target!r}, {self.body!r}, alpha={math.degrees(self.alpha):.6g}"
            f" deg, mu_s={self.mu_s:g}; paper rule: {self.reasons['paper']}, classical: "
            f"{self.reasons['normal_force']}; robustness {100 * self.score:.1f} %)"
        )

    def _repr_html_(self) -> str:
        rows = [
            ("body", f"chi = {num(self.body.chi)}, km = {num(self.body.km)}"),
            ("ramp", f"alpha = {deg(self.alpha)}"),
            ("friction", f"mu_s = {self.mu_s:g} ± {self.mu_s_err:g}"),
            (
                "verdict",
                f"paper rule: {self.reasons['paper']}, classical: {self.reasons['normal_force']}",
            ),
            ("robustness", f"{100 * self.score:.1f} % (the smallest relative margin)"),
        ]
        if self.p_success is not None:
            rows.append(("P(success)", _odds(self.p_success, self.tolerances)))
        if self.p_jarm is not None:
            rows.append(("P(JARM)", _chance(self.p_jarm, self.p_target)))
        rows += [
            (f"margin {m.name}", f"{num(m.margin, 4)} ({100 * m.relative:.1f} %)")
            for m in self.margins
        ]
        unit = " m" if self.si else " R"
        rows += [
            (
                f"flight ({f.rule})",
                f"apex {num(f.apex, 4)}{unit}, distance {num(f.distance, 4)}{unit}",
            )
            for f in self.flights
        ]
        return card("Design (print it for the lab sheet)", rows)

    _plot_doc = """The design on its region slice (``eccjump.plot.design_slice``): where its
    verdict holds over (χ, α) at its k_m and worst-case μ_s, the design and its
    margins in α and in the rod position. ``ax=``: the same, drawn into this
    matplotlib Axes and returned (``eccjump.plot.design_panel``), to compose figures;
    ``fig=``: in this empty Figure or SubFigure. ``kwargs`` (``resolution=``) go to it.
    Needs ``pip install eccjump[plot]``."""


def _odds(s: Success, tolerances: dict[str, float] | None) -> str:
    """P(success) with its interval and what it is for, in one line."""
    tol = ", ".join(
        f"alpha ± {math.degrees(v):.4g} deg" if k == "alpha" else f"{k} ± {v:g}"
        for k, v in (tolerances or {}).items()
    )
    return f"{s.p:.4f} [{s.low:.4f}, {s.high:.4f}] (95 %, {s.n_valid} samples; {tol})"


def _chance(s: PJarm, p_target: float | None) -> str:
    """P(JARM) with its interval, its rule and the target it reaches, in one line."""
    return (
        f"{s.p:.4f} [{s.low:.4f}, {s.high:.4f}] (95 %, {s.n_valid} samples, {s.rule} rule, "
        f"the lower; target {p_target:g} by the lower bound)"
    )


def _num(x: float) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _unit_names(si: bool) -> dict[str, str]:
    if si:
        return {"length": "m", "mass": "kg", "time": "s", "inertia": "kg m^2"}
    return {"length": "R", "mass": "M", "time": "sqrt(R/g)", "inertia": "M R^2"}


def _fmt(x: float, digits: int = 6) -> str:
    if math.isnan(x):
        return "n/a"
    if math.isinf(x):
        return "none"
    return f"{x:.{digits}g}"


def _sheet(d: Design) -> str:
    u = _unit_names(d.si)
    b = d.build
    L, Mu, Iu = u["length"], u["mass"], u["inertia"]
    jump = d.target == "jarm"
    roll_to = math.radians(max(d.theta_deg.values())) * b.radius
    head = (
        "a JARM: a jump straight out of pure rolling"
        if jump
        else "the control run: a body that slips before it lifts off"
    )
    lines = [f"eccjump design: {head}", "(verdict required under both lift-off rules)", ""]
    rows = [
        (
            "body",
            f"shell {_fmt(b.shell_mass, 4)} {Mu} + rod {_fmt(b.rod_mass, 4)} {Mu} at "
            f"r = {_fmt(b.rod_position, 4)} {L} from the axis (r/R = {d.rod_position:.4f})",
        ),
        (
            "",
            f"R = {_fmt(b.radius, 4)} {L}, M = {_fmt(b.mass, 4)} {Mu}, "
            f"d = {_fmt(b.d, 4)} {L}, I_C = {_fmt(b.I_C, 4)} {Iu} (about the axis)",
        ),
        ("", f"chi = {d.body.chi:.6f}, km = {d.body.km:.6f}, Ic = {d.body.Ic:.6f}"),
        ("ramp", f"alpha = {math.degrees(d.alpha):.4f} deg"),
        (
            "friction",
            f"mu_s = {d.mu_s:g} +- {d.mu_s_err:g} (worst case for the verdict: {d.mu_s_worst:g})",
        ),
        ("verdict", f"paper rule: {d.reasons['paper']}, classical: {d.reasons['normal_force']}"),
        *([("P(success)", _odds(d.p_success, d.tolerances))] if d.p_success is not None else []),
        *([("P(JARM)", _chance(d.p_jarm, d.p_target))] if d.p_jarm is not None else []),
        (
            "lift-off" if jump else "slip at",
            f"theta = {d.theta_deg['paper']:.4f} deg (paper rule), "
            f"{d.theta_deg['normal_force']:.4f} deg (classical rule)",
        ),
        (
            "ramp length",
            f"turn {d.turn}: the body rolls {_fmt(roll_to, 4)} {L} before it "
            f"(max_turns = {d.max_turns})",
        ),
    ]
    a, m, r = d.margin("alpha"), d.margin("mu_s"), d.margin("rod")

    def ends(x: Margin, scale: Callable[[float], float], unit: str) -> str:
        lo = "-" if math.isinf(x.lo) else f"{scale(x.lo):.5g}"
        hi = "-" if math.isinf(x.hi) else f"{scale(x.hi):.5g}"
        return f"region [{lo}, {hi}]{unit}"

    rows += [
        ("margins", f"to the exact boundary at mu_s = {d.mu_s_worst:g}; % = margin / value"),
        (
            "  alpha",
            f"{math.degrees(a.margin):.4f} deg ({100 * a.relative:.1f} %), "
            + ends(a, math.degrees, " deg"),
        ),
        (
            "  mu_s",
            (
                (
                    "unbounded"
                    if math.isinf(m.margin)
                    else f"{m.margin:.4g} beyond the uncertainty ({100 * m.relative:.1f} %), "
                )
                + (
                    f"a JARM needs mu_s >= {m.lo:.5g} (no upper limit)"
                    if jump
                    else (
                        ": slips first for every mu_s up to 1e6"
                        if math.isinf(m.hi)
                        else f"slips first while mu_s < {m.hi:.5g}"
                    )
                )
            ),
        ),
        (
            "  rod r/R",
            f"{r.margin:.4g} ({100 * r.relative:.1f} %) = {_fmt(r.margin * b.radius, 4)} {L}, "
            + ends(r, float, ""),
        ),
        ("  robustness", f"{100 * d.score:.1f} % (the smallest relative margin)"),
    ]
    for f in d.flights:
        name = "paper rule" if f.rule == "paper" else "classical"
        seq = " -> ".join(f.modes) if f.modes else "not simulated"
        rows.append((f"motion ({name})", seq))
        if math.isfinite(f.apex):
            rows.append(
                (
                    "",
                    f"first flight from theta = {f.theta_liftoff_deg:.3f} deg: apex "
                    f"{f.apex:.4g} {L}, distance {f.distance:.4g} {L}, "
                    f"time {f.duration:.4g} {u['time']}",
                )
            )
    width = max(len(k) for k, _ in rows)
    lines += [f"{k:<{width}}  {v}".rstrip() for k, v in rows]
    pct = f"{100 * d.error:g} %"
    lines += [
        "",
        f"sensitivity: each input -{pct} and +{pct}, the others nominal, mu_s = {d.mu_s_worst:g}",
        f"(theta: the {'lift-off' if jump else 'deciding event'} angle, paper rule)",
        f"  {'input':<22}{'nominal':>12}  {'-' + pct:<34}{'+' + pct}",
    ]
    names = {"L": L, "M": Mu, "I": Iu, "deg": "deg", "": ""}
    for s in d.sensitivity:
        unit = names[s.unit]
        label = f"{s.input} [{unit}]" if unit else s.input
        cells = []
        for verdict, th in ((s.minus, s.theta_minus_deg), (s.plus, s.theta_plus_deg)):
            cells.append(verdict if math.isnan(th) else f"{verdict}, {th:.2f} deg")
        lines.append(f"  {label:<22}{s.nominal:>12.5g}  {cells[0]:<34}{cells[1]:<34}".rstrip())
    lines += [f"note: {n}" for n in d.notes]
    return "\n".join(lines)
