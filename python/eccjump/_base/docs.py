"""The docstring entries that many functions share, written once (as scipy's ``doccer``).

A docstring names an entry by a line holding only its placeholder, ``%(alpha)s``, indented as
the entry's first line is to be; :func:`fill` (a decorator) puts the entry of
:data:`ENTRIES` there, each of its lines indented as the placeholder. ``help()``, the
doctests and the site's API reference (``docs/_ext/griffe_eccjump.py`` reads the filled
docstring) all see the whole text. An entry that two functions word differently on purpose
stays in each docstring; a variant used by several gets its own key (``mu_s_array``).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import TypeVar

T = TypeVar("T", bound=Callable[..., object])

#: Entries by key: a numpydoc parameter (or raised exception) with its description, as it
#: reads at the left margin.
ENTRIES: dict[str, str] = {
    # -- the point: ramp and body ------------------------------------------------------------
    "alpha": """\
alpha : array_like of float
    Ramp angle [rad], in [0, π/2] (``math.radians`` for degrees).""",
    "alpha_points": """\
alpha : array_like of float
    Ramp angle [rad], in [0, π/2] (``math.radians`` for degrees). A scalar outside is a
    ValueError; in an array, a point outside is invalid, and values in (π/2, 90] (degrees,
    by the look of them) give one UserWarning per call.""",
    "chi": """\
chi : array_like of float
    The body's d/R, in [0, 1].""",
    "km": """\
km : array_like of float
    The body's shell mass fraction k_m, in [0, 1 - χ].""",
    "body": """\
body : Cylinder
    The body (χ, km).""",
    # -- angles along the rolling path -------------------------------------------------------
    "theta": """\
theta : array_like of float
    Angle [rad].""",
    "theta_J": """\
theta_J : array_like of float
    The jump angle [rad].""",
    # -- friction, the turn, the rule --------------------------------------------------------
    "mu_s": """\
mu_s : float
    Static friction coefficient, in [0, inf).""",
    "mu_s_array": """\
mu_s : array_like of float
    Static friction coefficient, in [0, inf).""",
    "n_turn": """\
n : int, default 1
    The turn, ≥ 1 (not None: these formulas are for one given turn).""",
    "n_first": """\
n : int or None, default None
    The turn on which the jump must happen (1 ... 2**32 - 1), or None for the first jump
    whatever its turn.""",
    "rule": """\
rule : {"paper", "normal_force"}, default "paper"
    Lift-off rule: the paper's condition χ θ̇² cos θ = cos α, or Fy = 0.""",
    "rule_short": """\
rule : {"paper", "normal_force"}, default "paper"
    Lift-off rule.""",
    "rule_rolling": """\
rule : {"paper", "normal_force"}, default "paper"
    Lift-off rule from rolling.""",
    # -- the start ---------------------------------------------------------------------------
    "theta0": """\
theta0 : float, default 0.0
    Initial angle [rad], |theta0| ≤ 2π 1e6.""",
    "theta0_modulo": """\
theta0 : float, default 0.0
    Initial angle [rad], |theta0| ≤ 2π 1e6, taken modulo 2π.""",
    "omega0": """\
omega0 : float, default 0.0
    Initial angular velocity [√(g/R) rad], in [0, 1e6].""",
    # -- the work ----------------------------------------------------------------------------
    "grid_starts": """\
grid : int, default 40
    Points per axis of the midpoint grid of (α, χ, km_frac), 2 ... 128.""",
    "n_threads": """\
n_threads : int, default 0
    Threads, 0 (one per core) ... 256; results are identical for any value.""",
    # -- progress of long calls (eccjump._base.progress) ----------------------------------
    "progress": """\
progress : bool, callable or None, default None
    Progress of the work, in points: None or False, none; True, a bar on stderr (tqdm);
    a callable, called as ``progress(done, total)`` as the work advances. The results are
    the same bits either way.""",
    # -- the scales of SI units -------------------------------------------------------------
    "g": """\
g : float, default 9.81
    Gravitational acceleration [m/s²], in [1e-50, 1e50].""",
    # -- raised ------------------------------------------------------------------------------
    "value_error_broadcast": """\
ValueError
    For a value out of its range, naming the parameter and the index of the first
    invalid point, or arrays that do not broadcast.""",
    "type_error": """\
TypeError
    For an argument of the wrong type.""",
    "type_error_km": """\
TypeError
    If ``km`` is given, or an argument has the wrong type.""",
    "keyboard_interrupt": """\
KeyboardInterrupt
    On Ctrl-C, within about a second.""",
}

_PLACEHOLDER = re.compile(r"^([ \t]*)%\((\w+)\)s[ \t]*$", re.MULTILINE)


def render(doc: str) -> str:
    """``doc`` with each placeholder line replaced by its entry, indented as the placeholder.

    Raises
    ------
    KeyError
        For a placeholder with no entry, naming it.
    """

    def entry(match: re.Match[str]) -> str:
        indent, key = match.group(1), match.group(2)
        if key not in ENTRIES:
            raise KeyError(f"no docstring entry %({key})s in eccjump._base.docs.ENTRIES")
        return "\n".join(indent + line if line else line for line in ENTRIES[key].split("\n"))

    return _PLACEHOLDER.sub(entry, doc)


def fill(obj: T) -> T:
    """Decorator: fill the placeholders of ``obj``'s docstring (none under ``python -OO``)."""
    if obj.__doc__:
        obj.__doc__ = render(obj.__doc__)
    return obj
