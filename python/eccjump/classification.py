"""JARM classification (the paper's Section 3): does the cylinder jump straight out of pure
rolling, and if not, why. See ``docs/jarm.md`` for the semantics.

Everything broadcasts over numpy arrays and runs in Rust, in parallel over points with the
GIL released; results are bit-identical for any thread count.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, ClassVar, Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump._arrays import axis, broadcast_flat, fields_equal, fraction_axis, turns
from eccjump._bridge import Method, call_options, jarm_grid, jarm_points
from eccjump._checks import Integrator, Rule, real, real_array, short, text
from eccjump._html import best_slice, card, deg, jarm_slice, num, span
from eccjump._layout import (
    COORD_ATTRS,
    SWEEPABLE,
    Layout,
    layout_to_xarray,
    make_layout,
    map_attrs,
    require,
)
from eccjump._map import Map
from eccjump.fields import FIELDS, Reason, docstring
from eccjump.scale import lazy_fields, lazy_records

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr
    from matplotlib.figure import Figure


@dataclass(frozen=True, repr=False, eq=False)
class JarmResult:
    """Per-point classification, every field an array of the broadcast shape.

    Attributes
    ----------
    {fields}

    ``reason`` holds codes of :class:`Reason`; the fields are described once, in
    :mod:`eccjump.fields`.
    """

    is_jarm: NDArray[np.bool_]
    reason: NDArray[np.uint8]
    n: NDArray[np.uint32]
    theta_J: NDArray[np.float64]
    theta_event: NDArray[np.float64]
    Fx_J: NDArray[np.float64]
    Fy_J: NDArray[np.float64]
    max_ratio: NDArray[np.float64]
    theta_max_ratio: NDArray[np.float64]
    min_Fy: NDArray[np.float64]
    theta_min_Fy: NDArray[np.float64]

    @property
    def shape(self) -> tuple[int, ...]:
        return self.is_jarm.shape

    @property
    def lazy(self) -> bool:
        """True when the fields are dask arrays not yet computed."""
        return hasattr(self.is_jarm, "__dask_graph__")  # the dask collection protocol

    def reasons(self) -> NDArray[np.object_]:
        """The reasons as :class:`Reason` members (an object array; for display)."""
        out = np.empty(self.reason.shape, dtype=object)
        out.ravel()[:] = [Reason(int(c)) for c in self.reason.ravel()]
        return out

    def fields(self) -> dict[str, NDArray]:
        """Every field by name, in the order of :data:`eccjump.fields.FIELDS`."""
        return {k: getattr(self, k) for k in FIELDS}

    def counts(self) -> dict[Reason | int, int]:
        """How many points have each reason (codes that are not a :class:`Reason`, such as
        the fill value 255 of points not computed, are counted under their code)."""
        codes = np.bincount(np.asarray(self.reason, dtype=np.intp).ravel(), minlength=1)
        return {_reason(c): int(k) for c, k in enumerate(codes.tolist()) if k}

    def __repr__(self) -> str:
        if self.lazy:
            return f"JarmResult(shape={self.shape}, lazy: not computed)"
        if self.is_jarm.ndim == 0:
            reason = _reason_name(_reason(int(self.reason)))
            theta = float(self.theta_J)
            at = (
                ""
                if math.isnan(theta)
                else f", theta_J={theta:.6g} ({math.degrees(theta):.4g} deg)"
            )
            return f"JarmResult({reason}, n={int(self.n)}{at})"
        lines = [f"JarmResult(shape={self.shape}, {self.is_jarm.size} points)"]
        lines += [f"  {_reason_name(r):<18} {k}" for r, k in self.counts().items()]
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        if self.lazy:
            return card("JarmResult", [("shape", f"{self.shape}, lazy: not computed")])
        if self.is_jarm.ndim == 0:
            rows = [
                ("reason", _reason_name(_reason(int(self.reason)))),
                ("turn n", str(int(self.n))),
                ("theta_J", deg(float(self.theta_J))),
                ("Fx_J, Fy_J", f"{num(float(self.Fx_J))}, {num(float(self.Fy_J))} [M g]"),
                ("max |Fx|/Fy before", num(float(self.max_ratio))),
            ]
            return card("JarmResult", rows)
        rows = [("shape", f"{self.shape}, {self.is_jarm.size} points")]
        rows += [(_reason_name(r), str(k)) for r, k in self.counts().items()]
        return card("JarmResult", rows)

    __eq__ = fields_equal

    __hash__ = None  # type: ignore[assignment]  # mutable numpy arrays inside

    @staticmethod
    def _from_raw(raw: Mapping[str, NDArray], shape: tuple[int, ...]) -> JarmResult:
        return JarmResult(**{k: raw[k].reshape(shape) for k in FIELDS})


def _reason(code: int) -> Reason | int:
    """The :class:`Reason` of ``code``, or the code itself if it is none (fill: 255)."""
    try:
        return Reason(code)
    except ValueError:
        return code


def _reason_name(reason: Reason | int) -> str:
    return reason.name if isinstance(reason, Reason) else f"code {reason}"


JarmResult.__doc__ = (JarmResult.__doc__ or "").format(fields=docstring().replace("\n", "\n    "))
if tuple(f.name for f in dataclasses.fields(JarmResult)) != FIELDS:  # pragma: no cover
    raise ImportError("JarmResult and eccjump.fields.FIELDS list different fields")


def jarm(
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    mu_s: ArrayLike,
    n: int | ArrayLike | None = None,
    *,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float = 0.0,
    omega0: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    stop_at_slip: bool = False,
    n_threads: int = 0,
    integrator: Integrator = "RK45",
) -> JarmResult:
    """Classify points (alpha, chi, km, mu_s, n) as JARM or not, broadcasting the five inputs.

    Parameters
    ----------
    alpha : ramp angle [rad] in [0, pi/2].
    chi, km : the body (km is the shell mass fraction itself, in [0, 1 - chi]).
    mu_s : static friction coefficient, >= 0.
    n : the turn on which the jump must happen: an integer >= 1 or an array of them
        (broadcast with the other inputs), or None for the first jump whatever its turn
        (None only as a scalar). With first-jump semantics a point has at most one n, so the
        regions of different n never overlap.
    method : ``"closed_form"`` (the paper's formulas with a rigorous path scan) or ``"ode"``
        (integration with events; an independent route, ~10x slower).
    rule : lift-off rule, ``"paper"`` (default) or ``"normal_force"`` (classical).
    theta0, omega0 : initial angle [rad], |theta0| <= 2 pi 1e6, and angular velocity,
        0 <= omega0 <= 1e6 [sqrt(g/R) rad].
    rtol, atol : integrator tolerances (``method="ode"`` only).
    max_turns : cap of the search, in turns counted from the start's turn (1 ... 10**6).
    refine_extrema : refine max_ratio, min_Fy and their angles to full precision (closed
        form; default False, as in :func:`region`: the classification is the same either way,
        and refining costs about a third more time on a map).
    stop_at_slip : under the paper's rule, stop at the first slip and report ``Reason.SLIP``
        instead of following rolling on to the lift-off to tell SLIP_BEFORE from
        SLIP_AT_JUMP. ``is_jarm`` and every other reason are unchanged; maps where most
        points slip are faster (1.7x with ``method="ode"``). No effect under
        ``rule="normal_force"``.
    n_threads : threads (0 = one per core, at most 256); results are identical for any value.
    integrator : the Runge–Kutta pair of ``method="ode"``: ``"RK45"`` (Dormand–Prince 5(4),
        the default), ``"DOP853"`` (Dormand–Prince 8(5,3)), ``"Vern7"`` (Verner 7(6)) or
        ``"Vern9"`` (Verner 9(8)); the same verdicts: each finds an event that only grazes
        zero between two samples. For speed pick ``"Vern9"`` (at the default rtol 1.5–1.9×
        faster than RK45 and about 15× more accurate); keep ``"RK45"`` for step-for-step
        parity with scipy (``benches/bench_pairs.py``).

    Every bound, the memory and Ctrl-C behaviour: ``docs/limits.md``.

    Invalid points get ``Reason.INVALID_PARAMS``; a ``ValueError`` is raised only for
    arguments that apply to the whole call (shapes, rule, method, tolerances) and for an
    ``n`` that is not None or integers >= 1.
    """
    turn_arg = turns(n)
    opts = call_options(
        n=None if isinstance(turn_arg, np.ndarray) else turn_arg,
        rule=rule,
        method=method,
        rtol=rtol,
        atol=atol,
        theta0=theta0,
        omega0=omega0,
        max_turns=max_turns,
        refine_extrema=refine_extrema,
        stop_at_slip=stop_at_slip,
        n_threads=n_threads,
        integrator=integrator,
    )
    if isinstance(turn_arg, np.ndarray):
        shape, (a, c, k, m, nf) = broadcast_flat(alpha=alpha, chi=chi, km=km, mu_s=mu_s, n=turn_arg)
        raw = jarm_points(a, c, k, m, opts, n=nf.astype(np.int64))
    else:
        shape, (a, c, k, m) = broadcast_flat(alpha=alpha, chi=chi, km=km, mu_s=mu_s)
        raw = jarm_points(a, c, k, m, opts)
    return JarmResult._from_raw(raw, shape)


@dataclass(frozen=True, repr=False, eq=False)
class Region(Map):
    """A JARM map on the grid alpha x chi x km_frac, with k_m = km_frac (1 - chi).

    ``result`` holds the fields of :class:`JarmResult`, each of shape
    (len(alpha), len(chi), len(km_frac)); the remaining attributes record how it was made.
    As every :class:`~eccjump.maps.Map`: ``coords``, ``fields``, ``shape``, ``fraction()`` and
    ``to_xarray()``; :func:`eccjump.maps.save` writes it.
    """

    kind: ClassVar[str] = "jarm"
    jarm_field: ClassVar[str] = "is_jarm"

    alpha: NDArray[np.float64]
    chi: NDArray[np.float64]
    km_frac: NDArray[np.float64]
    result: JarmResult
    mu_s: float
    n: int | None
    rule: str
    method: str
    theta0: float
    omega0: float
    attrs: dict[str, object] = field(default_factory=dict)

    @property
    def km(self) -> NDArray[np.float64]:
        """k_m on the (chi, km_frac) plane, shape (len(chi), len(km_frac))."""
        return self.km_frac[None, :] * (1.0 - self.chi[:, None])

    @property
    def coords(self) -> dict[str, NDArray[np.float64]]:
        """The grid's axes by dimension name: alpha [rad], chi, km_frac."""
        return {"alpha": self.alpha, "chi": self.chi, "km_frac": self.km_frac}

    @property
    def fields(self) -> dict[str, NDArray]:
        """The fields of :attr:`result` by name (:data:`eccjump.fields.FIELDS`)."""
        return self.result.fields()

    @property
    def is_jarm(self) -> NDArray[np.bool_]:
        return self.result.is_jarm

    @property
    def lazy(self) -> bool:
        """True for a map made with ``chunks=`` and not yet computed (dask-array fields)."""
        return self.result.lazy

    def compute(self, **kwargs: object) -> Region:
        """A lazy map computed (all fields in one pass; ``kwargs`` go to ``dask.compute``);
        an already computed map is returned as is."""
        if not self.lazy:
            return self
        import dask  # a lazy map exists only if dask is installed

        values = dask.compute(*self.result.fields().values(), **kwargs)
        res = JarmResult(**dict(zip(FIELDS, values, strict=True)))
        return replace(self, result=res, attrs=dict(self.attrs))

    __eq__ = fields_equal

    __hash__ = None  # type: ignore[assignment]  # mutable numpy arrays inside

    def to_xarray(self) -> xr.Dataset:
        """The map as an ``xarray.Dataset`` (dask-backed if lazy); see :mod:`eccjump.labelled`.
        Needs ``pip install eccjump[xarray]``."""
        return layout_to_xarray(region_layout(self))

    def __repr__(self) -> str:
        def axis_line(name: str, values: NDArray[np.float64], unit: str = "") -> str:
            if values.size == 0:
                return f"  {name:<8} empty"
            return f"  {name:<8} [{values[0]:.6g}, {values[-1]:.6g}]{unit} x {values.size}"

        n = "first jump" if self.n is None else str(self.n)
        made = f"mu_s={self.mu_s:g}, n={n}, rule={self.rule}, method={self.method}"
        if self.method == "ode":
            made += f", integrator={self.attrs.get('integrator', 'RK45')}"
        if self.theta0 or self.omega0:
            made += f", theta0={self.theta0:g}, omega0={self.omega0:g}"
        size = " x ".join(str(x.size) for x in (self.alpha, self.chi, self.km_frac))
        jarm = "lazy: not computed" if self.lazy else f"{self.fraction():.6g}"
        return "\n".join(
            [
                f"Region({size} grid; {made})",
                axis_line("alpha", np.degrees(self.alpha), " deg"),
                axis_line("chi", self.chi),
                axis_line("km_frac", self.km_frac),
                f"  JARM fraction {jarm}",
            ]
        )

    def _repr_html_(self) -> str:
        made = f"mu_s = {self.mu_s:g}, n = {'first jump' if self.n is None else self.n}"
        rows = [
            ("alpha", span(np.degrees(self.alpha), " deg")),
            ("chi", span(self.chi)),
            ("km_frac", span(self.km_frac) + " (k_m / (1 - chi))"),
            ("made with", f"{made}, rule = {self.rule}, method = {self.method}"),
        ]
        if self.lazy:
            return card("Region", [*rows, ("JARM fraction", "lazy: not computed")])
        rows.append(("JARM fraction", f"{self.fraction():.4g}"))
        k, cut = best_slice(np.asarray(self.is_jarm, dtype=bool))
        caption = (
            f"JARM (green) over chi (across) and alpha (up) at km_frac = {self.km_frac[k]:.3g}"
        )
        return card("Region", rows, jarm_slice(cut, caption) if self.km_frac.size else "")

    def plot(self, **kwargs: Any) -> Figure:
        """The map in the (chi, alpha) plane, JARM points coloured by their turn, a few km_frac
        slices (``eccjump.plot.region_map``; ``kwargs`` go to it). Needs ``pip install
        eccjump[plot]``."""
        from eccjump import plot  # figures: the layer on top of every result

        return plot.region_map(self, **kwargs)


def region_attrs(region: Region) -> dict[str, Any]:
    """The attributes of a :class:`Region` in a labelled map (see :mod:`eccjump.labelled`)."""
    return map_attrs(
        region.mu_s,
        region.n,
        region.rule,
        region.method,
        region.theta0,
        region.omega0,
        **region.attrs,
    )


def region_layout(region: Region) -> Layout:
    """The labelled layout of a :class:`Region` (numpy only; dask arrays if lazy)."""
    return make_layout(
        region.alpha, region.chi, region.km_frac, region.result.fields(), region_attrs(region)
    )


@overload
def region(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: float,
    n: int | None = None,
    *,
    km: None = None,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float = 0.0,
    omega0: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    stop_at_slip: bool = False,
    n_threads: int = 0,
    integrator: Integrator = "RK45",
    chunks: Any = None,
    output: Literal["region"] = "region",
) -> Region: ...


@overload
def region(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    km: None = None,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    stop_at_slip: bool = False,
    n_threads: int = 0,
    integrator: Integrator = "RK45",
    chunks: Any = None,
    output: Literal["xarray"],
) -> xr.Dataset: ...


def region(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    km: None = None,
    method: Method = "closed_form",
    rule: Rule = "paper",
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_turns: int = 10_000,
    refine_extrema: bool = False,
    stop_at_slip: bool = False,
    n_threads: int = 0,
    integrator: Integrator = "RK45",
    chunks: Any = None,
    output: Literal["region", "xarray"] = "region",
) -> Region | xr.Dataset:
    """Map the JARM region on a rectangular grid, in parallel.

    The grid first, then ``mu_s``, as every entry point takes the point or body first.
    ``alpha`` [rad], ``chi`` and ``km_frac`` are 1-D coordinate arrays; ``km_frac`` is the
    shell mass fraction as the share k_m/(1 - chi) in [0, 1] of its largest value, so that
    every (chi, km_frac) pair of the grid is a valid body and the grid stays rectangular
    (``Region.km`` gives k_m itself). ``km``, the body's k_m everywhere else (:func:`jarm`,
    :func:`roll`, :func:`simulate`), is not a grid axis here: passing it is a TypeError.
    Other arguments as :func:`jarm`.

    chunks : None (default: compute now), or chunk sizes along (alpha, chi, km_frac) -- one int
        for all, a 3-sequence or a dict; -1/None for a whole axis. The map is then built
        lazily with dask, one Rust grid call per block (see :mod:`eccjump.scale`); call
        ``.compute()`` on the result. Bit-identical to the unchunked map. ``n_threads`` is
        per block: on a cluster use threads per worker / concurrent tasks per worker.
    output : ``"region"`` (default) a :class:`Region`; ``"xarray"`` an ``xarray.Dataset``
        (:mod:`eccjump.labelled`), and then ``mu_s``, ``theta0`` and ``omega0`` may be 1-D
        sequences, swept as extra leading dimensions (one Rust call per combination).

    The tolerances, the ``integrator``, ``max_turns``, ``refine_extrema`` and ``stop_at_slip``
    are recorded in
    ``Region.attrs`` (and in the attributes of its dataset and files) whatever the method, as
    given: the closed form ignores the tolerances and the integrator.
    """
    if output == "xarray":
        return region_dataset(
            mu_s=mu_s,
            n=n,
            alpha=alpha,
            chi=chi,
            km_frac=km_frac,
            km=km,
            method=method,
            rule=rule,
            theta0=theta0,
            omega0=omega0,
            rtol=rtol,
            atol=atol,
            max_turns=max_turns,
            refine_extrema=refine_extrema,
            stop_at_slip=stop_at_slip,
            n_threads=n_threads,
            integrator=integrator,
            chunks=chunks,
        )
    if text("output", output) != "region":
        raise ValueError(f"output = {short(output)}; use 'region' or 'xarray'")
    for name, value in (("mu_s", mu_s), ("theta0", theta0), ("omega0", omega0)):
        if isinstance(value, list | tuple) or (isinstance(value, np.ndarray) and value.ndim):
            raise ValueError(f"{name} must be a number here; sweeps need output='xarray'")
    mu = real("mu_s", mu_s)
    a, c, f = axis("alpha", alpha), axis("chi", chi), axis("km_frac", fraction_axis(km_frac, km))
    opts = call_options(
        n=n,
        rule=rule,
        method=method,
        rtol=rtol,
        atol=atol,
        theta0=real("theta0", theta0),
        omega0=real("omega0", omega0),
        max_turns=max_turns,
        refine_extrema=refine_extrema,
        stop_at_slip=stop_at_slip,
        n_threads=n_threads,
        integrator=integrator,
    )
    if chunks is None:
        raw = jarm_grid(a, c, f, mu, opts)
        res = JarmResult._from_raw(raw, (a.size, c.size, f.size))
    else:
        res = JarmResult(**lazy_fields(lazy_records(a, c, f, mu, opts, chunks)))
    return Region(
        alpha=a,
        chi=c,
        km_frac=f,
        result=res,
        mu_s=mu,
        n=opts.n,
        rule=opts.rule,
        method=opts.method,
        theta0=opts.theta0,
        omega0=opts.omega0,
        attrs={
            "rtol": opts.rtol,
            "atol": opts.atol,
            "integrator": opts.integrator,
            "max_turns": opts.max_turns,
            "refine_extrema": opts.refine_extrema,
            "stop_at_slip": opts.stop_at_slip,
        },
    )


def region_dataset(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    km: None = None,
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    **kwargs: Any,
) -> xr.Dataset:
    """Map the JARM region as an ``xarray.Dataset``, sweeping ``mu_s``, ``theta0`` and
    ``omega0`` when they are 1-D sequences (one Rust grid call per combination; the swept
    parameters become leading dimensions, in that order). Other arguments as
    :func:`eccjump.region` (``chunks=`` gives a dask-backed, lazily computed dataset). The
    layout is described in :mod:`eccjump.labelled`.
    """
    xarray = require("xarray")
    kwargs.pop("output", None)
    given = {"mu_s": mu_s, "theta0": theta0, "omega0": omega0}
    scalars: dict[str, float] = {}
    swept: dict[str, NDArray[np.float64]] = {}
    for name in SWEEPABLE:
        arr = real_array(name, given[name])
        if arr.ndim == 0:
            scalars[name] = float(arr)
        elif arr.ndim == 1 and arr.size:
            swept[name] = arr
        else:
            raise ValueError(f"{name} must be a number or a non-empty 1-D sequence")
    grid = {"alpha": alpha, "chi": chi, "km_frac": fraction_axis(km_frac, km)}

    def one(values: Mapping[str, float]) -> xr.Dataset:
        reg = region(n=n, **grid, **scalars, **values, **kwargs)  # type: ignore[call-overload]
        return reg.to_xarray()

    if not swept:
        return one({})
    names = list(swept)

    def build(level: int, fixed: dict[str, float]) -> xr.Dataset:
        name = names[level]
        parts = []
        for v in swept[name]:
            here = {**fixed, name: float(v)}
            if level + 1 < len(names):
                ds = build(level + 1, here)
            else:
                ds = one(here)
                for k in names:  # swept values live in coordinates, not attributes
                    ds.attrs.pop(k, None)
                ds = ds.assign_coords({k: xarray.Variable((), here[k]) for k in names})
            parts.append(ds)
        return xarray.concat(
            parts,
            dim=name,
            data_vars="all",
            coords="minimal",
            compat="override",
            join="exact",
            combine_attrs="override",
        )

    out = build(0, {})
    for k in names:
        out[k].attrs.update(COORD_ATTRS[k])
    out.attrs["swept"] = " ".join(names)
    return out


__all__ = [
    "FIELDS",
    "JarmResult",
    "Method",
    "Reason",
    "Region",
    "Rule",
    "jarm",
    "region",
    "region_attrs",
    "region_dataset",
    "region_layout",
]
