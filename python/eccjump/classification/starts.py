"""Initial conditions: how the JARM region depends on the start (theta0, omega0), and which
start maximises it (the paper's open question; the user guide's "Initial conditions" page).

The measure. For a start, the *JARM fraction* is the share of JARM points on the midpoint
grid of the unit cube of (α / (π/2), χ, km_frac), ``grid`` points per axis:
alpha_i = (i + 1/2) π / (2 grid), chi_j = (j + 1/2) / grid, km_frac_l = (l + 1/2) / grid,
k_m = km_frac (1 - χ) -- uniform in α, χ and the k_m fraction, the grid of
:func:`eccjump.region`. It converges to the volume fraction of the JARM set in that cube
(midpoint rule) as the grid is refined.

The start. The motion depends on theta0 only modulo 2π (the ramp is a translation
symmetry), so every function here takes theta0 modulo 2π, into [0, 2π) (the turns of the
classification count from there). omega0 ≥ 0 rolls down the ramp.

Everything runs in the Rust core (:func:`eccjump.region`); :func:`optimal_start` needs scipy
(``pip install eccjump[analysis]``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump._base.arrays import axis
from eccjump._base.canvas import Plottable
from eccjump._base.checks import U64_MAX, Rule, integer, real, rule_name, short
from eccjump._base.docs import fill
from eccjump._base.html import card, deg, num, span
from eccjump._base.progress import Progress, reporting
from eccjump.classification.classify import region
from eccjump.classification.fields import Reason

TWO_PI = 2.0 * math.pi
#: The largest grid (points per axis of the parameter cube): 128**3 = 2.1e6 points per start.
GRID_MAX = 128
#: The largest number of starts of one :func:`start_map`.
STARTS_MAX = 10_000
#: The largest |theta0| (as the core: beyond, an ulp of theta0 approaches its steps).
THETA0_MAX = TWO_PI * 1e6
#: The largest omega0 (as the core).
OMEGA0_MAX = 1e6
#: Bound of :func:`optimal_start`'s evaluations (each one a map of grid**3 points).
EVALUATIONS_MAX = 100_000
#: The range of ``omega_max`` of :func:`optimal_start` [sqrt(g/R) rad]. The search keys its
#: starts by omega0 rounded to 12 decimals and steps in units of the lattice's step
#: omega_max / (n_omega - 1) (n_omega <= 1000): below 1e-6 the steps no longer resolve
#: (omega_max = 5e-324 made the step 0, a ZeroDivisionError), and every start is rest anyway.
OMEGA_MAX_RANGE = (1e-6, 100.0)
N_REASONS = len(Reason)


def _midpoints(grid: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The (α, χ, km_frac) axes of the midpoint grid with ``grid`` points per axis."""
    g = integer("grid", grid, 2, GRID_MAX)
    u = (np.arange(g, dtype=np.float64) + 0.5) / g
    return u * (math.pi / 2), u.copy(), u.copy()


def _theta0(theta0: object) -> float:
    """``theta0`` [rad] modulo 2π, in [0, 2π) (finite, |theta0| ≤ 2π 1e6)."""
    th = real("theta0", theta0)
    if not (math.isfinite(th) and abs(th) <= THETA0_MAX):
        raise ValueError(f"theta0 = {short(th)} is outside the allowed range [-2pi 1e6, 2pi 1e6]")
    r = math.fmod(th, TWO_PI)
    r = r + TWO_PI if r < 0 else r
    return 0.0 if r >= TWO_PI else r  # fmod of a tiny negative number can round up to 2 pi


def _omega0(omega0: object) -> float:
    om = real("omega0", omega0)
    if not (0.0 <= om <= OMEGA0_MAX):  # NaN fails too
        raise ValueError(f"omega0 = {short(om)} is outside the allowed range [0, 1e6]")
    return om


def _mu(mu_s: object) -> float:
    mu = real("mu_s", mu_s)
    if not (0.0 <= mu < math.inf):
        raise ValueError(f"mu_s = {short(mu)} is outside the allowed range [0, inf)")
    return mu


def _shares(
    mu: float, theta0: float, omega0: float, grid: int, rule: Rule, n_threads: int
) -> NDArray[np.float64]:
    a, c, f = _midpoints(grid)
    reg = region(mu_s=mu, alpha=a, chi=c, km_frac=f, theta0=theta0, omega0=omega0, rule=rule,
                 n_threads=n_threads)  # fmt: skip
    counts = np.bincount(reg.result.reason.ravel().astype(np.intp), minlength=N_REASONS)
    return counts[:N_REASONS] / reg.result.reason.size


@fill
def reason_shares(
    mu_s: float,
    theta0: float = 0.0,
    omega0: float = 0.0,
    *,
    grid: int = 40,
    rule: Rule = "paper",
    n_threads: int = 0,
) -> dict[Reason, float]:
    """The share of every :class:`Reason` over the parameter cube for the start
    (theta0, omega0).

    The cube of (α / (π/2), χ, km_frac) is sampled on its midpoint grid of ``grid``
    points per axis (see the module's docstring). What blocks a JARM at a start:
    ``LIFTOFF_EARLIER`` is the immediate flight (paper's rule: χ omega0² cos theta0 > cos
    α, it leaves the ramp at theta0), ``ROCKS_BACK`` a start that rolls back up the ramp
    (omega reaches 0) before any event.

    Parameters
    ----------
    %(mu_s)s
    %(theta0_modulo)s
    %(omega0)s
    %(grid_starts)s
    %(rule_short)s
    %(n_threads)s

    Returns
    -------
    dict of Reason to float
        The share of each reason (every member, 0 for those not met); the shares sum to 1
        and ``[Reason.JARM]`` is :func:`jarm_fraction`.

    Raises
    ------
    ValueError
        For a parameter out of its range (the message names it).

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> shares = eccjump.reason_shares(1.0, grid=16)
    >>> {r.name: round(s, 4) for r, s in shares.items() if s}
    {'JARM': 0.0054, 'SLIP_BEFORE': 0.8457, 'SLIP_AT_JUMP': 0.1489}
    """
    mu, th, om = _mu(mu_s), _theta0(theta0), _omega0(omega0)
    s = _shares(mu, th, om, grid, rule_name(rule), _threads(n_threads))
    return {r: float(s[r.value]) for r in Reason}


@fill
def jarm_fraction(
    mu_s: float,
    theta0: float = 0.0,
    omega0: float = 0.0,
    *,
    grid: int = 40,
    rule: Rule = "paper",
    n_threads: int = 0,
) -> float:
    """The JARM fraction of the parameter cube for the start (theta0, omega0).

    The share of JARM points on the midpoint grid of (α, χ, km_frac) with ``grid``
    points per axis. At theta0 = omega0 = 0 it equals
    ``eccjump.region(alpha, chi, km_frac, mu_s).fraction()`` on the same grid.

    Parameters
    ----------
    %(mu_s)s
    %(theta0_modulo)s
    %(omega0)s
    %(grid_starts)s
    %(rule_short)s
    %(n_threads)s

    Returns
    -------
    float
        The fraction, in [0, 1].

    Raises
    ------
    ValueError
        For a parameter out of its range (the message names it).

    Examples
    --------
    From rest, and from the best start (theta0 about 271 deg, omega0 about 1):

    >>> import numpy as np
    >>> import eccjump
    >>> print(f"{eccjump.jarm_fraction(1.0, grid=16):.4f}")
    0.0054
    >>> print(f"{eccjump.jarm_fraction(1.0, np.radians(271), 1.0, grid=16):.4f}")
    0.2722
    """
    return reason_shares(mu_s, theta0, omega0, grid=grid, rule=rule, n_threads=n_threads)[
        Reason.JARM
    ]


def _threads(n_threads: object) -> int:
    return integer("n_threads", n_threads, 0, U64_MAX)


@dataclass(frozen=True, eq=False)
class StartMap(Plottable):
    """The reason shares over a lattice of starts (:func:`start_map`).

    Attributes
    ----------
    theta0 : numpy.ndarray
        The starts' angles [rad], taken modulo 2π, 1-D.
    omega0 : numpy.ndarray
        The starts' angular velocities [√(g/R) rad], 1-D.
    shares : numpy.ndarray
        ``shares[i, j, r]`` is the share of reason code r for the start (theta0[i],
        omega0[j]), shape (len(theta0), len(omega0), number of reasons).
    mu_s : float
        Static friction coefficient.
    grid : int
        Points per axis of the parameter cube's midpoint grid.
    rule : str
        Lift-off rule.
    """

    theta0: NDArray[np.float64]
    omega0: NDArray[np.float64]
    shares: NDArray[np.float64]
    mu_s: float
    grid: int
    rule: str

    @property
    def fraction(self) -> NDArray[np.float64]:
        """The JARM fraction, shape (len(theta0), len(omega0))."""
        return self.shares[..., Reason.JARM.value]

    @property
    def immediate_flight(self) -> NDArray[np.float64]:
        """The share of parameters that leave the ramp at the start (LIFTOFF_EARLIER)."""
        return self.shares[..., Reason.LIFTOFF_EARLIER.value]

    @property
    def rocks_back(self) -> NDArray[np.float64]:
        """The share of parameters that roll back before any event (ROCKS_BACK)."""
        return self.shares[..., Reason.ROCKS_BACK.value]

    @property
    def impossible(self) -> NDArray[np.bool_]:
        """Starts with no JARM anywhere on the grid."""
        return self.fraction == 0.0

    def best(self) -> tuple[float, float, float]:
        """The lattice start with the largest JARM fraction.

        Returns
        -------
        tuple of float
            (theta0 [rad], omega0 [√(g/R) rad], fraction).
        """
        i, j = np.unravel_index(int(np.argmax(self.fraction)), self.fraction.shape)
        return float(self.theta0[i]), float(self.omega0[j]), float(self.fraction[i, j])

    def __repr__(self) -> str:
        th, om, f = self.best()
        return (
            f"StartMap({self.theta0.size} x {self.omega0.size} starts, mu_s={self.mu_s:g}, "
            f"grid={self.grid}, rule={self.rule}; best {f:.6g} at theta0={th:.6g}, "
            f"omega0={om:.6g})"
        )

    def _repr_html_(self) -> str:
        th, om, f = self.best()
        rows = [
            ("theta0", span(np.degrees(self.theta0), " deg")),
            ("omega0", span(self.omega0, " sqrt(g/R)")),
            ("made with", f"mu_s = {self.mu_s:g}, grid = {self.grid}, rule = {self.rule}"),
            ("best start", f"theta0 = {deg(th)}, omega0 = {num(om)}: JARM fraction {f:.4g}"),
        ]
        return card("StartMap", rows)

    _plot_doc = """The JARM fraction over the starts (theta0, omega0) and the shares blocked at
    the start (``eccjump.plot.fraction_map``). ``ax=``: only the JARM fraction, drawn into
    this matplotlib Axes and returned (``eccjump.plot.fraction_panel``), to compose
    figures; ``fig=``: the full figure in this empty Figure or SubFigure. ``kwargs`` go
    to the function drawn. Needs ``pip install eccjump[plot]``."""


@fill
def start_map(
    mu_s: float,
    theta0: ArrayLike,
    omega0: ArrayLike,
    *,
    grid: int = 24,
    rule: Rule = "paper",
    n_threads: int = 0,
    progress: bool | Progress | None = None,
) -> StartMap:
    """The reason shares (and the JARM fraction) for every start of the lattice
    ``theta0`` x ``omega0``.

    Each start is a map of the parameter cube on its midpoint grid of ``grid`` points per
    axis, as :func:`reason_shares`.

    Parameters
    ----------
    %(mu_s)s
    theta0 : array_like of float, 1-D
        Initial angles [rad], |theta0| ≤ 2π 1e6, taken modulo 2π.
    omega0 : array_like of float, 1-D
        Initial angular velocities [√(g/R) rad], in [0, 1e6]; at most 10**4 starts in
        all.
    grid : int, default 24
        Points per axis of the midpoint grid of (α, χ, km_frac), 2 ... 128.
    %(rule_short)s
    %(n_threads)s
    progress : bool, callable or None, default None
        Progress of the work, in starts: None or False, none; True, a bar on stderr
        (tqdm); a callable, called as ``progress(done, total)`` after each start.

    Returns
    -------
    StartMap

    Raises
    ------
    ValueError
        For a parameter out of its range or more than 10**4 starts.
    TypeError
        If ``progress`` is not None, a bool or a callable.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.start_map(1.0, np.radians([0, 90, 180, 270]), [0.0, 1.0], grid=8)
    >>> m.fraction.round(4)
    array([[0.0039, 0.002 ],
           [0.0273, 0.0098],
           [0.0527, 0.1172],
           [0.1758, 0.2715]])
    """
    mu = _mu(mu_s)
    th = axis("theta0", theta0)
    om = axis("omega0", omega0)
    if th.size * om.size > STARTS_MAX or th.size == 0 or om.size == 0:
        raise ValueError(
            f"theta0 x omega0 has {th.size} x {om.size} starts; allowed 1 ... {STARTS_MAX}"
        )
    ths = [_theta0(float(x)) for x in th]
    oms = [_omega0(float(x)) for x in om]
    g = integer("grid", grid, 2, GRID_MAX)
    r, nt = rule_name(rule), _threads(n_threads)
    shares = np.empty((th.size, om.size, N_REASONS))
    total = th.size * om.size
    with reporting(progress, "start", unit_scale=False) as report:
        for i, t in enumerate(ths):
            for j, o in enumerate(oms):
                shares[i, j] = _shares(mu, t, o, g, r, nt)
                if report is not None:
                    report(i * om.size + j + 1, total)
    return StartMap(
        theta0=np.array(ths), omega0=np.array(oms), shares=shares, mu_s=mu, grid=g, rule=r
    )


@dataclass(frozen=True)
class OptimalStart:
    """The start that maximises the JARM fraction (:func:`optimal_start`).

    Attributes
    ----------
    mu_s : float
        Static friction coefficient.
    rule : str
        Lift-off rule.
    grid : int
        Points per axis of the coarse grid (the fine grid has 2 grid).
    omega_max : float
        Largest omega0 searched [√(g/R) rad].
    theta0 : float
        The optimum's angle on the fine grid [rad], in [0, 2π) -- the answer.
    omega0 : float
        The optimum's angular velocity on the fine grid [√(g/R) rad].
    fraction : float
        The JARM fraction there, on the fine grid.
    theta0_coarse : float
        The optimum on the coarse grid [rad].
    omega0_coarse : float
        The optimum on the coarse grid [√(g/R) rad].
    fraction_coarse : float
        The JARM fraction there, on the coarse grid.
    theta0_err : float
        Uncertainty of theta0 from the grid resolution: the difference of the two optima
        on the circle [rad].
    omega0_err : float
        Uncertainty of omega0 [√(g/R) rad].
    fraction_err : float
        Uncertainty of the fraction.
    step_theta0 : float
        Resolution of the search in theta0 (the last pattern step) [rad]: no start within 3
        steps along an axis or a diagonal does better, on either grid.
    step_omega0 : float
        Resolution of the search in omega0 [√(g/R) rad].
    fraction_at_rest : float
        The fraction at theta0 = omega0 = 0 on the fine grid, for comparison.
    evaluations : int
        Maps computed (each one a grid of grid³ or (2 grid)³ points).
    """

    mu_s: float
    rule: str
    grid: int
    omega_max: float
    theta0: float
    omega0: float
    fraction: float
    theta0_coarse: float
    omega0_coarse: float
    fraction_coarse: float
    theta0_err: float
    omega0_err: float
    fraction_err: float
    step_theta0: float
    step_omega0: float
    fraction_at_rest: float
    evaluations: int

    def _repr_html_(self) -> str:
        rows = [
            ("best start", f"theta0 = {deg(self.theta0)}, omega0 = {num(self.omega0)} sqrt(g/R)"),
            ("JARM fraction", f"{self.fraction:.4g} ± {self.fraction_err:.2g}"),
            ("from rest", f"{self.fraction_at_rest:.4g}"),
            ("made with", f"mu_s = {self.mu_s:g}, grid = {self.grid}, rule = {self.rule}"),
            ("maps computed", str(self.evaluations)),
        ]
        return card("OptimalStart", rows)

    def as_dict(self) -> dict[str, Any]:
        """The numbers, angles in degrees (for printing and JSON).

        Returns
        -------
        dict of str to object
            The fields, with ``theta0_deg`` etc. for the angles.
        """
        return {
            "mu_s": self.mu_s,
            "rule": self.rule,
            "grid": self.grid,
            "theta0_deg": math.degrees(self.theta0),
            "theta0_err_deg": math.degrees(self.theta0_err),
            "omega0": self.omega0,
            "omega0_err": self.omega0_err,
            "fraction": self.fraction,
            "fraction_err": self.fraction_err,
            "fraction_coarse": self.fraction_coarse,
            "fraction_at_rest": self.fraction_at_rest,
            "evaluations": self.evaluations,
        }


#: The directions of the pattern search: axes and diagonals, in units of the step.
_DIRECTIONS = ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1))
#: The multiples of the step tried along each direction.
_MULTIPLES = (1, 2, 3)


class _Objective:
    """The fraction on one grid as a function of the start, cached, counting evaluations."""

    def __init__(self, mu: float, grid: int, rule: Rule, n_threads: int, omega_max: float,
                 budget: list[int], report: Progress | None = None) -> None:  # fmt: skip
        self.mu, self.grid, self.rule, self.n_threads = mu, grid, rule, n_threads
        self.omega_max = omega_max
        self.budget = budget
        self.total = budget[0]
        self.report = report
        self.cache: dict[tuple[float, float], float] = {}

    def key(self, th: float, om: float) -> tuple[float, float]:
        """The start evaluated for (th, om), and its cache key: rounded to 12 decimals, so
        that the search's float paths to one start share its map, then put back inside
        [0, 2π) x [0, omega_max], which the rounding can step out of (omega_max =
        1.0207449999999998 rounds to 1.020745; 2π - 1e-14 to 6.28318530718)."""
        th = round(_theta0(th), 12)
        om = round(min(max(om, 0.0), self.omega_max), 12)
        return (0.0 if th >= TWO_PI else th, min(om, self.omega_max))

    def __call__(self, th: float, om: float) -> float:
        k = self.key(th, om)
        if k not in self.cache:
            if self.budget[0] <= 0:
                raise _BudgetSpent
            self.budget[0] -= 1
            s = _shares(self.mu, k[0], k[1], self.grid, self.rule, self.n_threads)
            self.cache[k] = float(s[Reason.JARM.value])
            if self.report is not None:
                self.report(self.total - self.budget[0], self.total)
        return self.cache[k]


class _BudgetSpent(Exception):
    pass


def _pattern_polish(
    f: _Objective, th: float, om: float, h_th: float, h_om: float
) -> tuple[float, float, float]:
    """Compass search on the lattice of steps (h_th, h_om) around (th, om): move to the best
    strictly better start among the 3 multiples of the 8 directions until none is better.
    The result is a local maximum on that lattice by construction."""
    best = f(th, om)
    while True:
        cands = []
        for dx, dy in _DIRECTIONS:
            for m in _MULTIPLES:
                t, o = th + m * dx * h_th, om + m * dy * h_om
                if 0.0 <= o <= f.omega_max:
                    cands.append((f(t, o), t, o))
        top = max(cands, key=lambda c: c[0], default=(best, th, om))
        if top[0] <= best:
            return f.key(th, om)[0], f.key(th, om)[1], best
        best, th, om = top


def _nelder_mead(
    f: _Objective, th: float, om: float, s_th: float, s_om: float, max_eval: int
) -> tuple[float, float]:
    """Nelder--Mead (scipy) on the start, in units of the lattice steps; omega0 bounded."""
    try:
        from scipy.optimize import minimize
    except ImportError as err:  # pragma: no cover - scipy is in the test extras
        raise ImportError("optimal_start needs scipy: pip install 'eccjump[analysis]'") from err

    def objective(u: NDArray[np.float64]) -> float:
        return -f(float(u[0]) * s_th, float(u[1]) * s_om)

    x0 = np.array([th / s_th, om / s_om])
    top = f.omega_max / s_om
    x0[1] = min(max(x0[1], 0.0), top)
    up = 1.0 if x0[1] + 1.0 <= top else -1.0  # the third vertex inside the bounds
    simplex = np.array([x0, x0 + np.array([1.0, 0.0]), x0 + np.array([0.0, up])])
    res = minimize(
        objective,
        x0,
        method="Nelder-Mead",
        bounds=[(None, None), (0.0, f.omega_max / s_om)],
        options={
            "initial_simplex": simplex,
            "xatol": 0.05,
            "fatol": 0.0,
            "maxfev": max_eval,
        },
    )
    return float(res.x[0]) * s_th, float(res.x[1]) * s_om


def _circle_distance(a: float, b: float) -> float:
    d = abs(a - b) % TWO_PI
    return min(d, TWO_PI - d)


@fill
def optimal_start(
    mu_s: float,
    *,
    grid: int = 32,
    omega_max: float = 3.0,
    lattice: tuple[int, int] = (24, 12),
    n_starts: int = 3,
    rule: Rule = "paper",
    n_threads: int = 0,
    max_evaluations: int = 2000,
    progress: bool | Progress | None = None,
) -> OptimalStart:
    """The start (theta0, omega0) that maximises the JARM fraction (:func:`jarm_fraction`),
    with its uncertainty from the grid. Needs scipy (``pip install "eccjump[analysis]"``).

    The fraction on a finite grid is piecewise constant in the start, so the search uses no
    derivative: (1) a lattice of ``lattice`` = (n_theta, n_omega) starts (theta0 = 2π i /
    n_theta, omega0 = omega_max j / (n_omega - 1)) on the grid of ``grid`` points per axis;
    (2) Nelder--Mead (scipy) from the ``n_starts`` best lattice starts, in units of the
    lattice steps; (3) a pattern search polishes the best with a step of 1/8 lattice step
    (8 directions, 1--3 steps each) until no neighbour is better: a local maximum on that
    lattice by construction; (4) steps (2)--(3) again on the grid of 2 ``grid`` points per
    axis, from the first optimum. The difference between the two optima is the uncertainty.

    Parameters
    ----------
    %(mu_s)s
    grid : int, default 32
        Points per axis of the coarse grid, 2 ... 64 (the fine grid is 2 grid).
    omega_max : float, default 3.0
        Largest omega0 searched [√(g/R) rad], in [1e-6, 100]; theta0 covers [0, 2π).
    lattice : tuple of (int, int), default (24, 12)
        Starts of the first lattice along theta0 and omega0, each 2 ... 1000.
    n_starts : int, default 3
        Lattice starts the local search begins from, 1 ... 50.
    %(rule_short)s
    %(n_threads)s
    max_evaluations : int, default 2000
        Bound of the maps computed in all, 1 ... 10**5.
    progress : bool, callable or None, default None
        Progress of the search, in maps computed: None or False, none; True, a bar on
        stderr (tqdm); a callable, called as ``progress(done, total)`` after each map,
        ``total`` the bound ``max_evaluations`` until the last call, where it is the count
        computed (``done == total``).

    Returns
    -------
    OptimalStart
        The optimum on both grids, its uncertainty and the fraction at rest.

    Raises
    ------
    ValueError
        For a parameter out of its range, or a search that reaches ``max_evaluations``.
    ImportError
        Without scipy.

    Examples
    --------
    A coarse search (the user guide's numbers use ``grid=32``):

    >>> import eccjump
    >>> best = eccjump.optimal_start(1.0, grid=6, lattice=(8, 4), n_starts=1)
    >>> bool(best.fraction > 10 * best.fraction_at_rest)
    True
    """
    mu = _mu(mu_s)
    g = integer("grid", grid, 2, GRID_MAX // 2)
    wmax = real("omega_max", omega_max)
    if not (OMEGA_MAX_RANGE[0] <= wmax <= OMEGA_MAX_RANGE[1]):
        raise ValueError(
            f"omega_max = {short(wmax)} [sqrt(g/R) rad] is outside the allowed range [1e-6, 100]"
        )
    if not isinstance(lattice, tuple | list) or len(lattice) != 2:
        raise TypeError("lattice must be a pair of integers (n_theta, n_omega)")
    n_th = integer("lattice", lattice[0], 2, 1000)
    n_om = integer("lattice", lattice[1], 2, 1000)
    k = integer("n_starts", n_starts, 1, 50)
    r, nt = rule_name(rule), _threads(n_threads)
    budget = [integer("max_evaluations", max_evaluations, 1, EVALUATIONS_MAX)]
    _shares(mu, 0.0, 0.0, 2, r, nt)  # a bad rule or n_threads is refused before any work
    with reporting(progress, "map", unit_scale=False) as report:
        found = _search(mu, g, r, nt, wmax, (n_th, n_om), k, budget, report)
        if report is not None:
            report(found.evaluations, found.evaluations)
    return found


def _search(
    mu: float,
    g: int,
    r: Rule,
    nt: int,
    wmax: float,
    lattice: tuple[int, int],
    k: int,
    budget: list[int],
    report: Progress | None,
) -> OptimalStart:
    """The search of :func:`optimal_start` on checked arguments, ``report(maps computed,
    budget)`` after each map."""
    n_th, n_om = lattice
    s_th, s_om = TWO_PI / n_th, wmax / (n_om - 1)
    max_evaluations = budget[0]
    coarse = _Objective(mu, g, r, nt, wmax, budget, report)
    fine = _Objective(mu, 2 * g, r, nt, wmax, budget, report)
    try:
        lat = [(coarse(i * s_th, j * s_om), i * s_th, j * s_om)
               for i in range(n_th) for j in range(n_om)]  # fmt: skip
        lat.sort(key=lambda c: -c[0])
        found = []
        for _, th0, om0 in lat[:k]:
            t, o = _nelder_mead(coarse, th0, om0, s_th, s_om, 200)
            found.append((coarse(t, o), t, o))
        _, t, o = max(found, key=lambda c: c[0])
        h_th, h_om = s_th / 8, s_om / 8
        tc, oc, fc = _pattern_polish(coarse, t, o, h_th, h_om)
        t, o = _nelder_mead(fine, tc, oc, s_th / 4, s_om / 4, 100)
        if fine(t, o) < fine(tc, oc):
            t, o = tc, oc
        tf, of, ff = _pattern_polish(fine, t, o, h_th, h_om)
        rest = fine(0.0, 0.0)
    except _BudgetSpent:
        raise ValueError(
            f"max_evaluations = {max_evaluations} maps were not enough for the search; "
            "raise it or use a coarser lattice"
        ) from None
    used = int(max_evaluations) - budget[0]
    return OptimalStart(
        mu_s=mu,
        rule=r,
        grid=g,
        omega_max=wmax,
        theta0=tf,
        omega0=of,
        fraction=ff,
        theta0_coarse=tc,
        omega0_coarse=oc,
        fraction_coarse=fc,
        theta0_err=_circle_distance(tf, tc),
        omega0_err=abs(of - oc),
        fraction_err=abs(ff - fc),
        step_theta0=h_th,
        step_omega0=h_om,
        fraction_at_rest=rest,
        evaluations=used,
    )


__all__ = [
    "GRID_MAX",
    "OptimalStart",
    "StartMap",
    "jarm_fraction",
    "optimal_start",
    "reason_shares",
    "start_map",
]
