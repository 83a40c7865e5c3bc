"""Units: the core works in g = R = M = 1; :class:`Units` converts to SI.

The equations of motion are invariant under scaling (paper, Sec. 2.4): with the same chi and
km, angles are unchanged, lengths scale with R, times with sqrt(R/g), angular velocities with
sqrt(g/R), angular accelerations with g/R, and forces with M g.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from eccjump._checks import real


@dataclass(frozen=True, slots=True)
class Units:
    """Physical scales: gravity ``g`` [m/s²], radius ``R`` [m], mass ``M`` [kg]."""

    g: float = 9.81
    R: float = 1.0
    M: float = 1.0

    def __post_init__(self) -> None:
        for name in ("g", "R", "M"):
            value = real(name, getattr(self, name))
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} = {value:g} is outside the allowed range (0, inf)")
            object.__setattr__(self, name, value)
        derived = (
            ("time sqrt(R/g)", "g, R", lambda: math.sqrt(self.R / self.g)),
            ("rate sqrt(g/R)", "g, R", lambda: 1.0 / math.sqrt(self.R / self.g)),
            ("acceleration g/R", "g, R", lambda: self.g / self.R),
            ("force M g", "M, g", lambda: self.M * self.g),
        )
        for what, names, scale in derived:
            try:
                value = scale()
            except (ZeroDivisionError, OverflowError):
                value = math.inf
            if not (math.isfinite(value) and value > 0):
                given = ", ".join(f"{n} = {getattr(self, n):g}" for n in names.split(", "))
                raise ValueError(
                    f"{given}: the {what} scale is {value:g}; it must be finite and non-zero"
                )

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
