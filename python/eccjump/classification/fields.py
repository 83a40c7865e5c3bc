"""The one description of the fields of a JARM classification result.

Every result of :func:`eccjump.jarm` and :func:`eccjump.region` has the same fields, in the
order of the Rust bridge. Each is described ONCE here -- name, numpy dtype, units, meaning
and the fill value of a point not computed -- and everything else derives from this table:
the :class:`~eccjump.JarmResult` dataclass and its documentation, the CF attributes of its
labelled form, and the map kind :data:`JARM` (:class:`~eccjump.maps.kinds.MapKind`) through
which the files of :mod:`eccjump.store`, their checks and the ``eccjump map`` command know a
JARM map.

This module depends on numpy, the compiled core (for the :class:`Reason` codes) and the map
layer's :class:`~eccjump.maps.kinds.MapKind`.
"""

from __future__ import annotations

import enum
import math
import sys
from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump.maps.kinds import MapKind, register


class Field(NamedTuple):
    """One result field."""

    #: Attribute, variable and bridge key.
    name: str
    #: numpy dtype of its arrays.
    dtype: np.dtype
    #: CF-style units (``"1"``: dimensionless; g = R = M = 1).
    units: str
    #: What it means, in one line (the CF ``long_name``).
    description: str
    #: Value of a point not computed (an interrupted map).
    fill: Any
    #: The physical range [lo, hi] of a float field's values other than NaN (checked when a
    #: map is read or written, :mod:`eccjump.maps.check`): finite unless a bound is infinite.
    valid: tuple[float, float] = (-sys.float_info.max, sys.float_info.max)


_BOOL, _U8, _U32, _F64 = (np.dtype(t) for t in (np.bool_, np.uint8, np.uint32, np.float64))
_NAN = float("nan")
#: Slack of a bound at 0 that a result reaches with rounding (a normal force at lift-off).
ROUNDING = 1e-9
#: The angles of a JARM search: from the start (|theta0| <= 2 pi 10^6) over at most 10^6
#: turns (max_turns), with room to spare.
ANGLES = (-2 * math.pi * 1e7, 2 * math.pi * 1e7)

#: Every field, in the order of the bridge.
TABLE: tuple[Field, ...] = (
    Field("is_jarm", _BOOL, "1", "jump straight out of pure rolling (JARM)", False),
    Field("reason", _U8, "1", "why the point is or is not a JARM (Reason code)", 255),
    Field(
        "n",
        _U32,
        "1",
        "turn of the jump (JARM), of the earlier lift-off or of the deciding event "
        "(round(theta / 2 pi), at least 1); 0 if none",
        0,
    ),
    Field(
        "theta_J",
        _F64,
        "rad",
        "lift-off angle (JARM, LIFTOFF_EARLIER, SLIP_AT_JUMP), else NaN",
        _NAN,
        ANGLES,
    ),
    Field(
        "theta_event", _F64, "rad", "angle of the deciding failure (NaN for a JARM)", _NAN, ANGLES
    ),
    Field("Fx_J", _F64, "M g", "friction force at the jump (JARM only)", _NAN),
    Field(
        "Fy_J",
        _F64,
        "M g",
        "normal force at the jump (JARM only)",
        _NAN,
        (-ROUNDING, sys.float_info.max),
    ),
    Field("max_ratio", _F64, "1", "largest |Fx|/Fy on the rolling path", _NAN, (0.0, math.inf)),
    Field("theta_max_ratio", _F64, "rad", "angle of the largest |Fx|/Fy", _NAN, ANGLES),
    Field("min_Fy", _F64, "M g", "smallest normal force on the rolling path", _NAN),
    Field("theta_min_Fy", _F64, "rad", "angle of the smallest normal force", _NAN, ANGLES),
)

#: Field names, in the order of the bridge.
FIELDS: tuple[str, ...] = tuple(f.name for f in TABLE)

#: What the derivative fields differentiate with respect to: their trailing axis (the
#: dimension ``wrt`` of a labelled map), alpha [rad] and the body's chi and k_m (independent).
WRT: tuple[str, ...] = ("alpha", "chi", "km")
#: The attributes of the coordinate ``wrt`` of a labelled map.
WRT_ATTRS = {"long_name": "parameter of the derivative: alpha [rad], chi or km (k_m itself)"}

#: The fields of a result made with ``derivatives=True`` (None otherwise), after :data:`TABLE`:
#: each float field has the point's shape plus a trailing axis of length 3 (:data:`WRT`).
DERIVATIVE_TABLE: tuple[Field, ...] = (
    Field(
        "d_theta_J",
        _F64,
        "rad",
        "derivative of theta_J with respect to (alpha, chi, km)",
        _NAN,
    ),
    Field("d_Fx_J", _F64, "M g", "derivative of Fx_J with respect to (alpha, chi, km)", _NAN),
    Field("d_Fy_J", _F64, "M g", "derivative of Fy_J with respect to (alpha, chi, km)", _NAN),
    Field(
        "d_mu_J",
        _F64,
        "1",
        "derivative of mu_J = -Fx_J/Fy_J (closed_form.mu at theta_J) w.r.t. (alpha, chi, km)",
        _NAN,
    ),
    Field(
        "d_singular",
        _BOOL,
        "1",
        "theta_J not differentiable (a double root or a tie): its derivatives are NaN",
        False,
    ),
)
#: Derivative field names, in order.
DERIVATIVES: tuple[str, ...] = tuple(f.name for f in DERIVATIVE_TABLE)

#: Field by name (the derivative fields too).
BY_NAME: dict[str, Field] = {f.name: f for f in TABLE + DERIVATIVE_TABLE}
#: numpy dtype of each field (the derivative fields too).
DTYPES: dict[str, np.dtype] = {f.name: f.dtype for f in TABLE + DERIVATIVE_TABLE}
#: Value of each field where a point was not computed (``reason`` 255 is not a Reason).
FILL: dict[str, Any] = {f.name: f.fill for f in TABLE}
#: The physical range of each float field (the derivative fields too), NaN aside.
VALID: dict[str, tuple[float, float]] = {
    f.name: f.valid for f in TABLE + DERIVATIVE_TABLE if f.dtype.kind == "f"
}


class Reason(enum.IntEnum):
    """Why a point is (JARM) or is not a jump after pure rolling: the ``reason`` codes of
    :class:`~eccjump.JarmResult` and :class:`~eccjump.Region` (an ``IntEnum``, codes stable).

    Written out here so that type checkers and editors see the members; the core's codes
    are checked against them at import.

    Attributes
    ----------
    JARM : 0
        Lift-off straight out of pure rolling.
    NO_ROOT : 1
        No lift-off (on the requested turn n, or ever).
    LIFTOFF_EARLIER : 2
        The lift-off rule held earlier than the requested turn n (or at the start).
    NORMAL_FORCE_LOST : 3
        F_y reached 0 before lift-off.
    SLIP_BEFORE : 4
        The rolling branch needs more than μ_s of friction before lift-off.
    SLIP_AT_JUMP : 5
        Friction fails on the final approach, and the paper's jump-point test (Eq. ineq2)
        fails at θ_J.
    ROCKS_BACK : 6
        The body stops and rolls back.
    TURN_LIMIT : 7
        Nothing happened within ``max_turns`` turns.
    INVALID_PARAMS : 8
        A parameter is NaN or out of range.
    SOLVER_FAILED : 9
        The integrator of ``method="ode"`` failed (no physical verdict).
    SLIP : 10
        Friction fails before the paper's lift-off, and the search stopped there
        (``stop_at_slip=True``): SLIP_BEFORE or SLIP_AT_JUMP, not told apart.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> r = eccjump.jarm(np.radians(30), 0.5, 0.4, mu_s=1.0)
    >>> eccjump.Reason(int(r.reason)).name
    'SLIP_BEFORE'
    >>> int(eccjump.Reason.JARM)
    0
    """

    JARM = 0
    NO_ROOT = 1
    LIFTOFF_EARLIER = 2
    NORMAL_FORCE_LOST = 3
    SLIP_BEFORE = 4
    SLIP_AT_JUMP = 5
    ROCKS_BACK = 6
    TURN_LIMIT = 7
    INVALID_PARAMS = 8
    SOLVER_FAILED = 9
    SLIP = 10


if {r.name.lower(): r.value for r in Reason} != {n: c for c, n in _core.reason_codes()}:
    raise ImportError("eccjump.Reason differs from the core's reason codes: rebuild eccjump")


def reason_table() -> str:
    """The Reason codes as ``"0: jarm, 1: no_root, ..."``."""
    return ", ".join(f"{r.value}: {r.name.lower()}" for r in Reason)


def cf_attrs(name: str) -> dict[str, Any]:
    """CF attributes of the variable of field ``name``: ``units`` and ``long_name``, and for
    ``reason`` the ``flag_values``/``flag_meanings`` of :class:`Reason`."""
    f = BY_NAME[name]
    attrs: dict[str, Any] = {"units": f.units, "long_name": f.description}
    if name == "reason":
        attrs["flag_values"] = np.array([r.value for r in Reason], dtype=f.dtype)
        attrs["flag_meanings"] = " ".join(r.name.lower() for r in Reason)
    return attrs


def map_attrs(
    mu_s: float,
    n: int | None,
    rule: str,
    method: str,
    theta0: float,
    omega0: float,
    **extra: Any,
) -> dict[str, Any]:
    """Attributes of a JARM map: how it was made (netCDF-safe scalars and strings only)."""
    return {
        "title": "JARM map of an eccentric cylinder on a ramp (eccjump)",
        "eccjump_version": _core.VERSION,
        "mu_s": float(mu_s),
        "n": 0 if n is None else int(n),
        "n_meaning": "requested turn of the jump; 0: the first jump whatever its turn",
        "rule": str(rule),
        "method": str(method),
        "theta0": float(theta0),
        "omega0": float(omega0),
        **{k: (int(v) if isinstance(v, bool) else v) for k, v in extra.items()},
        "reason_codes": reason_table(),
        "units": "g = R = M = 1: angles in rad, forces in M g, omega in sqrt(g/R) rad",
    }


#: Attributes written by :func:`map_attrs` that are not options of the map.
MAP_INFO = ("title", "eccjump_version", "n_meaning", "reason_codes", "units")


def _is_jarm_agrees(values: Mapping[str, NDArray]) -> str | None:
    """What is wrong with a JARM map's codes beyond their table: ``is_jarm`` must say whether
    ``reason`` is :attr:`Reason.JARM`."""
    is_jarm = np.asarray(values["is_jarm"], dtype=bool)
    if not np.array_equal(is_jarm, np.asarray(values["reason"]) == Reason.JARM):
        return "is_jarm contradicts reason"
    return None


#: The JARM map (:func:`eccjump.region`, ``eccjump map``) as a kind of map file.
JARM = register(
    MapKind(
        "jarm",
        FIELDS,
        DTYPES,
        FILL,
        cf_attrs,
        ("mu_s", "n", "rule", "method", "theta0", "omega0"),
        (
            ("mu_s", "mu_s"),
            ("theta0", "theta0"),
            ("omega0", "omega0"),
            ("alpha", "alpha"),
            ("chi", "chi"),
            ("km_frac", "km_frac"),
        ),
        ("alpha", "chi", "km_frac"),
        {"reason": frozenset([*(int(r) for r in Reason), FILL["reason"]])},
        computed_mark="reason",
        valid=VALID,
        invalid=("reason", frozenset([int(Reason.INVALID_PARAMS), FILL["reason"]])),
        agree=(
            ("is_jarm", "Fx_J", True),
            ("is_jarm", "Fy_J", True),
            ("is_jarm", "theta_J", False),
        ),
        validator=_is_jarm_agrees,
        title="JARM",
    )
)


def docstring() -> str:
    """The fields as the ``Attributes`` section of a numpy-style docstring."""
    fields = [
        f"{f.name} : numpy.ndarray of {f.dtype}\n    {f.description}"
        + ("" if f.units == "1" else f" [{f.units}]")
        + "."
        for f in TABLE
    ]
    fields += [
        f"{f.name} : numpy.ndarray of {f.dtype} or None\n    {f.description}"
        + ("" if f.units == "1" else f" [{f.units} per unit of the parameter, alpha in rad]")
        + (". Shape: the point's plus (3,)" if f.dtype == _F64 else ". The point's shape")
        + "; None unless made with ``derivatives=True``."
        for f in DERIVATIVE_TABLE
    ]
    return "\n".join(fields)


__all__ = [
    "BY_NAME",
    "DERIVATIVES",
    "DERIVATIVE_TABLE",
    "DTYPES",
    "FIELDS",
    "FILL",
    "JARM",
    "MAP_INFO",
    "TABLE",
    "VALID",
    "WRT",
    "WRT_ATTRS",
    "Field",
    "Reason",
    "cf_attrs",
    "docstring",
    "map_attrs",
    "reason_table",
]
