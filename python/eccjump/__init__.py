"""eccjump: when does an eccentric cylinder rolling down a ramp jump, and does it slip first?

A fast Rust core (Dormand–Prince integrator with exact events, the paper's closed forms)
behind a typed Python API. Units: g = R = M = 1 unless converted with :class:`Units`;
angles in radians.
"""

import sys
from typing import TYPE_CHECKING

from eccjump import _compat, maps
from eccjump._base.body import Cylinder
from eccjump._base.units import Units
from eccjump._core import VERSION as __version__
from eccjump.classification import closed_form
from eccjump.classification.boundary import alpha_interval_around, alpha_intervals, mu_s_min_path
from eccjump.classification.classify import JarmResult, Reason, Region, jarm, region
from eccjump.classification.dataset import region_dataset
from eccjump.classification.starts import (
    OptimalStart,
    StartMap,
    jarm_fraction,
    optimal_start,
    reason_shares,
    start_map,
)
from eccjump.explorer import explore
from eccjump.maps import Map, store
from eccjump.maps import load as load_map
from eccjump.maps.results import load
from eccjump.motion.dense import DenseSolution
from eccjump.motion.maps import MotionMap, motion_map
from eccjump.motion.points import MotionPoints, motion_points
from eccjump.motion.roll import EVENT_NAMES, Event, RollResult, roll
from eccjump.motion.simulation import SENSITIVITY_PARAMETERS, MotionResult, simulate
from eccjump.studies.design import Design, build, design
from eccjump.studies.experiment import Analysis, analyze
from eccjump.studies.experiment.video import VideoTrack, track
from eccjump.studies.uncertainty import Uncertainty, uncertainty
from eccjump.studies.uncertainty.map import (
    UncertaintyDeltaMap,
    UncertaintyMap,
    UncertaintyMotionMap,
    uncertainty_map,
)

__all__ = [
    "EVENT_NAMES",
    "SENSITIVITY_PARAMETERS",
    "Analysis",
    "Cylinder",
    "DenseSolution",
    "Design",
    "Event",
    "JarmResult",
    "Map",
    "MotionMap",
    "MotionPoints",
    "MotionResult",
    "OptimalStart",
    "Reason",
    "Region",
    "RollResult",
    "StartMap",
    "Uncertainty",
    "UncertaintyDeltaMap",
    "UncertaintyMap",
    "UncertaintyMotionMap",
    "Units",
    "VideoTrack",
    "__version__",
    "alpha_interval_around",
    "alpha_intervals",
    "analyze",
    "build",
    "closed_form",
    "design",
    "explore",
    "jarm",
    "jarm_fraction",
    "load",
    "load_map",
    "maps",
    "motion_map",
    "motion_points",
    "mu_s_min_path",
    "optimal_start",
    "reason_shares",
    "region",
    "region_dataset",
    "roll",
    "simulate",
    "start_map",
    "store",
    "track",
    "uncertainty",
    "uncertainty_map",
]

# The module paths before the layers (eccjump.rolling, eccjump.store, ...) for one release.
_compat.install(sys.modules[__name__])
if not TYPE_CHECKING:  # (a module __getattr__ would let mypy pass any eccjump.<typo>)

    def __getattr__(name: str):
        return _compat.old_attribute(name)
