"""Units: the core works in g = R = M = 1; :class:`Units` converts to SI.

The equations of motion are invariant under scaling (paper, Sec. 2.4): with the same χ and
km, angles are unchanged, lengths scale with R, times with √(R/g), angular velocities with
√(g/R), angular accelerations with g/R, speeds with √(g R), forces with M g and
energies with M g R.

Angles are in radians everywhere in the Python API (degrees on the command line). A ramp
angle lies in [0, π/2]; :func:`ramp_angle` and :func:`ramp_angles` are the one guard of
every entry point that takes one, so that a value in degrees is never silent: a scalar out
of the range is a ValueError that says radians and ``math.radians``, and an array (where a
point out of the range is an invalid point, not an error) with values that look like degrees
gives one :class:`AngleUnitWarning` per call.

Each of g, R and M lies in :data:`SCALE_RANGE`, [1e-50, 1e50] (SI units), which holds every
physical body and planet with room to spare. The bound is what keeps the derived units
exact: a product of three scales lies in [1e-150, 1e150], far from float64's overflow
(1.8e308) and its subnormals (below 2.2e-308), so a result in SI units is neither inf nor
flushed to 0 where the dimensionless one is a normal number below 1e150.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import real, real_array, short, stacklevel_outside
from eccjump._base.docs import fill

#: The allowed range of each of g [m/s²], R [m] and M [kg].
SCALE_RANGE = (1e-50, 1e50)
_UNITS = {"g": "m/s^2", "R": "m", "M": "kg"}


@fill
@dataclass(frozen=True, slots=True)
class Units:
    """Physical scales that convert a dimensionless result to SI units.

    The core works in g = R = M = 1; ``result.to_si(units)`` multiplies times by
    :attr:`time`, lengths by :attr:`length`, angular velocities by :attr:`rate`, angular
    accelerations by :attr:`acceleration` and forces by :attr:`force` (angles are unchanged).

    Parameters
    ----------
    %(g)s
    R : float, default 1.0
        Radius of the cylinder [m], in [1e-50, 1e50].
    M : float, default 1.0
        Mass of the cylinder [kg], in [1e-50, 1e50].

    Raises
    ------
    ValueError
        If a scale is NaN or outside [1e-50, 1e50] (the message names it and its unit).
    TypeError
        If a scale is not a real number.

    Examples
    --------
    >>> import eccjump
    >>> u = eccjump.Units(g=9.81, R=0.2, M=1.5)
    >>> print(f"{u.time:.6f} s, {u.rate:.4f} rad/s, {u.force:.3f} N")
    0.142784 s, 7.0036 rad/s, 14.715 N
    """

    g: float = 9.81
    R: float = 1.0
    M: float = 1.0

    def __post_init__(self) -> None:
        lo, hi = SCALE_RANGE
        for name, unit in _UNITS.items():
            value = real(name, getattr(self, name))
            if not lo <= value <= hi:  # NaN too
                raise ValueError(
                    f"{name} = {value:g} {unit} is outside the allowed range [{lo:g}, {hi:g}]"
                )
            object.__setattr__(self, name, value)

    @property
    def time(self) -> float:
        """Seconds per dimensionless time unit, √(R/g)."""
        return math.sqrt(self.R / self.g)

    @property
    def length(self) -> float:
        """Metres per dimensionless length unit, R."""
        return self.R

    @property
    def rate(self) -> float:
        """rad/s per dimensionless angular velocity, √(g/R)."""
        return 1.0 / self.time

    @property
    def acceleration(self) -> float:
        """rad/s² per dimensionless angular acceleration, g/R."""
        return self.g / self.R

    @property
    def force(self) -> float:
        """Newtons per dimensionless force, M g."""
        return self.M * self.g


#: The allowed range of a ramp angle [rad], as the core checks it, and how to say it.
RAMP_RANGE = (0.0, math.pi / 2)
FOR_DEGREES = "math.radians(deg) for degrees"
RAMP_ALLOWED = f"[0, pi/2] rad ({FOR_DEGREES})"
#: The largest ramp angle in degrees: a value in (pi/2, DEGREES_MAX] looks like degrees.
DEGREES_MAX = 90.0


class AngleUnitWarning(UserWarning):
    """Angles that look like degrees where the API takes radians (:func:`ramp_angles`)."""


def ramp_error(name: str, value: object) -> ValueError:
    """The error of a ramp angle out of its range, naming radians and ``math.radians``."""
    return ValueError(f"{name} = {short(value)} is outside the allowed range {RAMP_ALLOWED}")


def ramp_angle(name: str, value: object) -> float:
    """A scalar ramp angle [rad] in [0, π/2] as a float; ValueError (:func:`ramp_error`)
    outside it, NaN included: a ramp of 40 is 40 degrees meant, not 40 rad."""
    x = real(name, value)
    if not RAMP_RANGE[0] <= x <= RAMP_RANGE[1]:
        raise ramp_error(name, x)
    return x


def ramp_angles(name: str, value: object) -> NDArray[np.float64]:
    """Ramp angles [rad] given as a number or an array, as a float64 array of their shape:
    a scalar as :func:`ramp_angle`; an array as it is (a value out of the range makes its
    point invalid), with one :class:`AngleUnitWarning` when some values lie in
    (π/2, 90]: outside the range in radians, inside it in degrees."""
    a = real_array(name, value)
    if a.ndim == 0:
        ramp_angle(name, a)
        return a
    with np.errstate(invalid="ignore"):
        looks = int(np.count_nonzero((a > RAMP_RANGE[1]) & (a <= DEGREES_MAX)))
    if looks:
        warnings.warn(
            f"{name} holds {looks} value(s) in (pi/2, 90]: radians are due, in [0, pi/2] "
            f"(math.radians or np.radians for degrees); those points are invalid",
            AngleUnitWarning,
            stacklevel=stacklevel_outside(),
        )
    return a
