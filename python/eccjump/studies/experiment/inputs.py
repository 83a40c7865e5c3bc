"""The ranges of what ``eccjump.analyze`` takes: one table (:data:`BOUNDS`), checked by
:func:`in_range` in Python and by the parser of ``eccjump analyze`` (with its option names
and degrees), and the bounds on a track and its marker (the site's page "Limits").

Why these ranges: they hold every lab experiment (a body from a tenth of a millimetre to ten
metres, filmed at up to ten million frames per second) and keep the model's own inputs --
the duration in units of √(R/g), the start angle, squares of the noise -- finite and
inside the core's bounds, so that no message ever names a quantity the user did not give.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from eccjump._base.checks import optional_real, real, short
from eccjump._base.units import FOR_DEGREES


@dataclass(frozen=True)
class Bound:
    """[lo, hi] in ``unit`` (radians for an angle, which the command line takes in degrees),
    its option on the command line, and a hint for the message."""

    lo: float
    hi: float
    unit: str
    option: str
    hint: str = ""

    @property
    def degrees(self) -> bool:
        return self.unit == "rad"


#: The range of every real parameter of analyze that does not depend on another (chi and km:
#: ``Cylinder``; marker_radius: :data:`MARKER_IN_R`).
BOUNDS = {
    "radius": Bound(1e-4, 10.0, "m", "--radius"),
    "scale": Bound(1.0, 1e9, "px/m", "--scale"),
    "g": Bound(0.01, 100.0, "m/s^2", "--g"),
    "alpha": Bound(0.0, math.pi / 2, "rad", "--alpha", f" ({FOR_DEGREES})"),
    "marker_angle": Bound(-2 * math.pi, 2 * math.pi, "rad", "--marker-angle", f" ({FOR_DEGREES})"),
    # a friction measured apart from the track (friction.py): a coefficient, and its
    # standard deviation (zero would be a certainty no measurement has)
    "mu_s": Bound(1e-3, 10.0, "", "--mu-s"),
    "mu_s_err": Bound(1e-4, 10.0, "", "--mu-s-err"),
}
#: The marker's distance from the axle, given (marker_radius) or tracked, in units of R: a
#: point of the body, and not so close to the axle that theta drowns in the noise.
MARKER_IN_R = (1e-3, 2.0)
#: The largest coordinate of a track [m] (after ``scale``): a lab, not a planet.
MAX_POSITION = 1e6
#: The longest track [s] and the shortest median frame interval [s] (10 million fps). A
#: track's duration in sqrt(R/g) then stays below the model's bound on t_max (10^6).
MAX_SECONDS = 1e3
MIN_FRAME_INTERVAL = 1e-7


def in_range(name: str, value: object, given: str = "") -> float:
    """``value`` as a float within BOUNDS[name]; ValueError naming ``name``, its unit and the
    range (``given`` says where a value came from, e.g. " (from design)")."""
    b = BOUNDS[name]
    v = real(name, value)
    if not b.lo <= v <= b.hi:  # NaN too
        unit = f" {b.unit}" if b.unit else ""
        raise ValueError(
            f"{name} = {short(v)}{unit}{given} is outside the allowed range "
            f"[{b.lo:.6g}, {b.hi:.6g}]{unit}{b.hint if not given else ''}"
        )
    return v


def between(name: str, value: object, lo: float, hi: float, unit: str) -> float:
    """``value`` as a float in [lo, hi] ``unit``: a range that is not :data:`BOUNDS`' (a
    camera's, a synthetic track's); ValueError naming ``name``, its unit and the range."""
    v = real(name, value)
    if not lo <= v <= hi:  # NaN too
        raise ValueError(f"{name} = {short(v)} {unit} is outside [{lo:g}, {hi:g}] {unit}")
    return v


def marker_radius_in_range(value: object, radius: float) -> float | None:
    """marker_radius [m] within :data:`MARKER_IN_R` times R, or None."""
    r = optional_real("marker_radius", value)
    lo, hi = MARKER_IN_R
    if r is not None and not lo * radius <= r <= hi * radius:
        raise ValueError(
            f"marker_radius = {short(r)} m is outside the allowed range [R/{1 / lo:g}, "
            f"{hi:g} R] = [{lo * radius:.4g}, {hi * radius:.4g}] m"
        )
    return r


def cli_range(name: str) -> tuple[float, float, str]:
    """(lo, hi, unit) of BOUNDS[name] on the command line (angles in degrees)."""
    b = BOUNDS[name]
    if b.degrees:
        return math.degrees(b.lo), math.degrees(b.hi), "deg"
    return b.lo, b.hi, b.unit
