"""Experiment design: the body and ramp angle whose JARM (or, for a control run, whose slip
before lift-off) is most robust, with a printable lab sheet (``docs/design.md``).

The design space is the ramp angle alpha, the shell mass fraction k_m and the rod position
rho = r/R of the paper's body (a thin uniform shell plus a rod parallel to the axis): the rod
of mass (1 - k_m) M at distance r from the axis puts the centre of mass at d = (1 - k_m) r,
so chi = rho (1 - k_m), and I_C = k_m M R^2 + (1 - k_m) M r^2, i.e. Ic = k_m + chi^2/(1 - k_m).
Every (k_m, rho) in [0, 1) x [0, 1] is a valid body.

A verdict must hold under both lift-off rules (the rule is a modelling uncertainty) and for
every mu_s in [mu_s - mu_s_err, mu_s + mu_s_err]; JARM and slip-first are both monotone in
mu_s, so the worst case is one end of that interval (the lower one for a JARM, the upper one
for a slip). The margins, all at that worst case, are distances to the exact boundary of the
verdict's region: in alpha (the JARM alpha-interval around the design, ends to 1e-12), in
mu_s (beyond the uncertainty) and in rho (at fixed masses). The design maximises the
smallest RELATIVE margin -- the smallest fractional error of one input that can change the
verdict -- found on a coarse grid, then refined by a deterministic compass search.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump._checks import integer, optional_real, real, short, text
from eccjump.body import Cylinder
from eccjump.boundary import alpha_interval_around, mu_s_min_path
from eccjump.classification import jarm
from eccjump.fields import Reason
from eccjump.motion import simulate

Target = Literal["jarm", "slip"]
#: The lift-off rules a verdict must hold under.
RULES = ("paper", "normal_force")
_SLIPS = (int(Reason.SLIP_BEFORE), int(Reason.SLIP_AT_JUMP))
_HALF_PI = math.pi / 2
#: Bounds of the work: grid points per axis, compass-search evaluations per candidate.
GRID_RANGE = (4, 64)
_MAX_EVALS = 40
_CANDIDATES = 12
_REFINED = 2
_SCAN = 100  # samples per side in the outward scan for a boundary
_MU_CAP = 1e6  # mu_s_min_path's own cap


# --------------------------------------------------------------------------------------------
# the body in physical terms
# --------------------------------------------------------------------------------------------


class Build(NamedTuple):
    """A body of the paper's model in physical terms: a thin shell of mass ``shell_mass`` and
    radius ``radius`` plus a rod of mass ``rod_mass`` at distance ``rod_position`` from the
    axis; total ``mass``, CM offset ``d`` and moment of inertia ``I_C`` about the axis."""

    radius: float
    mass: float
    shell_mass: float
    rod_mass: float
    rod_position: float
    d: float
    I_C: float


def build(body: Cylinder, *, radius: float = 1.0, mass: float = 1.0) -> Build:
    """``body`` built as the paper's shell plus rod, of radius ``radius`` and mass ``mass``
    (both finite and > 0; units of your choice, e.g. m and kg). The inverse of
    :meth:`Cylinder.from_shell_and_line` and :meth:`Cylinder.from_inertia`."""
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    R, M = _positive("radius", radius), _positive("mass", mass)
    km, chi = body.km, body.chi
    rho = 0.0 if km >= 1.0 else min(chi / (1.0 - km), 1.0)
    return Build(
        radius=R,
        mass=M,
        shell_mass=km * M,
        rod_mass=(1.0 - km) * M,
        rod_position=rho * R,
        d=chi * R,
        I_C=body.Ic * M * R * R,
    )


def _positive(name: str, value: object) -> float:
    v = real(name, value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} = {short(v)} is outside the allowed range (0, inf)")
    if not math.isfinite(v * v * v) or v * v * v == 0.0:  # R^2 M stays a normal number
        raise ValueError(f"{name} = {short(v)} is outside the allowed range [1e-100, 1e100]")
    return v


# --------------------------------------------------------------------------------------------
# results
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Margin:
    """The distance of one input from the nearest boundary of the verdict's region.

    ``lo``/``hi``: the boundaries below and above ``value`` (-inf/inf: none in the input's
    whole range); ``margin``: the distance to the nearer one (for mu_s: beyond the stated
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
    """One input moved by -error and +error (the others nominal, mu_s at its worst case):
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
    """The full motion at the design point under one rule (nominal mu_s, restitution 0):
    the first modes, and the first flight (NaN if none): lift-off angle [deg], apex of the
    axis above contact, distance along the ramp and duration (SI if the design has units:
    m and s; else R and sqrt(R/g))."""

    rule: str
    modes: tuple[str, ...]
    theta_liftoff_deg: float
    apex: float
    distance: float
    duration: float


@dataclass(frozen=True)
class Design:
    """A lab design (:func:`design`): print it (``str(d)`` or :meth:`sheet`) for the lab sheet,
    :meth:`to_dict` for JSON. Angles in radians except the ``*_deg`` fields."""

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

    @property
    def rod_position(self) -> float:
        """rho = r/R."""
        return self.build.rod_position / self.build.radius

    def margin(self, name: str) -> Margin:
        """The margin of ``"alpha"``, ``"mu_s"`` or ``"rod"``."""
        for m in self.margins:
            if m.name == name:
                return m
        raise ValueError(f"name = {short(name)}; use 'alpha', 'mu_s' or 'rod'")

    def to_dict(self) -> dict[str, Any]:
        """Everything on the sheet as JSON-ready data (NaN and infinities as None)."""
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
        }

    def sheet(self) -> str:
        """The lab sheet, as text."""
        return _sheet(self)

    def __str__(self) -> str:
        return self.sheet()


def _num(x: float) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _unit_names(si: bool) -> dict[str, str]:
    if si:
        return {"length": "m", "mass": "kg", "time": "s", "inertia": "kg m^2"}
    return {"length": "R", "mass": "M", "time": "sqrt(R/g)", "inertia": "M R^2"}


# --------------------------------------------------------------------------------------------
# verdicts
# --------------------------------------------------------------------------------------------


class _Spec(NamedTuple):
    """What a verdict is: the target, the turns the ramp allows, and (JARM) the turn n of
    the jump (None: any turn up to ``turns``)."""

    target: str
    turns: int
    n: int | None = None


def _classify(
    alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, mu: ArrayLike, spec: _Spec
) -> tuple[NDArray[np.bool_], list[Any]]:
    """(the verdict holds under both rules, the results per rule)."""
    size = max(np.size(x) for x in (alpha, chi, km, mu))
    threads = 1 if size < 1024 else 0  # a pool costs more than a few hundred points
    res = [
        jarm(
            alpha,
            chi,
            km,
            mu,
            spec.n,
            rule=r,
            max_turns=spec.turns,
            refine_extrema=False,
            n_threads=threads,
        )
        for r in RULES
    ]
    if spec.target == "jarm":
        ok = res[0].is_jarm & res[1].is_jarm
    else:
        ok = np.isin(res[0].reason, _SLIPS) & np.isin(res[1].reason, _SLIPS)
    return ok, res


def _holds(spec: _Spec) -> Callable[[ArrayLike, ArrayLike, ArrayLike, ArrayLike], NDArray]:
    def pred(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, mu: ArrayLike) -> NDArray:
        return _classify(alpha, chi, km, mu, spec)[0]

    return pred


def _boundaries(
    ok: Callable[[NDArray], NDArray], x0: float, lo_end: float, hi_end: float, tol: float
) -> tuple[float, float]:
    """The nearest points below and above ``x0`` (where ``ok`` holds) at which ``ok`` stops
    holding, within [lo_end, hi_end]: an outward scan of _SCAN samples per side (a gap
    narrower than a sample spacing can be missed), then bisection of both brackets together
    to ``tol``. -inf/inf where ``ok`` holds up to the end."""
    k = np.arange(1, _SCAN + 1) / _SCAN
    xs = np.concatenate([x0 - (x0 - lo_end) * k, x0 + (hi_end - x0) * k])
    good = ok(xs)
    brackets: list[list[float]] = []
    for side in (0, 1):
        g = good[side * _SCAN : (side + 1) * _SCAN]
        bad = np.flatnonzero(~g)
        if bad.size == 0 or (side == 0 and x0 == lo_end) or (side == 1 and x0 == hi_end):
            brackets.append([math.nan, math.nan])
        else:
            i = int(bad[0])
            inner = x0 if i == 0 else float(xs[side * _SCAN + i - 1])
            brackets.append([inner, float(xs[side * _SCAN + i])])
    live = [b for b in brackets if not math.isnan(b[0])]
    for _ in range(200):
        if not any(abs(b[1] - b[0]) > tol for b in live):
            break
        mids = np.array([0.5 * (b[0] + b[1]) for b in live])
        for b, m, g in zip(live, mids, ok(mids), strict=True):
            b[0 if g else 1] = float(m)
    lo = -math.inf if math.isnan(brackets[0][0]) else brackets[0][1]
    hi = math.inf if math.isnan(brackets[1][0]) else brackets[1][1]
    return lo, hi


def _relative(name: str, value: float, lo: float, hi: float) -> Margin:
    m = min(value - lo, hi - value)
    rel = m / value if value > 0 else (math.inf if m > 0 else 0.0)
    return Margin(name, value, lo, hi, m, rel)


def _margins(
    spec: _Spec, alpha: float, km: float, rho: float, mu: float, mu_err: float, tol: float
) -> tuple[Margin, ...] | None:
    """The three margins at a point, or None if the verdict fails there. A JARM's margins
    are those of a JARM on the same turn (the jump where the sheet predicts it)."""
    chi = rho * (1.0 - km)
    jump = spec.target == "jarm"
    worst = mu - mu_err if jump else mu + mu_err
    ok, res = _classify(alpha, chi, km, worst, spec)
    if not bool(ok):
        return None
    if jump:
        turns = {int(r.n) for r in res}
        if len(turns) != 1:  # the rules jump on different turns: not a clear design
            return None
        spec = spec._replace(n=turns.pop())
    holds = _holds(spec)
    # alpha: the JARM alpha-interval of the turn (both rules), or a scan for a slip
    if jump:
        ends = [
            alpha_interval_around(alpha, chi, km, worst, spec.n, rule=r, n_threads=1) for r in RULES
        ]
        a_lo = max(float(e[0]) for e in ends)
        a_hi = min(float(e[1]) for e in ends)
    else:
        a_lo, a_hi = _boundaries(lambda a: holds(a, chi, km, worst), alpha, 0.0, _HALF_PI, tol)
    # mu_s: JARM needs mu_s >= mu_min (no upper side); slip needs mu_s < mu_star
    if jump:
        mu_min = max(
            float(mu_s_min_path(alpha, chi, km, spec.n, rule=r, n_threads=1)) for r in RULES
        )
        m = worst - mu_min
        mu_m = Margin("mu_s", mu, mu_min, math.inf, m, m / mu)
    else:
        mu_star = _mu_star(holds, alpha, chi, km, worst, tol)
        m = mu_star - worst
        mu_m = Margin("mu_s", mu, 0.0, mu_star, m, m / mu)
    # rod position at fixed masses
    r_lo, r_hi = _boundaries(lambda r: holds(alpha, r * (1.0 - km), km, worst), rho, 0.0, 1.0, tol)
    return (_relative("alpha", alpha, a_lo, a_hi), mu_m, _relative("rod", rho, r_lo, r_hi))


def _mu_star(
    holds: Callable[..., NDArray], alpha: float, chi: float, km: float, mu: float, tol: float
) -> float:
    """The smallest mu_s >= mu at which the body no longer slips first (inf up to 1e6)."""
    lo, hi = mu, max(2.0 * mu, 1e-3)
    while bool(holds(alpha, chi, km, hi)):
        lo, hi = hi, 2.0 * hi
        if hi > _MU_CAP:
            return math.inf
    while hi - lo > tol * hi:
        mid = 0.5 * (lo + hi)
        if bool(holds(alpha, chi, km, mid)):
            lo = mid
        else:
            hi = mid
    return hi


def _score(margins: tuple[Margin, ...] | None) -> float:
    return -math.inf if margins is None else min(m.relative for m in margins)


# --------------------------------------------------------------------------------------------
# the search
# --------------------------------------------------------------------------------------------


def _range(name: str, value: object, lo: float, hi: float, unit: str = "") -> tuple[float, float]:
    pair = TypeError(f"{name} must be a pair (lo, hi) of real numbers")
    if isinstance(value, str | bytes | np.ma.MaskedArray):
        raise pair
    if isinstance(value, np.ndarray):
        if value.ndim != 1:
            raise pair
        items = list(value)
    elif isinstance(value, Sequence):
        items = list(value)
    else:
        raise pair
    if len(items) != 2:
        raise ValueError(f"{name} must be a pair (lo, hi), not {len(items)} values")
    a, b = real(name, items[0]), real(name, items[1])
    if not (lo <= a <= b <= hi):
        raise ValueError(
            f"{name} = ({short(a)}, {short(b)}) must satisfy {lo:g} <= lo <= hi <= {hi:g}{unit}"
        )
    return a, b


def _axis(lo: float, hi: float, n: int) -> NDArray[np.float64]:
    return np.array([lo]) if lo == hi else np.linspace(lo, hi, n)


def _run_lengths(ok: NDArray[np.bool_], axis: int) -> NDArray[np.float64]:
    """For each True cell: the grid distance to the nearest False cell along ``axis``
    (the grid's ends count as one step past them), minus one half."""
    ok = np.moveaxis(ok, axis, 0)
    n = ok.shape[0]
    down = np.zeros(ok.shape)
    up = np.zeros(ok.shape)
    run = np.zeros(ok.shape[1:])
    for i in range(n):
        run = np.where(ok[i], run + 1, 0)
        down[i] = run
    run = np.zeros(ok.shape[1:])
    for i in range(n - 1, -1, -1):
        run = np.where(ok[i], run + 1, 0)
        up[i] = run
    return np.moveaxis(np.minimum(down, up) - 0.5, 0, axis)


def design(
    alpha_range: Sequence[float],
    mu_s: float,
    mu_s_err: float = 0.0,
    *,
    target: Target = "jarm",
    body: Cylinder | None = None,
    km_range: Sequence[float] = (0.01, 0.9),
    rod_range: Sequence[float] = (0.05, 0.95),
    radius: float | None = None,
    mass: float | None = None,
    g: float = 9.81,
    max_turns: int = 10,
    error: float = 0.05,
    grid: int = 24,
) -> Design:
    """The body and ramp angle whose verdict is most robust (``docs/design.md``).

    Parameters
    ----------
    alpha_range : (lo, hi), the ramp angles the lab can set [rad], 0 <= lo <= hi <= pi/2.
    mu_s, mu_s_err : the surface pair's static friction coefficient and its uncertainty
        (0 <= mu_s_err < mu_s, mu_s finite).
    target : ``"jarm"`` (a jump straight out of pure rolling) or ``"slip"`` (a body that
        certainly slips before it lifts off: the control run).
    body : a fixed body (then only the angle is chosen), or None to choose the body with
        k_m in ``km_range`` (within [0, 1)) and rod position r/R in ``rod_range``
        (within [0, 1]).
    radius, mass : R [m] and M [kg] for the sheet in SI units (both or neither); g [m/s^2].
    max_turns : the turns the ramp allows (1 ... 1000): the lift-off (or slip) must come
        within them, i.e. within 2 pi R max_turns of rolling.
    error : the fractional error of each input in the sensitivity table, in (0, 0.5].
    grid : points per axis of the coarse search grid, 4 ... 64.

    The verdict must hold under both lift-off rules and for every mu_s within the
    uncertainty; the margins are taken at the worst mu_s. Raises ValueError (naming the
    parameter) for bad input and when no point of the grid has the verdict.
    """
    tgt = text("target", target)
    if tgt not in ("jarm", "slip"):
        raise ValueError(f"target = {short(tgt)}; use 'jarm' or 'slip'")
    a_lo, a_hi = _range("alpha_range", alpha_range, 0.0, _HALF_PI, " rad")
    mu = real("mu_s", mu_s)
    if not (math.isfinite(mu) and mu > 0):
        raise ValueError(f"mu_s = {short(mu)} is outside the allowed range (0, inf)")
    err = real("mu_s_err", mu_s_err)
    if not (0.0 <= err < mu):
        raise ValueError(f"mu_s_err = {short(err)} is outside the allowed range [0, mu_s)")
    if body is not None and not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder or None, not {type(body).__name__}")
    k_lo, k_hi = _range("km_range", km_range, 0.0, 1.0)
    if k_hi >= 1.0:
        raise ValueError(f"km_range = ({short(k_lo)}, {short(k_hi)}): hi must be below 1")
    r_lo, r_hi = _range("rod_range", rod_range, 0.0, 1.0)
    R, M = optional_real("radius", radius), optional_real("mass", mass)
    if (R is None) != (M is None):
        raise ValueError("radius and mass: give both (SI units) or neither")
    si = R is not None
    R = 1.0 if R is None else _positive("radius", R)
    M = 1.0 if M is None else _positive("mass", M)
    gg = _positive("g", g)
    e = real("error", error)
    if not (0.0 < e <= 0.5):
        raise ValueError(f"error = {short(e)} is outside the allowed range (0, 0.5]")
    n = integer("grid", grid, *GRID_RANGE)
    spec = _Spec(tgt, integer("max_turns", max_turns, 1, 1000))

    notes: list[str] = []
    if body is not None:
        if body.km >= 1.0:
            raise ValueError("body: km = 1 (all mass in the shell) is never a JARM nor a slip")
        rho = min(body.chi / (1.0 - body.km), 1.0)
        k_lo = k_hi = body.km
        r_lo = r_hi = rho
    worst = mu - err if tgt == "jarm" else mu + err

    # 1. coarse grid over the free axes
    free = sum(lo < hi for lo, hi in ((a_lo, a_hi), (k_lo, k_hi), (r_lo, r_hi)))
    per_axis = n if free >= 3 else min(512, round(n ** (3 / max(free, 1))))
    axes = [_axis(a_lo, a_hi, per_axis), _axis(k_lo, k_hi, per_axis), _axis(r_lo, r_hi, per_axis)]
    A, K, P = np.meshgrid(*axes, indexing="ij")
    C = P * (1.0 - K)
    ok = _holds(spec)(A, C, K, worst)
    evaluations = int(ok.size)
    if not ok.any():
        what = "gives a JARM" if tgt == "jarm" else "slips first"
        raise ValueError(
            f"no grid point in alpha_range, km_range, rod_range {what} under both rules within "
            f"max_turns at mu_s = {worst:.4g}; widen the ranges or raise grid"
        )
    idx = np.flatnonzero(ok.ravel())
    coarse = np.full(idx.size, math.inf)
    for ax, vals in ((0, A), (2, P)):
        if axes[ax].size > 1:
            h = axes[ax][1] - axes[ax][0]
            dist = _run_lengths(ok, ax).ravel()[idx] * h
            v = vals.ravel()[idx]
            coarse = np.minimum(coarse, np.where(v > 0, dist / np.maximum(v, 1e-300), 0.0))
    a_i, c_i, k_i = A.ravel()[idx], C.ravel()[idx], K.ravel()[idx]
    if tgt == "jarm":
        mu_min = np.maximum.reduce([mu_s_min_path(a_i, c_i, k_i, rule=r) for r in RULES])
        coarse = np.minimum(coarse, (worst - mu_min) / mu)
    else:  # a lower bound of the slip margin: the last level of mu_s it still slips at
        level_margin, alive = np.zeros(idx.size), np.ones(idx.size, dtype=bool)
        for f in (0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 4.0):
            alive &= _holds(spec)(a_i, c_i, k_i, worst + f * mu)
            level_margin = np.where(alive, f, level_margin)
        coarse = np.minimum(coarse, level_margin)
    order = np.lexsort((idx, -coarse))[:_CANDIDATES]

    # 2. exact margins at the best grid points, 3. compass search from the best few
    lows = np.array([a_lo, k_lo, r_lo])
    spans = np.array([a_hi - a_lo, k_hi - k_lo, r_hi - r_lo])
    cache: dict[tuple[float, ...], tuple[float, tuple[Margin, ...] | None]] = {}

    def evaluate(u: NDArray[np.float64], tol: float = 1e-5) -> float:
        u = np.clip(u, 0.0, 1.0)
        key = (*np.round(u, 12).tolist(), tol)
        if key not in cache:
            x = lows + u * spans
            ms = _margins(spec, float(x[0]), float(x[1]), float(x[2]), mu, err, tol)
            cache[key] = (_score(ms), ms)
        return cache[key][0]

    def to_u(i: int) -> NDArray[np.float64]:
        x = np.array([A.ravel()[i], K.ravel()[i], P.ravel()[i]])
        return np.where(spans > 0, (x - lows) / np.where(spans > 0, spans, 1.0), 0.0)

    starts = sorted(((evaluate(to_u(int(idx[j]))), j) for j in order), key=lambda t: (-t[0], t[1]))[
        :_REFINED
    ]
    best_u, best = to_u(int(idx[starts[0][1]])), starts[0][0]
    for s, j in starts:
        u, f = _compass(evaluate, to_u(int(idx[j])), s, spans, per_axis)
        if f > best:
            best_u, best = u, f
    x = lows + np.clip(best_u, 0.0, 1.0) * spans
    alpha, km, rho = float(x[0]), float(x[1]), float(x[2])
    final = _margins(spec, alpha, km, rho, mu, err, 1e-12)
    if final is None:  # pragma: no cover - the search only keeps points that hold
        raise ValueError("mu_s: the design lost its verdict at full precision; raise grid")
    evaluations += len(cache)

    # 4. the sheet
    chosen = Cylinder(min(rho * (1.0 - km), 1.0 - km), km)
    _, res = _classify(alpha, chosen.chi, km, mu, spec)
    theta_deg, reasons = {}, {}
    for r, one in zip(RULES, res, strict=True):
        reasons[r] = Reason(int(one.reason)).name
        theta_deg[r] = math.degrees(_angle(one, tgt))
    turn = int(res[0].n)
    b = build(chosen, radius=R, mass=M)
    flights = tuple(_flight(chosen, alpha, mu, r, tgt, b if si else None, gg) for r in RULES)
    if chosen.km == 0.0:
        notes.append("km = 0: the full motion is not simulated (the spin in flight is free)")
    sens = _sensitivity(spec, chosen, alpha, mu, err, b, e)
    return Design(
        target=tgt,
        body=chosen,
        alpha=alpha,
        mu_s=mu,
        mu_s_err=err,
        mu_s_worst=worst,
        build=b,
        si=si,
        g=gg,
        margins=final,
        score=_score(final),
        theta_deg=theta_deg,
        turn=turn,
        max_turns=spec.turns,
        reasons=reasons,
        flights=flights,
        sensitivity=sens,
        error=e,
        evaluations=evaluations,
        notes=tuple(notes),
    )


def _compass(
    evaluate: Callable[[NDArray[np.float64]], float],
    u: NDArray[np.float64],
    f: float,
    spans: NDArray[np.float64],
    per_axis: int,
) -> tuple[NDArray[np.float64], float]:
    """Deterministic compass search (maximising ``evaluate`` on the unit cube of the free
    axes): try a step each way along each free axis, move to the best improvement, else
    halve the step; from one grid spacing down to 1/64 of it, at most _MAX_EVALS calls."""
    free = [i for i in range(3) if spans[i] > 0]
    step = 1.0 / max(per_axis - 1, 1)
    stop, calls = step / 64, 0
    while free and step >= stop and calls < _MAX_EVALS:
        trial = []
        for i in free:
            for sign in (-1.0, 1.0):
                v = u.copy()
                v[i] = min(1.0, max(0.0, v[i] + sign * step))
                if v[i] != u[i]:
                    trial.append((evaluate(v), i, sign, v))
                    calls += 1
        better = [t for t in trial if t[0] > f]
        if better:
            f, _, _, u = max(better, key=lambda t: (t[0], -t[1], -t[2]))
        else:
            step /= 2
    return u, f


def _flight(
    body: Cylinder, alpha: float, mu: float, rule: str, target: str, b: Build | None, g: float
) -> Flight:
    nan = math.nan
    if body.km == 0.0:
        return Flight(rule, (), nan, nan, nan, nan)
    run = simulate(
        body, alpha, mu_s=mu, rule=rule, max_transitions=2 if target == "jarm" else 4, t_max=1e4
    )
    modes = tuple(run.mode_names())
    if not run.flights:
        return Flight(rule, modes, nan, nan, nan, nan)
    f = run.flights[0]
    length, time = (b.radius, math.sqrt(b.radius / g)) if b is not None else (1.0, 1.0)
    return Flight(
        rule,
        modes,
        math.degrees(f.theta_liftoff),
        f.apex * length,
        f.distance * length,
        (f.t_landing - f.t_liftoff) * time,
    )


_SHORT = {
    "JARM": "JARM",
    "NO_ROOT": "no lift-off",
    "LIFTOFF_EARLIER": "lift-off earlier",
    "NORMAL_FORCE_LOST": "Fy lost",
    "SLIP_BEFORE": "slips",
    "SLIP_AT_JUMP": "slips at jump",
    "ROCKS_BACK": "rocks back",
    "TURN_LIMIT": "turn limit",
    "INVALID_PARAMS": "invalid",
}


def _angle(one: Any, target: str, i: Any = ()) -> float:
    """The angle of the deciding event of a classification (lift-off for a JARM, else the
    failure: the slip for a slip)."""
    th = float(one.theta_J[i]) if target == "jarm" and bool(one.is_jarm[i]) else math.nan
    if math.isnan(th):
        th = float(one.theta_event[i])
    return th if math.isfinite(th) else float(one.theta_J[i])


def _sensitivity(
    spec: _Spec, body: Cylinder, alpha: float, mu: float, err: float, b: Build, e: float
) -> tuple[Sensitivity, ...]:
    """Each input moved by -e and +e (the others nominal), re-classified at the worst mu_s.
    The body inputs are converted by the core's own constructors (an input that makes the
    body impossible gives the verdict "impossible body")."""
    target = spec.target
    sign = -1.0 if target == "jarm" else 1.0
    worst = mu + sign * err
    chi, km = body.chi, body.km
    R, M, mc, mp, r, d, ic = (
        b.radius,
        b.mass,
        b.shell_mass,
        b.rod_mass,
        b.rod_position,
        b.d,
        b.I_C,
    )

    def shell(m_c: float, m_p: float, radius: float, rod: float) -> Cylinder:
        return Cylinder.from_shell_and_line(m_c, m_p, radius, m_p * rod / (m_c + m_p))

    rows: list[tuple[str, str, float, Callable[[float], tuple[float, float, float, float]]]] = [
        (
            "ramp angle alpha",
            "deg",
            math.degrees(alpha),
            lambda v: (math.radians(v), chi, km, worst),
        ),
        ("friction mu_s", "", mu, lambda v: (alpha, chi, km, v + sign * err)),
    ]

    def via(make: Callable[[float], Cylinder]) -> Callable[[float], tuple[float, ...]]:
        def point(v: float) -> tuple[float, float, float, float]:
            c = make(v)
            return (alpha, c.chi, c.km, worst)

        return point

    rows += [
        ("rod position r", "L", r, via(lambda v: shell(mc, mp, R, v))),
        ("rod mass m_P", "M", mp, via(lambda v: shell(mc, v, R, r))),
        ("shell mass m_C", "M", mc, via(lambda v: shell(v, mp, R, r))),
        ("radius R (built)", "L", R, via(lambda v: shell(mc, mp, v, r))),
        ("CM offset d", "L", d, via(lambda v: Cylinder.from_inertia(M, R, v, ic))),
        ("inertia I_C", "I", ic, via(lambda v: Cylinder.from_inertia(M, R, d, v))),
        ("mass M (measured)", "M", M, via(lambda v: Cylinder.from_inertia(v, R, d, ic))),
        ("radius R (measured)", "L", R, via(lambda v: Cylinder.from_inertia(M, v, d, ic))),
    ]
    points: list[tuple[float, float, float, float]] = []
    where: list[int | None] = []
    for _, _, nominal, fn in rows:
        for s in (-1.0, 1.0):
            try:
                p = fn(nominal * (1.0 + s * e))
            except ValueError:
                where.append(None)
                continue
            where.append(len(points))
            points.append(p)
    arr = np.array(points, dtype=float).reshape(-1, 4)
    holds, res = _classify(arr[:, 0], arr[:, 1], arr[:, 2], arr[:, 3], spec)
    out = []
    for k, (name, unit, nominal, _) in enumerate(rows):
        cells: list[tuple[str, float]] = []
        for w in where[2 * k : 2 * k + 2]:
            if w is None:
                cells.append(("impossible body", math.nan))
                continue
            th = _angle(res[0], target, w)
            if holds[w]:
                cells.append(("kept", math.degrees(th)))
            else:
                p_, n_ = (_SHORT[Reason(int(x.reason[w])).name] for x in res)
                cells.append((f"LOST ({p_} / {n_})", math.degrees(th)))
        out.append(
            Sensitivity(name, unit, nominal, cells[0][0], cells[1][0], cells[0][1], cells[1][1])
        )
    return tuple(out)


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
