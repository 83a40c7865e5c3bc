"""The samples of an uncertainty study: which parameters vary and how (:class:`Spread`), the
unit-cube points (pseudo-random or scrambled Sobol), and their map onto the parameters.

Each varied parameter takes one column of the unit cube, in the order of :data:`PARAMETERS`,
and is mapped by its inverse CDF: a normal (nominal, sd) or a uniform (lo, hi). The physical
range of a parameter (:data:`RANGES`; k_m in [0, 1 - χ] and μ_k in [0, μ_s] of the sample's
own χ and μ_s) is handled by the ``invalid`` policy:

- ``"truncate"``: each distribution is conditioned on the physical range by the inverse CDF
  of the truncated distribution. No sample is redrawn: sample i is always the image of cube
  point i, so the Sobol structure and the seed's stream stay intact. Only a uniform whose
  (lo, hi) misses the range altogether (k_m bounds above 1 - χ) leaves a sample invalid.
- ``"count"``: the distributions as given; a sample outside the physical range is invalid.

Invalid samples are counted (``n_valid`` and ``p_invalid`` of the result) and left out of
every probability.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import KM_ROUNDING
from eccjump._base.checks import integer, mapping, real, short, text

#: The parameters that may vary, in the order of the cube's columns: k_m after chi and mu_k
#: after mu_s, whose sampled values bound them.
PARAMETERS = ("chi", "km", "alpha", "mu_s", "mu_k", "restitution", "theta0", "omega0")

#: The unit of each parameter, for messages and files.
UNITS = {
    "chi": "1",
    "km": "1",
    "alpha": "rad",
    "mu_s": "1",
    "mu_k": "1",
    "restitution": "1",
    "theta0": "rad",
    "omega0": "sqrt(g/R)",
}

#: The physical range of each parameter (km's upper end is 1 - chi, mu_k's is mu_s, of the
#: same sample; theta0 and omega0: the simulator's limits).
RANGES: dict[str, tuple[float, float]] = {
    "chi": (0.0, 1.0),
    "km": (0.0, 1.0),
    "alpha": (0.0, math.pi / 2),
    "mu_s": (0.0, math.inf),
    "mu_k": (0.0, math.inf),
    "restitution": (0.0, 1.0),
    "theta0": (-2 * math.pi * 1e6, 2 * math.pi * 1e6),
    "omega0": (-1e6, 1e6),
}

Sampling = Literal["random", "sobol"]
Invalid = Literal["truncate", "count"]

#: The most samples of one study (8 columns of float64 and the outcomes: ~2 GB).
N_MAX = 10**8

#: The widest spread of a parameter, its sd or its bounds' |lo| and |hi|: the variance of the
#: first-order estimate (sd**2, (hi - lo)**2 / 12) and its products with the derivatives stay
#: finite (a sd of 1e300 overflowed), and hi - lo of a uniform too. Far wider than any
#: physical range (|theta0| <= 2 pi 1e6 is the widest).
SPREAD_MAX = 1e100


@dataclass(frozen=True)
class Spread:
    """How the parameters vary: ``sd`` (normal standard deviations) and ``bounds`` (uniform
    ranges) by name, around the ``nominal`` values of all of :data:`PARAMETERS`;
    ``mu_k_follows``: μ_k was not given, so a sample's μ_k is its μ_s unless μ_k varies
    (then around the nominal μ_s)."""

    nominal: dict[str, float]
    sd: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    mu_k_follows: bool = False

    @property
    def varied(self) -> tuple[str, ...]:
        """The parameters that vary (sd > 0 or bounds lo < hi), in the cube's order."""
        return tuple(
            p
            for p in PARAMETERS
            if self.sd.get(p, 0.0) > 0 or (p in self.bounds and np.ptp(self.bounds[p]) > 0)
        )


def _name(option: str, key: object, allowed: tuple[str, ...]) -> str:
    if key in PARAMETERS and key not in allowed:
        raise ValueError(
            f"{option}: {key} does not enter question='jarm' (it varies {', '.join(allowed)}); "
            "use question='motion'"
        )
    if key not in allowed:
        raise ValueError(f"{option}: unknown parameter {short(key)}; allowed: {', '.join(allowed)}")
    return str(key)


def _sd(value: object, allowed: tuple[str, ...], option: str = "sd") -> dict[str, float]:
    """The standard deviations by name; ``option`` is what the caller calls them (``sd``,
    ``tolerances``), for the messages."""
    out = {}
    for key, v in (mapping(option, value) or {}).items():
        name = _name(option, key, allowed)
        x = real(f"{option}[{name!r}]", v)
        if not 0 <= x <= SPREAD_MAX:
            raise ValueError(
                f"{option}[{name!r}] = {short(x)} [{UNITS[name]}] is outside the allowed range "
                f"[0, {SPREAD_MAX:g}]"
            )
        out[name] = x
    return out


def _bounds(value: object, allowed: tuple[str, ...]) -> dict[str, tuple[float, float]]:
    out = {}
    for key, v in (mapping("bounds", value) or {}).items():
        name = _name("bounds", key, allowed)
        if isinstance(v, str | bytes) or not hasattr(v, "__len__") or len(v) != 2:
            raise TypeError(f"bounds[{name!r}] must be a pair (lo, hi), not {short(v)}")
        lo, hi = (real(f"bounds[{name!r}]", x) for x in v)
        if not -SPREAD_MAX <= lo <= hi <= SPREAD_MAX:
            raise ValueError(
                f"bounds[{name!r}] = ({short(lo)}, {short(hi)}) [{UNITS[name]}]: "
                f"need -{SPREAD_MAX:g} <= lo <= hi <= {SPREAD_MAX:g}"
            )
        out[name] = (lo, hi)
    return out


def check_nominal(nominal: Mapping[str, float]) -> None:
    """ValueError naming the first nominal value outside its physical range."""
    upper = {"km": 1.0 - nominal["chi"] + KM_ROUNDING, "mu_k": nominal["mu_s"]}
    for p in PARAMETERS:
        lo, hi = RANGES[p][0], upper.get(p, RANGES[p][1])
        x = nominal[p]
        if not (math.isfinite(x) and lo <= x <= hi):
            end = f"{short(hi)}]" if math.isfinite(hi) else "inf)"
            raise ValueError(
                f"{p} = {short(x)} [{UNITS[p]}] is outside the allowed range [{short(lo)}, {end}"
            )


def spread(
    nominal: Mapping[str, float],
    sd: object,
    bounds: object,
    allowed: tuple[str, ...],
    mu_k_follows: bool = False,
    sd_option: str = "sd",
) -> Spread:
    """The checked :class:`Spread`: names among ``allowed``, sd ≥ 0, lo ≤ hi, no parameter
    both in ``sd`` and in ``bounds`` (ValueError or TypeError naming it; ``sd`` as the caller
    calls it, ``sd_option``)."""
    s, b = _sd(sd, allowed, sd_option), _bounds(bounds, allowed)
    both = sorted(set(s) & set(b), key=PARAMETERS.index)
    if both:
        raise ValueError(f"{both[0]}: give sd or bounds, not both")
    check_nominal(nominal)
    return Spread(dict(nominal), s, b, mu_k_follows)


def options(
    n: object, seed: object, sampling: object, invalid: object
) -> tuple[int, int, str, str]:
    """The checked sample size, seed, sampling and invalid policy."""
    size = integer("n", n, 1, N_MAX)
    sd = integer("seed", seed, 0, 2**64 - 1)
    how = text("sampling", sampling)
    if how not in ("random", "sobol"):
        raise ValueError(f"sampling must be 'random' or 'sobol', not {short(how)}")
    policy = text("invalid", invalid)
    if policy not in ("truncate", "count"):
        raise ValueError(f"invalid must be 'truncate' or 'count', not {short(policy)}")
    return size, sd, how, policy


def unit_cube(n: int, d: int, seed: int, sampling: str, stream: int = 0) -> NDArray[np.float64]:
    """n points of [0, 1)^d: numpy's PCG64 stream of ``seed``, or the first n points of
    Owen-scrambled Sobol' (``scipy.stats.qmc.Sobol``, scrambled with ``seed``). Sobol'
    points balance best for n a power of 2 (scipy's warning about it is not repeated).

    ``stream`` > 0 gives another cube of the same seed, independent of stream 0 (numpy's
    ``SeedSequence(seed, spawn_key=(stream,))``): the second matrix of a Saltelli design.
    Stream 0 is the study's own samples, drawn from ``seed`` itself."""
    if d == 0:
        return np.empty((n, 0))
    source: Any = seed
    if stream:
        source = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(stream,)))
    if sampling == "random":
        return np.random.default_rng(source).random((n, d))
    qmc = _scipy().qmc
    with warnings.catch_warnings():
        warnings.filterwarnings(
            "ignore", message=".*balance properties of Sobol", category=UserWarning
        )
        return np.asarray(qmc.Sobol(d, scramble=True, seed=source).random(n), dtype=np.float64)


def _scipy() -> Any:
    try:
        import scipy.special
        import scipy.stats
    except ImportError as err:  # pragma: no cover - scipy is in the test extras
        raise ImportError("uncertainty needs scipy: pip install 'eccjump[analysis]'") from err
    return scipy.stats


def _normal(
    u: NDArray[np.float64], m: float, s: float, lo: Any, hi: Any, truncate: bool
) -> NDArray[np.float64]:
    """N(m, s²) at quantiles u, truncated to [lo, hi] if ``truncate``."""
    stats = _scipy()
    if not truncate:
        return m + s * stats.norm.ppf(u)
    with np.errstate(invalid="ignore", divide="ignore"):
        x = stats.truncnorm.ppf(u, (lo - m) / s, (hi - m) / s, loc=m, scale=s)
    return np.asarray(x, dtype=np.float64)


def _uniform(
    u: NDArray[np.float64], lo: float, hi: float, range_lo: Any, range_hi: Any, truncate: bool
) -> NDArray[np.float64]:
    """U(lo, hi) at quantiles u, restricted to [range_lo, range_hi] if ``truncate`` (NaN
    where the two do not meet)."""
    if not truncate:
        return lo + u * (hi - lo)
    a, b = np.maximum(lo, range_lo), np.minimum(hi, range_hi)
    with np.errstate(invalid="ignore"):
        return np.where(a <= b, a + u * (b - a), np.nan)


def draw(
    spec: Spread, n: int, seed: int, sampling: str, invalid: str
) -> tuple[dict[str, NDArray[np.float64]], NDArray[np.bool_]]:
    """The columns of all :data:`PARAMETERS` (a constant one where a parameter does not vary;
    μ_k follows μ_s where its nominal is None and it does not vary) and the valid samples."""
    return columns(spec, unit_cube(n, len(spec.varied), seed, sampling), invalid)


def columns(
    spec: Spread, cube: NDArray[np.float64], invalid: str
) -> tuple[dict[str, NDArray[np.float64]], NDArray[np.bool_]]:
    """:func:`draw`'s columns and valid samples from given points of the unit cube (one
    column per varied parameter, in :attr:`Spread.varied`'s order)."""
    varied = spec.varied
    n = cube.shape[0]
    truncate = invalid == "truncate"
    cols: dict[str, NDArray[np.float64]] = {}
    for p in PARAMETERS:
        lo = RANGES[p][0]
        hi: float | NDArray[np.float64] = RANGES[p][1]
        if p == "km":
            hi = 1.0 - cols["chi"]
        elif p == "mu_k":
            hi = cols["mu_s"]
        if p not in varied:
            follows = p == "mu_k" and spec.mu_k_follows
            cols[p] = cols["mu_s"].copy() if follows else np.full(n, spec.nominal[p])
            continue
        u = cube[:, varied.index(p)]
        if p in spec.sd:
            cols[p] = _normal(u, spec.nominal[p], spec.sd[p], lo, hi, truncate)
        else:
            cols[p] = _uniform(u, *spec.bounds[p], lo, hi, truncate)
    return cols, _in_range(cols)


def _in_range(cols: Mapping[str, NDArray[np.float64]]) -> NDArray[np.bool_]:
    """The samples whose every value lies in its physical range (NaN never does)."""
    ok = np.ones(cols["chi"].size, dtype=bool)
    upper = {"km": 1.0 - cols["chi"] + KM_ROUNDING, "mu_k": cols["mu_s"]}
    for p in PARAMETERS:
        lo, hi = RANGES[p][0], upper.get(p, RANGES[p][1])
        ok &= (cols[p] >= lo) & (cols[p] <= hi)
    return ok


__all__ = [
    "N_MAX",
    "PARAMETERS",
    "RANGES",
    "SPREAD_MAX",
    "UNITS",
    "Invalid",
    "Sampling",
    "Spread",
    "check_nominal",
    "columns",
    "draw",
    "options",
    "spread",
    "unit_cube",
]
