"""Type stubs of the compiled bridge ``eccjump._core`` (Rust, pyo3)."""

from typing import Any

import numpy as np
from numpy.typing import NDArray

VERSION: str

def body_derived(chi: float, km: float) -> tuple[float, float, float]: ...
def body_from_inertia(M: float, R: float, d: float, I_C: float) -> tuple[float, float]: ...
def body_from_shell_and_line(m_C: float, m_P: float, R: float, d: float) -> tuple[float, float]: ...
def roll(
    chi: float,
    km: float,
    alpha: float,
    theta0: float,
    omega0: float,
    mu_s: float | None,
    t_max: float,
    theta_max: float,
    rtol: float,
    atol: float,
    max_steps: int,
    dense_output: bool,
    rule: str,
) -> dict[str, Any]: ...

#: (n, rule, method, rtol, atol, theta0, omega0, max_turns, refine_extrema, n_threads)
CallOptions = tuple[int | None, str, str, float, float, float, float, int, bool, int]

def jarm_points(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: NDArray[np.float64],
    options: CallOptions,
) -> dict[str, NDArray[Any]]: ...
def jarm_grid(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    frac: NDArray[np.float64],
    mu_s: float,
    options: CallOptions,
) -> dict[str, NDArray[Any]]: ...
def reason_codes() -> list[tuple[int, str]]: ...
def pointwise(
    name: str,
    inputs: list[NDArray[np.float64]],
    n: int,
    theta0: float = 0.0,
    omega0: float = 0.0,
) -> list[NDArray[np.float64]]: ...
def alpha_intervals(
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: float,
    n: int | None,
    rule: str,
    n_scan: int,
    n_threads: int,
) -> list[list[tuple[float, float]]]: ...
def mu_s_min_path(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    n: int | None,
    rule: str,
    n_threads: int,
) -> NDArray[np.float64]: ...
