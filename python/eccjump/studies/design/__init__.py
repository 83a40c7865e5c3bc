"""Experiment design: the body and ramp angle whose JARM (or, for a control run, whose slip
before lift-off) is most robust, with a printable lab sheet (the user guide's "Experiment
design" page).

The design space is the ramp angle α, the shell mass fraction k_m and the rod position
ρ = r/R of the paper's body (a thin uniform shell plus a rod parallel to the axis): the rod
of mass (1 - k_m) M at distance r from the axis puts the centre of mass at d = (1 - k_m) r,
so χ = ρ (1 - k_m), and I_C = k_m M R² + (1 - k_m) M r², i.e. Ic = k_m + chi²/(1 - k_m).
Every (k_m, ρ) in [0, 1) x [0, 1] is a valid body.

A verdict must hold under both lift-off rules (the rule is a modelling uncertainty) and for
every μ_s in [μ_s - mu_s_err, μ_s + mu_s_err]; JARM and slip-first are both monotone in
μ_s, so the worst case is one end of that interval (the lower one for a JARM, the upper one
for a slip). The margins, all at that worst case, are distances to the exact boundary of the
verdict's region: in α (the JARM α-interval around the design, ends to 1e-12), in
μ_s (beyond the uncertainty) and in ρ (at fixed masses). The design maximises the
smallest RELATIVE margin -- the smallest fractional error of one input that can change the
verdict -- found on a coarse grid, then refined by a deterministic compass search.
"""

from eccjump.studies.design._common import GRID_RANGE, RULES, Target
from eccjump.studies.design.physical import Build, build
from eccjump.studies.design.results import Design, Flight, Margin, Sensitivity
from eccjump.studies.design.search import design

__all__ = [
    "GRID_RANGE",
    "RULES",
    "Build",
    "Design",
    "Flight",
    "Margin",
    "Sensitivity",
    "Target",
    "build",
    "design",
]
