"""The body in physical terms: the paper's shell plus a rod, built to a radius and a mass."""

from __future__ import annotations

import math
from typing import NamedTuple

from eccjump._checks import real, short
from eccjump.body import Cylinder


class Build(NamedTuple):
    """A body of the paper's model in physical terms: a thin shell of mass ``shell_mass`` and
    radius ``radius`` plus a rod of mass ``rod_mass`` at distance ``rod_position`` from the
    axis; total ``mass``, CM offset ``d`` and moment of inertia ``I_C`` about the axis."""

    radius: float
    mass: float
    shell_mass: float
    rod_mass: float
    rod_position: float
    d: float
    I_C: float


def build(body: Cylinder, *, radius: float = 1.0, mass: float = 1.0) -> Build:
    """``body`` built as the paper's shell plus rod, of radius ``radius`` and mass ``mass``
    (both finite and > 0; units of your choice, e.g. m and kg). The inverse of
    :meth:`Cylinder.from_shell_and_line` and :meth:`Cylinder.from_inertia`."""
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    R, M = _positive("radius", radius), _positive("mass", mass)
    km, chi = body.km, body.chi
    rho = 0.0 if km >= 1.0 else min(chi / (1.0 - km), 1.0)
    return Build(
        radius=R,
        mass=M,
        shell_mass=km * M,
        rod_mass=(1.0 - km) * M,
        rod_position=rho * R,
        d=chi * R,
        I_C=body.Ic * M * R * R,
    )


def _positive(name: str, value: object) -> float:
    v = real(name, value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} = {short(v)} is outside the allowed range (0, inf)")
    if not math.isfinite(v * v * v) or v * v * v == 0.0:  # R^2 M stays a normal number
        raise ValueError(f"{name} = {short(v)} is outside the allowed range [1e-100, 1e100]")
    return v
