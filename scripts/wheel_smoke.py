"""What `scripts/check_wheel.sh` runs with an installed eccjump (never the checkout's): the
package comes from the environment that runs it, rolls the README's JARM body to its lift-off,
and the ODE route -- whose 8-lane integrator takes AVX2 only where the CPU reports it -- agrees
with the closed form on a small grid. Exits non-zero, naming what failed, otherwise."""

from __future__ import annotations

import math
import sys

import numpy as np

import eccjump

# The README's worked example: alpha = 40 deg, chi = 0.15, km = 0.02, mu_s = 1.
README_THETA_J_DEG = 334.3438379
# Both routes locate theta_J to ~1e-9 rad (rtol 1e-10); far below this, far above a wrong path.
THETA_J_AGREE = 1e-7


def check_installed() -> None:
    if not eccjump.__file__ or not eccjump.__file__.startswith(sys.prefix):
        sys.exit(f"eccjump imported from {eccjump.__file__}, not from {sys.prefix}")


def check_roll() -> None:
    res = eccjump.roll(eccjump.Cylinder(chi=0.15, km=0.02), math.radians(40), mu_s=1.0)
    theta_deg = math.degrees(res.theta[-1])
    if res.terminal_event != "liftoff" or abs(theta_deg - README_THETA_J_DEG) > 1e-6:
        sys.exit(f"roll: {res.terminal_event} at {theta_deg} deg, want liftoff at 334.3438379")


def check_lanes() -> None:
    grid = dict(
        alpha=np.radians(np.linspace(20, 60, 9)),
        chi=[0.15, 0.3, 0.5],
        km_frac=[0.02, 0.3, 0.8],
        mu_s=1.0,
    )
    exact = eccjump.region(**grid).result
    ode = eccjump.region(**grid, method="ode").result
    if not np.array_equal(exact.reason, ode.reason) or not exact.is_jarm.any():
        sys.exit("region: the ODE route's reasons differ from the closed form's")
    gap = np.nanmax(np.abs(exact.theta_J - ode.theta_J))
    if not gap <= THETA_J_AGREE:
        sys.exit(f"region: theta_J of the two routes differs by {gap} rad")


def main() -> None:
    check_installed()
    check_roll()
    check_lanes()
    print(f"eccjump {eccjump.__version__} from {eccjump.__file__}: roll and region agree")


if __name__ == "__main__":
    main()
