"""``eccjump.uncertainty_map``: P(JARM) under stated tolerances at every point of a region grid
(α × χ × km_frac), with its Wilson interval and the share of each outcome, as a map of
kind "uncertainty" (:class:`UncertaintyMap`): saved, loaded and labelled like every map.

The samples are those of :func:`eccjump.uncertainty` around each grid point (the same
unit-cube points at every grid point: common random numbers, :mod:`.grid`), classified in
batches by the closed form, or run to their first landing (``question="motion"``,
:mod:`.grid_motion`: a map of kind "uncertainty_motion", :class:`UncertaintyMotionMap`)."""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.arrays import axis, fields_equal, fraction_axis, refuses_km
from eccjump._base.checks import Rule, file_error, real, rule_name, short, text
from eccjump._base.docs import fill
from eccjump._base.html import card, span
from eccjump._base.progress import Progress, checked, reporting
from eccjump._base.sizes import F64, check_fits, result_bytes
from eccjump._base.units import ramp_angles
from eccjump.maps import store
from eccjump.maps.dask import Chunks, lazy_fields, normalize_chunks
from eccjump.maps.kinds import MapKind
from eccjump.maps.layout import Layout, make_layout
from eccjump.maps.map import Map
from eccjump.motion.fields import MOTION
from eccjump.motion.options import MotionOptions
from eccjump.studies.uncertainty.grid import BLOCK, GridSpread, grid_fields
from eccjump.studies.uncertainty.grid_delta import delta_grid_fields
from eccjump.studies.uncertainty.grid_motion import MOTION_BLOCK, motion_grid_fields
from eccjump.studies.uncertainty.map_fields import (
    UNCERTAINTY,
    UNCERTAINTY_DELTA,
    UNCERTAINTY_MOTION,
)
from eccjump.studies.uncertainty.results import check_confidence
from eccjump.studies.uncertainty.sampling import Sampling, options, spread, unit_cube

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: What the map can vary: the parameters of the closed form (as ``uncertainty(question=
#: "jarm")``).
MAP_PARAMETERS = ("chi", "km", "alpha", "mu_s")
#: File attributes of how a map was made, beyond the required ones: text (JSON for the
#: spreads, which no format stores as a dict).
_TEXT = ("sampling", "invalid", "question", "sd", "bounds")


@dataclass(frozen=True, eq=False, repr=False)
class UncertaintyMap(Map, kind=UNCERTAINTY):
    """P(JARM) under tolerances on the grid α × χ × km_frac (:func:`uncertainty_map`).

    As every :class:`~eccjump.Map`: ``coords``, ``fields``, ``shape``, ``to_xarray()``;
    :func:`eccjump.maps.save` (or :meth:`save`) writes it and :func:`eccjump.load` reads it
    back. Each field is also an attribute (``m.p_jarm``).

    Attributes
    ----------
    alpha, chi, km_frac : numpy.ndarray
        The grid's axes (α in rad; k_m = km_frac (1 − χ)).
    fields : dict of str to numpy.ndarray
        Per grid point: ``p_jarm``, its Wilson interval ``p_jarm_low`` and ``p_jarm_high``,
        ``n_valid`` (the samples in the physical range) and the share ``p_<reason>`` of each
        other outcome (``p_slip_before``, ``p_no_root``, ...; :data:`.map_fields.OUTCOMES`),
        all among the valid samples (NaN where there is none).
    mu_s : float
        The nominal static friction of the whole map.
    sd, bounds : dict
        The tolerances: normal standard deviations, and uniform ranges as offsets (lo, hi)
        from each grid point, by parameter (``chi``, ``km``, ``alpha`` [rad], ``mu_s``).
    n, seed, sampling, invalid, confidence, rule
        As given to :func:`uncertainty_map`.
    """

    jarm_field: ClassVar[str] = "p_jarm"
    #: The map's kind (its fields) and the question its samples answered.
    map_kind: ClassVar[MapKind] = UNCERTAINTY
    question: ClassVar[str] = "jarm"

    alpha: NDArray[np.float64]
    chi: NDArray[np.float64]
    km_frac: NDArray[np.float64]
    fields: dict[str, NDArray]
    mu_s: float
    sd: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    n: int
    seed: int
    sampling: str
    invalid: str
    confidence: float
    rule: str

    __eq__ = fields_equal
    __hash__ = None  # type: ignore[assignment]

    def __getattr__(self, name: str) -> NDArray:
        fields = self.__dict__.get("fields", {})
        if name in fields:
            return fields[name]
        raise AttributeError(f"UncertaintyMap has no attribute {name!r}")

    @property
    def coords(self) -> dict[str, NDArray[np.float64]]:
        """The grid's axes by dimension name: α [rad], χ, km_frac."""
        return {"alpha": self.alpha, "chi": self.chi, "km_frac": self.km_frac}

    @property
    def km(self) -> NDArray[np.float64]:
        """k_m on the (χ, km_frac) plane, shape (len(χ), len(km_frac))."""
        return self.km_frac[None, :] * (1.0 - self.chi[:, None])

    @property
    def lazy(self) -> bool:
        """True for a map made with ``chunks=`` and not yet computed (dask-array fields)."""
        return not isinstance(self.fields["p_jarm"], np.ndarray)

    def fraction(self) -> float:
        """The mean of P(JARM) over the grid points with a valid sample: the expected share
        of grid points that are a JARM under the tolerances (0.0 for an empty map)."""
        p = np.asarray(self.fields["p_jarm"], dtype=np.float64)
        p = p[~np.isnan(p)]
        return float(np.mean(p)) if p.size else 0.0

    def compute(self, **kwargs: Any) -> UncertaintyMap:
        """A lazy map (made with ``chunks=``) computed, all fields in one pass; ``kwargs`` go
        to ``dask.compute`` (``scheduler="processes"``, ...). A computed map: itself."""
        if not self.lazy:
            return self
        import dask  # a lazy map exists only if dask is installed

        names = self.map_kind.fields
        values = dask.compute(*(self.fields[k] for k in names), **kwargs)
        return replace(self, fields=dict(zip(names, values, strict=True)))

    def attrs(self) -> dict[str, Any]:
        """How the map was made, as netCDF-safe file attributes (the spreads as JSON)."""
        return {
            "title": "P(JARM) under tolerances of an eccentric cylinder on a ramp (eccjump)",
            "kind": self.map_kind.name,
            "eccjump_version": _core.VERSION,
            "mu_s": float(self.mu_s),
            "n": int(self.n),
            "seed": int(self.seed),
            "confidence": float(self.confidence),
            "rule": self.rule,
            "sampling": self.sampling,
            "invalid": self.invalid,
            "question": self.question,
            "sd": json.dumps(self.sd),
            "bounds": json.dumps({k: list(v) for k, v in self.bounds.items()}),
            "units": "alpha and its tolerance in rad; bounds are offsets from each grid point",
        }

    def to_layout(self) -> Layout:
        """The map as a layout (numpy only; dask arrays if lazy)."""
        return make_layout(
            self.alpha, self.chi, self.km_frac, self.fields, self.attrs(), None, self.map_kind
        )

    @classmethod
    def from_layout(cls, lay: Layout, source: object) -> UncertaintyMap:
        """The map of the layout ``lay`` of a valid uncertainty map read from ``source``."""
        dv, co, at = lay["data_vars"], lay["coords"], lay["attrs"]
        try:
            sd = {str(k): float(v) for k, v in json.loads(str(at["sd"])).items()}
            bounds = {
                str(k): (float(lo), float(hi))
                for k, (lo, hi) in json.loads(str(at["bounds"])).items()
            }
            sampling, invalid = str(at["sampling"]), str(at["invalid"])
        except (KeyError, TypeError, ValueError) as err:
            raise file_error(source, f"is a damaged uncertainty map ({short(str(err))})") from None
        return cls(
            alpha=np.asarray(co["alpha"][1], dtype=np.float64),
            chi=np.asarray(co["chi"][1], dtype=np.float64),
            km_frac=np.asarray(co["km_frac"][1], dtype=np.float64),
            fields={
                k: np.asarray(dv[k][1], dtype=cls.map_kind.dtypes[k]) for k in cls.map_kind.fields
            },
            mu_s=float(at["mu_s"]),
            sd=sd,
            bounds=bounds,
            n=int(at["n"]),
            seed=int(at["seed"]),
            sampling=sampling,
            invalid=invalid,
            confidence=float(at["confidence"]),
            rule=str(at["rule"]),
        )

    def save(self, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
        """Write the map to ``path`` (``.nc``, ``.zarr`` or ``.npz``) by
        :func:`eccjump.maps.save`; :func:`eccjump.load` reads it back."""
        return store.save(self, path, overwrite=overwrite)

    def plot(self, **kwargs: Any) -> Figure:
        """P(JARM) over (χ, α) on a km_frac slice with its 0.5 and 0.95 contours
        (:func:`eccjump.plot.probability_map`; ``kwargs`` go to it). Needs matplotlib."""
        from eccjump import plot  # figures: the layer on top of every result

        return plot.probability_map(self, **kwargs)

    def _spreads(self) -> str:
        out = [f"{k} ± {v:.3g}" for k, v in self.sd.items() if v > 0]
        out += [f"{k} + [{lo:.3g}, {hi:.3g}]" for k, (lo, hi) in self.bounds.items()]
        return "; ".join(out) or "nothing"

    @property
    def estimate(self) -> str:
        """How P(JARM) was estimated, in words: ``"2000 random samples per point"``."""
        return f"{self.n} {self.sampling} samples per point"

    def __repr__(self) -> str:
        size = " x ".join(str(x.size) for x in self.coords.values())
        mean = "lazy: not computed" if self.lazy else f"mean P(JARM) {self.fraction():.4g}"
        return (
            f"{type(self).__name__}({size} grid; mu_s={self.mu_s:g}, {self.estimate}; "
            f"{self._spreads()}; {mean})"
        )

    def _repr_html_(self) -> str:
        rows = [
            ("alpha", span(np.degrees(self.alpha), " deg")),
            ("chi", span(self.chi)),
            ("km_frac", span(self.km_frac) + " (k_m / (1 - chi))"),
            ("tolerances", self._spreads()),
            ("estimate", f"{self.estimate} (seed {self.seed})" if self.n else self.estimate),
        ]
        if not self.lazy:
            rows.append(("mean P(JARM)", f"{self.fraction():.4g}"))
        return card(type(self).__name__, rows)


@dataclass(frozen=True, eq=False, repr=False)
class UncertaintyMotionMap(UncertaintyMap, kind=UNCERTAINTY_MOTION):
    """P(JARM) of the full motion and its first flight under tolerances on the grid
    α × χ × km_frac (``uncertainty_map(..., question="motion")``): an
    :class:`UncertaintyMap` (saved, loaded, plotted alike) of kind "uncertainty_motion".

    Its fields per grid point (:data:`.map_fields.MOTION_FIELDS`): ``p_jarm`` (a lift-off
    straight out of pure rolling, by the full motion), ``p_jarm_low``, ``p_jarm_high``,
    ``n_valid``, the shares ``p_flies`` (lift off at all) and ``p_slipped_first`` (slip before
    the first flight), and the median, 2.5 % and 97.5 % quantiles of the first lift-off's time
    [√(R/g)], the first flight's duration [√(R/g)] and distance down the ramp [R]
    (``liftoff_t_median``, ``flight_time_q025``, ``distance_q975``, ...; NaN where no valid
    sample flies), each as ``uncertainty(question="motion").distributions`` gives it there.
    """

    map_kind: ClassVar[MapKind] = UNCERTAINTY_MOTION
    question: ClassVar[str] = "motion"


@dataclass(frozen=True, eq=False, repr=False)
class UncertaintyDeltaMap(UncertaintyMap, kind=UNCERTAINTY_DELTA):
    """The first-order (delta-method) P(JARM) on the grid α × χ × km_frac
    (``uncertainty_map(..., method="delta")``): an :class:`UncertaintyMap` (saved, loaded,
    plotted alike) of kind "uncertainty_delta", made of no sample (``n`` 0, ``sampling``
    "delta").

    Its fields per grid point: ``p_jarm`` (Phi of the friction margin at the jump over its
    first-order spread; NaN where the linearisation fails at the nominal point),
    ``theta_J_sd`` [rad] (the first-order spread of the lift-off angle) and ``delta_status``,
    0 where P(JARM) is given, else why not
    (:class:`eccjump.studies.uncertainty.delta.Status`: 1 the nominal point is no JARM, 2 an
    earlier friction ratio decides (a kink), 3 singular derivatives, 4 the classical rule,
    5 a point outside the physical range), and 6 where P(JARM) is given but a probe at
    ± 2 sd along a varied input reaches another verdict (a slip before the jump: near a
    kink, where the first order is too high). Sample where it matters.
    """

    map_kind: ClassVar[MapKind] = UNCERTAINTY_DELTA

    @property
    def estimate(self) -> str:
        """How P(JARM) was estimated, in words."""
        return "first order (delta method)"


def _grid_axes(
    alpha: ArrayLike, chi: ArrayLike, km_frac: ArrayLike
) -> tuple[NDArray[np.float64], ...]:
    """The three axes, each a 1-D array of values in its range (ValueError naming it)."""
    out = [axis("alpha", ramp_angles("alpha", alpha))]
    for name, values in (("chi", chi), ("km_frac", fraction_axis(km_frac))):
        a = axis(name, values)
        if not ((a >= 0.0) & (a <= 1.0)).all():
            bad = a[~((a >= 0.0) & (a <= 1.0))][0]
            raise ValueError(f"{name} holds {short(float(bad))}, outside the allowed range [0, 1]")
        out.append(a)
    return tuple(out)


def _method(method: object, question: str) -> str:
    m = text("method", method)
    if m not in ("sampling", "delta"):
        raise ValueError(f"method = {short(m)} is not one of 'sampling', 'delta'")
    if m == "delta" and question != "jarm":
        raise ValueError("method = 'delta' needs question='jarm' (the closed form's derivatives)")
    return m


def _question(question: object) -> str:
    q = text("question", question)
    if q not in ("jarm", "motion"):
        raise ValueError(f"question = {short(q)} is not one of 'jarm', 'motion'")
    return q


@refuses_km
@fill
def uncertainty_map(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: float,
    *,
    km: None = None,
    sd: dict[str, float] | None = None,
    bounds: dict[str, tuple[float, float]] | None = None,
    n: int = 2_000,
    seed: int = 0,
    sampling: Sampling = "random",
    question: str = "jarm",
    method: str = "sampling",
    invalid: str = "truncate",
    confidence: float = 0.95,
    rule: Rule = "paper",
    chunks: Chunks = None,
    n_threads: int = 0,
    progress: bool | Progress | None = None,
) -> UncertaintyMap:
    """P(JARM) under tolerances at every point of the grid α × χ × km_frac (and, with
    ``question="motion"``, the first flight's statistics).

    At every grid point (the nominal body χ, k_m = km_frac (1 − χ) on a ramp of angle
    α, with the map's ``mu_s``) ``n`` samples spread by ``sd`` and ``bounds`` are
    classified by the closed form, as :func:`uncertainty` does at one point: the map's fields
    at a grid point are ``uncertainty``'s P(JARM), its interval and its outcome shares
    there. The same ``n`` unit-cube points are used at every grid point (common random
    numbers), so neighbouring points differ by the physics, not by sampling noise, and a
    point's values do not depend on the rest of the grid. The work runs in the core in
    batches of about 1.3e5 samples (20 x 20 x 4 points with n = 2000: a few seconds).

    With ``question="motion"`` each sample runs the full motion to its first landing
    (:func:`eccjump.motion_points`, batches of about 6.6e4 samples: about 6 s per 1e5 samples
    on 2 cores) with the defaults of ``uncertainty(question="motion")`` (μ_k the sample's μ_s,
    no restitution, a start at rest): an :class:`UncertaintyMotionMap` whose fields at a grid
    point are that ``uncertainty``'s P(JARM), interval, the shares that fly and that slip
    first, and the median and 95 % range of the first lift-off's time, flight time and
    distance.

    Parameters
    ----------
    alpha : array_like of float, 1-D
        Nominal ramp angles [rad], each in [0, π/2].
    chi : array_like of float, 1-D
        Nominal d/R, each in [0, 1].
    km_frac : array_like of float, 1-D
        Nominal k_m/(1 − χ), each in [0, 1].
    mu_s : float
        Nominal static friction coefficient of the whole map, in [0, inf).
    km : None
        Not accepted (the axis is ``km_frac``); a TypeError.
    sd : dict of str to float or None, default None
        Normal standard deviations, absolute (in the parameter's unit: α in rad), by
        name among ``chi``, ``km`` (k_m itself), ``alpha`` and ``mu_s``; ≥ 0.
    bounds : dict of str to (float, float) or None, default None
        Uniform ranges as offsets (lo ≤ hi) from each grid point, by the same names:
        ``{"alpha": (-0.004, 0.004)}`` is α ± 0.004 rad at every grid point.
    n : int, default 2000
        Samples per grid point, 1 ... 10**8.
    seed : int, default 0
        Seed of the unit-cube points (numpy's PCG64, or the Sobol' scrambling), ≥ 0.
    sampling : {"random", "sobol"}, default "random"
        As in :func:`uncertainty`.
    question : {"jarm", "motion"}, default "jarm"
        ``"jarm"``: the closed-form JARM classification; ``"motion"``: the full motion to the
        first landing (the same four parameters vary; its options are the defaults).
    method : {"sampling", "delta"}, default "sampling"
        ``"delta"``: no sample, a fast first look: the first-order (delta-method) P(JARM) of
        :func:`uncertainty`'s ``delta`` at every grid point, from one batched
        ``jarm(..., derivatives=True)`` over the grid (``n``, ``seed``, ``sampling`` and
        ``invalid`` play no part): an :class:`UncertaintyDeltaMap`, NaN with a
        ``delta_status`` where the linearisation fails at the nominal point (no JARM there,
        an earlier friction ratio deciding, singular derivatives), flagged (status 6) where
        the tolerances reach another verdict. Question "jarm" only.
    invalid : {"truncate", "count"}, default "truncate"
        Samples outside the physical range, as in :func:`uncertainty`.
    confidence : float, default 0.95
        Level of the Wilson intervals, in (0, 1 - 1e-15].
    %(rule_rolling)s
    chunks : int, sequence of int, dict or None, default None
        None computes now. Otherwise chunk sizes along (α, χ, km_frac) as in
        :func:`region`: the map is built lazily with dask, one batch per block, bit-identical
        to the map computed now for any chunking, scheduler or cluster; ``.compute()`` it.
    %(n_threads)s
    progress : bool, callable or None, default None
        Progress in samples, as in :func:`uncertainty`. Not with ``chunks`` (a ValueError).

    Returns
    -------
    UncertaintyMap
        The fields per grid point (``p_jarm``, ``p_jarm_low``, ``p_jarm_high``,
        ``n_valid``, ``p_<reason>``); for "motion" an :class:`UncertaintyMotionMap` (``p_jarm``
        and its interval, ``n_valid``, ``p_flies``, ``p_slipped_first``, and
        ``<quantity>_median``, ``_q025``, ``_q975`` of ``liftoff_t``, ``flight_time``,
        ``distance``); for ``method="delta"`` an :class:`UncertaintyDeltaMap` (``p_jarm``,
        ``theta_J_sd``, ``delta_status``).

    Raises
    ------
    ValueError
        For an axis out of range, a bad ``mu_s``, tolerance or option, ``question`` other
        than "jarm" or "motion", ``method="delta"`` with "motion"; the message names the
        parameter and its range.
    TypeError
        For ``km=`` or an argument of the wrong type.
    MemoryError
        If the map and its samples cannot fit in memory (before any work).
    ImportError
        Without scipy, or dask for ``chunks``.

    See Also
    --------
    uncertainty : the full study at one point.
    region : the JARM map without tolerances.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.uncertainty_map(
    ...     np.radians([38, 40, 42]), [0.14, 0.15], [0.02 / 0.85], 1.0,
    ...     sd={"alpha": np.radians(0.25), "chi": 0.002}, n=1000,
    ... )
    >>> m.shape, sorted(m.fields)[:3]
    ((3, 2, 1), ['n_valid', 'p_jarm', 'p_jarm_high'])
    """
    q = _question(question)
    how_ = _method(method, q)
    a, c, f = _grid_axes(alpha, chi, km_frac)
    mu = real("mu_s", mu_s)
    probe = {"chi": 0.0, "km": 0.0, "alpha": 0.0, "mu_s": mu, "mu_k": mu}
    probe |= {"restitution": 0.0, "theta0": 0.0, "omega0": 0.0}
    spec = spread(probe, sd, bounds, MAP_PARAMETERS)
    size, seed_, how, policy = options(n, seed, sampling, invalid)
    level = check_confidence(confidence)
    MotionOptions(rule=rule).to_core(n_threads)  # the rule and threads checked by the core
    name = rule_name(rule)
    spreads = GridSpread(spec.sd, spec.bounds, spec.varied, policy == "truncate", mu, name, level)
    shape = (a.size, c.size, f.size)
    points = math.prod(shape)
    if how_ == "delta":  # no sample: the derivatives at the nominal points only
        size, seed_, how, policy = 0, 0, "delta", "none"
    _fits(q, points, size, len(spec.varied))
    cube = unit_cube(size, len(spec.varied), seed_, how) if size else np.empty((0, 0))
    cls, kind, grid = _ESTIMATORS[q if how_ == "sampling" else "delta"]
    if chunks is None:
        with reporting(progress, "sample" if size else "point") as report:
            flat = grid(a, c, f, cube, spreads, n_threads, report)
        fields = {k: v.reshape(shape) for k, v in flat.items()}
    else:
        if checked(progress):
            raise ValueError("progress needs chunks=None (dask reports the progress of a lazy map)")
        blocks = normalize_chunks(chunks, shape)
        fields = lazy_fields(kind, grid, (a, c, f), blocks, (cube, spreads, n_threads))
    return cls(
        alpha=a,
        chi=c,
        km_frac=f,
        fields=fields,
        mu_s=mu,
        sd=dict(spec.sd),
        bounds=dict(spec.bounds),
        n=size,
        seed=seed_,
        sampling=how,
        invalid=policy,
        confidence=level,
        rule=name,
    )


#: The map class, kind and grid function of each question (sampled) and of the first order.
_ESTIMATORS: dict[str, tuple[type[UncertaintyMap], MapKind, Callable[..., dict[str, NDArray]]]] = {
    "jarm": (UncertaintyMap, UNCERTAINTY, grid_fields),
    "motion": (UncertaintyMotionMap, UNCERTAINTY_MOTION, motion_grid_fields),
    "delta": (UncertaintyDeltaMap, UNCERTAINTY_DELTA, delta_grid_fields),
}

#: Bytes per sample of a batch: its four parameter columns, the grid copies, the cube and the
#: outcomes of :func:`.questions.evaluate` (about 30 bytes), with room.
_SAMPLE_BYTES = 24 * F64
#: The same for the full motion: eight parameter columns, their copies and the outcomes of
#: a motion point, with room.
_MOTION_SAMPLE_BYTES = 24 * F64 + 2 * MOTION.bytes_per_point()


def _fits(question: str, points: int, n: int, varied: int) -> None:
    """MemoryError before any work if the map, the cube and a batch cannot fit (a batch of
    the full motion holds at least one grid point's n samples)."""
    kind = UNCERTAINTY if question == "jarm" else UNCERTAINTY_MOTION
    per_point = kind.bytes_per_point() + 3 * F64  # the grid's nominal columns
    need = result_bytes(points, per_point) + n * max(varied, 1) * F64
    if question == "jarm":
        need += min(BLOCK, max(n, 1) * points) * _SAMPLE_BYTES
    else:
        need += max(min(MOTION_BLOCK, n * points), n) * _MOTION_SAMPLE_BYTES
    check_fits("uncertainty_map", points, need, "alpha, chi, km_frac or n")


__all__ = [
    "MAP_PARAMETERS",
    "UncertaintyDeltaMap",
    "UncertaintyMap",
    "UncertaintyMotionMap",
    "uncertainty_map",
]
