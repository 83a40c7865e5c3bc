"""Dense output of a run: ``sol(t)``, evaluated by the core on the 4th-order
Dormand–Prince interpolant of every accepted step (as scipy's ``RkDenseOutput``). It covers
the run exactly: from its start to its end (the terminal event), not beyond."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core


class DenseSolution:
    """Callable ``sol(t)`` returning the state (theta, omega) at times ``t``.

    Scalar ``t`` gives shape (2,); an array of shape (n,) gives shape (2, n), as scipy's
    ``OdeSolution``. Times outside [t_min, t_max] raise ``ValueError``.
    """

    def __init__(self, core: _core.DenseSolution) -> None:
        self._core = core
        self.t_min = float(core.t_min)
        self.t_max = float(core.t_max)

    @staticmethod
    def _times(t: ArrayLike) -> tuple[NDArray[np.float64], bool]:
        tt = np.asarray(t, dtype=np.float64)
        if tt.ndim > 1:
            raise ValueError(f"t must be a number or a 1-D array of times, got shape {tt.shape}")
        return np.ascontiguousarray(np.atleast_1d(tt)), tt.ndim == 0

    def __call__(self, t: ArrayLike) -> NDArray[np.float64]:
        flat, scalar = self._times(t)
        y = self._core.states(flat)
        return y[:, 0] if scalar else y

    def kinematics(self, t: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """theta, omega, omega_dot, Fx, Fy at times ``t`` (1-D), from the core's equations of
        the run's mode."""
        flat, _ = self._times(t)
        return self._core.kinematics(flat)
