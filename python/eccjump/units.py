"""Units: the core works in g = R = M = 1; :class:`Units` converts to SI.

The equations of motion are invariant under scaling (paper, Sec. 2.4): with the same chi and
km, angles are unchanged, lengths scale with R, times with sqrt(R/g), angular velocities with
sqrt(g/R), angular accelerations with g/R, speeds with sqrt(g R), forces with M g and
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

from eccjump._checks import real

#: The allowed range of each of g [m/s²], R [m] and M [kg].
SCALE_RANGE = (1e-50, 1e50)
_UNITS = {"g": "m/s^2", "R": "m", "M": "kg"}


@dataclass(frozen=True, slots=True)
class Units:
    """Physical scales: gravity ``g`` [m/s²], radius ``R`` [m], mass ``M`` [kg], each in
    :data:`SCALE_RANGE` (a ValueError naming the scale outside it)."""

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
        """Seconds per dimensionless time unit, sqrt(R/g)."""
        return math.sqrt(self.R / self.g)

    @property
    def length(self) -> float:
        """Metres per dimensionless length unit, R."""
        return self.R

    @property
    def rate(self) -> float:
        """rad/s per dimensionless angular velocity, sqrt(g/R)."""
        return 1.0 / self.time

    @property
    def acceleration(self) -> float:
        """rad/s² per dimensionless angular acceleration, g/R."""
        return self.g / self.R

    @property
    def force(self) -> float:
        """Newtons per dimensionless force, M g."""
        return self.M * self.g
