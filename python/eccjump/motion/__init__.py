"""The motion: rolling (``roll``), the full motion (:func:`simulate`, in ``simulation``), its
dense output, its fields, and motion points and maps. Its public names are those of
``eccjump.motion.simulation`` (the former ``eccjump.motion`` module), re-exported here."""

from eccjump.motion.simulation import (
    MAX_STEPS,
    MAX_TRANSITIONS,
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
    checked_motion_options,
    motion_options,
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
    "MotionResult",
    "MotionSolution",
    "Segment",
    "Transition",
    "checked_motion_options",
    "motion_options",
    "simulate",
]
