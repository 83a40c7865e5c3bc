"""Dense output of a run: ``sol(t)``, evaluated by the core on the 4th-order
Dormand–Prince interpolant of every accepted step (as scipy's ``RkDenseOutput``). It covers
the run exactly: from its start to its end (the terminal event), not beyond."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.checks import real_array


class DenseSolution:
    """Dense output of a rolling run: callable ``sol(t)`` returning (θ, θ̇) at ``t``.

    Returned as ``RollResult.sol`` by ``eccjump.roll(..., dense_output=True)``. It
    evaluates the interpolant of every accepted step (as scipy's ``OdeSolution``) and covers
    the run from its start to its end (the terminal event), not beyond.

    Parameters
    ----------
    core : eccjump._core.DenseSolution
        The core's interpolant (made by :func:`eccjump.roll`, not by hand).

    Attributes
    ----------
    t_min : float
        Start of the run [√(R/g)].
    t_max : float
        End of the run [√(R/g)]: the interpolant covers [t_min, t_max].

    Examples
    --------
    >>> import math
    >>> import eccjump
    >>> body = eccjump.Cylinder(chi=0.15, km=0.02)
    >>> res = eccjump.roll(body, math.radians(40), mu_s=1.0, dense_output=True)
    >>> theta, omega = res.sol(1.0)  # at t = 1 sqrt(R/g)
    >>> print(f"theta = {theta:.6f} rad, omega = {omega:.6f} sqrt(g/R)")
    theta = 0.277564 rad, omega = 0.560613 sqrt(g/R)
    >>> res.sol([0.0, 1.0, 2.0]).shape
    (2, 3)
    """

    def __init__(self, core: _core.DenseSolution) -> None:
        self._core = core
        self.t_min = float(core.t_min)
        self.t_max = float(core.t_max)

    @staticmethod
    def _times(t: ArrayLike) -> tuple[NDArray[np.float64], bool]:
        tt = real_array("t", t)
        if tt.ndim > 1:
            raise ValueError(f"t must be a number or a 1-D array of times, got shape {tt.shape}")
        return np.ascontiguousarray(np.atleast_1d(tt)), tt.ndim == 0

    def __copy__(self) -> DenseSolution:
        return self  # immutable: copies share the core's interpolant

    def __deepcopy__(self, memo: dict[int, object]) -> DenseSolution:
        return self

    def same_as(self, other: object, t: ArrayLike | None = None) -> bool:
        """Whether ``other`` is the same dense output: the same interpolant object, or the
        same t_min and t_max and the same states at the times ``t`` (default: 33 times evenly
        spaced over [t_min, t_max]; :class:`RollResult` uses its step times)."""
        if not isinstance(other, DenseSolution):
            return False
        if other._core is self._core:
            return True
        if (self.t_min, self.t_max) != (other.t_min, other.t_max):
            return False
        times = np.linspace(self.t_min, self.t_max, 33) if t is None else t
        return bool(np.array_equal(self(times), other(times), equal_nan=True))

    def __eq__(self, other: object) -> bool:
        """See :meth:`same_as` (states at 33 evenly spaced times)."""
        if not isinstance(other, DenseSolution):
            return NotImplemented
        return self.same_as(other)

    __hash__ = None  # type: ignore[assignment]

    def __call__(self, t: ArrayLike) -> NDArray[np.float64]:
        """The state (θ [rad], θ̇ [√(g/R) rad]) at the times ``t``.

        Parameters
        ----------
        t : float or array_like of shape (n,)
            Times [√(R/g)], each in [t_min, t_max].

        Returns
        -------
        numpy.ndarray
            Shape (2,) for a scalar ``t``, (2, n) for an array: rows θ and θ̇.

        Raises
        ------
        ValueError
            If a time is outside [t_min, t_max], not finite, or ``t`` has more than one
            dimension.
        MemoryError
            If the result cannot be allocated.
        """
        flat, scalar = self._times(t)
        y = self._core.states(flat)
        return y[:, 0] if scalar else y

    def kinematics(self, t: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """θ, θ̇, θ̈, F_x, F_y at times ``t``, from the core's equations of the
        run's mode.

        Parameters
        ----------
        t : float or array_like of shape (n,)
            Times [√(R/g)], each in [t_min, t_max].

        Returns
        -------
        dict of str to numpy.ndarray
            ``theta`` [rad], ``omega`` [√(g/R) rad], ``omega_dot`` [g/R rad], ``Fx`` and
            ``Fy`` [M g], each of shape (n,).

        Raises
        ------
        ValueError
            If a time is outside [t_min, t_max] or not finite.
        """
        flat, _ = self._times(t)
        return self._core.kinematics(flat)
