"""The full motion to the first landing at given points: :func:`motion_points`.

Where :func:`eccjump.motion_map` runs the product of its axes, :func:`motion_points` runs the
points it is given (broadcast together, as :func:`eccjump.jarm`), each with its own body,
ramp, friction, restitution and start -- what a Monte Carlo sample needs
(:func:`eccjump.uncertainty`). Each point keeps the summary of a motion map (the fields of
:data:`eccjump.motion.fields.TABLE`) and is exactly what :func:`eccjump.simulate` gives
there; the points run in parallel in the Rust core, bit-identical for any thread count.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.arrays import broadcast_flat, fields_equal
from eccjump._base.checks import Integrator, Rule
from eccjump._base.docs import fill
from eccjump._base.progress import Progress, points_in_parts, reporting
from eccjump._base.sizes import check_fits, result_bytes
from eccjump._base.units import ramp_angles
from eccjump.maps import results
from eccjump.maps.results import Result
from eccjump.motion.fields import FIELDS, INVALID, MOTION, sequence_name
from eccjump.motion.options import MotionOptions

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray as xr


@dataclass(frozen=True, eq=False)
class MotionPoints(Result, kind="motion_points"):
    """The summary of the full motion at each point of :func:`motion_points`, one array per
    field of the broadcast shape (the fields of :data:`eccjump.motion.fields.TABLE`, with
    their units and meanings).

    Attributes
    ----------
    status : numpy.ndarray of uint8
        How the run ended (:data:`eccjump.motion.fields.STATUS_NAMES`); 255: invalid point.
    sequence : numpy.ndarray of uint16
        The first modes as a code (:func:`eccjump.motion.fields.sequence_name`).
    n_modes : numpy.ndarray of uint16
        Modes in the run, the start's included.
    jarm : numpy.ndarray of bool
        Lift-off straight out of pure rolling from the start.
    slipped_first : numpy.ndarray of bool
        A slip came before the first flight.
    slip_t, slip_theta : numpy.ndarray of float64
        Time [√(R/g)] and angle [rad] of the first slip onset (NaN: none).
    liftoff_reason : numpy.ndarray of uint8
        Why the first flight began (255: none).
    liftoff_t, liftoff_theta : numpy.ndarray of float64
        Time [√(R/g)] and angle [rad] of the first lift-off (NaN: none).
    flight_time : numpy.ndarray of float64
        Duration of the first flight [√(R/g)] (NaN: did not land).
    apex : numpy.ndarray of float64
        Largest height of the first flight above contact [R] (NaN: no flight).
    distance : numpy.ndarray of float64
        Distance down the ramp covered by the first flight [R] (NaN: no flight).
    landing : numpy.ndarray of uint8
        How the first landing ended (:data:`eccjump.motion.fields.LANDINGS`).
    energy_lost : numpy.ndarray of float64
        Energy dissipated by sliding and impacts [M g R].
    """

    status: NDArray[np.uint8]
    sequence: NDArray[np.uint16]
    n_modes: NDArray[np.uint16]
    jarm: NDArray[np.bool_]
    slipped_first: NDArray[np.bool_]
    slip_t: NDArray[np.float64]
    slip_theta: NDArray[np.float64]
    liftoff_reason: NDArray[np.uint8]
    liftoff_t: NDArray[np.float64]
    liftoff_theta: NDArray[np.float64]
    flight_time: NDArray[np.float64]
    apex: NDArray[np.float64]
    distance: NDArray[np.float64]
    landing: NDArray[np.uint8]
    energy_lost: NDArray[np.float64]

    __eq__ = fields_equal
    __hash__ = None  # type: ignore[assignment]

    @property
    def valid(self) -> NDArray[np.bool_]:
        """The points whose parameters are valid (status not 255)."""
        return self.status != INVALID

    def sequences(self) -> dict[str, int]:
        """Each sequence of modes among the valid points, by name, with its count (most
        frequent first)."""
        codes, counts = np.unique(self.sequence[self.valid], return_counts=True)
        order = np.argsort(-counts, kind="stable")
        return {sequence_name(int(codes[i])): int(counts[i]) for i in order}

    def as_dict(self) -> dict[str, NDArray[Any]]:
        """The fields by name."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    # Taking the result elsewhere (save and eccjump.load: eccjump.maps.results).
    def to_xarray(self) -> xr.Dataset:
        """The points as an ``xarray.Dataset`` (needs xarray): one variable per field over
        ``point`` (``point_0``, ``point_1``, ... for more than one axis; none for one
        point) with ``units``, ``long_name`` and the codes as CF flags."""
        return results.points(self, self.as_dict(), MOTION.var_attrs)

    def to_dataframe(self) -> pandas.DataFrame:
        """The fields as a ``pandas.DataFrame``, one row per point (indexed by its
        position), the units of the columns in ``attrs["units"]``."""
        return results.to_frame(self.to_xarray(), results.point_dims(self.status.shape))


@fill
def motion_points(
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    mu_s: ArrayLike,
    *,
    mu_k: ArrayLike | None = None,
    restitution: ArrayLike = 0.0,
    theta0: ArrayLike = 0.0,
    omega0: ArrayLike = 0.0,
    rule: Rule = "paper",
    t_max: float = 100.0,
    max_transitions: int = 100,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_steps: int = 1_000_000,
    n_threads: int = 0,
    integrator: Integrator = "RK45",
    progress: bool | Progress | None = None,
) -> MotionPoints:
    """The full motion, to the first landing, at each point (α, χ, km, μ_s, μ_k,
    restitution, theta0, omega0), broadcasting the eight inputs.

    Each point runs :func:`eccjump.simulate` to its first landing (or ``t_max``,
    ``max_transitions``) and keeps the summary of a motion map; the points run in parallel
    in the Rust core with the GIL released, their rolling and sliding segments side by side,
    each exactly what ``simulate`` gives there, bit-identical for any ``n_threads``. The
    point first, as :func:`eccjump.jarm` (``km`` is the body's k_m), then ``mu_s``, then
    keyword-only options with :func:`eccjump.motion_map`'s names and defaults. A point whose
    own values are invalid (k_m > 1 - χ, k_m = 0, μ_k > μ_s, a value out of range) has
    status 255 and the fill values.

    Parameters
    ----------
    alpha : array_like of float
        Ramp angles [rad], in [0, π/2] (``np.radians`` for degrees): a scalar out of it is
        a ValueError; values in (π/2, 90] (degrees?) give one UserWarning.
    chi : array_like of float
        The bodies' d/R, in [0, 1].
    km : array_like of float
        The bodies' shell mass fraction k_m, in (0, 1 - χ].
    mu_s : array_like of float
        Static friction coefficients, in [0, inf).
    mu_k : array_like of float or None, default None
        Kinetic friction coefficients, in [0, μ_s]; None: μ_k = μ_s at every point.
    restitution : array_like of float, default 0.0
        Stronge's energetic coefficients of restitution, in [0, 1].
    theta0 : array_like of float, default 0.0
        Initial angles [rad], |theta0| ≤ 2π 1e6.
    omega0 : array_like of float, default 0.0
        Initial angular velocities [√(g/R) rad], |omega0| ≤ 1e6.
    %(rule_rolling)s
    t_max : float, default 100.0
        End time of each run [√(R/g)], in (0, 1e6].
    max_transitions : int, default 100
        Transitions of each run after the start, 1 ... 10**6.
    rtol : float, default 1e-10
        Relative tolerance, in [1e-15, 1e-6].
    atol : float, default 1e-12
        Absolute tolerance, in [1e-300, 1e-6].
    max_steps : int, default 1_000_000
        Accepted steps of each run, 1 ... 10**7.
    %(n_threads)s
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair. For speed pick ``"Vern9"`` or ``"DOP853"``; keep ``"RK45"``
        for step-for-step parity with scipy.
    %(progress)s

    Returns
    -------
    MotionPoints
        One array per summary field, of the broadcast shape.

    Raises
    ------
    ValueError
        For a bad shared option (naming it and its range) or inputs that do not broadcast.
    TypeError
        If an argument has the wrong type.
    MemoryError
        If the result does not fit in memory.
    KeyboardInterrupt
        On Ctrl-C (the work stops within a second).

    See Also
    --------
    motion_map : the same summaries over the product of axes.
    simulate : one run, recorded in full.

    Examples
    --------
    The paper's JARM point and its Fig. 3b body, which slips first:

    >>> import numpy as np
    >>> import eccjump
    >>> p = eccjump.motion_points(np.radians([40, 30]), [0.15, 0.5], [0.02, 0.4], 1.0)
    >>> p.jarm.tolist(), p.slipped_first.tolist()
    ([True, False], [False, True])
    >>> print(f"apex {p.apex[0]:.6f} R, distance {p.distance[1]:.5f} R")
    apex 0.006696 R, distance 3.49484 R
    """
    named: dict[str, object] = {
        "alpha": ramp_angles("alpha", alpha),
        "chi": chi,
        "km": km,
        "mu_s": mu_s,
        "restitution": restitution,
        "theta0": theta0,
        "omega0": omega0,
    }
    if mu_k is not None:
        named["mu_k"] = mu_k
    opts = MotionOptions(
        rule=rule,
        t_max=t_max,
        max_transitions=max_transitions,
        rtol=rtol,
        atol=atol,
        max_steps=max_steps,
        integrator=integrator,
    ).to_core(n_threads)
    shape, flat = broadcast_flat(**named)
    points = flat[0].size
    need = result_bytes(points, MOTION.bytes_per_point(), len(flat))
    check_fits("motion_points", points, need, "the inputs")
    columns = dict(zip(named, flat, strict=True))
    columns.setdefault("mu_k", np.empty(0))  # empty: mu_k = mu_s at every point
    order = ("alpha", "chi", "km", "mu_s", "mu_k", "restitution", "theta0", "omega0")

    def part(i0: int, i1: int) -> dict[str, NDArray]:
        cols = (np.ascontiguousarray(columns[k][i0:i1]) for k in order)
        return _core.motion_points(*cols, options=opts)

    with reporting(progress) as report:
        raw = points_in_parts(part, points, report)
    return MotionPoints(**{k: raw[k].reshape(shape) for k in FIELDS})


__all__ = ["MotionPoints", "motion_points"]
