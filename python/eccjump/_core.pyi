"""Type stubs of the compiled bridge ``eccjump._core`` (Rust, pyo3).

One convention (``docs/architecture.md``, "The bridge"): the arrays or numbers computed over
come positionally, every option keyword-only, each of a plain type (the options that several
entry points share gathered once in a frozen options class, ``ClassifyOptions``,
``BoundaryOptions`` and ``MotionMapOptions``, itself made from keyword-only plain values);
results come back by name as plain values: a dict of one numpy array per field for a map or
a run's series, of one list per field for a run's records (the TypedDicts below), from which
the Python layer makes its result objects by name.
"""

from typing import Any, TypedDict, final

import numpy as np
from numpy.typing import NDArray

# The module's exports (stubtest compares them with the list pyo3 makes at run time).
__all__ = [
    "INVALID",
    "MAX_STEPS",
    "MAX_TRANSITIONS",
    "MOTION_PARAMETERS",
    "SEQUENCE_LEN",
    "VERSION",
    "BoundaryOptions",
    "ClassifyOptions",
    "DenseSolution",
    "MotionDense",
    "MotionMapOptions",
    "alpha_interval_around",
    "alpha_intervals",
    "alpha_min",
    "body_derived",
    "body_from_inertia",
    "body_from_shell_and_line",
    "gamma",
    "green_turn",
    "impact",
    "j_brackets",
    "j_paper",
    "jarm_derivatives",
    "jarm_grid",
    "jarm_points",
    "jump_forces",
    "landing_codes",
    "liftoff_function",
    "mode_codes",
    "motion_grid",
    "motion_points",
    "mu",
    "mu_s_min",
    "mu_s_min_path",
    "path_forces",
    "reason_codes",
    "roll",
    "sequence_code",
    "simulate",
    "status_codes",
    "theta_j_range",
    "theta_nj",
    "transition_reason_codes",
]

VERSION: str
"""The package version, e.g. "0.2.0" (`eccjump --version` prints it; `eccjump.__version__`)."""

MOTION_PARAMETERS: list[str]
"""The parameters of a full-motion run, in the order of the sensitivities' last axis."""

MAX_TRANSITIONS: int
"""The largest ``max_transitions`` of a full-motion run."""

MAX_STEPS: int
"""The largest ``max_steps`` of an integration."""

SEQUENCE_LEN: int
"""The modes a motion map's sequence code keeps."""

INVALID: int
"""The ``status`` of a motion map's point whose parameters are invalid."""

# (code, name) of the full motion's modes, transition reasons and statuses, by code
# (eccjump.motion checks its MODES, REASONS and STATUSES against them at import).
def mode_codes() -> list[tuple[int, str]]: ...
def transition_reason_codes() -> list[tuple[int, str]]: ...
def status_codes() -> list[tuple[int, str]]: ...
def sequence_code(codes: list[int]) -> int:
    """The sequence code a motion map stores for the modes ``codes`` (codes of
    ``mode_codes``; the first ``SEQUENCE_LEN`` count). ValueError for a code that is no
    mode."""

_F64 = NDArray[np.float64]

def body_derived(chi: float, km: float) -> tuple[float, float, float]: ...
def body_from_inertia(M: float, R: float, d: float, I_C: float) -> tuple[float, float]: ...
def body_from_shell_and_line(m_C: float, m_P: float, R: float, d: float) -> tuple[float, float]: ...

class _ImpactResult(TypedDict):
    """One impact (``impact``): W = (wtt, wtn; wtn, wnn), the impulse (pt, pn) per M, the
    contact velocity after it (ut = l' - theta', un = b'), whether the contact point ends
    sticking, the velocities after it (omega, ldot, bdot) and the works (compression, normal,
    friction; <= 0) in M g R."""

    wtt: float
    wtn: float
    wnn: float
    pt: float
    pn: float
    ut: float
    un: float
    sticking: bool
    omega: float
    ldot: float
    bdot: float
    compression_work: float
    normal_work: float
    friction_work: float

def impact(
    chi: float,
    km: float,
    state: tuple[float, float, float, float],
    law: tuple[float, float, float],
) -> _ImpactResult:
    """One impact of the body (chi, km) at the state (theta, omega, ldot, bdot) under the law
    (mu_s, mu_k, restitution): Routh's method with Coulomb friction (mu_s, mu_k) and
    Stronge's energetic restitution (docs/impact_law.md). Private, for the tests. ValueError
    (validated by the core) for a bad parameter, a non-finite state or km = 0."""

class _EventColumns(TypedDict):
    """The events of a rolling run, one list per field of ``eccjump.motion.roll.Event``."""

    name: list[str]
    t: list[float]
    theta: list[float]
    omega: list[float]

class _RollRun(TypedDict):
    """A rolling run by the field names of ``RollResult`` (all but the body, alpha, mu_s,
    rule and units, which ``eccjump.roll`` adds)."""

    t: _F64
    theta: _F64
    omega: _F64
    omega_dot: _F64
    Fx: _F64
    Fy: _F64
    l: _F64
    friction_ratio: _F64
    events: _EventColumns
    terminal_event: str | None
    status: int
    message: str
    nfev: int
    sol: DenseSolution | None

def roll(
    chi: float,
    km: float,
    alpha: float,
    *,
    theta0: float,
    omega0: float,
    mu_s: float | None,
    t_max: float,
    theta_max: float,
    rtol: float,
    atol: float,
    dense_output: bool,
    max_steps: int,
    rule: str,
    integrator: str,
) -> _RollRun:
    """One pure-rolling run of the body (chi, km) on a ramp of angle alpha, with the GIL
    released. The options of ``eccjump.roll``, all required (it gives the defaults), checked
    by the core: a ValueError names the parameter. Returns the run by name, from which
    ``eccjump.roll`` makes the ``RollResult``."""

@final
class DenseSolution:
    """The dense output of a run, evaluated by the core (ends at the run's end)."""

    @property
    def t_min(self) -> float: ...
    @property
    def t_max(self) -> float: ...
    def states(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """(theta, omega) at the times ``t`` (1-D float64), shape (2, len(t)). ValueError
        names the first time outside [t_min, t_max]; MemoryError for too many times."""

    def kinematics(self, t: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
        """theta, omega, omega_dot, Fx, Fy and ratio at the times ``t`` (1-D float64), each
        of shape (len(t),); errors as :meth:`states`."""

class _TransitionColumns(TypedDict):
    """One list per field of ``eccjump.motion.Transition``."""

    t: list[float]
    from_mode: list[str | None]
    to_mode: list[str]
    reason: list[str]
    theta: list[float]
    omega: list[float]
    l: list[float]
    ldot: list[float]
    b: list[float]
    bdot: list[float]

class _FlightColumns(TypedDict):
    """One list per field of ``eccjump.motion.FlightRecord``."""

    t_liftoff: list[float]
    t_landing: list[float]
    theta_liftoff: list[float]
    theta_landing: list[float]
    apex: list[float]
    distance: list[float]

class _ImpactColumns(TypedDict):
    """One list per field of ``eccjump.motion.ImpactRecord``."""

    t: list[float]
    normal_speed: list[float]
    slip_before: list[float]
    pt: list[float]
    pn: list[float]
    energy_lost: list[float]
    sticking: list[bool]
    outcome: list[str]

class _SegmentColumns(TypedDict):
    """One list per field of ``eccjump.motion.Segment``."""

    mode: list[str]
    reason: list[str]
    t_start: list[float]
    t_end: list[float]
    nfev: list[int]

class _MotionRun(TypedDict):
    """A full-motion run by the field names of ``MotionResult`` (all but the body, alpha,
    the friction, restitution, rule and units, which ``eccjump.simulate`` adds)."""

    t: _F64
    theta: _F64
    omega: _F64
    l: _F64
    ldot: _F64
    b: _F64
    bdot: _F64
    Fx: _F64
    Fy: _F64
    energy: _F64
    dissipated: _F64
    mode: NDArray[np.int8]
    transitions: _TransitionColumns
    flights: _FlightColumns
    impacts: _ImpactColumns
    segments: _SegmentColumns
    energy0: float
    dissipated_slip: float
    dissipated_impacts: float
    status: str
    message: str
    nfev: int
    sol: MotionDense | None
    d_transitions: NDArray[np.float64] | None
    d_singular: NDArray[np.bool_] | None

def simulate(
    chi: float,
    km: float,
    alpha: float,
    *,
    mu_s: float,
    mu_k: float,
    restitution: float,
    rule: str,
    theta0: float,
    omega0: float,
    slip0: float,
    t_max: float,
    l_max: float,
    max_transitions: int,
    rtol: float,
    atol: float,
    max_steps: int,
    dense_output: bool,
    integrator: str,
    sensitivities: bool,
) -> _MotionRun:
    """The full motion of the body (chi, km) on a ramp of angle alpha (docs/motion.md), with
    the GIL released. The options of ``eccjump.simulate``, all required (it gives the
    defaults; mu_k resolved), checked by the core: a ValueError names the parameter. Returns
    the run by name (the sensitivities None unless asked for), from which
    ``eccjump.simulate`` makes the ``MotionResult``."""

@final
class MotionDense:
    """The dense output of a full-motion run (``MotionResult.sol``), evaluated by the core."""

    @property
    def t_max(self) -> float:
        """Last time covered: the end of the run."""

    def states(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """(theta, omega, l, ldot, b, bdot) at the times ``t`` (1-D float64), shape
        (6, len(t)); at an impact, the state after it. ValueError names the first time
        outside [0, t_max]; MemoryError for too many times."""

@final
class ClassifyOptions:
    """The options of ``jarm_points`` and ``jarm_grid`` but the turn, converted once: made
    from keyword-only plain values named as ``eccjump.jarm`` names them. ValueError for an
    unknown rule, route or pair and for tolerances out of range."""

    def __new__(
        cls,
        *,
        rule: str,
        method: str,
        rtol: float,
        atol: float,
        theta0: float,
        omega0: float,
        max_turns: int,
        refine_extrema: bool,
        stop_at_slip: bool,
        n_threads: int,
        integrator: str,
    ) -> ClassifyOptions: ...

def jarm_points(
    alpha: _F64,
    chi: _F64,
    km: _F64,
    mu_s: _F64,
    n: NDArray[np.uint32],
    *,
    options: ClassifyOptions,
) -> dict[str, NDArray[Any]]: ...
def jarm_grid(
    alpha: _F64,
    chi: _F64,
    frac: _F64,
    mu_s: float,
    *,
    n: int,
    options: ClassifyOptions,
) -> dict[str, NDArray[Any]]: ...
def reason_codes() -> list[tuple[int, str]]: ...

# The exact derivatives of a classification's theta_J, Fx_J, Fy_J and mu_J = -Fx_J/Fy_J with
# respect to (alpha, chi, km): four (N, 3) arrays and the flag of the singular points.
def jarm_derivatives(
    alpha: _F64,
    chi: _F64,
    km: _F64,
    mu_s: _F64,
    theta_j: _F64,
    *,
    rule: str,
    theta0: float,
    omega0: float,
) -> tuple[_F64, _F64, _F64, _F64, NDArray[np.bool_]]: ...

# The paper's closed forms over equal-length 1-D arrays, each returning its output columns.
def jump_forces(alpha: _F64, chi: _F64, km: _F64, theta_j: _F64) -> list[_F64]: ...
def mu(chi: _F64, km: _F64, theta_j: _F64) -> list[_F64]: ...
def green_turn(alpha: _F64, theta_j: _F64) -> list[_F64]: ...
def mu_s_min(chi: _F64, km: _F64) -> list[_F64]: ...
def theta_j_range(chi: _F64, km: _F64, mu_s: _F64, *, n: int) -> list[_F64]: ...
def alpha_min(chi: _F64, km: _F64, mu_s: _F64, *, n: int) -> list[_F64]: ...
def gamma(chi: _F64, km: _F64) -> list[_F64]: ...
def j_paper(theta: _F64, alpha: _F64, chi: _F64, km: _F64) -> list[_F64]: ...
def liftoff_function(
    theta: _F64, alpha: _F64, chi: _F64, km: _F64, *, theta0: float, omega0: float
) -> list[_F64]: ...
def j_brackets(alpha: _F64, chi: _F64, km: _F64, *, n: int) -> list[_F64]: ...
def theta_nj(alpha: _F64, chi: _F64, km: _F64, *, n: int) -> list[_F64]: ...
def path_forces(
    theta: _F64, alpha: _F64, chi: _F64, km: _F64, *, theta0: float, omega0: float
) -> list[_F64]: ...

@final
class BoundaryOptions:
    """The options every boundary search takes: the turn (0 = the first jump), the rule and
    the threads, made from keyword-only plain values. ValueError for an unknown rule."""

    def __new__(cls, *, n: int, rule: str, n_threads: int) -> BoundaryOptions: ...

def alpha_intervals(
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: float,
    *,
    n_scan: int,
    options: BoundaryOptions,
) -> list[list[tuple[float, float]]]: ...
def mu_s_min_path(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    *,
    options: BoundaryOptions,
) -> NDArray[np.float64]: ...
def alpha_interval_around(
    seed: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: float,
    *,
    step: float,
    options: BoundaryOptions,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...

@final
class MotionMapOptions:
    """The options of ``motion_grid`` and ``motion_points``, converted once: made from
    keyword-only plain values named as ``eccjump.motion_map`` names them
    (``eccjump.motion.options.MotionOptions.to_core``). ValueError for an unknown rule or
    pair (the core checks the ranges when a call uses them)."""

    def __new__(
        cls,
        *,
        rule: str,
        t_max: float,
        max_transitions: int,
        rtol: float,
        atol: float,
        max_steps: int,
        n_threads: int,
        integrator: str,
    ) -> MotionMapOptions: ...

def motion_grid(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    frac: NDArray[np.float64],
    mu_s: NDArray[np.float64],
    mu_k: NDArray[np.float64],
    restitution: NDArray[np.float64],
    theta0: NDArray[np.float64],
    omega0: NDArray[np.float64],
    *,
    options: MotionMapOptions,
) -> dict[str, NDArray[Any]]:
    """The full motion to the first landing at every point of the product of the eight 1-D
    axes (k_m = frac (1 - chi); an empty ``mu_k``: mu_k = mu_s), flat in C order, with the
    GIL released. One array per summary field (``eccjump.motion.maps.TABLE``); a point with
    invalid values has status 255. A bad shared option is a ValueError naming it."""

def motion_points(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: NDArray[np.float64],
    mu_k: NDArray[np.float64],
    restitution: NDArray[np.float64],
    theta0: NDArray[np.float64],
    omega0: NDArray[np.float64],
    *,
    options: MotionMapOptions,
) -> dict[str, NDArray[Any]]:
    """The full motion to the first landing at each point (alpha[i], chi[i], km[i], mu_s[i],
    mu_k[i], restitution[i], theta0[i], omega0[i]) (km: the body's k_m; columns of one
    length, an empty ``mu_k``: mu_k = mu_s), with the GIL released, each point exactly what
    ``simulate`` gives there, for any thread count. One array per summary field
    (``eccjump.motion.fields.TABLE``); an invalid point has status 255. A bad shared option
    or a column of another length is a ValueError naming it."""

def landing_codes() -> list[tuple[int, str]]:
    """(code, name) of every landing outcome of a motion map."""
