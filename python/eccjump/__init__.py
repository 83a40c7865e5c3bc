"""eccjump: when does an eccentric cylinder rolling down a ramp jump, and does it slip first?

A fast Rust core (Dormand–Prince integrator with exact events, the paper's closed forms)
behind a typed Python API. Units: g = R = M = 1 unless converted with :class:`Units`;
angles in radians.
"""

from eccjump._core import VERSION as __version__
from eccjump.body import Cylinder
from eccjump.dense import DenseSolution
from eccjump.rolling import EVENT_NAMES, Event, RollResult, roll
from eccjump.units import Units

__all__ = [
    "EVENT_NAMES",
    "Cylinder",
    "DenseSolution",
    "Event",
    "RollResult",
    "Units",
    "__version__",
    "roll",
]
