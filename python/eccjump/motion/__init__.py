"""The motion: rolling (``roll``), the full motion (:func:`simulate`, in ``simulation``), its
options (:class:`MotionOptions`, in ``options``), its dense output, its fields, and motion
points and maps. Its public names are those of ``eccjump.motion.simulation`` (the former
``eccjump.motion`` module) and ``eccjump.motion.options``, re-exported here."""

from eccjump.motion.options import MAX_STEPS, MAX_TRANSITIONS, MotionOptions
from eccjump.motion.simulation import (
    MODES,
    REASONS,
    SENSITIVITY_PARAMETERS,
    STATUSES,
    FlightRecord,
    ImpactRecord,
    MotionResult,
    MotionSolution,
    Segment,
    Transition,
    simulate,
)

__all__ = [
    "MAX_STEPS",
    "MAX_TRANSITIONS",
    "MODES",
    "REASONS",
    "SENSITIVITY_PARAMETERS",
    "STATUSES",
    "FlightRecord",
    "ImpactRecord",
    "MotionOptions",
    "MotionResult",
    "MotionSolution",
    "Segment",
    "Transition",
    "simulate",
]
