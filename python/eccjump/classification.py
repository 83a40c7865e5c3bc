"""JARM classification (the paper's Section 3): does the cylinder jump straight out of pure
rolling, and if not, why. See ``docs/jarm.md`` for the semantics.

Everything broadcasts over numpy arrays and runs in Rust, in parallel over points with the
GIL released; results are bit-identical for any thread count.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._arrays import axis, broadcast_flat, turn, turns_array

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

Method = Literal["closed_form", "ode"]
Rule = Literal["paper", "normal_force"]

Reason = enum.IntEnum("Reason", {name.upper(): code for code, name in _core.reason_codes()})
Reason.__doc__ = """Why a point is (JARM) or is not a jump after pure rolling.

JARM: lift-off straight out of pure rolling. NO_ROOT: no lift-off (on the requested turn n,
or ever). LIFTOFF_EARLIER: the lift-off rule held earlier than the requested turn n (or at the
start). NORMAL_FORCE_LOST: F_y reached 0 before lift-off. SLIP_BEFORE: the rolling branch
needs more than mu_s of friction before lift-off. SLIP_AT_JUMP: friction fails on the final
approach, and the paper's jump-point test (Eq. ineq2) fails at theta_J. ROCKS_BACK: the body
stops and rolls back. TURN_LIMIT: nothing happened within max_turns turns. INVALID_PARAMS: a
parameter is NaN or out of range."""

#: Result fields, in the order of the bridge.
FIELDS = (
    "is_jarm",
    "reason",
    "n",
    "theta_J",
    "theta_event",
    "Fx_J",
    "Fy_J",
    "max_ratio",
    "theta_max_ratio",
    "min_Fy",
    "theta_min_Fy",
)


@dataclass(frozen=True)
class JarmResult:
    """Per-point classification, every field an array of the broadcast shape.

    Attributes
    ----------
    is_jarm : bool, a jump straight out of pure rolling.
    reason : uint8 codes of :class:`Reason`.
    n : turn of the jump (JARM), of the earlier lift-off, or of the deciding event; 0 if none.
    theta_J : lift-off angle [rad] (JARM, LIFTOFF_EARLIER, SLIP_AT_JUMP), else NaN.
    theta_event : angle [rad] of the deciding failure (NaN for a JARM).
    Fx_J, Fy_J : friction and normal force at the jump [M g] (JARM only).
    max_ratio, theta_max_ratio : largest |Fx|/Fy on the rolling path and where [rad].
    min_Fy, theta_min_Fy : smallest normal force on the rolling path [M g] and where [rad].
    """

    is_jarm: NDArray[np.bool_]
    reason: NDArray[np.uint8]
    n: NDArray[np.uint32]
    theta_J: NDArray[np.float64]
    theta_event: NDArray[np.float64]
    Fx_J: NDArray[np.float64]
    Fy_J: NDArray[np.float64]
    max_ratio: NDArray[np.float64]
    theta_max_ratio: NDArray[np.float64]
    min_Fy: NDArray[np.float64]
    theta_min_Fy: NDArray[np.float64]

    @property
    def shape(self) -> tuple[int, ...]:
        return self.is_jarm.shape

    def reasons(self) -> NDArray[np.object_]:
        """The reasons as :class:`Reason` members (an object array; for display)."""
        out = np.empty(self.reason.shape, dtype=object)
        out.ravel()[:] = [Reason(int(c)) for c in self.reason.ravel()]
        return out

    @staticmethod
    def _from_raw(raw: dict[str, NDArray], shape: tuple[int, ...]) -> JarmResult:
        return JarmResult(**{k: raw[k].reshape(shape) for k in FIELDS})


def _common(
    n: int | None,
    rule: str,
    method: str,
    rtol: float,
    atol: float,
    theta0: float,
    omega0: float,
    max_turns: int,
    refine_extrema: bool,
    n_threads: int,
) -> dict[str, Any]:
    """The options dict the bridge takes (``CallOptions`` in rust/eccjump-py), with the turn
    ``n`` (0 = the first jump) for grid calls. Only types are checked here; the core checks
    every range."""
    if isinstance(n_threads, bool) or not isinstance(n_threads, int) or n_threads < 0:
        raise ValueError(f"n_threads = {n_threads!r} is outside the allowed range [0, inf)")
    if isinstance(max_turns, bool) or not isinstance(max_turns, int) or max_turns < 1:
        raise ValueError(f"max_turns = {max_turns!r} is outside the allowed range [1, inf)")
    return {
        "n": turn(n) or 0,
        "rule": str(rule),
        "method": str(method),
        "rtol": float(rtol),
        "atol": float(atol),
        "theta0": float(theta0),
        "omega0": float(omega0),
        "max_turns": int(max_turns),
        "refine_extrema": bool(refine_extrema),
        "n_threads": int(n_threads),
    }


def jarm(
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    mu_s: ArrayLike,
    n: int | None = None,
    *,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float = 0.0,
    omega0: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = True,
    n_threads: int = 0,
) -> JarmResult:
    """Classify points (alpha, chi, km, mu_s) as JARM or not, broadcasting the four inputs.

    Parameters
    ----------
    alpha : ramp angle [rad] in [0, pi/2].
    chi, km : the body (km is the shell mass fraction itself, in [0, 1 - chi]).
    mu_s : static friction coefficient, >= 0.
    n : the turn on which the jump must happen (>= 1), or None for the first jump whatever
        its turn. With first-jump semantics a point has at most one n, so the regions of
        different n never overlap.
    method : ``"closed_form"`` (the paper's formulas with a rigorous path scan) or ``"ode"``
        (integration with events; an independent route, ~10x slower).
    rule : lift-off rule, ``"paper"`` (default) or ``"normal_force"`` (classical).
    theta0, omega0 : initial angle [rad] and angular velocity (>= 0) [sqrt(g/R) rad].
    rtol, atol : integrator tolerances (``method="ode"`` only).
    max_turns : cap of the search, in turns.
    refine_extrema : refine max_ratio and min_Fy to full precision (closed form).
    n_threads : threads (0 = one per core); results are identical for any value.

    Invalid points get ``Reason.INVALID_PARAMS``; a ``ValueError`` is raised only for
    arguments that apply to the whole call (shapes, rule, method, n, tolerances).
    """
    shape, (a, c, k, m) = broadcast_flat(alpha=alpha, chi=chi, km=km, mu_s=mu_s)
    turns = turns_array(n, shape)
    opts = _common(
        None, rule, method, rtol, atol, theta0, omega0, max_turns, refine_extrema, n_threads
    )
    raw = _core.jarm_points(a, c, k, m, turns, opts)
    return JarmResult._from_raw(raw, shape)


@dataclass(frozen=True)
class Region:
    """A JARM map on the grid alpha x chi x km_frac, with k_m = km_frac (1 - chi).

    ``result`` holds the fields of :class:`JarmResult`, each of shape
    (len(alpha), len(chi), len(km_frac)); the remaining attributes record how it was made.
    """

    alpha: NDArray[np.float64]
    chi: NDArray[np.float64]
    km_frac: NDArray[np.float64]
    result: JarmResult
    mu_s: float
    n: int | None
    rule: str
    method: str
    theta0: float
    omega0: float
    attrs: dict[str, object] = field(default_factory=dict)

    @property
    def km(self) -> NDArray[np.float64]:
        """k_m on the (chi, km_frac) plane, shape (len(chi), len(km_frac))."""
        return self.km_frac[None, :] * (1.0 - self.chi[:, None])

    @property
    def is_jarm(self) -> NDArray[np.bool_]:
        return self.result.is_jarm

    def fraction(self) -> float:
        """Fraction of grid points that are a JARM."""
        return float(np.mean(self.result.is_jarm)) if self.result.is_jarm.size else 0.0

    @property
    def lazy(self) -> bool:
        """True for a map made with ``chunks=`` and not yet computed (dask-array fields)."""
        return not isinstance(self.result.is_jarm, np.ndarray)

    def compute(self, **kwargs: object) -> Region:
        """A lazy map computed (all fields in one pass; ``kwargs`` go to ``dask.compute``);
        an already computed map is returned as is."""
        if not self.lazy:
            return self
        from eccjump.scale import compute_region

        return compute_region(self, **kwargs)

    def to_xarray(self) -> xr.Dataset:
        """The map as an ``xarray.Dataset`` (dask-backed if lazy); see :mod:`eccjump.labelled`.
        Needs ``pip install eccjump[xarray]``."""
        from eccjump.labelled import to_xarray

        return to_xarray(self)


@overload
def region(
    mu_s: float,
    n: int | None = None,
    *,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float = 0.0,
    omega0: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    n_threads: int = 0,
    chunks: Any = None,
    output: Literal["region"] = "region",
) -> Region: ...


@overload
def region(
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    n_threads: int = 0,
    chunks: Any = None,
    output: Literal["xarray"],
) -> xr.Dataset: ...


def region(
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    n_threads: int = 0,
    chunks: Any = None,
    output: Literal["region", "xarray"] = "region",
) -> Region | xr.Dataset:
    """Map the JARM region on a rectangular grid, in parallel.

    ``alpha`` [rad], ``chi`` and ``km`` are 1-D coordinate arrays; ``km`` is given as the
    fraction k_m/(1 - chi) in [0, 1], so that every (chi, km) pair of the grid is a valid
    body and the grid stays rectangular. Other arguments as :func:`jarm`; ``refine_extrema``
    defaults to False here (the classification does not depend on it; maps are faster).

    chunks : None (default: compute now), or chunk sizes along (alpha, chi, km) -- one int
        for all, a 3-sequence or a dict; -1/None for a whole axis. The map is then built
        lazily with dask, one Rust grid call per block (see :mod:`eccjump.scale`); call
        ``.compute()`` on the result. Bit-identical to the unchunked map. ``n_threads`` is
        per block: on a cluster use threads per worker / concurrent tasks per worker.
    output : ``"region"`` (default) a :class:`Region`; ``"xarray"`` an ``xarray.Dataset``
        (:mod:`eccjump.labelled`), and then ``mu_s``, ``theta0`` and ``omega0`` may be 1-D
        sequences, swept as extra leading dimensions (one Rust call per combination).

    The tolerances, ``max_turns`` and ``refine_extrema`` are recorded in ``Region.attrs``.
    """
    if output == "xarray":
        from eccjump.labelled import region_dataset

        return region_dataset(
            mu_s,
            n,
            alpha=alpha,
            chi=chi,
            km=km,
            method=method,
            rule=rule,
            theta0=theta0,
            omega0=omega0,
            rtol=rtol,
            atol=atol,
            max_turns=max_turns,
            refine_extrema=refine_extrema,
            n_threads=n_threads,
            chunks=chunks,
        )
    if output != "region":
        raise ValueError(f"output = {output!r}; use 'region' or 'xarray'")
    for name, value in (("mu_s", mu_s), ("theta0", theta0), ("omega0", omega0)):
        if np.ndim(value) != 0:
            raise ValueError(f"{name} must be a number here; sweeps need output='xarray'")
    a, c, f = axis("alpha", alpha), axis("chi", chi), axis("km", km)
    opts = _common(
        n, rule, method, rtol, atol, theta0, omega0, max_turns, refine_extrema, n_threads
    )
    if chunks is None:
        raw = _core.jarm_grid(a, c, f, float(mu_s), opts["n"], opts)
        res = JarmResult._from_raw(raw, (a.size, c.size, f.size))
    else:
        from eccjump.scale import lazy_records, lazy_result

        res = lazy_result(lazy_records(a, c, f, float(mu_s), opts, chunks))
    return Region(
        alpha=a,
        chi=c,
        km_frac=f,
        result=res,
        mu_s=float(mu_s),
        n=turn(n),
        rule=str(rule),
        method=str(method),
        theta0=float(theta0),
        omega0=float(omega0),
        attrs={
            "rtol": float(rtol),
            "atol": float(atol),
            "max_turns": int(max_turns),
            "refine_extrema": bool(refine_extrema),
        },
    )
