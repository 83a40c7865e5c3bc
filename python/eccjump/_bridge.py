"""The only calls of the Rust classification bridge (``_core.jarm_points``, ``_core.jarm_grid``).

:func:`call_options` validates the options that apply to a whole call into a
:class:`CallOptions`; :func:`_bridge_options` alone knows how the bridge takes them (today a
positional tuple, see ``rust/eccjump-py/src/options.rs``), so a change of that format touches
this module only. :func:`jarm_points_per_n` is the per-point turn ``n`` done in Python (one
bridge call per distinct n) until the core takes an array of turns.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._arrays import turn
from eccjump.fields import DTYPES, FIELDS

Method = Literal["closed_form", "ode"]
Rule = Literal["paper", "normal_force"]

#: The raw result of a bridge call: one flat array per field.
Raw = dict[str, NDArray]


@dataclass(frozen=True)
class CallOptions:
    """Validated options of one classification call, the same for every point.

    n : the turn of the jump (>= 1), or None for the first jump whatever its turn.
    rule : lift-off rule, ``"paper"`` or ``"normal_force"`` (checked by the core).
    method : ``"closed_form"`` or ``"ode"`` (checked by the core).
    rtol, atol : integrator tolerances (``method="ode"``; checked by the core).
    theta0, omega0 : initial angle [rad] and angular velocity [sqrt(g/R) rad].
    max_turns : cap of the search, in turns (>= 1).
    refine_extrema : refine max_ratio and min_Fy to full precision (closed form).
    n_threads : threads per call (0 = one per core); results do not depend on it.

    A plain module-level frozen dataclass: it pickles into dask graphs.
    """

    n: int | None
    rule: str
    method: str
    rtol: float
    atol: float
    theta0: float
    omega0: float
    max_turns: int
    refine_extrema: bool
    n_threads: int


def call_options(
    *,
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
) -> CallOptions:
    """The options of a classification call, validated and converted to plain Python types.

    Raises ValueError (naming the argument and its allowed range) for ``n``, ``max_turns``
    and ``n_threads``; ``rule``, ``method`` and the tolerances are checked by the core.
    """
    if isinstance(n_threads, bool) or not isinstance(n_threads, int | np.integer) or n_threads < 0:
        raise ValueError(f"n_threads = {n_threads!r} is outside the allowed range [0, inf)")
    if isinstance(max_turns, bool) or not isinstance(max_turns, int | np.integer) or max_turns < 1:
        raise ValueError(f"max_turns = {max_turns!r} is outside the allowed range [1, inf)")
    return CallOptions(
        n=turn(n),
        rule=str(rule),
        method=str(method),
        rtol=float(rtol),
        atol=float(atol),
        theta0=float(theta0),
        omega0=float(omega0),
        max_turns=int(max_turns),
        refine_extrema=bool(refine_extrema),
        n_threads=int(n_threads),
    )


def _bridge_options(opts: CallOptions) -> tuple:
    """``opts`` in the form the bridge takes: the positional tuple
    ``(n, rule, method, rtol, atol, theta0, omega0, max_turns, refine_extrema, n_threads)``."""
    return (
        opts.n,
        opts.rule,
        opts.method,
        opts.rtol,
        opts.atol,
        opts.theta0,
        opts.omega0,
        opts.max_turns,
        opts.refine_extrema,
        opts.n_threads,
    )


def jarm_points(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: NDArray[np.float64],
    opts: CallOptions,
) -> Raw:
    """Classify equal-length contiguous 1-D float64 arrays of points (``mu_s`` may have
    length 1): one flat array per field."""
    return _core.jarm_points(alpha, chi, km, mu_s, _bridge_options(opts))


def jarm_grid(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    frac: NDArray[np.float64],
    mu_s: float,
    opts: CallOptions,
) -> Raw:
    """Classify the grid alpha x chi x frac (k_m = frac (1 - chi)): one array per field,
    flat in C order."""
    return _core.jarm_grid(alpha, chi, frac, float(mu_s), _bridge_options(opts))


def jarm_points_per_n(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: NDArray[np.float64],
    n: NDArray[np.int64],
    opts: CallOptions,
) -> Raw:
    """:func:`jarm_points` with a turn per point (``n``, validated, >= 1, same length as the
    others): one bridge call per distinct turn, the results scattered back in place.
    ``opts.n`` is ignored. To become one call once the core takes an array of turns."""
    turns, inverse = np.unique(n, return_inverse=True)
    if turns.size == 1:
        return jarm_points(alpha, chi, km, mu_s, replace(opts, n=int(turns[0])))
    out = {k: np.empty(n.size, dtype=DTYPES[k]) for k in FIELDS}
    for i, v in enumerate(turns.tolist()):
        idx = np.flatnonzero(inverse == i)
        raw = jarm_points(alpha[idx], chi[idx], km[idx], mu_s[idx], replace(opts, n=int(v)))
        for k in FIELDS:
            out[k][idx] = raw[k]
    return out
