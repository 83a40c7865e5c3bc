"""The one palette of the modes, shared by the figures (``eccjump.plot``), the notebook views
(:mod:`eccjump._base.html`) and the explorer (its script receives these colours from the
server with the sliders, ``explorer.api.controls_spec``): a mode has one colour everywhere.

The colours are Okabe and Ito's, told apart with every common colour-vision deficiency:
ROLL bluish green, SLIP orange, FLIGHT sky blue (the hues the figures had, made safe:
bluish green and a darker blue would merge for tritanopes)."""

from __future__ import annotations

#: The colour of each mode, in every picture of a motion.
MODE_COLORS = {"ROLL": "#009E73", "SLIP": "#E69F00", "FLIGHT": "#56B4E9"}
#: JARM (a jump straight out of rolling: the ROLL colour) and not JARM, in map slices.
JARM_COLOR, OTHER_COLOR = MODE_COLORS["ROLL"], "#e8e8e8"

__all__ = ["JARM_COLOR", "MODE_COLORS", "OTHER_COLOR"]
