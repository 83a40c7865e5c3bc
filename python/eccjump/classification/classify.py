"""JARM classification (the paper's Section 3): does the cylinder jump straight out of pure
rolling, and if not, why. The user guide's "JARM analysis" page gives the semantics.

Everything broadcasts over numpy arrays and runs in Rust, in parallel over points with the
GIL released; results are bit-identical for any thread count.
"""

from __future__ import annotations

import dataclasses
import math
import os
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump._base.arrays import (
    axis,
    broadcast_flat,
    fields_equal,
    fraction_axis,
    refuses_km,
    turns,
)
from eccjump._base.bridge import CallOptions, Method, call_options, jarm_grid, jarm_points
from eccjump._base.canvas import Plottable
from eccjump._base.checks import (
    Integrator,
    Rule,
    file_error,
    flag,
    real,
    short,
    stacklevel_outside,
    text,
)
from eccjump._base.docs import fill
from eccjump._base.html import best_slice, card, deg, jarm_slice, num, span
from eccjump._base.progress import Progress, checked, cut, grid_in_parts, reporting
from eccjump._base.sizes import F64, check_fits, field_bytes, result_bytes
from eccjump._base.units import ramp_angles
from eccjump.classification.derivatives import derivative_fields
from eccjump.classification.fields import (
    BY_NAME,
    DERIVATIVE_TABLE,
    DERIVATIVES,
    DTYPES,
    FIELDS,
    JARM,
    MAP_INFO,
    WRT,
    WRT_ATTRS,
    Reason,
    docstring,
    map_attrs,
)
from eccjump.maps import results, store
from eccjump.maps.dask import lazy_fields, normalize_chunks
from eccjump.maps.layout import (
    DIMS,
    Layout,
    make_layout,
)
from eccjump.maps.map import Map
from eccjump.maps.results import Result

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray as xr


@dataclass(frozen=True, repr=False, eq=False)
class JarmResult(Result, Plottable, kind="jarm_points"):
    """Per-point classification, every field an array of the broadcast shape.

    Attributes
    ----------
    {fields}

    ``reason`` holds codes of :class:`Reason`; the fields are described once, in
    :mod:`eccjump.classification.fields`.
    The ``d_*`` fields are the exact derivatives of ``theta_J``,
    ``Fx_J``, ``Fy_J`` and ``mu_J = -Fx_J/Fy_J`` with respect to (α, χ, km), in a
    trailing axis of length 3, made by ``derivatives=True`` (see :func:`jarm`).
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
    d_theta_J: NDArray[np.float64] | None = None
    d_Fx_J: NDArray[np.float64] | None = None
    d_Fy_J: NDArray[np.float64] | None = None
    d_mu_J: NDArray[np.float64] | None = None
    d_singular: NDArray[np.bool_] | None = None

    @property
    def shape(self) -> tuple[int, ...]:
        return self.is_jarm.shape

    @property
    def lazy(self) -> bool:
        """True when the fields are dask arrays not yet computed."""
        return hasattr(self.is_jarm, "__dask_graph__")  # the dask collection protocol

    def reasons(self) -> NDArray[np.object_]:
        """The reasons as :class:`Reason` members, for display.

        Returns
        -------
        numpy.ndarray of object
            The :class:`Reason` of each point, of the result's shape.
        """
        out = np.empty(self.reason.shape, dtype=object)
        out.ravel()[:] = [Reason(int(c)) for c in self.reason.ravel()]
        return out

    def fields(self) -> dict[str, NDArray]:
        """Every field by name, in the order of
        :data:`eccjump.classification.fields.FIELDS` (the derivative fields are in
        :meth:`derivatives`).

        Returns
        -------
        dict of str to numpy.ndarray
        """
        return {k: getattr(self, k) for k in FIELDS}

    def derivatives(self) -> dict[str, NDArray]:
        """The derivative fields by name (:data:`eccjump.classification.fields.DERIVATIVES`), or
        an empty dict for a result made without ``derivatives=True``.

        Returns
        -------
        dict of str to numpy.ndarray

        Examples
        --------
        >>> import numpy as np
        >>> import eccjump
        >>> r = eccjump.jarm(np.radians(40), 0.15, 0.02, 1.0, derivatives=True)
        >>> {k: v.shape for k, v in r.derivatives().items()}["d_theta_J"]
        (3,)
        >>> eccjump.jarm(np.radians(40), 0.15, 0.02, 1.0).derivatives()
        {}
        """
        if self.d_theta_J is None:
            return {}
        return {k: getattr(self, k) for k in DERIVATIVES}

    def counts(self) -> dict[Reason | int, int]:
        """How many points have each reason.

        Returns
        -------
        dict of Reason or int to int
            The count of each reason met; codes that are not a :class:`Reason` (the fill
            value 255 of points not computed) are counted under their code.

        Examples
        --------
        >>> import numpy as np
        >>> import eccjump
        >>> r = eccjump.jarm(np.radians([30, 40]), [0.5, 0.15], [0.4, 0.02], mu_s=1.0)
        >>> {reason.name: k for reason, k in r.counts().items()}
        {'JARM': 1, 'SLIP_BEFORE': 1}
        """
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

    _plot_doc = """θ_J, the forces at the jump and the path condition (the largest
    |F_x|/F_y and the smallest F_y on the rolling path) over the points
    (``eccjump.plot.jarm_points``; ``x=`` and ``xlabel=``: a coordinate of the points,
    ``mu_s=``: its line). ``ax=``: only θ_J, drawn into this matplotlib Axes and
    returned (``eccjump.plot.jarm_panel``), to compose figures; ``fig=``: the full figure
    in this empty Figure or SubFigure. ``kwargs`` go to the function drawn. Needs
    ``pip install eccjump[plot]``."""

    # Taking the result elsewhere (save and eccjump.load: eccjump.maps.results).
    def to_xarray(self) -> xr.Dataset:
        """The points as an ``xarray.Dataset`` (needs xarray; computed if lazy): one
        variable per field over ``point`` (``point_0``, ``point_1``, ... for more than one
        axis; none for one point) with ``units``, ``long_name`` and the reason codes as CF
        flags, the derivative fields with a trailing ``wrt`` (``alpha``, ``chi``, ``km``)."""
        ds = results.points(self, {**self.fields(), **self.derivatives()}, JARM.var_attrs)
        if self.d_theta_J is None:
            return ds
        return ds.assign_coords(wrt=("wrt", list(WRT), WRT_ATTRS))

    def to_dataframe(self) -> pandas.DataFrame:
        """The fields as a ``pandas.DataFrame``, one row per point (indexed by its position),
        the units of the columns in ``attrs["units"]`` (the derivatives: :meth:`to_xarray`)."""
        return results.to_frame(self.to_xarray(), results.point_dims(self.shape))


def _reason(code: int) -> Reason | int:
    """The :class:`Reason` of ``code``, or the code itself if it is none (fill: 255)."""
    try:
        return Reason(code)
    except ValueError:
        return code


def _reason_name(reason: Reason | int) -> str:
    return reason.name if isinstance(reason, Reason) else f"code {reason}"


JarmResult.__doc__ = (JarmResult.__doc__ or "").format(fields=docstring().replace("\n", "\n    "))
if (
    tuple(f.name for f in dataclasses.fields(JarmResult)) != FIELDS + DERIVATIVES
):  # pragma: no cover
    raise ImportError("JarmResult and eccjump.classification.fields.FIELDS list different fields")


@fill
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
    derivatives: bool = False,
) -> JarmResult:
    """Classify points (α, χ, km, μ_s, n) as JARM or not, broadcasting the five inputs.

    A point is a JARM (a jump after rolling motion) when the body, started at (theta0,
    omega0) in pure rolling, meets the lift-off rule before the friction cone is left or the
    normal force vanishes; otherwise ``reason`` says what came first.

    Parameters
    ----------
    %(alpha_points)s
    %(chi)s
    km : array_like of float
        The body's shell mass fraction k_m itself, in [0, 1 - χ].
    %(mu_s_array)s
    n : int, array_like of int or None, default None
        The turn on which the jump must happen: an integer ≥ 1 (at most 2**32 - 1) or an
        array of them (broadcast with the other inputs), or None for the first jump whatever
        its turn (None only as a scalar). With first-jump semantics a point has at most one
        n, so the regions of different n never overlap.
    method : {"closed_form", "ode"}, default "closed_form"
        ``"closed_form"``: the paper's formulas with a rigorous path scan; ``"ode"``:
        integration with events, an independent route (~10x slower).
    rule : {"paper", "normal_force"}, default "paper"
        Lift-off rule: the paper's condition χ θ̇² cos θ = cos α, or the
        classical Fy = 0.
    %(theta0)s
    %(omega0)s
    rtol : float, default 1e-10
        Relative tolerance of ``method="ode"``, in [1e-15, 1e-3] (checked and recorded,
        unused by the closed form).
    atol : float, default 1e-12
        Absolute tolerance of ``method="ode"``, in [1e-300, 1e-3].
    max_turns : int, default 10_000
        Cap of the search, in turns counted from the start's turn, 1 ... 10**6.
    refine_extrema : bool, default False
        Refine ``max_ratio``, ``min_Fy`` and their angles to full precision (closed form).
        The classification is the same either way; refining costs about a third more time
        on a map.
    stop_at_slip : bool, default False
        Under the paper's rule, stop at the first slip and report ``Reason.SLIP`` instead of
        following rolling on to the lift-off to tell SLIP_BEFORE from SLIP_AT_JUMP.
        ``is_jarm`` and every other reason are unchanged; maps where most points slip are
        faster (1.7x with ``method="ode"``). No effect under ``rule="normal_force"``.
    %(n_threads)s
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair of ``method="ode"``: Dormand–Prince 5(4), Dormand–Prince
        8(5,3) or Verner 9(8); the same verdicts. For speed pick ``"Vern9"``
        (at the default rtol 1.5–1.9× faster than RK45 and about 15× more accurate); keep
        ``"RK45"`` for step-for-step parity with scipy.
    derivatives : bool, default False
        Also give the exact derivatives of ``theta_J``, ``Fx_J``, ``Fy_J`` and
        ``mu_J = -Fx_J/Fy_J`` (:func:`eccjump.closed_form.mu` at θ_J) with respect to
        (α, χ, km), χ and km independent, μ_s and the start fixed: the fields
        ``d_theta_J``, ``d_Fx_J``, ``d_Fy_J``, ``d_mu_J`` (the broadcast shape plus a
        trailing axis of length 3) and ``d_singular``. NaN where θ_J (for the forces:
        ``Fx_J``) is NaN. ``d_singular`` is True where θ_J is not differentiable (a
        double root of the lift-off function, or under ``rule="normal_force"`` a tie
        Fx = Fy = 0); its derivatives are NaN there. At km = 0 the km column is NaN (one-sided:
        km < 0 is no body). On the friction cone (``rule="normal_force"``, Fy_J > 0) ``d_mu_J``
        is exactly 0. By implicit differentiation from the
        classified θ_J (either method: the ODE route's carry its error in θ_J); the
        user guide's "JARM analysis", section "Derivatives". Without it nothing is computed.

    Returns
    -------
    JarmResult
        Every field an array of the broadcast shape of the five inputs (0-d for scalars);
        the ``d_*`` fields None unless ``derivatives=True``.
        Invalid points get ``Reason.INVALID_PARAMS``, not an error (but a scalar
        ``alpha`` out of [0, π/2] is one: see ``alpha``).

    Raises
    ------
    ValueError
        For arguments that apply to the whole call (shapes that do not broadcast, rule,
        method, tolerances, max_turns, n_threads, integrator), a scalar ``alpha`` out of
        [0, π/2] (radians; degrees are a likely mistake) and for an ``n`` that is not
        None or integers ≥ 1; the message names the parameter and its range.
    %(type_error)s
    %(keyboard_interrupt)s
    MemoryError
        If the result cannot be allocated.

    See Also
    --------
    region : the same classification on a grid, in parallel.
    roll : one run of pure rolling, with its events.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> r = eccjump.jarm(np.radians([30, 40, 60]), [0.5, 0.15, 0.15], [0.4, 0.02, 0.02], 1.0)
    >>> [eccjump.Reason(int(c)).name for c in r.reason]
    ['SLIP_BEFORE', 'JARM', 'SLIP_BEFORE']
    >>> print(f"theta_J = {np.degrees(r.theta_J[1]):.6f} deg, Fy_J = {r.Fy_J[1]:.5f} M g")
    theta_J = 334.343838 deg, Fy_J = 0.01543 M g

    The independent route by integration agrees:

    >>> ode = eccjump.jarm(np.radians(40), 0.15, 0.02, 1.0, method="ode")
    >>> bool(abs(ode.theta_J - r.theta_J[1]) < 1e-9)
    True

    How the lift-off angle moves with (α, χ, km):

    >>> d = eccjump.jarm(np.radians(40), 0.15, 0.02, 1.0, derivatives=True)
    >>> print(np.round(d.d_theta_J, 4), bool(d.d_singular))
    [-3.5887 -8.8737  1.3812] False
    """
    want_derivatives = flag("derivatives", derivatives)
    alpha = ramp_angles("alpha", alpha)
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
        _fits_in_memory("jarm", a.size, want_derivatives, 5)
        raw = jarm_points(a, c, k, m, opts, n=nf.astype(np.int64))
    else:
        shape, (a, c, k, m) = broadcast_flat(alpha=alpha, chi=chi, km=km, mu_s=mu_s)
        _fits_in_memory("jarm", a.size, want_derivatives, 4)
        raw = jarm_points(a, c, k, m, opts)
    res = JarmResult._from_raw(raw, shape)
    if not want_derivatives:
        return res
    return replace(res, **derivative_fields((a, c, k, m), raw, opts, shape))


#: Bytes per point of the derivative fields (each float one of len(WRT) values) and of the
#: six float64 columns the derivative pass builds (the grid's points, k_m, mu_s).
_DERIVATIVE_BYTES = field_bytes((f.dtype for f in DERIVATIVE_TABLE), len(WRT)) + 6 * F64


def _fits_in_memory(what: str, points: int, derivatives: bool, inputs: int) -> None:
    """MemoryError before any work if the result (with its derivative fields) cannot fit."""
    axes = "alpha, chi or km_frac" if what == "region" else "the inputs"
    shrink = f"{axes} (or derivatives=False)" if derivatives else axes
    per_point = JARM.bytes_per_point() + (_DERIVATIVE_BYTES if derivatives else 0)
    check_fits(what, points, result_bytes(points, per_point, inputs), shrink)


@dataclass(frozen=True, repr=False, eq=False)
class Region(Map, Plottable, kind=JARM):
    """A JARM map on the grid α × χ × km_frac, with k_m = km_frac (1 - χ).

    Made by :func:`region`. As every :class:`~eccjump.Map`: ``coords``, ``fields``,
    ``shape``, ``fraction()`` and ``to_xarray()``; :func:`eccjump.maps.save` writes it.

    Attributes
    ----------
    alpha : numpy.ndarray
        The ramp angles of the grid [rad], 1-D.
    chi : numpy.ndarray
        The bodies' d/R of the grid, 1-D.
    km_frac : numpy.ndarray
        The shell mass fraction as the share k_m/(1 - χ) of its largest value, 1-D.
    result : JarmResult
        The classification, each field of shape ``(len(alpha), len(chi), len(km_frac))``.
    mu_s : float
        Static friction coefficient of the whole map.
    n : int or None
        The requested turn, or None for the first jump.
    rule : str
        Lift-off rule, ``"paper"`` or ``"normal_force"``.
    method : str
        ``"closed_form"`` or ``"ode"``.
    theta0 : float
        Initial angle [rad].
    omega0 : float
        Initial angular velocity [√(g/R) rad].
    attrs : dict
        How it was made: tolerances, integrator, max_turns, refine_extrema, stop_at_slip.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.region(np.radians(np.linspace(1, 90, 90)), np.linspace(0.01, 0.99, 50),
    ...                    np.linspace(0, 0.99, 50), 1.0)
    >>> m.shape, m.km.shape
    ((90, 50, 50), (50, 50))
    >>> print(f"{m.fraction():.7f}")
    0.0077022
    """

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
        """k_m on the (χ, km_frac) plane, shape ``(len(chi), len(km_frac))``."""
        return self.km_frac[None, :] * (1.0 - self.chi[:, None])

    @property
    def coords(self) -> dict[str, NDArray[np.float64]]:
        """The grid's axes by dimension name: ``alpha`` [rad], ``chi``, ``km_frac``."""
        return {"alpha": self.alpha, "chi": self.chi, "km_frac": self.km_frac}

    @property
    def fields(self) -> dict[str, NDArray]:
        """The fields of :attr:`result` by name (:data:`eccjump.classification.fields.FIELDS`)."""
        return self.result.fields()

    @property
    def is_jarm(self) -> NDArray[np.bool_]:
        return self.result.is_jarm

    @property
    def lazy(self) -> bool:
        """True for a map made with ``chunks=`` and not yet computed (dask-array fields)."""
        return self.result.lazy

    def compute(self, **kwargs: object) -> Region:
        """A lazy map (made with ``chunks=``) computed, all fields in one pass.

        Parameters
        ----------
        **kwargs
            Passed to ``dask.compute`` (e.g. ``scheduler="synchronous"``).

        Returns
        -------
        Region
            The computed map; an already computed map is returned as is.
        """
        if not self.lazy:
            return self
        import dask  # a lazy map exists only if dask is installed

        values = dask.compute(*self.result.fields().values(), **kwargs)
        res = JarmResult(**dict(zip(FIELDS, values, strict=True)))
        return replace(self, result=res, attrs=dict(self.attrs))

    __eq__ = fields_equal

    __hash__ = None  # type: ignore[assignment]  # mutable numpy arrays inside

    def save(self, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
        """Write the map to ``path`` (``.nc``, ``.zarr`` or ``.npz``) by :func:`eccjump.maps.save`,
        whose rules for what may be replaced hold; :func:`eccjump.load` reads it back."""
        return store.save(self, path, overwrite=overwrite)

    def to_layout(self) -> Layout:
        """The map as a layout (:func:`region_layout`)."""
        return region_layout(self)

    @classmethod
    def from_layout(cls, lay: Layout, source: object) -> Region:
        """The Region of the layout ``lay`` of a valid JARM map read from ``source`` (a path,
        for messages); ``alpha_done``, if there, goes to :attr:`attrs`. ValueError naming
        ``source`` if it holds swept maps."""
        dv, co, at = lay["data_vars"], lay["coords"], dict(lay["attrs"])
        if tuple(dv["is_jarm"][0]) != DIMS:
            raise file_error(source, "holds swept maps: open it with eccjump.store.open_dataset")
        names = FIELDS + (DERIVATIVES if "d_theta_J" in dv else ())
        res = JarmResult(**{k: np.asarray(dv[k][1], dtype=DTYPES[k]) for k in names})
        made = JARM.required_attrs
        attrs = {k: _plain(v) for k, v in at.items() if k not in MAP_INFO and k not in made}
        if "alpha_done" in dv:
            attrs["alpha_done"] = np.asarray(dv["alpha_done"][1], dtype=bool)
        n = int(at["n"])
        return cls(
            alpha=np.asarray(co["alpha"][1], dtype=np.float64),
            chi=np.asarray(co["chi"][1], dtype=np.float64),
            km_frac=np.asarray(co["km_frac"][1], dtype=np.float64),
            result=res,
            mu_s=float(at["mu_s"]),
            n=None if n == 0 else n,
            rule=str(at["rule"]),
            method=str(at["method"]),
            theta0=float(at["theta0"]),
            omega0=float(at["omega0"]),
            attrs=attrs,
        )

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

    _plot_doc = """The map in the (χ, α) plane, JARM points coloured by their turn, a few
    km_frac slices (``eccjump.plot.region_map``). ``ax=``: only one slice (``km_frac=``;
    default: the one with the most JARM points), drawn into this matplotlib Axes and
    returned (``eccjump.plot.region_panel``), to compose figures; ``fig=``: the full
    figure in this empty Figure or SubFigure. ``kwargs`` go to the function drawn. Needs
    ``pip install eccjump[plot]``."""


def _plain(value: Any) -> Any:
    """An attribute read from a file as a Python value (a numpy scalar as its item)."""
    return value.item() if isinstance(value, np.generic) else value


def _grid_derivatives(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    mu_s: float,
    raw: Mapping[str, NDArray],
    opts: CallOptions,
) -> dict[str, NDArray]:
    """The derivative fields of the grid classification ``raw`` (flat in C order)."""
    a, c, f = np.meshgrid(alpha, chi, km_frac, indexing="ij")
    points = tuple(np.ascontiguousarray(x.ravel()) for x in (a, c, f * (1.0 - c)))
    mu = np.full(a.size, mu_s)
    return derivative_fields((*points, mu), dict(raw), opts, a.shape)


def region_attrs(region: Region) -> dict[str, Any]:
    """The attributes of a :class:`Region` in a labelled map (see :mod:`eccjump.maps.xarray`)."""
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
    """The labelled layout of a :class:`Region` (numpy only; dask arrays if lazy). The
    attribute ``alpha_done`` of a Region loaded from a map file (which slices were computed)
    goes back to the variable it came from: no format stores an array of bools as an
    attribute."""
    attrs = region_attrs(region)
    done = attrs.pop("alpha_done", None)
    lay = make_layout(
        region.alpha,
        region.chi,
        region.km_frac,
        region.result.fields(),
        attrs,
        None if done is None else np.asarray(done),
        JARM,
    )
    return _with_derivatives(lay, region.result.derivatives())


def _with_derivatives(layout: Layout, derivatives: Mapping[str, Any]) -> Layout:
    """``layout`` with the derivative fields ``derivatives`` (of
    :data:`eccjump.classification.fields.DERIVATIVES`; none: ``layout`` itself) as variables,
    the float ones with the trailing dimension ``wrt`` and its coordinate of parameter names."""
    if not derivatives:
        return layout
    data_vars = dict(layout["data_vars"])
    for k, v in derivatives.items():
        dims = (*DIMS, "wrt") if BY_NAME[k].dtype.kind == "f" else DIMS
        data_vars[k] = (dims, v, JARM.var_attrs(k))
    wrt = (("wrt",), np.array(WRT), WRT_ATTRS)
    return {**layout, "coords": {**layout["coords"], "wrt": wrt}, "data_vars": data_vars}


@refuses_km
@fill
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
    derivatives: bool = False,
    output: Literal["region"] = "region",
    progress: bool | Progress | None = None,
) -> Region:
    """Map the JARM region on a rectangular grid, in parallel.

    The grid first, then ``mu_s``, as every entry point takes the point or body first. Each
    point is classified as by :func:`jarm` (in Rust, with the GIL released), bit-identical
    for any ``n_threads``. The third axis is ``km_frac``, the shell mass fraction as the
    share k_m/(1 - χ) in [0, 1] of its largest value, so that every (χ, km_frac) pair of
    the grid is a valid body and the grid stays rectangular (``Region.km`` gives k_m
    itself).

    Parameters
    ----------
    alpha : array_like of float, 1-D
        Ramp angles [rad], each in [0, π/2] (``np.radians`` for degrees): one value out of
        it is a ValueError; values in (π/2, 90] (degrees?) give one UserWarning.
    chi : array_like of float, 1-D
        The bodies' d/R, each in [0, 1].
    km_frac : array_like of float, 1-D
        k_m/(1 - χ), each in [0, 1].
    mu_s : float
        Static friction coefficient, in [0, inf), one value for the whole map
        (:func:`region_dataset` sweeps a sequence of them).
    n : int or None, default None
        The turn on which the jump must happen (1 ... 2**32 - 1), or None for the first
        jump whatever its turn.
    km : None
        Not accepted: ``km`` is the body's k_m in :func:`jarm`, :func:`roll` and
        :func:`simulate`; on a map the axis is ``km_frac``. Passing it is a TypeError.
    method : {"closed_form", "ode"}, default "closed_form"
        The paper's formulas with a rigorous path scan, or integration with events.
    %(rule)s
    theta0 : float, default 0.0
        Initial angle [rad], |theta0| ≤ 2π 1e6 (:func:`region_dataset` sweeps it).
    omega0 : float, default 0.0
        Initial angular velocity [√(g/R) rad], in [0, 1e6] (swept as ``theta0``).
    rtol : float, default 1e-10
        Relative tolerance of ``method="ode"``, in [1e-15, 1e-3].
    atol : float, default 1e-12
        Absolute tolerance of ``method="ode"``, in [1e-300, 1e-3].
    max_turns : int, default 10_000
        Cap of the search per point, in turns from the start's turn, 1 ... 10**6.
    refine_extrema : bool, default False
        Refine ``max_ratio``, ``min_Fy`` and their angles to full precision (about a third
        more time; the classification is the same).
    stop_at_slip : bool, default False
        Under the paper's rule, a slip ends the search (``Reason.SLIP``): the same
        ``is_jarm``, faster where most points slip (1.7x with ``method="ode"``, 1.2x with
        the closed form).
    n_threads : int, default 0
        Threads, 0 (one per core) ... 256; with ``chunks``, per block.
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair of ``method="ode"``. For speed pick ``"Vern9"``; keep
        ``"RK45"`` for step-for-step parity with scipy.
    chunks : int, sequence of int, dict or None, default None
        None computes now. Otherwise chunk sizes along (α, χ, km_frac) -- one int for
        all, a 3-sequence or a dict; -1 or None for a whole axis: the map is built lazily
        with dask (``pip install "eccjump[dask]"``), one Rust grid call per block,
        bit-identical to the unchunked map; call ``.compute()`` on the result. On a cluster
        use ``n_threads`` = threads per worker / concurrent tasks per worker.
    derivatives : bool, default False
        Also give the exact derivatives of θ_J, Fx_J, Fy_J and μ_J with respect to
        (α, χ, km) at every grid point, as :func:`jarm` does: the ``d_*`` fields of
        ``result`` (shape of the grid plus 3), variables with a trailing dimension ``wrt``
        in the labelled form and in the files of :func:`eccjump.maps.save` (not in the
        chunked files of ``eccjump map``). Not with ``chunks``. With respect to k_m itself,
        not km_frac: dk_m = (1 - χ) dkm_frac at fixed χ.
    output : {"region"}, default "region"
        A :class:`Region`. ``"xarray"`` is deprecated (it works until the next release,
        with a DeprecationWarning): write ``region(...).to_xarray()``, or
        :func:`region_dataset` to sweep ``mu_s``, ``theta0`` and ``omega0``.
    %(progress)s
        Not with ``chunks`` (a ValueError).

    Returns
    -------
    Region
        The map; its ``attrs`` record the tolerances, the integrator, ``max_turns``,
        ``refine_extrema`` and ``stop_at_slip`` as given, whatever the method (the closed
        form ignores the tolerances and the integrator).

    Raises
    ------
    ValueError
        For an axis that is not a 1-D array of values in range, a bad ``mu_s``, ``n`` or
        option (a sequence of ``mu_s``, ``theta0`` or ``omega0``: :func:`region_dataset`
        sweeps them); the message names the parameter and its range.
    %(type_error_km)s
    MemoryError
        If the map does not fit in memory (refused before any work, naming its size).
    ImportError
        For ``chunks`` without dask.
    %(keyboard_interrupt)s

    See Also
    --------
    jarm : the classification of scattered points.
    region_dataset : the same as an ``xarray.Dataset``, sweeping mu_s, theta0 and omega0.
    motion_map : maps of the full motion.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.region(
    ...     alpha=np.radians(np.linspace(1, 90, 90)),
    ...     chi=np.linspace(0.01, 0.99, 50),
    ...     km_frac=np.linspace(0, 0.99, 50),
    ...     mu_s=1.0,
    ... )
    >>> print(m.is_jarm.shape, f"{m.fraction():.7f}")
    (90, 50, 50) 0.0077022
    """
    xarray = _deprecated_output(output)
    want_derivatives = flag("derivatives", derivatives)
    if want_derivatives and chunks is not None:
        raise ValueError("derivatives=True needs chunks=None (a map computed now)")
    if checked(progress) and chunks is not None:
        raise ValueError("progress needs chunks=None (dask reports the progress of a lazy map)")
    for name, value in (("mu_s", mu_s), ("theta0", theta0), ("omega0", omega0)):
        if isinstance(value, list | tuple) or (isinstance(value, np.ndarray) and value.ndim):
            raise ValueError(f"{name} must be a number here; region_dataset(...) sweeps it")
    mu = real("mu_s", mu_s)
    a, c, f = (
        axis("alpha", ramp_angles("alpha", alpha)),
        axis("chi", chi),
        axis("km_frac", fraction_axis(km_frac)),
    )
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
        _fits_in_memory("region", a.size * c.size * f.size, want_derivatives, 0)

        def part(ax: int, values: slice) -> dict[str, NDArray]:
            x, y, z = cut((a, c, f), ax, values)
            return jarm_grid(x, y, z, mu, opts)

        with reporting(progress) as report:
            raw = grid_in_parts(part, (a.size, c.size, f.size), report)
        res = JarmResult._from_raw(raw, (a.size, c.size, f.size))
        if want_derivatives:
            res = replace(res, **_grid_derivatives(a, c, f, mu, raw, opts))
    else:
        blocks = normalize_chunks(chunks, (a.size, c.size, f.size))
        res = JarmResult(**lazy_fields(JARM, jarm_grid, (a, c, f), blocks, (mu, opts)))
    reg = Region(
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
    # the deprecated output="xarray" (typed away: the signature says what to write instead)
    return reg.to_xarray() if xarray else reg  # type: ignore[return-value]


def _deprecated_output(output: object) -> bool:
    """Whether ``output`` asks for the deprecated labelled result (with its warning);
    ValueError for anything but "region" and "xarray"."""
    if text("output", output) not in ("region", "xarray"):
        raise ValueError(f"output = {short(output)}; use 'region'")
    if output == "xarray":
        warnings.warn(
            "eccjump.region(output='xarray') is deprecated: use region(...).to_xarray(), or "
            "region_dataset(...) to sweep mu_s, theta0, omega0 (until the next release)",
            DeprecationWarning,
            stacklevel=stacklevel_outside(),
        )
    return output == "xarray"


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
    "region_layout",
]
