"""Figures: the paper's Fig. 3b and Fig. 4 (JARM regions), a pure-rolling trajectory, and the
full motion of :func:`eccjump.simulate` (panels and an animated GIF), an uncertainty study
(:func:`eccjump.uncertainty`) and P(JARM) under tolerances over a grid
(:func:`eccjump.uncertainty_map`).

Every function returns a :class:`matplotlib.figure.Figure` (:func:`animate_motion` writes a GIF
instead; matplotlib is imported only when a function is called: ``pip install eccjump[plot]``).
Angles are shown in degrees; units are g = R = M = 1 (forces in M g, rates in sqrt(g/R), times
in sqrt(R/g)).

The Fig. 4 regions are drawn from their exact boundary surfaces alpha_lo(chi, k_m) and
alpha_hi(chi, k_m) (:func:`eccjump.alpha_intervals`, bisection to 1e-12), not from a
thresholded grid, so thin regions keep their true thickness in alpha.
"""

from eccjump.plot._common import TURN_COLORS
from eccjump.plot.full_motion import MAX_FRAMES, MODE_COLORS, animate_motion, motion
from eccjump.plot.maps import fraction_map, probability_map, region_map, sequence_map
from eccjump.plot.paper import (
    MAX_RESOLUTION,
    MAX_SLICE_RESOLUTION,
    JarmSurfaces,
    fig3b,
    fig4,
    fig4_slices,
    jarm_surfaces,
)
from eccjump.plot.trajectories import trajectory
from eccjump.plot.uncertainty_study import uncertainty

__all__ = [
    "MAX_FRAMES",
    "MAX_RESOLUTION",
    "MAX_SLICE_RESOLUTION",
    "MODE_COLORS",
    "TURN_COLORS",
    "JarmSurfaces",
    "animate_motion",
    "fig3b",
    "fig4",
    "fig4_slices",
    "fraction_map",
    "jarm_surfaces",
    "motion",
    "probability_map",
    "region_map",
    "sequence_map",
    "trajectory",
    "uncertainty",
]
