"""Figures: the paper's Fig. 3b and Fig. 4 (JARM regions), a pure-rolling trajectory, and the
full motion of :func:`eccjump.simulate` (panels and an animated GIF), a JARM classification
over its points, a design on its region slice, an uncertainty study
(:func:`eccjump.uncertainty`) and P(JARM) under tolerances over a grid
(:func:`eccjump.uncertainty_map`).

Every result's ``.plot()`` goes through :func:`draw`: ``.plot()`` is the full figure,
``.plot(fig=fig)`` the same drawn into an empty Figure or SubFigure of the caller's, and
``.plot(ax=ax)`` the result's main panel drawn into the caller's Axes (returned), so that
plots compose into one figure. The ``*_panel`` functions draw those panels, the others
return a :class:`matplotlib.figure.Figure` (:func:`animate_motion` writes a GIF instead;
matplotlib is imported only when a function is called: ``pip install eccjump[plot]``). The
modes have one palette everywhere (:data:`MODE_COLORS`, colour-blind safe).
Angles are shown in degrees; units are g = R = M = 1 (forces in M g, rates in √(g/R), times
in √(R/g)).

The Fig. 4 regions are drawn from their exact boundary surfaces alpha_lo(χ, k_m) and
alpha_hi(χ, k_m) (:func:`eccjump.alpha_intervals`, bisection to 1e-12), not from a
thresholded grid, so thin regions keep their true thickness in α.
"""

from eccjump._base.palette import MODE_COLORS
from eccjump.plot._common import TURN_COLORS
from eccjump.plot.compose import draw
from eccjump.plot.designs import design_panel, design_slice
from eccjump.plot.full_motion import MAX_FRAMES, animate_motion, motion, motion_panel
from eccjump.plot.maps import (
    fraction_map,
    fraction_panel,
    probability_map,
    region_map,
    region_panel,
    sequence_map,
    sequence_panel,
)
from eccjump.plot.paper import (
    MAX_RESOLUTION,
    MAX_SLICE_RESOLUTION,
    JarmSurfaces,
    fig3b,
    fig4,
    fig4_slices,
    jarm_surfaces,
)
from eccjump.plot.points import jarm_panel, jarm_points
from eccjump.plot.trajectories import roll_panel, trajectory
from eccjump.plot.uncertainty_study import outcomes_panel, uncertainty

__all__ = [
    "MAX_FRAMES",
    "MAX_RESOLUTION",
    "MAX_SLICE_RESOLUTION",
    "MODE_COLORS",
    "TURN_COLORS",
    "JarmSurfaces",
    "animate_motion",
    "design_panel",
    "design_slice",
    "draw",
    "fig3b",
    "fig4",
    "fig4_slices",
    "fraction_map",
    "fraction_panel",
    "jarm_panel",
    "jarm_points",
    "jarm_surfaces",
    "motion",
    "motion_panel",
    "outcomes_panel",
    "probability_map",
    "region_map",
    "region_panel",
    "roll_panel",
    "sequence_map",
    "sequence_panel",
    "trajectory",
    "uncertainty",
]
