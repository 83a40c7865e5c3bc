"""Type stubs of the compiled bridge ``eccjump._core`` (Rust, pyo3)."""

from typing import Any

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
