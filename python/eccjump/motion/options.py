"""How each run of the full motion goes: :class:`MotionOptions`, the one list of the options
that every entry point of the full motion shares, with its checks."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from eccjump import _core
from eccjump._base.checks import Integrator, Rule, integer, real, rule_name, text

#: The core's bounds on the work of a run, checked here first so that the error states the
#: true range.
MAX_TRANSITIONS: int = _core.MAX_TRANSITIONS
MAX_STEPS: int = _core.MAX_STEPS


@dataclass(frozen=True)
class MotionOptions:
    """The options of every run of the full motion, named and defaulted as in
    :func:`eccjump.simulate`: the lift-off rule, the end of a run and the integrator.

    :func:`eccjump.simulate`, :func:`eccjump.motion_map`, :func:`eccjump.motion_points`,
    :func:`eccjump.uncertainty`, :func:`eccjump.studies.experiment.synthetic_track` and
    :func:`eccjump.explore` take these as keywords and carry them as one ``MotionOptions``.
    The point's own values (``mu_k``, ``restitution``, ``theta0``, ``omega0``, beside
    ``alpha``, the body and ``mu_s``) are not options: one number in ``simulate``, an axis of
    a map, a column of ``motion_points``, a distribution in ``uncertainty``.

    The types are checked when it is made: a TypeError names the keyword, as the entry point
    names it. The ranges are the core's (``SimOptions::validate``): :meth:`to_core` checks
    them, and ``simulate`` with the point's values.

    Attributes
    ----------
    rule : {"paper", "normal_force"}, default "paper"
        Lift-off rule from rolling.
    t_max : float, default 100.0
        End time of a run [√(R/g)], in (0, 1e6].
    max_transitions : int, default 100
        Transitions of a run after the start, 1 ... 10**6.
    rtol : float, default 1e-10
        Relative tolerance of the integrator, in [1e-15, 1e-6].
    atol : float, default 1e-12
        Absolute tolerance of the integrator, in [1e-300, 1e-6].
    max_steps : int, default 1_000_000
        Accepted steps of a run, 1 ... 10**7.
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair.

    Examples
    --------
    >>> from eccjump.motion.options import MotionOptions
    >>> MotionOptions(t_max=20.0).keywords()["t_max"]
    20.0
    >>> MotionOptions(max_steps=0)
    Traceback (most recent call last):
    ValueError: max_steps = 0 is outside the allowed range [1, 10000000]
    """

    rule: Rule = "paper"
    t_max: float = 100.0
    max_transitions: int = 100
    rtol: float = 1e-10
    atol: float = 1e-12
    max_steps: int = 1_000_000
    integrator: Integrator = "RK45"

    def __post_init__(self) -> None:
        """The type checks, in the order of the fields (of several bad keywords the first is
        named), each value made the plain Python type the bridge takes."""
        self.__dict__.update(  # frozen: not through its __setattr__
            rule=rule_name(self.rule),
            t_max=real("t_max", self.t_max),
            max_transitions=integer("max_transitions", self.max_transitions, 1, MAX_TRANSITIONS),
            rtol=real("rtol", self.rtol),
            atol=real("atol", self.atol),
            max_steps=integer("max_steps", self.max_steps, 1, MAX_STEPS),
            integrator=text("integrator", self.integrator),
        )

    def keywords(self) -> dict[str, Any]:
        """The options by name: the keywords of :func:`eccjump.simulate` (and of every entry
        point above), and the attributes a motion map records."""
        return dict(self.__dict__)  # the fields, in their order (no other attribute)

    def to_core(self, n_threads: object = 0) -> _core.MotionMapOptions:
        """The options as the core's maps take them, with ``n_threads`` (0 ... 256), their
        ranges checked by the core before any work (a call on no points): a ValueError
        naming the first bad one, as ``simulate`` names it."""
        threads = integer("n_threads", n_threads, 0, 256)
        opts = _core.MotionMapOptions(**self.keywords(), n_threads=threads)
        none = np.empty(0)
        _core.motion_points(none, none, none, none, none, none, none, none, options=opts)
        return opts


__all__ = ["MAX_STEPS", "MAX_TRANSITIONS", "MotionOptions"]
