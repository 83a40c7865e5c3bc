"""Which tolerance matters: the first-order and total Sobol' indices of P(JARM) by Saltelli's
design and Jansen's estimators, with bootstrap intervals.

**The design** (Saltelli et al. 2010). A is the study's own n points of the unit cube (one
column per varied parameter), B another n points of the same seed (the last d columns of a
2d-dimensional cube from an independent stream, :func:`.sampling.unit_cube`'s ``stream=1``:
for Sobol' points A and B are then one 2d-dimensional net), and AB_i is A with its column i
taken from B. The model is answered at B and at every AB_i besides A: n (d + 2) runs for d
varied parameters, n of them the study itself, so ``indices=True`` costs n (d + 1) runs more
and leaves the study's own results bit-identical.

**The estimators** (Jansen 1999; Saltelli et al. 2010, table 2 (f)), with V the variance of
f over A and B together:

- first order S_i = (V - mean((f(B) - f(AB_i))²) / 2) / V: f(B) and f(AB_i) share only x_i;
- total S_Ti = mean((f(A) - f(AB_i))²) / 2 / V: f(A) and f(AB_i) differ only in x_i.

These are the estimators of ``scipy.stats.sobol_indices`` for the total and, for the first
order, Jansen's in place of scipy's ``saltelli_2010`` (f(B) (f(AB_i) - f(A))): the same limit,
and Jansen's is the one recommended for its smaller error where an index is small. scipy's
function itself does not fit: it draws its own cube from independent distributions, while the
study's samples are the truncated, chained ones of :mod:`.sampling`. A raw estimate is
returned: a first-order index near 0 can come out slightly negative, and an index can pass 1.

**What the inputs are.** The indices are those of the model on the unit cube, whose columns are
independent uniforms, as the study maps them (:func:`.sampling.columns`). Where the truncation
of k_m to [0, 1 − χ] (or of μ_k to [0, μ_s]) does not bind, a column is its parameter and the
indices are the usual ones of independent inputs. Where it binds, k_m is the quantile u_km of
its range given the sample's χ, so "km" is the index of that quantile, and χ's index
includes χ's effect through the range of k_m: the physical k_m and χ are then dependent and
no variance decomposition of them exists; that of the cube's columns does.

**Invalid samples.** A row of the design (A, B and the d AB_i at one index) with an invalid
sample is left out of every estimate. Under ``invalid="truncate"`` no sample is invalid except
where a uniform k_m range misses [0, 1 − χ] (and k_m = 0 in the full motion), so nothing is
left out; under ``"count"`` the rows kept are not a sample of the whole cube, and the indices
are only an estimate of those of the model restricted to the physical range. Where fewer than
half the rows are in range the estimate would describe a corner of the cube: a ValueError
naming ``indices``, before any sample is answered.

**The lift-off time.** For the full motion (``question="motion"``) the same design gives the
indices of the first lift-off's time [√(R/g)] too, over the rows where every sample lifts
off within ``t_max`` (the others are left out, as invalid ones: an estimate conditional on the
lift-off; None where fewer than half the rows lift off).

**The intervals** are percentile bootstrap intervals at the study's ``confidence``: the rows
of the design are resampled (:data:`RESAMPLES` times; beyond :data:`GROUPS` rows in groups of
rows i mod :data:`GROUPS`, whose sums are independent, so the work stays bounded for any n),
from numpy's PCG64 stream of ``SeedSequence(seed, spawn_key=(2,))``. For Sobol' points they are
those of random sampling, conservative. Where f does not vary over A and B (every sample jumps,
or none), no tolerance matters: every index is 0.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump._base.progress import Progress
from eccjump.studies.uncertainty.questions import evaluate, jumps, ran
from eccjump.studies.uncertainty.sampling import Spread, columns, unit_cube

#: Bootstrap resamples of an interval.
RESAMPLES = 1000
#: The most groups of rows the bootstrap resamples (all rows where there are fewer).
GROUPS = 4096
#: Resamples computed at once (memory: this many x GROUPS x the terms of a row, ~30 MB).
_BATCH = 50


class Estimate(NamedTuple):
    """An index and its bootstrap interval at the study's confidence."""

    value: float
    low: float
    high: float


class SobolIndex(NamedTuple):
    """A varied parameter's first-order and total Sobol' indices: the share of the variance
    of the output that the parameter explains alone (``first``) and with all its interactions
    (``total``)."""

    first: Estimate
    total: Estimate


def _terms(f_a: NDArray, f_b: NDArray, f_ab: NDArray) -> NDArray[np.float64]:
    """The terms of each row whose sums make the estimates: a count, f_A + f_B and
    f_A² + f_B² (centred on their mean, so that a variance small against the mean keeps its
    digits), and per parameter (f_B - f_AB_i)² and (f_A - f_AB_i)². Shape (n, 3 + 2d)."""
    centre = (f_a.sum() + f_b.sum()) / (2 * f_a.size) if f_a.size else 0.0
    a, b, ab = f_a - centre, f_b - centre, f_ab - centre
    return np.column_stack(
        [np.ones_like(a), a + b, a * a + b * b, ((b - ab) ** 2).T, ((a - ab) ** 2).T]
    )


def _estimates(sums: NDArray[np.float64], d: int) -> tuple[NDArray, NDArray]:
    """Jansen's first-order and total indices from summed terms (:func:`_terms`) of shape
    (..., 3 + 2d): arrays (..., d). 0 where the output does not vary."""
    count = sums[..., :1]
    mean = sums[..., 1:2] / (2 * count)
    var = sums[..., 2:3] / (2 * count) - mean * mean
    varies = var > 0
    safe = np.where(varies, var, 1.0)
    first = (var - sums[..., 3 : 3 + d] / (2 * count)) / safe
    total = sums[..., 3 + d :] / (2 * count) / safe
    return np.where(varies, first, 0.0), np.where(varies, total, 0.0)


def _group_sums(terms: NDArray[np.float64]) -> NDArray[np.float64]:
    """The sums of the terms over the rows i mod G, G = min(n, GROUPS): (G, columns)."""
    n, k = terms.shape
    g = min(n, GROUPS)
    padded = np.zeros((-(-n // g) * g, k))
    padded[:n] = terms
    return padded.reshape(-1, g, k).sum(axis=0)


def _bootstrap(
    groups: NDArray[np.float64], d: int, seed: int, confidence: float
) -> tuple[NDArray, NDArray]:
    """The percentile intervals (2, d) of the first-order and total indices over
    :data:`RESAMPLES` resamples of the groups."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(2,)))
    g = groups.shape[0]
    firsts, totals = [], []
    for start in range(0, RESAMPLES, _BATCH):
        pick = rng.integers(0, g, size=(min(_BATCH, RESAMPLES - start), g))
        first, total = _estimates(groups[pick].sum(axis=1), d)
        firsts.append(first)
        totals.append(total)
    tail = (1 - confidence) / 2
    q = (tail, 1 - tail)
    return np.quantile(np.vstack(firsts), q, axis=0), np.quantile(np.vstack(totals), q, axis=0)


def _rows(f_a: NDArray, f_b: NDArray, f_ab: NDArray) -> NDArray[np.bool_]:
    """The rows of the design whose every output is a number."""
    return np.isfinite(f_a) & np.isfinite(f_b) & np.isfinite(f_ab).all(axis=0)


def sobol_indices(
    f_a: NDArray[np.float64],
    f_b: NDArray[np.float64],
    f_ab: NDArray[np.float64],
    names: Sequence[str],
    confidence: float,
    seed: int,
) -> dict[str, SobolIndex]:
    """Jansen's first-order and total indices of the outputs f_A (n), f_B (n) and f_AB (d, n)
    of a Saltelli design, by parameter name, with percentile bootstrap intervals at
    ``confidence``; a row with a NaN output anywhere is left out. ValueError naming
    ``indices`` where no row is left."""
    f_ab = np.asarray(f_ab, dtype=np.float64).reshape(len(names), -1)
    keep = _rows(f_a, f_b, f_ab)
    if not keep.any():
        raise ValueError(
            "indices: no row of the Saltelli design has all its d + 2 samples valid; "
            "use invalid='truncate' or narrower tolerances"
        )
    terms = _terms(f_a[keep], f_b[keep], f_ab[:, keep])
    first, total = _estimates(terms.sum(axis=0), len(names))
    (f_lo, f_hi), (t_lo, t_hi) = _bootstrap(_group_sums(terms), len(names), seed, confidence)
    return {
        name: SobolIndex(
            Estimate(float(first[i]), float(f_lo[i]), float(f_hi[i])),
            Estimate(float(total[i]), float(t_lo[i]), float(t_hi[i])),
        )
        for i, name in enumerate(names)
    }


#: The columns of the samples of a question and which of them are valid.
Samples = tuple[dict[str, NDArray[np.float64]], NDArray[np.bool_]]
#: The outcomes of samples and which of them are valid.
Answers = tuple[dict[str, NDArray[Any]], NDArray[np.bool_]]


def cubes(
    n: int, d: int, seed: int, sampling: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The unit-cube points of A (the study's own) and B, n x d each."""
    a = unit_cube(n, d, seed, sampling)
    # B is the last d columns of a 2d-dimensional cube: for Sobol' points, the columns d + 1
    # ... 2d of the sequence, which with A's columns 1 ... d make one 2d-dimensional net. A
    # second scramble of the same d columns would pair each row of A with a scramble of the
    # same point (a correlation of -0.75 between A's and B's first columns at n = 2**14, and
    # the Ishigami indices off by 0.5).
    return a, unit_cube(n, 2 * d, seed, sampling, stream=1)[:, d:]


def design(
    spec: Spread, n: int, seed: int, sampling: str, invalid: str, valid: NDArray[np.bool_]
) -> Samples | None:
    """The samples of B, then of AB_1 ... AB_d, stacked ((d + 1) n of them), as the study
    maps its own (A, whose samples in range are ``valid``); None where nothing varies.
    ValueError naming ``indices`` where fewer than half the rows are in range (before any
    work: the estimate would describe a corner of the cube, not the study)."""
    d = len(spec.varied)
    if d == 0:
        return None
    a, b = cubes(n, d, seed, sampling)
    pages = [b]
    for i in range(d):
        ab = a.copy()
        ab[:, i] = b[:, i]
        pages.append(ab)
    cols, ok = columns(spec, np.vstack(pages), invalid)
    rows = int((valid & ok.reshape(d + 1, n).all(axis=0)).sum())
    if 2 * rows < n:
        raise ValueError(
            f"indices: only {rows} of {n} rows of the Saltelli design have all their samples "
            "in the physical range (half needed); use invalid='truncate' or narrower tolerances"
        )
    return cols, ok


def evaluate_all(
    question: str,
    study: Samples,
    extra: Samples | None,
    opts: Mapping[str, Any],
    progress: Progress | None,
) -> tuple[dict[str, NDArray[Any]], Answers | None]:
    """The outcomes of the study's samples, and the design's outcomes with its valid flags
    (None without a design), in one :func:`.questions.evaluate` so that the progress has one
    total. Each sample is answered from its own values alone: the study's outcomes are the
    bits they are without a design."""
    cols, valid = study
    if extra is None:
        return evaluate(question, cols, valid, opts, progress), None
    n = valid.size
    both = {k: np.concatenate([v, extra[0][k]]) for k, v in cols.items()}
    out = evaluate(question, both, np.concatenate([valid, extra[1]]), opts, progress)
    return {k: v[:n] for k, v in out.items()}, ({k: v[n:] for k, v in out.items()}, extra[1])


def study_indices(
    question: str,
    names: Sequence[str],
    study: Answers,
    extra: Answers | None,
    confidence: float,
    seed: int,
) -> tuple[dict[str, SobolIndex], dict[str, SobolIndex] | None]:
    """The indices of the JARM indicator from the outcomes and valid flags of the study (A)
    and of the design (B, AB_i), {} where nothing varies; and for the full motion those of
    the first lift-off's time over the rows where every sample lifts off (None for "jarm", or
    where fewer than half the rows do: a conditional estimate of so few would mislead)."""
    motion = question == "motion"
    if extra is None:
        return {}, ({} if motion else None)

    def output(answers: Answers, liftoff: bool) -> NDArray:
        outcomes, valid = answers
        value = outcomes["liftoff_t"] if liftoff else jumps(question, outcomes)
        return np.where(valid & ran(question, outcomes), value, np.nan)

    n = study[1].size
    f_a, f = output(study, False), output(extra, False)
    jarm = sobol_indices(f_a, f[:n], f[n:], names, confidence, seed)
    if not motion:
        return jarm, None
    f_a, f = output(study, True), output(extra, True)
    if 2 * int(_rows(f_a, f[:n], f[n:].reshape(len(names), n)).sum()) < n:
        return jarm, None
    return jarm, sobol_indices(f_a, f[:n], f[n:], names, confidence, seed)


def as_json(indices: Mapping[str, SobolIndex] | None) -> dict[str, Any] | None:
    """The indices for JSON: {name: {"first": [value, low, high], "total": [...]}}."""
    if indices is None:
        return None
    return {k: {"first": list(v.first), "total": list(v.total)} for k, v in indices.items()}


def from_json(value: Mapping[str, Any] | None) -> dict[str, SobolIndex] | None:
    """:func:`as_json`'s inverse."""
    if value is None:
        return None
    return {
        str(k): SobolIndex(
            Estimate(*(float(x) for x in v["first"])), Estimate(*(float(x) for x in v["total"]))
        )
        for k, v in value.items()
    }


__all__ = [
    "GROUPS",
    "RESAMPLES",
    "Estimate",
    "SobolIndex",
    "as_json",
    "cubes",
    "design",
    "evaluate_all",
    "from_json",
    "sobol_indices",
    "study_indices",
]
