"""The JARM region's boundary surfaces alpha_lo(χ, k_m) and alpha_hi(χ, k_m) on a mesh of
bodies, for the paper's Fig. 4 (drawn by :func:`eccjump.plot.fig4` and
:func:`eccjump.plot.fig4_slices`): a scan of the ramp angles of every body, then a flood fill
that recovers the intervals thinner than the scan step next to found ones."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer
from eccjump.classification.boundary import alpha_interval_around, alpha_intervals
from eccjump.classification.classify import jarm

#: The largest (chi, k_m) mesh of :func:`jarm_surfaces` (and so of :func:`eccjump.plot.fig4`),
#: per axis: each body is scanned ``n_scan`` times and drawn as polygons; 200 takes about a
#: minute per figure.
MAX_RESOLUTION = 200


@dataclass(frozen=True)
class JarmSurfaces:
    """The boundary surfaces of the JARM region for one (μ_s, n) on a (χ, k_m) mesh.

    ``lo``/``hi`` [rad] have shape ``(len(chi), len(km))``: the first JARM α-interval of each
    body (NaN where there is none, or where k_m > 1 - χ); ``n_intervals`` counts the
    intervals (almost always 0 or 1; a second one is only drawn in the slices).
    """

    mu_s: float
    n: int
    chi: NDArray[np.float64]
    km: NDArray[np.float64]
    lo: NDArray[np.float64]
    hi: NDArray[np.float64]
    n_intervals: NDArray[np.int64]

    @property
    def any(self) -> bool:
        return bool(np.any(self.n_intervals > 0))


def _is_jarm(
    a: NDArray[np.float64], c: NDArray[np.float64], k: NDArray[np.float64], mu_s: float, n: int
) -> NDArray[np.bool_]:
    return jarm(a, c, k, mu_s, n, refine_extrema=False).is_jarm


def grid_intervals(
    c: NDArray[np.float64], k: NDArray[np.float64], mu_s: float, n: int, n_scan: int
) -> list[list[tuple[float, float]]]:
    """α-intervals of every body of a 1-D or 2-D grid (c, k), flat in C order, [] where
    k > 1 - c. A first pass scans ``n_scan`` angles (:func:`eccjump.alpha_intervals`). Then a
    flood fill: an empty body next to a body with a JARM (along the grid axes) is probed at
    angles spread over its neighbours' intervals, and where a probe is a JARM the interval
    around it is found by bisection (:func:`eccjump.jarm`), repeatedly. This recovers the
    thin parts of a region (α-intervals narrower than the scan step, common on later
    turns) at a fraction of the cost of a fine scan."""
    shape = c.shape
    flat_c, flat_k = c.ravel(), k.ravel()
    valid = flat_k <= 1.0 - flat_c
    out: list[list[tuple[float, float]]] = [[] for _ in range(flat_c.size)]
    idx = np.flatnonzero(valid)
    if idx.size:
        ivs = alpha_intervals(flat_c[idx], flat_k[idx], mu_s, n, n_scan=n_scan)
        for i, iv in zip(idx, ivs, strict=True):
            out[i] = iv
    probed = ~valid
    offsets = np.linspace(-0.5, 1.5, 9)
    while True:
        hit = np.array([bool(iv) for iv in out])
        todo, probes = [], []
        for i in np.flatnonzero(~hit & ~probed):
            pos = np.unravel_index(i, shape)
            p: list[float] = []
            for axis in range(len(shape)):
                for step in (1, -1):
                    q = list(pos)
                    q[axis] += step
                    if 0 <= q[axis] < shape[axis]:
                        j = int(np.ravel_multi_index(tuple(q), shape))
                        for lo, hi in out[j]:
                            p.extend(lo + (hi - lo) * offsets)
            if p:
                todo.append(i)
                probes.append(np.clip(p, 1e-9, 0.5 * math.pi))
        if not todo:
            return out
        probed[todo] = True
        sizes = np.array([len(p) for p in probes])
        a = np.concatenate(probes)
        body = np.repeat(np.array(todo), sizes)
        ok = _is_jarm(a, flat_c[body], flat_k[body], mu_s, n)
        first = np.r_[0, np.cumsum(sizes)[:-1]]
        seeds, where = [], []
        for b, (f, sz) in enumerate(zip(first, sizes, strict=True)):
            hits = np.flatnonzero(ok[f : f + sz])
            if hits.size:
                seeds.append(a[f + hits[0]])
                where.append(todo[b])
        if not seeds:
            return out
        w = np.array(where)
        lows, highs = alpha_interval_around(np.array(seeds), flat_c[w], flat_k[w], mu_s, n)
        for i, lo_i, hi_i in zip(w, lows, highs, strict=True):
            out[i] = [(float(lo_i), float(hi_i))]


def _intervals_on_mesh(
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: float,
    n: int,
    n_scan: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]:
    c, k = np.meshgrid(chi, km, indexing="ij")
    ivs = grid_intervals(c, k, mu_s, n, n_scan)
    lo = np.full(c.shape, np.nan)
    hi = np.full(c.shape, np.nan)
    count = np.zeros(c.shape, dtype=np.int64)
    for i, iv in enumerate(ivs):
        count.flat[i] = len(iv)
        if iv:
            lo.flat[i], hi.flat[i] = iv[0]
    return lo, hi, count


def jarm_surfaces(
    mu_s: float,
    n: int,
    *,
    resolution: int = 36,
    chi_range: tuple[float, float] | None = None,
    km_range: tuple[float, float] | None = None,
    n_scan: int = 90,
) -> JarmSurfaces:
    """alpha_lo/alpha_hi of the JARM region on turn ``n`` over a ``resolution``² (χ, k_m)
    mesh. Without explicit ranges, a coarse scan of the whole body triangle
    0 ≤ k_m ≤ 1 - χ finds the footprint of the region and the mesh is fitted to it
    (two coarse cells wider).
    Each body's ramp angles are scanned at ``n_scan`` points over (0, 90 deg], and intervals
    narrower than the scan step are recovered next to found ones (see :func:`grid_intervals`).
    ``resolution``: 2 ... :data:`MAX_RESOLUTION`."""
    resolution = integer("resolution", resolution, 2, MAX_RESOLUTION)
    if chi_range is None or km_range is None:
        cc = np.linspace(0.0, 1.0, 21)
        kk = np.linspace(0.0, 1.0, 21)
        _, _, cnt = _intervals_on_mesh(cc, kk, mu_s, n, max(n_scan, 180))
        hit_c, hit_k = np.nonzero(cnt > 0)
        if hit_c.size == 0:
            c_box, k_box = (0.0, 1.0), (0.0, 1.0)
        else:
            dc, dk = 2.0 * (cc[1] - cc[0]), 2.0 * (kk[1] - kk[0])
            c_box = (max(0.0, cc[hit_c.min()] - dc), min(1.0, cc[hit_c.max()] + dc))
            k_box = (max(0.0, kk[hit_k.min()] - dk), min(1.0, kk[hit_k.max()] + dk))
        chi_range = chi_range if chi_range is not None else c_box
        km_range = km_range if km_range is not None else k_box
    chi = np.linspace(*chi_range, resolution)
    km = np.linspace(*km_range, resolution)
    lo, hi, cnt = _intervals_on_mesh(chi, km, mu_s, n, n_scan)
    return JarmSurfaces(float(mu_s), int(n), chi, km, lo, hi, cnt)
