"""The body in physical terms: the paper's shell plus a rod, built to a radius and a mass."""

from __future__ import annotations

import math
from typing import NamedTuple

from eccjump._base.body import Cylinder
from eccjump._base.checks import real, short
from eccjump._base.docs import fill


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


@fill
def build(body: Cylinder, *, radius: float = 1.0, mass: float = 1.0) -> Build:
    """``body`` built as the paper's shell plus rod, of radius ``radius`` and mass ``mass``.

    The inverse of :meth:`Cylinder.from_shell_and_line` and :meth:`Cylinder.from_inertia`:
    a thin uniform shell of mass k_m M plus a rod of mass (1 - k_m) M at distance
    r = d/(1 - k_m) from the axis.

    Parameters
    ----------
    %(body)s
    radius : float, default 1.0
        R, finite and > 0, in units of your choice (e.g. m).
    mass : float, default 1.0
        M, finite and > 0, in units of your choice (e.g. kg).

    Returns
    -------
    Build
        ``radius``, ``mass``, ``shell_mass``, ``rod_mass``, ``rod_position`` (r, from the
        axis), ``d`` (the centre of mass from the axis) and ``I_C`` (about the axis, in mass
        x length²).

    Raises
    ------
    ValueError
        If ``radius`` or ``mass`` is not finite and > 0.
    TypeError
        If ``body`` is not a Cylinder.

    Examples
    --------
    >>> import eccjump
    >>> b = eccjump.build(eccjump.Cylinder(chi=0.15, km=0.02), radius=0.05, mass=0.5)
    >>> print(f"shell {b.shell_mass:.3f} kg, rod {b.rod_mass:.3f} kg at {b.rod_position:.6f} m")
    shell 0.010 kg, rod 0.490 kg at 0.007653 m
    """
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
