"""Argument types shared by the subcommands: each checks its range and says it in the units
of the command line."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import get_args

from eccjump._bridge import Integrator

#: The choices of ``--integrator`` (the Runge-Kutta pairs).
INTEGRATORS: tuple[str, ...] = get_args(Integrator)


def add_integrator(p: argparse._ActionsContainer, when: str = "") -> None:
    """``--integrator {RK45,DOP853,Vern7,Vern9}`` (default RK45); ``when`` says where it
    applies."""
    p.add_argument(
        "--integrator",
        choices=INTEGRATORS,
        default="RK45",
        help=f"Runge-Kutta pair{when}: RK45 (Dormand-Prince 5(4), default), DOP853 (8(5,3)), "
        "Vern7 (Verner 7(6)) or Vern9 (Verner 9(8))",
    )


def int_at_least(lo: int) -> Callable[[str], int]:
    """An integer option >= lo."""

    def parse(text: str) -> int:
        value = int(text)
        if value < lo:
            raise argparse.ArgumentTypeError(f"{value!r} is outside the allowed range [{lo}, inf)")
        return value

    parse.__name__ = f"integer >= {lo}"
    return parse


def degrees_in(lo: float, hi: float) -> Callable[[str], float]:
    """An angle option in degrees, within [lo, hi]."""

    def parse(text: str) -> float:
        value = float(text)
        if not (lo <= value <= hi):
            raise argparse.ArgumentTypeError(
                f"{value!r} is outside the allowed range [{lo:g}, {hi:g}] deg"
            )
        return value

    parse.__name__ = "degrees"
    return parse
