"""The only calls of the Rust classification bridge (``_core.jarm_points``, ``_core.jarm_grid``).

:func:`call_options` converts the options that apply to a whole call into a
:class:`CallOptions` (plain values: it pickles into dask graphs); :func:`_bridge_options`
alone knows how the bridge takes them (one ``_core.ClassifyOptions``, made for each call,
``rust/eccjump-py/src/options.rs``), so a change of those touches this module only. The
turn ``n`` travels separately: one per point for ``jarm_points``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._base.arrays import turn
from eccjump._base.checks import U32_MAX, U64_MAX, flag, integer, real, text

Method = Literal["closed_form", "ode"]

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
    stop_at_slip : stop at the first slip with reason SLIP (paper rule; see :func:`jarm`).
    n_threads : threads per call (0 = one per core); results do not depend on it.
    integrator : the Runge–Kutta pair of ``method="ode"``, ``"RK45"``, ``"DOP853"``
        or ``"Vern9"``.

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
    integrator: str = "RK45"
    stop_at_slip: bool = False


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
    integrator: str = "RK45",
    stop_at_slip: bool = False,
) -> CallOptions:
    """The options of a classification call, type-checked and converted to plain Python
    types (TypeError naming the argument for a wrong type; see :mod:`eccjump._base.checks`).

    ValueError for ``n`` < 1, ``max_turns`` < 1 and ``n_threads`` < 0 and for integers the
    bridge cannot carry; ``rule``, ``method``, the tolerances, ``theta0``, ``omega0`` and the
    upper bounds are checked by the core.
    """
    return CallOptions(
        n=turn(n),
        rule=text("rule", rule),
        method=text("method", method),
        rtol=real("rtol", rtol),
        atol=real("atol", atol),
        theta0=real("theta0", theta0),
        omega0=real("omega0", omega0),
        max_turns=integer("max_turns", max_turns, 1, U32_MAX),
        refine_extrema=flag("refine_extrema", refine_extrema),
        n_threads=integer("n_threads", n_threads, 0, U64_MAX),
        integrator=text("integrator", integrator),
        stop_at_slip=flag("stop_at_slip", stop_at_slip),
    )


def _bridge_options(opts: CallOptions) -> _core.ClassifyOptions:
    """``opts`` as the bridge takes them: the options without the turn, converted once."""
    return _core.ClassifyOptions(
        rule=opts.rule,
        method=opts.method,
        rtol=opts.rtol,
        atol=opts.atol,
        theta0=opts.theta0,
        omega0=opts.omega0,
        max_turns=opts.max_turns,
        refine_extrema=opts.refine_extrema,
        stop_at_slip=opts.stop_at_slip,
        n_threads=opts.n_threads,
        integrator=opts.integrator,
    )


def jarm_points(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: NDArray[np.float64],
    opts: CallOptions,
    n: NDArray[np.int64] | None = None,
) -> Raw:
    """Classify equal-length contiguous 1-D float64 arrays of points (``mu_s`` may have
    length 1), with a turn per point ``n`` (validated, ≥ 1, same length) or ``opts.n`` for
    all: one flat array per field."""
    turns = np.ascontiguousarray([opts.n or 0] if n is None else n, dtype=np.uint32)
    return _core.jarm_points(alpha, chi, km, mu_s, turns, options=_bridge_options(opts))


def jarm_grid(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    frac: NDArray[np.float64],
    mu_s: float,
    opts: CallOptions,
) -> Raw:
    """Classify the grid α × χ × frac (k_m = frac (1 - χ)) on the turn ``opts.n``:
    one array per field, flat in C order."""
    mu_s = real("mu_s", mu_s)
    return _core.jarm_grid(alpha, chi, frac, mu_s, n=opts.n or 0, options=_bridge_options(opts))
