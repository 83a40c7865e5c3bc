"""The search for the most robust design (coarse grid, exact margins, compass search)."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump._base.checks import Rule, integer, optional_real, real, short, text
from eccjump._base.docs import fill
from eccjump._base.progress import Progress, checked, reporting
from eccjump._base.units import FOR_DEGREES
from eccjump.classification.boundary import mu_s_min_path
from eccjump.classification.fields import Reason
from eccjump.motion.simulation import simulate
from eccjump.studies.design._common import (
    _CANDIDATES,
    _HALF_PI,
    _MAX_EVALS,
    _REFINED,
    GRID_RANGE,
    RULES,
    Target,
)
from eccjump.studies.design.margins import _classify, _holds, _margins, _score, _Spec
from eccjump.studies.design.physical import Build, _positive, build
from eccjump.studies.design.probability import apex, best, tolerance_spread
from eccjump.studies.design.results import Design, Flight, Margin, PJarm, Sensitivity
from eccjump.studies.design.target import check_p_target, reach


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


@fill
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
    min_apex: float = 0.0,
    tolerances: Mapping[str, float] | None = None,
    maximise: Literal["margin", "probability"] = "margin",
    samples: int = 10_000,
    seed: int = 0,
    p_target: float | None = None,
    progress: bool | Progress | None = None,
) -> Design:
    """The body and ramp angle whose verdict is most robust, with a printable lab sheet.

    The design space is the ramp angle, the shell mass fraction k_m and the rod position
    r/R of the paper's shell-plus-rod body. The verdict must hold under both lift-off rules
    and for every μ_s within the uncertainty; the margins -- distances to the exact
    boundaries of the verdict's region in α, μ_s and r/R -- are taken at the worst
    μ_s, and the design maximises the smallest relative margin (a coarse grid, then a
    deterministic compass search).

    Parameters
    ----------
    alpha_range : sequence of two floats
        (lo, hi), the ramp angles the lab can set [rad], 0 ≤ lo ≤ hi ≤ π/2.
    mu_s : float
        The surface pair's static friction coefficient, finite and > 0.
    mu_s_err : float, default 0.0
        Its uncertainty, in [0, μ_s).
    target : {"jarm", "slip"}, default "jarm"
        ``"jarm"``: a jump straight out of pure rolling; ``"slip"``: a body that certainly
        slips before it lifts off (the control run).
    body : Cylinder or None, default None
        A fixed body (then only the angle is chosen), or None to choose the body.
    km_range : sequence of two floats, default (0.01, 0.9)
        The range of k_m searched, within [0, 1).
    rod_range : sequence of two floats, default (0.05, 0.95)
        The range of the rod position r/R searched, within [0, 1].
    radius : float or None, default None
        R [m] for a sheet in SI units (with ``mass``; both or neither).
    mass : float or None, default None
        M [kg] for a sheet in SI units (with ``radius``).
    g : float, default 9.81
        Gravitational acceleration [m/s²] for the SI sheet.
    max_turns : int, default 10
        The turns the ramp allows, 1 ... 1000: the lift-off (or slip) must come within
        them, i.e. within 2π R max_turns of rolling.
    error : float, default 0.05
        The fractional error of each input in the sensitivity table, in (0, 0.5].
    grid : int, default 24
        Points per axis of the coarse search grid, 4 ... 64.
    min_apex : float, default 0.0
        The least apex of the first flight (the gap to the ramp, under both rules, at the
        nominal μ_s) [R, or m with ``radius``], in [0, 10 R]: ask for a jump you can see.
        0 asks for none (a JARM's first flight is often below 0.01 R); target "jarm" only.
    tolerances : mapping of str to float or None, default None
        The lab's tolerances as normal standard deviations by name, among ``chi``, ``km``,
        ``alpha`` [rad] and ``mu_s`` (as in :func:`eccjump.uncertainty`): the design then
        reports ``p_success``, the probability that a body built to it keeps the verdict
        (under both rules, within ``max_turns``, with ``min_apex``), from ``samples``
        random samples truncated to the physical range (needs scipy: ``eccjump[analysis]``).
    maximise : {"margin", "probability"}, default "margin"
        What the design maximises: the smallest relative margin, or (with ``tolerances``)
        ``p_success``, compared on the same samples over the best grid points and the
        refined designs (a choice among candidates, not a search of its own).
    samples : int, default 10_000
        Samples per probability, 100 ... 10**6.
    seed : int, default 0
        The seed of the samples (the same for every candidate), ≥ 0.
    p_target : float or None, default None
        With ``tolerances`` and target "jarm": the P(JARM) the design must reach, in (0, 1).
        The candidates (those of ``maximise="probability"``) are scored in one batch by
        P(JARM) as :func:`eccjump.uncertainty` computes it (``samples`` samples of
        ``seed``), the lower of the two rules' values; the design is the best-margin
        candidate (the most likely one with ``maximise="probability"``) whose 95 % Wilson
        lower bound is at least ``p_target``, reported as ``p_jarm``. A ValueError, with
        the best P(JARM) found, when no candidate reaches it.
    progress : bool, callable or None, default None
        Progress of the search, in stages (the grid, the search, the probabilities with
        ``tolerances``, the sheet): None or False, none; True, a bar on stderr (tqdm); a
        callable, called as ``progress(done, total)`` after each stage. The design is the
        same either way.

    Returns
    -------
    Design
        The body, the angle, the margins, the lift-off angles, the first flight and the
        sensitivity table; ``str(design)`` is the lab sheet.

    Raises
    ------
    ValueError
        For bad input (naming the parameter and its range), when no point of the grid
        has the verdict, and when no candidate reaches ``p_target``.
    %(type_error)s

    Examples
    --------
    >>> import math
    >>> import eccjump
    >>> d = eccjump.design([math.radians(10), math.radians(40)], 0.6, 0.1, grid=8)
    >>> d.target, d.reasons
    ('jarm', {'paper': 'JARM', 'normal_force': 'JARM'})
    >>> bool(d.margin("alpha").relative > 0.05)
    True
    >>> print(str(d).splitlines()[0])
    eccjump design: a JARM: a jump straight out of pure rolling
    """
    tgt = text("target", target)
    if tgt not in ("jarm", "slip"):
        raise ValueError(f"target = {short(tgt)}; use 'jarm' or 'slip'")
    a_lo, a_hi = _range("alpha_range", alpha_range, 0.0, _HALF_PI, f" rad ({FOR_DEGREES})")
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
    apex_min = real("min_apex", min_apex) / R
    if not (0.0 <= apex_min <= 10.0):
        raise ValueError(
            f"min_apex = {short(min_apex)} is outside the allowed range [0, 10] R"
            + (" (in m: radius given)" if si else "")
        )
    if apex_min > 0 and tgt != "jarm":
        raise ValueError("min_apex: only a JARM design (target='jarm') has a flight to ask for")
    spec = _Spec(tgt, integer("max_turns", max_turns, 1, 1000))
    odds = _odds_options(tolerances, maximise, samples, seed, mu)
    goal = check_p_target(p_target, tolerances, tgt)
    checked(progress)

    stages = 3 if odds is None else 4  # the grid, the search, (the odds,) the sheet
    with reporting(progress, "stage", unit_scale=False) as report:
        stage = _stage_reporter(report, stages)
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
        axes = [
            _axis(a_lo, a_hi, per_axis),
            _axis(k_lo, k_hi, per_axis),
            _axis(r_lo, r_hi, per_axis),
        ]
        A, K, P = np.meshgrid(*axes, indexing="ij")
        C = P * (1.0 - K)
        ok = _holds(spec)(A, C, K, worst)
        evaluations = int(ok.size)
        if apex_min > 0:
            ok[ok] = apex(A[ok], C[ok], K[ok], mu) >= apex_min
        if not ok.any():
            what = "gives a JARM" if tgt == "jarm" else "slips first"
            if apex_min > 0:
                what += f" with an apex of at least {apex_min:.3g} R"
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
        stage(1)

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
                if apex_min > 0 and ms is not None:
                    c = x[2] * (1.0 - x[1])
                    ms = ms if apex(x[:1], np.array([c]), x[1:2], mu)[0] >= apex_min else None
                cache[key] = (_score(ms), ms)
            return cache[key][0]

        def to_u(i: int) -> NDArray[np.float64]:
            x = np.array([A.ravel()[i], K.ravel()[i], P.ravel()[i]])
            return np.where(spans > 0, (x - lows) / np.where(spans > 0, spans, 1.0), 0.0)

        starts = sorted(
            ((evaluate(to_u(int(idx[j]))), j) for j in order), key=lambda t: (-t[0], t[1])
        )[:_REFINED]
        refined = [_compass(evaluate, to_u(int(idx[j])), s, spans, per_axis) for s, j in starts]
        best_u = max(refined, key=lambda uf: uf[1])[0]  # the first of equals, as before
        x = lows + np.clip(best_u, 0.0, 1.0) * spans
        stage(2)
        success = None
        chance: PJarm | None = None
        if odds is not None:
            tol, n_samples, seed_, by_odds = odds
            # the refined designs, then the grid's best points that hold, best margin first
            us = [u for u, _ in sorted(refined, key=lambda uf: -uf[1])]
            us += [to_u(int(idx[j])) for j in order if evaluate(to_u(int(idx[j]))) > 0]
            some = us if by_odds or goal is not None else us[:1]
            xs = [lows + np.clip(u, 0.0, 1.0) * spans for u in some]
            cands = [(float(c[0]), float(c[1]), float(c[2] * (1.0 - c[1]))) for c in xs]
            if goal is not None:  # only the candidate that reaches the target goes on
                got, chance = reach(_bodies(cands), tol, mu, n_samples, seed_, goal, by_odds)
                xs, cands = [xs[got]], [cands[got]]
            pick, all_odds = best(spec, cands, tol, mu, n_samples, seed_, apex_min)
            x, success = xs[pick], all_odds[pick]
            stage(3)
        alpha, km, rho = float(x[0]), float(x[1]), float(x[2])
        final = _margins(spec, alpha, km, rho, mu, err, 1e-12)
        if final is None:  # pragma: no cover - the search only keeps points that hold
            raise ValueError("mu_s: the design lost its verdict at full precision; raise grid")
        evaluations += len(cache)

        # 4. the sheet
        chosen = Cylinder(min(rho * (1.0 - km), 1.0 - km), km)
        _, res = _classify(alpha, chosen.chi, km, mu, spec)
        theta_deg: dict[str, float] = {}
        reasons: dict[str, str] = {}
        for r, one in zip(RULES, res, strict=True):
            reasons[r] = Reason(int(one.reason)).name
            theta_deg[r] = math.degrees(_angle(one, tgt))
        turn = int(res[0].n)
        b = build(chosen, radius=R, mass=M)
        flights = tuple(_flight(chosen, alpha, mu, r, tgt, b if si else None, gg) for r in RULES)
        if chosen.km == 0.0:
            notes.append("km = 0: the full motion is not simulated (the spin in flight is free)")
        notes += _on_edges(
            ((a_lo, a_hi, alpha, "alpha"), (k_lo, k_hi, km, "km"), (r_lo, r_hi, rho, "rod"))
        )
        sens = _sensitivity(spec, chosen, alpha, mu, err, b, e)
        stage(stages)
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
            tolerances=None if odds is None else dict(odds[0]),
            p_success=success,
            p_target=goal,
            p_jarm=chance,
        )


def _bodies(cands: Sequence[tuple[float, float, float]]) -> list[tuple[float, float, float]]:
    """The candidates (α, k_m, χ) with χ as the sheet builds the chosen body (the same
    floats: its P(JARM) is that of the body on the sheet)."""
    return [(a, k, min(c, 1.0 - k)) for a, k, c in cands]


def _stage_reporter(report: Progress | None, stages: int) -> Callable[[int], None]:
    """``stage(k)``: report that ``k`` of the design's ``stages`` are done (nothing without a
    reporter); stage 0 is reported at once."""

    def stage(k: int) -> None:
        if report is not None:
            report(k, stages)

    stage(0)
    return stage


def _odds_options(
    tolerances: object, maximise: object, samples: object, seed: object, mu: float
) -> tuple[dict[str, float], int, int, bool] | None:
    """The checked tolerances, sample size and seed, and whether the design maximises its
    probability of success (None without tolerances)."""
    how = text("maximise", maximise)
    if how not in ("margin", "probability"):
        raise ValueError(f"maximise must be 'margin' or 'probability', not {short(how)}")
    n = integer("samples", samples, 100, 10**6)
    s = integer("seed", seed, 0, 2**64 - 1)
    if tolerances is None:
        if how == "probability":
            raise ValueError("maximise='probability' needs tolerances (sd by parameter name)")
        return None
    # checked by name and value here, around a placeholder design
    tol = tolerance_spread(tolerances, 0.5, 0.1, 0.1, mu).sd
    return tol, n, s, how == "probability"


_RANGE_OF = {"alpha": "alpha_range", "km": "km_range", "rod": "rod_range"}


def _on_edges(axes: Sequence[tuple[float, float, float, str]]) -> list[str]:
    """A note for each free input (lo < hi) the design put at an end of its range: the most
    robust design may lie beyond it."""
    notes = []
    for lo, hi, x, name in axes:
        if lo < hi and (x - lo <= 1e-9 * (hi - lo) or hi - x <= 1e-9 * (hi - lo)):
            end = "lower" if x - lo <= hi - x else "upper"
            notes.append(
                f"{name} = {x:.6g} is the {end} end of {_RANGE_OF[name]}: a more robust "
                "design may lie beyond it (widen the range if you can build it)"
            )
    return notes


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
    body: Cylinder, alpha: float, mu: float, rule: Rule, target: str, b: Build | None, g: float
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
    "SLIP": "slips",
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
    """Each input moved by -e and +e (the others nominal), re-classified at the worst μ_s.
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

    def via(
        make: Callable[[float], Cylinder],
    ) -> Callable[[float], tuple[float, float, float, float]]:
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
