"""A fake ``eccjump.simulate`` result, with the field names of MotionResult (only the
documented ones: no ``body``, ``alpha`` or ``mu_s``), for testing the CLI table, the JSON and
the figure writers before (and independently of) the real integrator.

The run: ROLL from rest (0 <= t <= 2), SLIP (2 <= t <= 3) with a ``reverse`` at t = 2.5,
lift-off (``normal_force``) into FLIGHT (3 <= t <= 3.6), an ``impact`` back into ROLL
(3.6 <= t <= 4.5), then status ``t_max``. The curves are smooth made-up functions, not the
dynamics; what is consistent: l' = theta' in ROLL, b = 1 and b' = 0 in contact, F = 0 in
flight, the energy is E(state) of docs/motion.md, and ``dissipated`` = E(0) - E, so the
ledger closes exactly. At every transition the point appears twice (end of the old segment,
start of the new one), as in the real result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from reference_points import SLIP_FIRST_ALPHA, SLIP_FIRST_BODY

MODES = ("ROLL", "SLIP", "FLIGHT")

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Transition:
    t: float
    from_mode: str | None
    to_mode: str
    reason: str
    theta: float
    omega: float
    l: float  # noqa: E741 - the name of the field in the API
    ldot: float
    b: float
    bdot: float


@dataclass(frozen=True)
class FlightRecord:
    t_liftoff: float
    t_landing: float
    theta_liftoff: float
    theta_landing: float
    apex: float
    distance: float


@dataclass(frozen=True)
class ImpactRecord:
    t: float
    normal_speed: float
    pt: float
    pn: float
    energy_lost: float
    sticking: bool
    outcome: str


@dataclass(frozen=True, eq=False)
class FakeMotionResult:
    t: Array
    theta: Array
    omega: Array
    l: Array  # noqa: E741
    ldot: Array
    b: Array
    bdot: Array
    Fx: Array
    Fy: Array
    energy: Array
    dissipated: Array
    mode: NDArray[np.int8]
    transitions: tuple[Transition, ...]
    flights: tuple[FlightRecord, ...]
    impacts: tuple[ImpactRecord, ...]
    energy0: float
    dissipated_slip: float
    dissipated_impacts: float
    status: str
    message: str
    nfev: int
    sol: Any = None
    units: Any = None
    calls: list[int] = field(default_factory=list)  # test bookkeeping: sol() calls

    @property
    def slip_velocity(self) -> Array:
        return self.ldot - self.omega

    @property
    def height(self) -> Array:
        return self.b - 1.0

    def mode_names(self) -> list[str]:
        return [tr.to_mode for tr in self.transitions]


def energy(chi: float, icm: float, alpha: float, theta, omega, l, ldot, b, bdot):  # noqa: E741
    """E of docs/motion.md (per M g R)."""
    vx = ldot + chi * np.cos(theta) * omega
    vy = bdot - chi * np.sin(theta) * omega
    return (
        0.5 * (vx**2 + vy**2)
        + 0.5 * icm * omega**2
        - (l + chi * np.sin(theta)) * math.sin(alpha)
        + (b + chi * np.cos(theta)) * math.cos(alpha)
    )


def fake_result(
    chi: float = SLIP_FIRST_BODY[0],
    km: float = SLIP_FIRST_BODY[1],
    alpha: float = SLIP_FIRST_ALPHA,
    *,
    with_sol: bool = False,
) -> FakeMotionResult:
    icm = km + chi**2 / (1.0 - km) - chi**2
    segs: list[dict[str, Array]] = []

    def seg(t: Array, mode: int, **cols: Array) -> dict[str, Array]:
        d = {"t": t, "mode": np.full(t.size, mode, dtype=np.int8)}
        for k in ("theta", "omega", "l", "ldot", "b", "bdot", "Fx", "Fy"):
            d[k] = np.broadcast_to(np.asarray(cols[k], float), t.shape).astype(float)
        segs.append(d)
        return d

    # ROLL from rest
    t = np.linspace(0.0, 2.0, 41)
    th = 0.6 * t**2
    r1 = seg(
        t,
        0,
        theta=th,
        omega=1.2 * t,
        l=th,
        ldot=1.2 * t,
        b=1.0,
        bdot=0.0,
        Fx=-0.2 - 0.1 * np.sin(th),
        Fy=0.8 + 0.1 * np.cos(th),
    )
    th1, w1, l1 = r1["theta"][-1], r1["omega"][-1], r1["l"][-1]

    # SLIP, v = 0.8 tau (tau - 0.5): negative, 0 at tau = 0.5 (reverse), then positive
    def slip(tau: Array) -> dict[str, Array]:
        w = w1 + 0.6 * tau
        fy = 0.6 - 0.5 * tau
        v = 0.8 * tau * (tau - 0.5)
        return {
            "theta": th1 + w1 * tau + 0.3 * tau**2,
            "omega": w,
            "l": l1 + w1 * tau + 0.3 * tau**2 + 0.8 * (tau**3 / 3 - 0.25 * tau**2),
            "ldot": w + v,
            "b": np.ones_like(tau),
            "bdot": np.zeros_like(tau),
            "Fx": -0.3 * np.sign(v) * fy,
            "Fy": fy,
        }

    tau = np.linspace(0.0, 0.5, 11)
    seg(2.0 + tau, 1, **slip(tau))
    tau = np.linspace(0.5, 1.0, 11)
    r3 = seg(2.0 + tau, 1, **slip(tau))
    th2, w2, l2, ld2 = r3["theta"][-1], r3["omega"][-1], r3["l"][-1], r3["ldot"][-1]

    # FLIGHT for 0.6
    tau = np.linspace(0.0, 0.6, 25)
    ld = ld2 + math.sin(alpha) * tau
    r4 = seg(
        3.0 + tau,
        2,
        theta=th2 + w2 * tau,
        omega=w2,
        l=l2 + ld2 * tau + 0.5 * math.sin(alpha) * tau**2,
        ldot=ld,
        b=1.0 + 0.4 * tau * (0.6 - tau),
        bdot=0.4 * (0.6 - 2.0 * tau),
        Fx=0.0,
        Fy=0.0,
    )
    th3, l3, ld3, bd3 = r4["theta"][-1], r4["l"][-1], r4["ldot"][-1], r4["bdot"][-1]

    # impact into ROLL (theta' = l' after it), then ROLL to t = 4.5
    w4 = 0.8 * ld3
    tau = np.linspace(0.0, 0.9, 19)
    seg(
        3.6 + tau,
        0,
        theta=th3 + w4 * tau + 0.25 * tau**2,
        omega=w4 + 0.5 * tau,
        l=l3 + w4 * tau + 0.25 * tau**2,
        ldot=w4 + 0.5 * tau,
        b=1.0,
        bdot=0.0,
        Fx=-0.25,
        Fy=0.9,
    )

    cols = {k: np.concatenate([s[k] for s in segs]) for k in segs[0]}
    e = energy(chi, icm, alpha, *(cols[k] for k in ("theta", "omega", "l", "ldot", "b", "bdot")))
    e0 = float(e[0])
    diss = e0 - e
    # the segment boundaries in the concatenated arrays: 41, 52, 63, 88
    i_slip, i_rev, i_fly, i_imp = 41, 52, 63, 88

    def tr(i: int, frm: str | None, to: str, reason: str) -> Transition:
        return Transition(
            float(cols["t"][i]),
            frm,
            to,
            reason,
            *(float(cols[k][i]) for k in ("theta", "omega", "l", "ldot", "b", "bdot")),
        )

    transitions = (
        tr(0, None, "ROLL", "start"),
        tr(i_slip, "ROLL", "SLIP", "slip"),
        tr(i_rev, "SLIP", "SLIP", "reverse"),
        tr(i_fly, "SLIP", "FLIGHT", "normal_force"),
        tr(i_imp, "FLIGHT", "ROLL", "impact"),
    )
    fl = slice(i_fly, i_imp)
    flights = (
        FlightRecord(
            3.0,
            3.6,
            float(cols["theta"][i_fly]),
            float(cols["theta"][i_imp]),
            float(np.max(cols["b"][fl]) - 1.0),
            float(cols["l"][i_imp] - cols["l"][i_fly]),
        ),
    )
    lost = float(e[i_imp - 1] - e[i_imp])
    impacts = (ImpactRecord(3.6, float(-bd3), 0.1, 0.2, lost, True, "ROLL"),)
    d_slip = float(diss[i_fly])
    res = FakeMotionResult(
        **{k: cols[k] for k in ("t", "theta", "omega", "l", "ldot", "b", "bdot", "Fx", "Fy")},
        energy=e,
        dissipated=diss,
        mode=cols["mode"],
        transitions=transitions,
        flights=flights,
        impacts=impacts,
        energy0=e0,
        dissipated_slip=d_slip,
        dissipated_impacts=float(diss[-1]) - d_slip,
        status="t_max",
        message="reached t_max = 4.5",
        nfev=1234,
    )
    if with_sol:
        object.__setattr__(res, "sol", _interp_sol(res))
    return res


def _interp_sol(res: FakeMotionResult):
    def sol(t):
        res.calls.append(np.size(t))
        names = ("theta", "omega", "l", "ldot", "b", "bdot")
        return np.array([np.interp(t, res.t, getattr(res, k)) for k in names])

    return sol
