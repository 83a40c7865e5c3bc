"""Names shared by the modules of :mod:`eccjump.design`."""

from __future__ import annotations

import math
from typing import Literal

from eccjump._base.checks import Rule
from eccjump.classification.fields import Reason

Target = Literal["jarm", "slip"]
#: The lift-off rules a verdict must hold under.
RULES: tuple[Rule, ...] = ("paper", "normal_force")
_SLIPS = (int(Reason.SLIP_BEFORE), int(Reason.SLIP_AT_JUMP), int(Reason.SLIP))
_HALF_PI = math.pi / 2
#: Bounds of the work: grid points per axis, compass-search evaluations per candidate.
GRID_RANGE = (4, 64)
_MAX_EVALS = 40
_CANDIDATES = 12
_REFINED = 2
_SCAN = 100  # samples per side in the outward scan for a boundary
_MU_CAP = 1e6  # mu_s_min_path's own cap
