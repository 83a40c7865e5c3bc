"""Dense output of a run: the 4th-order Dormand–Prince interpolant of every accepted step.

Each step k covers [t_old[k], t_old[k] + h[k]] and gives
y(t_old + s h) = y_old + h * sum_j Q[:, j] s^(j+1), j = 0..3 (as scipy's ``RkDenseOutput``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


class DenseSolution:
    """Callable ``sol(t)`` returning the state (theta, omega) at times ``t``.

    Scalar ``t`` gives shape (2,); an array of shape (n,) gives shape (2, n), as scipy's
    ``OdeSolution``. Times outside [t_min, t_max] raise ``ValueError``.
    """

    def __init__(
        self,
        t_old: NDArray[np.float64],
        h: NDArray[np.float64],
        y_old: NDArray[np.float64],
        q: NDArray[np.float64],
    ) -> None:
        self._t_old, self._h, self._y_old, self._q = t_old, h, y_old, q
        self.t_min = float(t_old[0])
        self.t_max = float(t_old[-1] + h[-1])

    def __call__(self, t: ArrayLike) -> NDArray[np.float64]:
        tt = np.asarray(t, dtype=np.float64)
        flat = np.atleast_1d(tt)
        if np.any(~np.isfinite(flat)) or np.any((flat < self.t_min) | (flat > self.t_max)):
            raise ValueError(
                f"t is outside the allowed range [{self.t_min}, {self.t_max}] of the dense output"
            )
        k = np.clip(np.searchsorted(self._t_old, flat, side="right") - 1, 0, len(self._h) - 1)
        h = self._h[k]
        s = (flat - self._t_old[k]) / h
        q = self._q[k]  # (n, 2, 4)
        acc = q[:, :, 3]
        for j in (2, 1, 0):
            acc = q[:, :, j] + acc * s[:, None]
        y = self._y_old[k] + acc * (h * s)[:, None]
        return y[0] if tt.ndim == 0 else y.T
