"""The explorer's controls, described once: the page builds its sliders from this table (it
asks for it as ``/api/controls``), and the server and the widget check every value against
it. Angles are in degrees here, as on the command line; :func:`to_api` turns a point into the
Python API's radians.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, NamedTuple

from eccjump._base.checks import Rule, short


class Control(NamedTuple):
    """One slider: its key (the query parameter), its label, unit, range, step and start."""

    key: str
    label: str
    #: Shown after the value; "" for a ratio.
    unit: str
    lo: float
    hi: float
    step: float
    default: float
    #: What the slider means, for the tooltip and the docs.
    help: str


#: The sliders, in the order of the page.
CONTROLS: tuple[Control, ...] = (
    Control("alpha", "ramp angle α", "°", 0.0, 90.0, 0.5, 40.0, "angle of the ramp"),
    Control("chi", "CM offset χ = d/R", "", 0.0, 1.0, 0.01, 0.15, "centre of mass off the axis"),
    Control("km", "shell mass k_m", "", 0.0, 1.0, 0.005, 0.02, "mass fraction in the shell"),
    Control("mu_s", "static friction μ_s", "", 0.0, 3.0, 0.05, 1.0, "static friction"),
    Control("mu_k", "kinetic friction μ_k", "", 0.0, 3.0, 0.05, 1.0, "kinetic friction"),
    Control("restitution", "restitution e", "", 0.0, 1.0, 0.05, 0.0, "energetic restitution"),
    Control("theta0", "start angle θ₀", "°", -180.0, 180.0, 1.0, 0.0, "angle at the start"),
    Control(
        "omega0",
        "start rate θ̇₀",
        "√(g/R)",
        0.0,
        3.0,
        0.05,
        0.0,
        "rate at the start (down the ramp)",
    ),
    Control("t_max", "duration", "√(R/g)", 2.0, 60.0, 1.0, 15.0, "length of the motion"),
)
BY_KEY: dict[str, Control] = {c.key: c for c in CONTROLS}
#: The sliders in degrees (radians in the Python API).
ANGLES = frozenset({"alpha", "theta0"})

#: The lift-off rules, as the page's select offers them.
RULES: tuple[Rule, ...] = ("paper", "normal_force")

#: The region slice's grid: points along each of χ and α (coarse enough to redraw at once).
GRID = 60
GRID_RANGE = (8, 120)


def spec() -> dict[str, Any]:
    """The table as JSON-ready data for the page."""
    return {
        "controls": [c._asdict() for c in CONTROLS],
        "rules": list(RULES),
        "grid": GRID,
    }


def checked(key: str, value: float) -> float:
    """``value`` if it lies in the slider's range, else a ValueError naming ``key`` with its
    unit and range."""
    c = BY_KEY[key]
    if not c.lo <= value <= c.hi:  # NaN fails too
        unit = "" if c.unit in ("", "°") else " "
        unit += c.unit
        raise ValueError(
            f"{key} = {short(value)}{unit} is outside the explorer's range "
            f"[{c.lo:g}, {c.hi:g}]{unit}"
        )
    return value


def rule_checked(value: str) -> Rule:
    """``value`` if it names a lift-off rule, else a ValueError naming ``rule``."""
    if value not in RULES:
        raise ValueError(f"rule = {value[:30]!r} is not one of {', '.join(RULES)}")
    return value


def body_problem(chi: float, km: float) -> str | None:
    """Why (χ, km) is no body, in words for the page, or None for a valid body."""
    if km > 1.0 - chi + 1e-12:
        return (
            f"No such body: k_m = {km:g} is above 1 − χ = {1.0 - chi:g} (the shell cannot "
            "hold more than the mass off the axis). Lower k_m or χ."
        )
    return None


def to_api(point: Mapping[str, float]) -> dict[str, float]:
    """A point in the sliders' units as the Python API takes it (angles in radians)."""
    out = dict(point)
    for key in ANGLES:
        if key in out:
            out[key] = math.radians(out[key])
    return out
