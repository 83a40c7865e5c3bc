"""The result of :func:`eccjump.uncertainty`: the samples, what each did, and the
probabilities and distributions made of them (:class:`Uncertainty`), with the Wilson score
interval of a binomial share (:func:`wilson`)."""

from __future__ import annotations

import errno
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump._base.arrays import fields_equal
from eccjump._base.canvas import Plottable
from eccjump._base.checks import flag, real, short
from eccjump._base.checks import path as path_arg
from eccjump._base.html import card, num
from eccjump._base.overwrite import check_overwrite, never
from eccjump.maps import results, store
from eccjump.maps.results import Result
from eccjump.studies.uncertainty.delta import Delta
from eccjump.studies.uncertainty.indices import SobolIndex, as_json, from_json
from eccjump.studies.uncertainty.questions import OUTCOME_DTYPES
from eccjump.studies.uncertainty.sampling import UNITS

if TYPE_CHECKING:
    import xarray as xr

#: The quantiles of each distribution's summary.
QUANTILES = (0.025, 0.25, 0.5, 0.75, 0.975)

#: The outcome quantities whose distributions are summarised, with their units: the
#: lift-off angle for both questions (the JARM angle theta_J for "jarm", the first lift-off,
#: from any mode, for "motion"), the rest for "motion" only.
QUANTITIES = {
    "liftoff_theta": "rad",
    "liftoff_t": "sqrt(R/g)",
    "flight_time": "sqrt(R/g)",
    "apex": "R",
    "distance": "R",
}


#: The largest confidence level: the two-sided quantile is that of 0.5 + confidence/2, which
#: must stay below 1 in floating point (at 1 - 2**-53 it rounds to 1, where the normal
#: quantile is infinite); 1 - 1e-15 keeps a clear margin (z = 8.1).
CONFIDENCE_MAX = 1 - 1e-15


def check_confidence(value: object) -> float:
    """The confidence level, in (0, :data:`CONFIDENCE_MAX`]; ValueError naming it."""
    level = real("confidence", value)
    if not 0 < level <= CONFIDENCE_MAX:
        raise ValueError(f"confidence = {short(level)} is outside the allowed range (0, 1 - 1e-15]")
    return level


def wilson(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """The Wilson score interval of a share k/n at ``confidence`` (two-sided, in
    (0, 1 - 1e-15]); (0, 1) for n = 0. Its coverage is close to nominal even for shares near
    0 or 1, unlike the normal approximation, and it needs no iteration (Clopper–Pearson's is
    wider than nominal)."""
    z = _z(check_confidence(confidence))
    if n == 0:
        return 0.0, 1.0
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    # At k = 0 or k = n an end is exactly 0 or 1; rounding would put it a few ulps inside,
    # on the wrong side of the share itself.
    low = 0.0 if k == 0 else max(0.0, centre - half)
    high = 1.0 if k == n else min(1.0, centre + half)
    return low, high


def _z(confidence: float) -> float:
    """The standard normal quantile of a two-sided ``confidence``."""
    from statistics import NormalDist

    return NormalDist().inv_cdf(0.5 + confidence / 2)


class Summary(NamedTuple):
    """A distribution in numbers: the samples it holds (n), mean, standard deviation and the
    :data:`QUANTILES` (NaN where it holds none)."""

    n: int
    mean: float
    sd: float
    q025: float
    q25: float
    median: float
    q75: float
    q975: float

    @classmethod
    def of(cls, x: NDArray[np.float64]) -> Summary:
        x = x[np.isfinite(x)]
        if x.size == 0:
            return cls(0, *([math.nan] * 7))
        q = np.quantile(x, QUANTILES)
        sd = float(np.std(x, ddof=1)) if x.size > 1 else math.nan
        return cls(int(x.size), float(np.mean(x)), sd, *(float(v) for v in q))


@dataclass(frozen=True, eq=False, repr=False)
class Uncertainty(Result, Plottable, kind="uncertainty", suffixes=(".csv",)):
    """What the spread of the inputs does to a JARM or to the first flight
    (:func:`eccjump.uncertainty`).

    Attributes
    ----------
    question : {"jarm", "motion"}
        What each sample answered: the JARM classification (:func:`eccjump.jarm`) or the
        full motion to the first landing (:func:`eccjump.motion_points`).
    sampling : {"random", "sobol"}
        Pseudo-random (numpy's PCG64) or scrambled Sobol' points.
    invalid : {"truncate", "count"}
        How samples outside the physical range were treated (:mod:`.sampling`).
    n, seed : int
        The sample size and the seed.
    confidence : float
        The level of the confidence intervals.
    nominal : dict of str to float
        The nominal value of every parameter (χ, km, α, μ_s, μ_k, restitution,
        theta0, omega0).
    sd, bounds : dict
        The normal standard deviations and uniform ranges, by parameter.
    samples : dict of str to numpy.ndarray
        The sampled values of the varied parameters, one array of length n each.
    valid : numpy.ndarray of bool
        The samples within the physical range that the question could answer (the others
        count in no probability).
    outcomes : dict of str to numpy.ndarray
        What each sample did: for "jarm" ``is_jarm``, ``reason``, ``liftoff_theta`` (θ_J of
        a JARM, else NaN), ``Fy_J``, ``max_ratio``; for "motion" every field of
        :class:`eccjump.MotionPoints` (``jarm``, ``sequence``, ``liftoff_theta``, ``apex``, ...).
    n_valid : int
        The valid samples.
    p_jarm : float
        The share of valid samples that jump straight out of pure rolling (a JARM).
    p_jarm_ci : tuple of float
        Its Wilson score interval at ``confidence``. For Sobol' samples this is the interval
        of random sampling of the same size: conservative, as the quasi-random error is
        usually smaller (estimate it from repeated seeds).
    counts : dict of str to int
        The valid samples of each outcome: each :class:`eccjump.Reason` by name ("jarm"),
        each sequence of modes such as ``"ROLL→FLIGHT→SLIP"`` ("motion"), most frequent
        first (:attr:`probabilities`: their shares).
    distributions : dict of str to Summary
        Count, mean, sd and quantiles of the lift-off angle [rad] ("jarm": over the JARM
        samples) and, for "motion", the lift-off time, flight time, apex and distance of the
        first flight (over the samples that fly).
    delta : Delta or None
        The first-order (delta-method) estimate beside the Monte Carlo one, from the exact
        derivatives of ``jarm(..., derivatives=True)`` ("jarm") or of
        ``simulate(..., sensitivities=True)`` ("motion") at the nominal point; None where the
        nominal point is no JARM ("jarm") or does not fly ("motion")
        (:func:`eccjump.studies.uncertainty.delta.delta_method`).
    indices : dict of str to SobolIndex or None
        With ``indices=True``, which tolerance matters: by varied parameter (a parameter held
        fixed has none), the first-order and total Sobol' indices of the JARM indicator,
        ``.first`` and ``.total``, each an ``Estimate`` (``value``, ``low``, ``high``: the
        bootstrap interval at ``confidence``)
        (:mod:`eccjump.studies.uncertainty.indices`); None without.
    liftoff_indices : dict of str to SobolIndex or None
        With ``indices=True`` and ``question="motion"``, the same for the first lift-off's
        time, over the rows of the design where every sample lifts off; None otherwise (or
        where fewer than half the rows do).
    """

    question: str
    sampling: str
    invalid: str
    n: int
    seed: int
    confidence: float
    nominal: dict[str, float]
    sd: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    samples: dict[str, NDArray[np.float64]]
    valid: NDArray[np.bool_]
    outcomes: dict[str, NDArray[Any]]
    n_valid: int
    p_jarm: float
    p_jarm_ci: tuple[float, float]
    counts: dict[str, int]
    distributions: dict[str, Summary]
    delta: Delta | None = None
    indices: dict[str, SobolIndex] | None = None
    liftoff_indices: dict[str, SobolIndex] | None = None

    __eq__ = fields_equal
    __hash__ = None  # type: ignore[assignment]

    @property
    def p_invalid(self) -> float:
        """The share of samples outside the physical range."""
        return 1.0 - self.n_valid / self.n

    @property
    def probabilities(self) -> dict[str, float]:
        """The share of each outcome of :attr:`counts` among the valid samples."""
        return {k: c / max(self.n_valid, 1) for k, c in self.counts.items()}

    def interval(self, outcome: str) -> tuple[float, float]:
        """The Wilson interval of the probability of ``outcome`` (a key of :attr:`counts`;
        one no sample had: (0, upper end)) at ``confidence``."""
        return wilson(self.counts.get(outcome, 0), self.n_valid, self.confidence)

    def to_dict(self) -> dict[str, Any]:
        """The numbers (no sample arrays), JSON-ready: a number that is not finite (the
        summary of a distribution without samples, for one) is None (null)."""
        return {
            "question": self.question,
            "sampling": self.sampling,
            "invalid": self.invalid,
            "n": self.n,
            "seed": self.seed,
            "confidence": self.confidence,
            "nominal": self.nominal,
            "sd": self.sd,
            "bounds": {k: list(v) for k, v in self.bounds.items()},
            "n_valid": self.n_valid,
            "p_jarm": self.p_jarm,
            "p_jarm_ci": list(self.p_jarm_ci),
            "counts": self.counts,
            "probabilities": self.probabilities,
            "distributions": {
                k: {f: _json(v) for f, v in s._asdict().items()}
                for k, s in self.distributions.items()
            },
            "delta": None
            if self.delta is None
            else {k: _json(v) for k, v in self.delta._asdict().items()},
            "indices": as_json(self.indices),
            "liftoff_indices": as_json(self.liftoff_indices),
        }

    def columns(self) -> dict[str, NDArray[Any]]:
        """One array per sample: ``valid``, the varied parameters, then the outcomes."""
        return {"valid": self.valid, **self.samples, **self.outcomes}

    def to_xarray(self) -> xr.Dataset:
        """The samples and outcomes as an ``xarray.Dataset`` along ``sample``, the numbers of
        :meth:`to_dict` as attributes (JSON text where nested or None)."""
        import json

        units = {**UNITS, **QUANTITIES}
        data = {
            k: ("sample", v, {"units": units[k]} if k in units else {})
            for k, v in self.columns().items()
        }
        attrs = {
            k: (json.dumps(v) if v is None or isinstance(v, dict | list) else v)
            for k, v in self.to_dict().items()
        }
        return results.dataset(self, data, {"sample": np.arange(self.n)}, attrs)

    def save(self, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
        """Write the samples and outcomes: ``.csv`` (numpy only; the numbers of
        :meth:`to_dict` in a ``#`` comment line first) or ``.nc`` (netCDF, needs xarray);
        :meth:`load` reads either back. The file appears whole or not at all (it is written
        under a temporary name and renamed); a file already at ``path`` is replaced only
        with ``overwrite=True`` (else ValueError). An OSError names ``path`` (a missing
        directory, a full disk)."""
        target = Path(path_arg("path", path))
        suffix = target.suffix.lower()
        if suffix not in (".csv", ".nc"):
            raise ValueError(f"path: the suffix must be .csv or .nc, not {suffix or 'none'!r}")
        check_overwrite(
            target,
            overwrite=flag("overwrite", overwrite),
            option="overwrite=True",
            ours=never,
            what="an uncertainty result",
            name="path",
        )
        tmp = store.temp_sibling(target)
        try:
            if suffix == ".csv":
                self._write_csv(tmp)
            else:
                self.to_xarray().to_netcdf(tmp, engine=store.netcdf_engine())
            store.install(tmp, target)
        except RuntimeError as err:  # netCDF4 reports a failed write as "NetCDF: HDF error"
            raise OSError(errno.EIO, f"netCDF write failed ({err})", str(target)) from err
        except OSError as err:  # the user's path, not the temporary one
            raise OSError(err.errno, err.strerror or str(err), str(target)) from err
        finally:
            store.remove(tmp)
        return target

    def _write_csv(self, path: Path) -> None:
        import json

        cols = self.columns()
        header = "\n".join([json.dumps(self.to_dict(), ensure_ascii=False), ",".join(cols)])
        table = np.column_stack([np.asarray(v, dtype=np.float64) for v in cols.values()])
        np.savetxt(path, table, delimiter=",", header=header, fmt="%.17g", encoding="utf-8")

    @classmethod
    def load(cls, path: str | os.PathLike) -> Uncertainty:
        """The study written by :meth:`save` (``.csv`` or ``.nc``): equal to the one saved.

        ValueError naming ``path`` for a file that is no saved study; OSError for one that
        cannot be read."""
        source = Path(path_arg("path", path))
        suffix = source.suffix.lower()
        if suffix not in (".csv", ".nc"):
            raise ValueError(f"path: the suffix must be .csv or .nc, not {suffix or 'none'!r}")
        try:
            numbers, columns = _read_csv(source) if suffix == ".csv" else _read_netcdf(source)
            return cls._from_saved(numbers, columns)
        except (KeyError, TypeError, ValueError, IndexError) as err:
            shown = str(source) if len(str(source)) <= 60 else str(source)[:57] + "..."
            raise ValueError(f"path {shown!r} is no saved uncertainty study ({err})"[:200]) from err

    @classmethod
    def _read(cls, path: Path, suffix: str) -> Uncertainty:
        """:func:`eccjump.load` of a study's file: :meth:`load`."""
        return cls.load(path)

    @classmethod
    def _from_saved(cls, d: Mapping[str, Any], columns: Mapping[str, NDArray]) -> Uncertainty:
        """The study from the numbers of :meth:`to_dict` and the columns of :meth:`columns`."""
        dtypes = OUTCOME_DTYPES[d["question"]]
        delta = d["delta"]
        return cls(
            question=d["question"],
            sampling=d["sampling"],
            invalid=d["invalid"],
            n=int(d["n"]),
            seed=int(d["seed"]),
            confidence=float(d["confidence"]),
            nominal={k: float(v) for k, v in d["nominal"].items()},
            sd={k: float(v) for k, v in d["sd"].items()},
            bounds={k: (float(lo), float(hi)) for k, (lo, hi) in d["bounds"].items()},
            samples={k: np.asarray(v, np.float64) for k, v in columns.items() if k in UNITS},
            valid=np.asarray(columns["valid"]).astype(bool),
            outcomes={k: np.asarray(columns[k]).astype(t) for k, t in dtypes.items()},
            n_valid=int(d["n_valid"]),
            p_jarm=float(d["p_jarm"]),
            p_jarm_ci=(float(d["p_jarm_ci"][0]), float(d["p_jarm_ci"][1])),
            counts={k: int(v) for k, v in d["counts"].items()},
            distributions={
                k: Summary(int(s["n"]), *(_number(s[f]) for f in Summary._fields[1:]))
                for k, s in d["distributions"].items()
            },
            delta=None if delta is None else Delta(**delta),
            indices=from_json(d.get("indices")),  # files written before indices: none
            liftoff_indices=from_json(d.get("liftoff_indices")),
        )

    def __repr__(self) -> str:
        lo, hi = self.p_jarm_ci
        varied = "; ".join(self._spreads()) or "nothing"
        return (
            f"Uncertainty({self.question}: p_jarm={self.p_jarm:.4g} [{lo:.4g}, {hi:.4g}] "
            f"from {self.n_valid} of {self.n} {self.sampling} samples; {varied})"
        )

    def _repr_html_(self) -> str:
        lo, hi = self.p_jarm_ci
        pct = f"{100 * self.confidence:g} %"
        rows = [
            ("question", f"{self.question}, {self.n} samples ({self.sampling}, seed {self.seed})"),
            ("varied", ", ".join(self._spreads()) or "nothing"),
            ("valid", f"{self.n_valid} ({100 * (1 - self.p_invalid):.4g} %, {self.invalid})"),
            ("P(JARM)", f"{num(self.p_jarm, 4)}  [{num(lo, 4)}, {num(hi, 4)}] ({pct}, Wilson)"),
        ]
        for name, p in list(self.probabilities.items())[:6]:
            rows.append((f"P({name})", num(p, 4)))
        for name, s in self.distributions.items():
            if s.n:
                spread = f"[{num(s.q025, 5)}, {num(s.q975, 5)}] {QUANTITIES[name]}"
                rows.append((name, f"median {num(s.median, 5)} {spread} (95 % of {s.n})"))
        if self.delta is not None:
            rows.append(("first order", _first_order(self.delta)))
        for name, ix in (self.indices or {}).items():
            rows.append((f"Sobol' {name}", index_line(ix)))
        for name, ix in (self.liftoff_indices or {}).items():
            rows.append((f"Sobol' {name} (lift-off time)", index_line(ix)))
        return card("Uncertainty", rows)

    def _spreads(self) -> list[str]:
        out = [f"{k} ± {num(v, 3)}" for k, v in self.sd.items() if v > 0]
        out += [f"{k} in [{num(lo, 4)}, {num(hi, 4)}]" for k, (lo, hi) in self.bounds.items()]
        return out

    _plot_doc = """The study (``eccjump.plot.uncertainty``): its outcomes with their Wilson
    intervals, the samples and the distributions. ``ax=``: only the distribution of the
    outcomes, drawn into this matplotlib Axes and returned
    (``eccjump.plot.outcomes_panel``), to compose figures; ``fig=``: the full figure in
    this empty Figure or SubFigure. ``kwargs`` go to the function drawn. Needs
    ``pip install eccjump[plot]``."""


def _first_order(d: Delta) -> str:
    """The delta-method estimate in one line (angles' spreads in degrees)."""
    if d.liftoff_t_sd is not None:  # the full motion
        flight = "n/a" if d.flight_time_sd is None else f"{d.flight_time_sd:.5g}"
        return (
            f"lift-off angle sd {math.degrees(d.theta_J_sd):.4f} deg, time sd "
            f"{d.liftoff_t_sd:.5g}, flight time sd {flight} (exact as tolerances -> 0)"
        )
    p = "n/a (not the friction at the jump)" if d.p_jarm is None else f"{d.p_jarm:.5f}"
    return (
        f"theta_J sd {math.degrees(d.theta_J_sd):.4f} deg, P(JARM) {p} (exact as tolerances -> 0)"
    )


def index_line(ix: SobolIndex) -> str:
    """A parameter's Sobol' indices in one line: each with its interval."""
    f, t = ix.first, ix.total
    return (
        f"first {f.value:.3f} [{f.low:.3f}, {f.high:.3f}], "
        f"total {t.value:.3f} [{t.low:.3f}, {t.high:.3f}]"
    )


def _json(x: float | int | None) -> float | int | None:
    """A number for JSON: a non-finite float (NaN, inf) as None (null)."""
    return None if isinstance(x, float) and not math.isfinite(x) else x


def _number(x: float | None) -> float:
    """A summary's number read back: null is NaN (:func:`_json`)."""
    return math.nan if x is None else float(x)


def _read_csv(path: Path) -> tuple[dict[str, Any], dict[str, NDArray]]:
    """The numbers (the first comment line) and the columns of a study's ``.csv``."""
    import json

    with open(path, encoding="utf-8") as fh:
        numbers = json.loads(fh.readline().removeprefix("# "))
        names = fh.readline().removeprefix("# ").strip().split(",")
    table = np.loadtxt(path, delimiter=",", comments="#", ndmin=2, encoding="utf-8")
    if table.shape[1] != len(names):
        raise ValueError(f"{table.shape[1]} columns under {len(names)} names")
    return numbers, {k: table[:, i] for i, k in enumerate(names)}


def _read_netcdf(path: Path) -> tuple[dict[str, Any], dict[str, NDArray]]:
    """The numbers (the attributes, JSON where nested) and the columns of a study's ``.nc``."""
    import json

    import xarray as xr

    with xr.open_dataset(path, engine=store.netcdf_engine()) as ds:
        ds.load()
        columns = {str(k): np.asarray(v.values) for k, v in ds.data_vars.items()}
        attrs = dict(ds.attrs)
    numbers = {k: json.loads(v) if k in _NESTED else _plain(v) for k, v in attrs.items()}
    return numbers, columns


#: The numbers of :meth:`Uncertainty.to_dict` that a netCDF file holds as JSON text.
_NESTED = frozenset(
    {
        "nominal",
        "sd",
        "bounds",
        "p_jarm_ci",
        "counts",
        "probabilities",
        "distributions",
        "delta",
        "indices",
        "liftoff_indices",
    }
)


def _plain(v: Any) -> Any:
    """A netCDF attribute as a Python value (numpy scalars as int, float)."""
    return v.item() if isinstance(v, np.generic) else v


__all__ = ["QUANTILES", "QUANTITIES", "Summary", "Uncertainty", "wilson"]
