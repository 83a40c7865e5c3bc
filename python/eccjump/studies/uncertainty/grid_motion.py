"""The full motion under tolerances at every point of a grid (``uncertainty_map(question=
"motion")``): the samples of a block of grid points (:func:`.grid.columns`, the same unit-cube
points at every grid point) run to their first landing by the core's vectorised
:func:`eccjump.motion_points` (:func:`.questions.evaluate`, the path of
:func:`eccjump.uncertainty`), never by a Python loop over grid points.

A grid point's statistics need all its samples at once (quantiles do not add up as counts
do), so a block holds whole grid points: about :data:`MOTION_BLOCK` samples, or one grid
point with all its samples where n is larger. The other inputs are the defaults of
``uncertainty(question="motion")``: μ_k is each sample's μ_s, no restitution, a start at
rest at θ = 0, and the full motion's default options under the map's rule.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from eccjump._base.progress import Progress
from eccjump.motion.options import MotionOptions
from eccjump.studies.uncertainty.grid import GridSpread, _physical, columns, nominal_of
from eccjump.studies.uncertainty.map_fields import MOTION_FIELDS, MOTION_QUANTITIES
from eccjump.studies.uncertainty.questions import CHUNK, evaluate, jumps, ran
from eccjump.studies.uncertainty.results import Summary, wilson

#: Samples per block of grid points: four core calls of :data:`.questions.CHUNK` samples
#: (about 15 MB of columns and outcomes).
MOTION_BLOCK = 4 * CHUNK["motion"]


def _outcomes(
    nominal: Mapping[str, NDArray[np.float64]],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int,
) -> tuple[dict[str, NDArray], NDArray[np.bool_]]:
    """The full motion's outcomes of every sample of the grid points ``nominal`` and which
    are valid, each of shape (G, n)."""
    grid = columns(nominal, cube, how)
    flat = {p: np.ascontiguousarray(v).ravel() for p, v in grid.items()}
    zero = np.zeros(flat["chi"].size)
    flat |= {"mu_k": flat["mu_s"], "restitution": zero, "theta0": zero, "omega0": zero}
    valid = _physical(flat) & np.repeat(_physical(nominal), cube.shape[0])
    opts = {**MotionOptions(rule=how.rule).keywords(), "n_threads": n_threads}
    out = evaluate("motion", flat, valid, opts)
    valid &= ran("motion", out)  # k_m = 0 has no full motion, as in uncertainty()
    shape = (nominal["chi"].size, cube.shape[0])
    return {k: v.reshape(shape) for k, v in out.items()}, valid.reshape(shape)


def _row_fields(out: Mapping[str, NDArray], valid: NDArray[np.bool_], level: float) -> list:
    """The fields of one grid point from its samples' outcomes, by the rules of
    :func:`eccjump.uncertainty` (:class:`.results.Summary` for the quantiles)."""
    m = int(valid.sum())
    if m == 0:
        return [np.nan] * 3 + [0] + [np.nan] * (len(MOTION_FIELDS) - 4)
    k = int(jumps("motion", out)[valid].sum())
    row: list = [k / m, *wilson(k, m, level), m]
    row += [np.isfinite(out["liftoff_t"][valid]).sum() / m, out["slipped_first"][valid].sum() / m]
    for q in MOTION_QUANTITIES:
        s = Summary.of(np.where(valid, out[q], np.nan))
        row += [s.median, s.q025, s.q975]
    return row


def motion_grid_fields(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int = 0,
    report: Progress | None = None,
) -> dict[str, NDArray]:
    """The motion fields of every point of the grid α × χ × km_frac (flat, C order):
    the grid function of :func:`eccjump.maps.dask.lazy_fields` and of the map computed now.
    The statistics of a grid point are computed from its own samples (a short loop of
    quantiles per grid point, after the core's batch)."""
    nominal = nominal_of(alpha, chi, km_frac, how.mu_s)
    points, n = nominal["chi"].size, cube.shape[0]
    per_block = max(1, MOTION_BLOCK // max(n, 1))
    rows: list[list] = []
    for g0 in range(0, points, per_block):
        part = {p: v[g0 : g0 + per_block] for p, v in nominal.items()}
        out, valid = _outcomes(part, cube, how, n_threads)
        rows += [
            _row_fields({k: v[i] for k, v in out.items()}, valid[i], how.confidence)
            for i in range(valid.shape[0])
        ]
        if report is not None:
            report(min(g0 + per_block, points) * n, points * n)
    table = np.array(rows, dtype=np.float64).reshape(points, len(MOTION_FIELDS))
    fields: dict[str, NDArray] = {k: table[:, i].copy() for i, k in enumerate(MOTION_FIELDS)}
    fields["n_valid"] = fields["n_valid"].astype(np.uint32)
    return fields


__all__ = ["MOTION_BLOCK", "motion_grid_fields"]
