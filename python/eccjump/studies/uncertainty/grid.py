"""P(JARM) under tolerances at every point of a grid, in batches through the core: the
samples of a block of grid points are built as flat arrays (grid points x samples) and
classified by one vectorised :func:`eccjump.jarm` call per block (:func:`.questions.evaluate`,
the path of :func:`eccjump.uncertainty`), never by a Python loop over grid points.

Common random numbers: the n unit-cube points are drawn once (:func:`.sampling.unit_cube`)
and mapped through each grid point's distributions, exactly as :func:`.sampling.draw` maps
them around one nominal point. A grid point's samples, and so its fields, depend on its own
nominal values and the cube alone: they are the same bits whatever the other grid points,
the blocks, the dask chunks or the thread count.

Everything here is a plain module-level function of numpy arrays and a :class:`GridSpread`
of plain values, so that a dask graph of it pickles to any cluster.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import Rule
from eccjump._base.progress import Progress
from eccjump.classification.fields import Reason
from eccjump.studies.uncertainty.map_fields import FIELDS, SHARE_OF
from eccjump.studies.uncertainty.questions import CHUNK, evaluate
from eccjump.studies.uncertainty.results import wilson
from eccjump.studies.uncertainty.sampling import RANGES, _in_range, _normal, _uniform

#: Samples per block (grid points x samples): one core call of :data:`.questions.CHUNK`
#: samples each, about 40 MB of working columns.
BLOCK = CHUNK["jarm"]
#: Reason codes counted per grid point (room above the largest Reason).
CODES = 16
#: The parameters the map varies, in the cube's order (that of :data:`.sampling.PARAMETERS`).
VARIED = ("chi", "km", "alpha", "mu_s")


@dataclass(frozen=True)
class GridSpread:
    """How the samples spread around each grid point: ``sd`` (normal standard deviations)
    and ``bounds`` (uniform ranges as offsets (lo, hi) from the grid point) by name, the
    parameters ``varied`` (the cube's columns, in order), ``truncate`` (the ``invalid``
    policy), the map's ``mu_s``, the lift-off ``rule`` and the ``confidence`` of the
    intervals."""

    sd: Mapping[str, float]
    bounds: Mapping[str, tuple[float, float]]
    varied: tuple[str, ...]
    truncate: bool
    mu_s: float
    rule: Rule
    confidence: float


def columns(
    nominal: Mapping[str, NDArray[np.float64]], cube: NDArray[np.float64], how: GridSpread
) -> dict[str, NDArray[np.float64]]:
    """The samples of grid points with ``nominal`` values (each of shape (G,)), one row per
    grid point and one column per cube point: shape (G, m) each; k_m's range is that of the
    sample's own χ, as in :func:`.sampling.draw`."""
    cols: dict[str, NDArray[np.float64]] = {}
    shape = (nominal["chi"].size, cube.shape[0])
    for p in VARIED:
        x0: Any = nominal[p][:, None]  # a column: each grid point's row of samples
        lo, hi = RANGES[p][0], (1.0 - cols["chi"]) if p == "km" else RANGES[p][1]
        if p not in how.varied:
            cols[p] = np.broadcast_to(x0, shape)
            continue
        u = cube[None, :, how.varied.index(p)]
        if p in how.sd:
            cols[p] = _normal(u, x0, how.sd[p], lo, hi, how.truncate)
        else:
            off_lo, off_hi = how.bounds[p]
            cols[p] = _uniform(u, x0 + off_lo, x0 + off_hi, lo, hi, how.truncate)
        cols[p] = np.broadcast_to(cols[p], shape)
    return cols


def reason_counts(
    nominal: Mapping[str, NDArray[np.float64]],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int,
) -> NDArray[np.int64]:
    """How many samples of each grid point end with each Reason code, shape (G, CODES);
    samples outside the physical range count as INVALID_PARAMS."""
    grid = columns(nominal, cube, how)
    flat = {p: np.ascontiguousarray(v).ravel() for p, v in grid.items()}
    # A grid point outside the physical range (a ramp angle past pi/2, NaN) has no valid
    # sample, as a region's point there is invalid: its truncated samples would be a point
    # inside.
    inside = np.repeat(_physical(nominal), cube.shape[0])
    valid = _physical(flat) & inside
    opts = {"rule": how.rule, "n_threads": n_threads}
    reason = evaluate("jarm", flat, valid, opts)["reason"].astype(np.int64)
    rows = np.repeat(np.arange(nominal["chi"].size), cube.shape[0])
    size = nominal["chi"].size * CODES
    return np.bincount(rows * CODES + reason, minlength=size).reshape(-1, CODES)


def _physical(values: Mapping[str, NDArray[np.float64]]) -> NDArray[np.bool_]:
    """Whether each (χ, km, α, μ_s) lies in its physical range
    (:func:`.sampling._in_range`, the parameters the closed form does not take at 0)."""
    zero = np.zeros(())
    rest = {"mu_k": values["mu_s"], "restitution": zero, "theta0": zero, "omega0": zero}
    return _in_range({**values, **rest})


def _counts_in_blocks(
    nominal: Mapping[str, NDArray[np.float64]],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int,
    report: Progress | None,
) -> NDArray[np.int64]:
    """:func:`reason_counts` of every grid point, in blocks of about :data:`BLOCK` samples
    (a block of grid points with all their samples, or one grid point's samples in parts:
    counts add up), so that the memory stays bounded."""
    points, n = nominal["chi"].size, cube.shape[0]
    per_block = max(1, BLOCK // max(n, 1))
    step = BLOCK if per_block == 1 else n
    counts = np.zeros((points, CODES), dtype=np.int64)
    for g0 in range(0, points, per_block):
        part = {p: v[g0 : g0 + per_block] for p, v in nominal.items()}
        for s0 in range(0, n, step):
            counts[g0 : g0 + per_block] += reason_counts(part, cube[s0 : s0 + step], how, n_threads)
        if report is not None:
            report(min(g0 + per_block, points) * n, points * n)
    return counts


def fields_of(counts: NDArray[np.int64], confidence: float) -> dict[str, NDArray]:
    """The map's fields from the Reason counts of each grid point (shape (G, CODES)): NaN
    shares and n_valid 0 where a point has no valid sample."""
    n_valid = counts.sum(axis=1) - counts[:, Reason.INVALID_PARAMS]
    jarm = counts[:, Reason.JARM]
    with np.errstate(invalid="ignore", divide="ignore"):
        share = counts / n_valid[:, None]
    # The interval of each point by the one Wilson formula of uncertainty() (a loop over
    # grid points of a few arithmetic operations each, after the samples' work).
    pairs = zip(jarm.tolist(), n_valid.tolist(), strict=True)
    ends = np.array(
        [wilson(k, m, confidence) if m else (np.nan, np.nan) for k, m in pairs], dtype=np.float64
    ).reshape(-1, 2)
    out: dict[str, NDArray] = {
        "p_jarm": share[:, Reason.JARM],
        "p_jarm_low": ends[:, 0],
        "p_jarm_high": ends[:, 1],
        "n_valid": n_valid.astype(np.uint32),
    }
    out.update({name: share[:, r] for r, name in SHARE_OF.items()})
    return {k: np.ascontiguousarray(out[k]) for k in FIELDS}


def nominal_of(
    alpha: NDArray[np.float64], chi: NDArray[np.float64], km_frac: NDArray[np.float64], mu_s: float
) -> dict[str, NDArray[np.float64]]:
    """The nominal (α, χ, km, μ_s) of every point of the grid α × χ × km_frac,
    flat in C order (k_m = km_frac (1 − χ))."""
    a, c, f = np.meshgrid(alpha, chi, km_frac, indexing="ij")
    return {
        "alpha": a.ravel(),
        "chi": c.ravel(),
        "km": (f * (1.0 - c)).ravel(),
        "mu_s": np.full(a.size, mu_s),
    }


def grid_fields(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int = 0,
    report: Progress | None = None,
) -> dict[str, NDArray]:
    """The fields of every point of the grid α × χ × km_frac (flat, C order): the
    grid function of :func:`eccjump.maps.dask.lazy_fields` and of the map computed now."""
    nominal = nominal_of(alpha, chi, km_frac, how.mu_s)
    return point_fields(nominal, cube, how, n_threads, report)


def point_fields(
    nominal: Mapping[str, NDArray[np.float64]],
    cube: NDArray[np.float64],
    how: GridSpread,
    n_threads: int = 0,
    report: Progress | None = None,
) -> dict[str, NDArray]:
    """The fields of any points (``nominal``: flat columns ``chi``, ``km``, ``alpha``,
    ``mu_s`` of shape (G,)), not only a grid's: the batch path of :func:`grid_fields`, also that of
    ``design(..., p_target=)`` over its candidate designs."""
    return fields_of(_counts_in_blocks(nominal, cube, how, n_threads, report), how.confidence)


__all__ = [
    "BLOCK",
    "VARIED",
    "GridSpread",
    "columns",
    "fields_of",
    "grid_fields",
    "nominal_of",
    "point_fields",
    "reason_counts",
]
