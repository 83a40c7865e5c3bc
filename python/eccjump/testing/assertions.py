"""Assertions about eccjump's results, with messages that say where and by how much:
:func:`assert_ledger_closes` (the energy ledger of a full motion) and
:func:`assert_maps_equal` (two maps bit for bit)."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from eccjump import Map, MotionResult
from eccjump.motion.simulation import MODES

#: The ledger's default tolerance, against the energies in play (:func:`ledger_scale`), at
#: simulate's default rtol and atol: the largest error seen over 40 000 random runs was 5e-8,
#: near a Painlevé point with forces of 5e7.
LEDGER = 1e-7

#: The most differences an assertion lists.
SHOWN = 5


def ledger_scale(result: MotionResult) -> float:
    """The energies in play in a run, 1 + |E0| + max |l| + the energy dissipated [M g R]:
    the kinetic and potential energies grow like the distance travelled, so the integration
    error of the ledger does too."""
    return (
        1.0 + abs(result.energy0) + float(np.max(np.abs(result.l))) + float(result.dissipated[-1])
    )


def assert_ledger_closes(result: MotionResult, *, tol: float = LEDGER) -> None:
    """Assert that the energy ledger of a full motion closes.

    E + dissipated = E0 is an identity of the equations of motion (the sliding work and each
    impact's loss are kept apart from the integration of the motion), so it checks the
    integration and the bookkeeping of a run: the ledger closes at every point and, by the
    run's totals, at its end; the dissipation never decreases; friction opposes the slip at
    every slip point but those that end a slip (located to the rounding of t).

    Parameters
    ----------
    result : MotionResult
        A run of :func:`eccjump.simulate`.
    tol : float
        The tolerance, relative to :func:`ledger_scale`: the default holds at simulate's
        default tolerances; 1e-3 at its loosest (rtol = atol = 1e-6).

    Returns
    -------
    None

    Raises
    ------
    AssertionError
        Naming the first check that fails, where (t, point, mode) and by how much.

    Examples
    --------
    >>> import eccjump
    >>> from eccjump.testing import assert_ledger_closes
    >>> r = eccjump.simulate(eccjump.Cylinder(0.5, 0.4), 0.52, mu_s=1.0, t_max=20.0)
    >>> assert_ledger_closes(r)
    """
    problems = list(_ledger_problems(result, tol * ledger_scale(result)))
    if problems:
        raise AssertionError(f"status {result.status}: " + "; ".join(problems))


def _ledger_problems(r: MotionResult, tol: float) -> Iterator[str]:
    def at(i: int) -> str:
        return f"at t = {r.t[i]:.9g} (point {i} of {r.t.size}, mode {MODES[r.mode[i]]})"

    along = r.energy + r.dissipated - r.energy0
    off = np.flatnonzero(np.abs(along) > tol)
    if off.size:
        i, worst = int(off[0]), float(np.max(np.abs(along)))
        yield f"E + dissipated - E0 = {along[i]:.3g} {at(i)}, beyond {tol:.3g} (max {worst:.3g})"
    end = r.energy[-1] + r.dissipated_slip + r.dissipated_impacts - r.energy0
    if abs(end) > tol:
        yield f"the totals: E + dissipated_slip + dissipated_impacts - E0 = {end:.3g} at the end"
    steps = np.diff(r.dissipated)
    if steps.size and steps.min() < -tol:
        i = int(np.argmin(steps))
        yield f"dissipated falls by {-steps[i]:.3g} {at(i + 1)}, beyond {tol:.3g}"
    slip = r.mode == MODES.index("SLIP")
    interior = np.flatnonzero(slip[:-1] & (np.diff(r.t) > 0))  # not the event ending a slip
    work = (r.Fx * r.slip_velocity)[interior]
    if work.size and work.max() > 0.0:
        i = int(interior[np.argmax(work)])
        yield f"friction works along the slip (F_x v = {work.max():.3g} > 0) {at(i)}"


def assert_maps_equal(actual: Map, expected: Map) -> None:
    """Assert that two maps are equal bit for bit: the same class, coordinates, fields (by
    dtype, shape and bytes: NaN payloads and the sign of zero count) and the same scalars,
    options and attributes. Lazy maps are computed first.

    Parameters
    ----------
    actual, expected : Map
        Two :class:`~eccjump.Region` or :class:`~eccjump.MotionMap` (or a loaded map).

    Returns
    -------
    None

    Raises
    ------
    AssertionError
        Listing the differences: for a field, how many points differ and the first of them
        by its coordinates, with both values.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> from eccjump.testing import assert_maps_equal
    >>> grid = (np.radians([35, 40]), [0.15], [0.0, 0.1])
    >>> one = eccjump.region(*grid, 1.0, n_threads=1)
    >>> assert_maps_equal(eccjump.region(*grid, 1.0, n_threads=2), one)
    >>> assert_maps_equal(eccjump.region(np.radians([35, 45]), *grid[1:], 1.0), one)
    Traceback (most recent call last):
    ...
    AssertionError: maps differ:
      coords['alpha']: 1 of 2 points differ, first at (1,): 0.7853981633974483 != 0.6981317007977318
    """
    if not isinstance(actual, Map) or not isinstance(expected, Map):
        raise TypeError(f"assert_maps_equal compares two maps, not {type(actual).__name__} "
                        f"and {type(expected).__name__}")  # fmt: skip
    if type(actual) is not type(expected):
        raise AssertionError(
            f"maps differ: a {type(actual).__name__} and a {type(expected).__name__}"
        )
    a, b = actual.compute(), expected.compute()
    diffs = list(_differences("coords", a.coords, b.coords, a))
    for f in dataclasses.fields(a):  # type: ignore[arg-type]  # how each map was made
        if f.name not in _GRID:
            diffs += _differences(f.name, getattr(a, f.name), getattr(b, f.name), a)
    if not any(d.startswith("coords") for d in diffs):  # point by point on one grid only
        diffs += _differences("fields", a.fields, b.fields, a)
    if diffs:
        more = [f"and {len(diffs) - SHOWN} more"] if len(diffs) > SHOWN else []
        raise AssertionError("\n  ".join(["maps differ:", *diffs[:SHOWN], *more]))


#: What the coordinates and the fields hold already (a Region keeps them as attributes).
_GRID = {"coords", "fields", "alpha", "chi", "km_frac", "result"}


def _differences(where: str, x: Any, y: Any, grid: Map) -> Iterator[str]:
    """What differs between x and y, bit for bit, each as ``where: ...``."""
    if isinstance(x, Mapping) and isinstance(y, Mapping):
        if x.keys() != y.keys():
            yield f"{where}: keys {sorted(x)} != {sorted(y)}"
            return
        for k in x:
            yield from _differences(f"{where}[{k!r}]", x[k], y[k], grid)
    elif isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
        yield from _array_difference(where, np.asarray(x), np.asarray(y), grid)
    elif isinstance(x, float) and isinstance(y, float):
        if np.float64(x).tobytes() != np.float64(y).tobytes():
            yield f"{where}: {x!r} != {y!r}"
    elif _kind(x) != _kind(y) or x != y:
        yield f"{where}: {x!r} != {y!r}"


def _kind(value: Any) -> type:
    """The type of a setting, a bool as an int: files store a flag as 0 or 1 (netCDF has no
    boolean attribute), so a loaded map says ``stop_at_slip = 0`` where it said False."""
    return int if isinstance(value, bool | np.bool_ | np.integer) else type(value)


def _array_difference(where: str, x: np.ndarray, y: np.ndarray, grid: Map) -> Iterator[str]:
    if x.dtype != y.dtype or x.shape != y.shape:
        yield f"{where}: {x.dtype}{list(x.shape)} != {y.dtype}{list(y.shape)}"
        return
    if x.tobytes() == y.tobytes():
        return
    # by the bytes of each point: NaN == NaN with the same payload, 0.0 != -0.0
    cells, other = (np.ascontiguousarray(v).reshape(v.size, -1).view(np.uint8) for v in (x, y))
    bad = np.flatnonzero((cells != other).any(axis=-1))
    first = np.unravel_index(int(bad[0]), x.shape)
    p, q = repr(x[first].item()), repr(y[first].item())
    if p == q:  # NaNs of other payloads, or 0.0 and -0.0: their bits
        p, q = (f"{v[first].item()!r} (bits {v[first].tobytes().hex()})" for v in (x, y))
    at = _point(first, x.shape, grid)
    yield f"{where}: {bad.size} of {x.size} points differ, first {at}: {p} != {q}"


def _point(index: tuple[Any, ...], shape: tuple[int, ...], grid: Map) -> str:
    """A point of an array by its coordinates where it spans the map's grid, else its index."""
    if shape != grid.shape:
        return f"at {tuple(int(i) for i in index)}"
    named = (f"{k} = {v[i]:.6g}" for (k, v), i in zip(grid.coords.items(), index, strict=True))
    return "at " + ", ".join(named)
