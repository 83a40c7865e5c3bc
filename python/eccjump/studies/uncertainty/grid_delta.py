"""The first-order (delta-method) P(JARM) at every point of a grid
(``uncertainty_map(..., method="delta")``): one batched ``jarm(..., derivatives=True)`` over
the grid's nominal points (in blocks of :data:`.grid.BLOCK` points, for bounded memory) and
the one rule of :func:`.delta.first_order`, no sample at all. Where the linearisation fails at
a nominal point it says so (:class:`.delta.Status`) and gives NaN; see :mod:`.delta` for what
it cannot see (a kink that only the tolerances reach).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from eccjump._base.progress import Progress
from eccjump.classification.classify import jarm
from eccjump.studies.uncertainty.delta import Status, first_order
from eccjump.studies.uncertainty.grid import BLOCK, GridSpread, _physical, nominal_of


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
    for i0 in range(0, inside.size, BLOCK):
        idx = inside[i0 : i0 + BLOCK]
        x = {p: v[idx] for p, v in nominal.items()}
        r = jarm(x["alpha"], x["chi"], x["km"], x["mu_s"], rule=how.rule,
                 derivatives=True, n_threads=n_threads)  # fmt: skip
        est = first_order(r, x["mu_s"], how, how.rule)
        out["p_jarm"][idx], out["theta_J_sd"][idx] = est.p_jarm, est.theta_J_sd
        out["delta_status"][idx] = est.status
        if report is not None:
            report(min(i0 + BLOCK, inside.size), inside.size)
    return out


__all__ = ["delta_grid_fields"]
