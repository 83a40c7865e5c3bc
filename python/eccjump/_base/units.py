"""Units: the core works in g = R = M = 1; :class:`Units` converts to SI.

The equations of motion are invariant under scaling (paper, Sec. 2.4): with the same χ and
km, angles are unchanged, lengths scale with R, times with √(R/g), angular velocities with
√(g/R), angular accelerations with g/R, speeds with √(g R), forces with M g and
energies with M g R.

Each of g, R and M lies in :data:`SCALE_RANGE`, [1e-50, 1e50] (SI units), which holds every
physical body and planet with room to spare. The bound is what keeps the derived units
exact: a product of three scales lies in [1e-150, 1e150], far from float64's overflow
(1.8e308) and its subnormals (below 2.2e-308), so a result in SI units is neither inf nor
flushed to 0 where the dimensionless one is a normal number below 1e150.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from eccjump._base.checks import real
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
