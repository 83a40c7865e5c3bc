"""The first-order (delta-method) P(JARM) at every point of a grid
(``uncertainty_map(..., method="delta")``): one batched ``jarm(..., derivatives=True)`` over
the grid's nominal points (in blocks of :data:`DELTA_BLOCK` points, for bounded memory) and
the one rule of :func:`.delta.first_order`, no sample at all. Where the linearisation fails at
a nominal point it says so (:class:`.delta.Status`) and gives NaN; where the tolerances reach
another verdict (a kink the nominal point does not show) probes along the inputs flag it
(:func:`_reaches`, status REACHES), the value kept.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from eccjump._base.progress import Progress
from eccjump.classification.classify import jarm
from eccjump.classification.fields import Reason
from eccjump.studies.uncertainty.delta import Status, first_order
from eccjump.studies.uncertainty.grid import BLOCK, GridSpread, _physical, nominal_of

#: Grid points per block: with their 2 probes per varied input (at most 8), about
#: :data:`.grid.BLOCK` closed-form points per call, as the sampled map's batches.
DELTA_BLOCK = BLOCK // 8


def delta_grid_fields(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int = 0,
    report: Progress | None = None,
) -> dict[str, NDArray]:
    """``p_jarm``, ``theta_J_sd`` and ``delta_status`` of every point of the grid
    α × χ × km_frac (flat, C order); ``cube`` is not used (the signature of every grid
    function of :func:`eccjump.maps.dask.lazy_fields`)."""
    nominal = nominal_of(alpha, chi, km_frac, how.mu_s)
    points = nominal["chi"].size
    out = {
        "p_jarm": np.full(points, np.nan),
        "theta_J_sd": np.full(points, np.nan),
        "delta_status": np.full(points, Status.INVALID, dtype=np.uint8),
    }
    # A grid point outside the physical range is invalid, as in the sampled map (and jarm
    # is not asked: it would warn about its angle a second time).
    inside = np.flatnonzero(_physical(nominal))
    for i0 in range(0, inside.size, DELTA_BLOCK):
        idx = inside[i0 : i0 + DELTA_BLOCK]
        x = {p: v[idx] for p, v in nominal.items()}
        r = jarm(x["alpha"], x["chi"], x["km"], x["mu_s"], rule=how.rule,
                 derivatives=True, n_threads=n_threads)  # fmt: skip
        est = first_order(r, x["mu_s"], how, how.rule)
        out["p_jarm"][idx], out["theta_J_sd"][idx] = est.p_jarm, est.theta_J_sd
        status = est.status.copy()
        status[(status == Status.ESTIMATE) & _reaches(x, how, n_threads)] = Status.REACHES
        out["delta_status"][idx] = status
        if report is not None:
            report(min(i0 + DELTA_BLOCK, inside.size), inside.size)
    return out


#: How far the probes of :func:`_reaches` go along a normal input, in standard deviations
#: (a uniform one: to its ends). 2: a share of about 5 % of the samples lies beyond.
PROBE_SD = 2.0
#: The verdicts the friction margin at the jump decides between; any other at a probe is a
#: verdict the first order cannot see.
_MARGIN_VERDICTS = (Reason.JARM, Reason.SLIP_AT_JUMP)


def _reaches(x: dict[str, NDArray[np.float64]], how: GridSpread, n_threads: int) -> NDArray:
    """Whether the tolerances reach another verdict than the margin's at each nominal point
    ``x``: the closed form at the probes x ± PROBE_SD sd (or the ends of a uniform) along each
    varied input, kept in the physical range, in one batched call; True where one of them is
    neither a JARM nor a slip at the jump. Probes along the axes: a combination of inputs
    that reaches a kink while no single one does is not seen."""
    rows = []
    for p in how.varied:
        lo, hi = (-PROBE_SD * how.sd[p], PROBE_SD * how.sd[p]) if p in how.sd else how.bounds[p]
        rows += [{**x, p: x[p] + lo}, {**x, p: x[p] + hi}]
    if not rows:
        return np.zeros(x["chi"].size, dtype=bool)
    y = {k: np.concatenate([r[k] for r in rows]) for k in x}
    chi = np.clip(y["chi"], 0.0, 1.0)
    km = np.clip(y["km"], 0.0, 1.0 - chi)
    alpha, mu = np.clip(y["alpha"], 0.0, np.pi / 2), np.maximum(y["mu_s"], 0.0)
    r = jarm(alpha, chi, km, mu, rule=how.rule, n_threads=n_threads)
    other = ~np.isin(np.asarray(r.reason), _MARGIN_VERDICTS)
    return np.asarray(other.reshape(len(rows), -1).any(axis=0))


__all__ = ["DELTA_BLOCK", "PROBE_SD", "delta_grid_fields"]
