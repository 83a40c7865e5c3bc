"""Independent scipy reference of the full motion (docs/motion.md): ROLL, SLIP, FLIGHT, impacts.

This module does NOT import eccjump and shares no code with the Rust core. It is (a) the test
oracle for ``eccjump.simulate`` and (b) the "straightforward scipy ``solve_ivp`` event-driven
implementation" that the Rust version is benchmarked against.

Units g = R = M = 1. State (θ, θ̇, l, l̇, b, ḃ): θ the angle of C → CM from the ramp normal
(growing as the body rolls down), l the position of the centre C along the ramp (x down the
ramp), b the height of C above the ramp (b = 1 in contact). Gravity is (sin α, −cos α).

Derivation (Newton–Euler, derived here, not copied from the closed forms)
--------------------------------------------------------------------------
CM position r = (l + χ sin θ, b + χ cos θ). The contact force F = (F_x, F_y) acts at the
contact point P = (l, b − 1); Newton F + (sin α, −cos α) = r̈ gives the first two rows, the
torque about the CM (lever arm P − r = (−χ sin θ, −(1 + χ cos θ)) in contact; θ clockwise)
the third::

    l̈ + χ cos θ θ̈ − F_x = sin α + χ sin θ θ̇²
    b̈ − χ sin θ θ̈ − F_y = χ cos θ θ̇² − cos α
    Ĩ_CM θ̈ + (1 + χ cos θ) F_x − χ sin θ F_y = 0

Each mode adds two rows, and the 5×5 system in (θ̈, l̈, b̈, F_x, F_y) is solved numerically
with ``numpy.linalg.solve`` at every right-hand-side call:

- ROLL:   b̈ = 0, l̈ − θ̈ = 0;
- SLIP:   b̈ = 0, F_x − σ μ_k F_y = 0 (σ = −sign v, v = l̇ − θ̇ the slip velocity);
- FLIGHT: F_x = 0, F_y = 0 (the flight is integrated with the resulting free equations
  θ̈ = 0, l̈ = χθ̇² sin θ + sin α, b̈ = χθ̇² cos θ − cos α, written out as a user would).

The closed forms K, D of physics.md are used only for the switches of a slip's form and the
jam test below.

Slips near D = 0: the normal impulse as the independent variable
----------------------------------------------------------------
In SLIP, F_y = Ĩ_CM B/D (B = cos α − χθ̇² cos θ) grows without bound as D = Ĩ_CM + χ K sin θ
→ 0⁺ (Painlevé), yet the motion may go on (physics.md). Divide the three rows by F_y: with
b̈ = 0 and F_x/F_y = σ μ_k known they are linear in (θ̈/F_y, l̈/F_y, 1/F_y)::

    χ cos θ (θ̈/F_y) + (l̈/F_y) − (sin α + χ sin θ θ̇²)(1/F_y) = σ μ_k
    −χ sin θ (θ̈/F_y) + B (1/F_y) = 1
    Ĩ_CM (θ̈/F_y) = χ sin θ − σ μ_k (1 + χ cos θ)   (= K)

Its determinant is Ĩ_CM B: the system stays regular at D = 0 (Ĩ_CM > 0, B > 0 in a slip);
``newton_euler_impulse`` builds it from the same rows as ``newton_euler`` and solves it with
``numpy.linalg.solve``. With the normal impulse P (dP = F_y dt) as the independent variable::

    dt/dP = 1/F_y, dθ/dP = θ̇/F_y, dθ̇/dP = θ̈/F_y, dl/dP = l̇/F_y, dl̇/dP = l̈/F_y,
    dq/dP = μ_k |v|

are finite at D = 0. There 1/F_y = D/(Ĩ_CM B) → 0: t and θ freeze, the velocities move on a
line in P, and D decays like exp(−cP), so it reaches 0 at no finite impulse. The ledger
(dq/dP = μ_k|v|, the kinetic energy convex on that line) forces the slip velocity to 0 at a
finite P: the slip goes on (stick, reversal) if that happens at a D float64 resolves,
otherwise the rigid model needs an impulsive tangential impact: a jam.

A slip is integrated in time while D > ``D_SWITCH`` = 1e-3 and in P below it, state
(t, θ, θ̇, l, l̇, q), with the events: v = 0 (then ``decide`` as in time), D rises to
2 ``D_SWITCH`` (back to time; the factor 2 keeps the forms from chattering), B falls to 0
(flight), t reaches t_max, and D falls to ``D_JAM`` = 1e-12 with the slip still on: status
"painleve", message "Painlevé jam: ..." (likewise if P reaches ``P_MAX`` = 1e6). A switch of
form is not a transition. |dθ̇/dP| = |K|/Ĩ_CM ≤ (1 + 2μ_k)/Ĩ_CM, so the P steps are capped
at ``MAX_STEP`` Ĩ_CM/(1 + 2μ_k): θ̇ changes by at most ``MAX_STEP`` per step.

Impact law (written here from the impulse–momentum equations)
--------------------------------------------------------------
An impulse (P_t, P_n) at P changes the CM velocity by (P_t, P_n) and θ̇ by
Δθ̇ = (s P_n − c P_t)/Ĩ_CM with s = χ sin θ, c = 1 + χ cos θ. The contact point moves with
u = (u_t, u_n) = (l̇ − θ̇, ḃ), so Δu = W P with::

    W = [[1 + c²/Ĩ, −cs/Ĩ], [−cs/Ĩ, 1 + s²/Ĩ]]   (symmetric, positive definite for Ĩ_CM > 0)

Routh's method integrates in the normal impulse p. u is linear in p on every segment
(sliding with dP_t = −sgn(u_t) μ_k dp, or sticking with dP_t/dp = −W_tn/W_tt when that ratio
is at most μ_s), so the segments are stepped exactly: a segment ends when u_t reaches 0, when
u_n reaches 0 (end of compression), or when the normal work reaches Stronge's target (the
work of the normal impulse in restitution = −e² × its work in compression). Sliding uses μ_k,
the stick test μ_s. If a sliding restitution segment drives u_n back to 0 before the target
is reached, the impact ends there (u_n = 0; more energy is lost than the target; rare).
Ĩ_CM = 0 (k_m = 0) makes W infinite: an impact of such a body ends the run with status
"failed" (rolling and slipping work).

Events are located by ``solve_ivp`` itself (Brent on the dense output of each step); an event
is seen only if its function changes sign between two step ends (``max_step`` = 0.05 caps the
steps). Each event function is replaced by a value on its "not yet crossed" side at the exact
start time of a segment, so that a zero at the start (v = 0 at slip onset, the gap at
lift-off) never fires; roots after the start are found.

Tolerances of the decision (documented numerical parameters): a slip velocity with
|v| ≤ ``V_ZERO`` = 1e-12 counts as 0; the slip-acceleration sign test of step 4 of the
consistency test agrees when |v̇| ≤ 1e-12 (1 + |l̈| + |θ̈|); the quantity of the event that
just fired is taken as exactly 0 and on its post-crossing side.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

ROLL, SLIP, FLIGHT = "ROLL", "SLIP", "FLIGHT"
SETTLE_SPEED = 1e-6
D_SWITCH = 1e-3
D_JAM = 1e-12
P_MAX = 1e6
V_ZERO = 1e-12
MAX_STEP = 0.05
STATUSES = ("t_max", "max_transitions", "painleve", "jam", "failed")
REASONS = (
    "start",
    "slip",
    "liftoff",
    "normal_force",
    "slip_inconsistent",
    "stick",
    "reverse",
    "impact",
    "settle",
)


class Body:
    """χ, k_m, α and the derived Ĩ_CM (shell + line-mass model)."""

    def __init__(self, chi: float, km: float, alpha: float) -> None:
        if not (0.0 <= chi <= 1.0):
            raise ValueError(f"chi must lie in [0, 1], got {chi}")
        if not (0.0 <= km <= 1.0 - chi + 1e-15):
            raise ValueError(f"km must lie in [0, 1 - chi], got {km}")
        if not (0.0 <= alpha <= math.pi / 2):
            raise ValueError(f"alpha must lie in [0, pi/2], got {alpha}")
        self.chi, self.km, self.alpha = float(chi), float(km), float(alpha)
        self.sa = math.sin(alpha)
        self.ca = 0.0 if alpha == math.pi / 2 else math.cos(alpha)
        if km >= 1.0:  # only with chi = 0
            self.icm = km
        else:
            self.icm = km * (1.0 - km + chi * chi) / (1.0 - km)


# ---------------------------------------------------------------------------------------------
# Newton–Euler
# ---------------------------------------------------------------------------------------------


def newton_euler_rows(body: Body, th: float, om: float):
    """The three Newton–Euler rows A z = r in z = (θ̈, l̈, b̈, F_x, F_y): A (3×5), r (3)."""
    chi = body.chi
    s, c = math.sin(th), math.cos(th)
    a = np.zeros((3, 5))
    r = np.zeros(3)
    a[0, 0], a[0, 1], a[0, 3] = chi * c, 1.0, -1.0
    r[0] = body.sa + chi * s * om * om
    a[1, 0], a[1, 2], a[1, 4] = -chi * s, 1.0, -1.0
    r[1] = chi * c * om * om - body.ca
    a[2, 0], a[2, 3], a[2, 4] = body.icm, 1.0 + chi * c, -chi * s
    return a, r


def newton_euler(body: Body, mode: str, th: float, om: float, sigma: float = 0.0, mu_k=0.0):
    """Solve the 5×5 Newton–Euler system of ``mode``: returns (θ̈, l̈, b̈, F_x, F_y)."""
    a = np.zeros((5, 5))
    r = np.zeros(5)
    a[:3], r[:3] = newton_euler_rows(body, th, om)
    if mode == ROLL:
        a[3, 2] = 1.0
        a[4, 0], a[4, 1] = -1.0, 1.0
    elif mode == SLIP:
        a[3, 2] = 1.0
        a[4, 3], a[4, 4] = 1.0, -sigma * mu_k
    elif mode == FLIGHT:
        a[3, 3] = 1.0
        a[4, 4] = 1.0
    else:
        raise ValueError(mode)
    return np.linalg.solve(a, r)


def newton_euler_impulse(body: Body, th: float, om: float, sigma: float, mu_k: float):
    """The sliding rows divided by F_y: returns (θ̈/F_y, l̈/F_y, 1/F_y), finite as D → 0.

    With b̈ = 0 and F_x/F_y = σ μ_k the rows A z = r become, in x = (θ̈/F_y, l̈/F_y, 1/F_y),
    A[:, 0] x0 + A[:, 1] x1 − r x2 = −σ μ_k A[:, 3] − A[:, 4]; its determinant is Ĩ_CM B.
    """
    a, r = newton_euler_rows(body, th, om)
    m = np.column_stack([a[:, 0], a[:, 1], -r])
    return np.linalg.solve(m, -sigma * mu_k * a[:, 3] - a[:, 4])


def slip_d(body: Body, th: float, sigma: float, mu_k: float) -> float:
    """D = Ĩ_CM + χ K sin θ, K = χ sin θ − σ μ_k (1 + χ cos θ) (for the switches and the jam)."""
    s, c = math.sin(th), math.cos(th)
    k = body.chi * s - sigma * mu_k * (1.0 + body.chi * c)
    return body.icm + body.chi * k * s


def lift_l(body: Body, th: float, om: float) -> float:
    """L = χθ̇² cos θ − cos α = b̈ of the free flight (= −B)."""
    return body.chi * om * om * math.cos(th) - body.ca


def energy(body: Body, th, om, x, ld, b, bd) -> float:
    """Mechanical energy per M g R: kinetic + potential (reference: C at l = 0, b = 0)."""
    chi = body.chi
    s, c = math.sin(th), math.cos(th)
    xd = ld + chi * c * om
    yd = bd - chi * s * om
    kin = 0.5 * (xd * xd + yd * yd) + 0.5 * body.icm * om * om
    return kin - (x + chi * s) * body.sa + (b + chi * c) * body.ca


# ---------------------------------------------------------------------------------------------
# Impact law: Routh + Coulomb + Stronge, stepped exactly segment by segment
# ---------------------------------------------------------------------------------------------


def contact_w(body: Body, th: float):
    """(W_tt, W_tn, W_nn): Δ(u_t, u_n) = W (P_t, P_n)."""
    if body.icm <= 0.0:
        raise ZeroDivisionError("Ĩ_CM = 0: the impact law of this reference needs k_m > 0")
    s = body.chi * math.sin(th)
    c = 1.0 + body.chi * math.cos(th)
    i = body.icm
    return 1.0 + c * c / i, -c * s / i, 1.0 + s * s / i


def _first_root(un: float, k: float, r: float) -> float:
    """Smallest x > 0 with un x + k x²/2 = r (r > 0, un ≥ 0); inf if none."""
    disc = un * un + 2.0 * k * r
    if disc < 0.0:
        return math.inf
    den = un + math.sqrt(disc)
    return 2.0 * r / den if den > 0.0 else math.inf


def impact_impulse(wtt, wtn, wnn, ut, un, mu_s, mu_k, e):
    """Routh's method in the normal impulse p. Returns (P_t, P_n, u_t, u_n, segments)."""
    if un >= 0.0:
        return 0.0, 0.0, ut, un, []
    p = pt = work = 0.0
    compressing = True
    target = 0.0
    segments = []
    for _ in range(50):
        if ut != 0.0:
            rho = -math.copysign(mu_k, ut)
            kind = "slide"
        else:
            ratio = -wtn / wtt
            if abs(ratio) <= mu_s:
                rho, kind = ratio, "stick"
            else:  # slides away in the direction the impulse pushes it
                rho, kind = -math.copysign(mu_k, wtn), "slide"
        dut = wtt * rho + wtn
        dun = wtn * rho + wnn
        if kind == "stick":
            dut = 0.0
        cand = {}
        if ut != 0.0 and dut * ut < 0.0:
            cand["ut0"] = -ut / dut
        if compressing:
            if dun > 0.0:
                cand["comp"] = -un / dun
        else:
            rem = target - work
            cand["rest"] = _first_root(un, dun, rem) if rem > 0.0 else 0.0
            if dun < 0.0:
                cand["un0"] = -un / dun
        if not cand:
            raise RuntimeError("impact: no segment end (W not positive definite?)")
        which = min(cand, key=cand.get)
        dp = cand[which]
        work += un * dp + 0.5 * dun * dp * dp
        un += dun * dp
        ut += dut * dp
        pt += rho * dp
        p += dp
        segments.append((kind, dp))
        if which == "ut0":
            ut = 0.0
        elif which == "comp":
            un = 0.0
            compressing = False
            target = work * (1.0 - e * e)  # total normal work at the end (≤ 0)
            if e == 0.0:
                break
        elif which == "rest":
            break
        elif which == "un0":
            un = 0.0
            break
    else:
        raise RuntimeError("impact: too many segments")
    return pt, p, ut, un, segments


def chi_sin(body: Body, th) -> float:
    """The lever arm χ sin θ of a normal impulse about the CM (contact at angle θ)."""
    return body.chi * math.sin(th)


def apply_impact(body: Body, th, om, ld, bd, mu_s, mu_k, e):
    """Velocities (θ̇, l̇, ḃ) after the impact at contact angle θ, and the impulse."""
    wtt, wtn, wnn = contact_w(body, th)
    pt, pn, _, _, _ = impact_impulse(wtt, wtn, wnn, ld - om, bd, mu_s, mu_k, e)
    chi = body.chi
    dom = (chi * math.sin(th) * pn - (1.0 + chi * math.cos(th)) * pt) / body.icm
    return om + dom, ld + pt - chi * math.cos(th) * dom, bd + pn + chi * math.sin(th) * dom, pt, pn


# ---------------------------------------------------------------------------------------------
# Consistency test (docs/motion.md, "Consistency of a contact mode")
# ---------------------------------------------------------------------------------------------


def decide(body: Body, th, om, v, rule, mu_s, mu_k, event=None):
    """Mode at a contact state with u_n = 0. Returns (mode, sigma, kind).

    kind: "slip" (step 1 or 4), "liftoff" (step 2), "roll" (step 3), "normal_force" or
    "slip_inconsistent" (step 5, flight), "jam". ``event`` names the quantity that just
    crossed 0 ("L_rise", "Fy_fall", "cone_fall", "B_fall", "v_zero", None): it is taken as 0
    and on its post-crossing side.
    """
    lval = lift_l(body, th, om)
    l_forced = event in ("L_rise", "B_fall")
    b_pos = (not l_forced) and (-lval > 0.0)
    l_nonneg = l_forced or lval >= 0.0
    if event == "v_zero":
        v = 0.0
    flight_kind = "normal_force" if event in ("Fy_fall", "B_fall") else "slip_inconsistent"
    if abs(v) > V_ZERO:
        sigma = -math.copysign(1.0, v)
        if slip_d(body, th, sigma, mu_k) > 0.0 and b_pos:
            return SLIP, sigma, "slip"
    else:
        # step 2: the paper's rule
        if rule == "paper":
            if l_forced or lval > 0.0:
                return FLIGHT, 0.0, "liftoff"
            if lval == 0.0:
                thdd = newton_euler(body, ROLL, th, om)[0]
                if body.chi * om * (2.0 * thdd * math.cos(th) - om * om * math.sin(th)) > 0:
                    return FLIGHT, 0.0, "liftoff"
        # step 3: the rolling branch
        z = newton_euler(body, ROLL, th, om)
        fx, fy = z[3], z[4]
        fy_ok = fy > 0.0 and event != "Fy_fall"
        cone_ok = mu_s * fy - abs(fx) >= 0.0 and event != "cone_fall"
        if fy_ok and cone_ok:
            return ROLL, 0.0, "roll"
        # step 4: slip onset, friction in the direction the rolling branch needs
        sigma = 1.0 if fx >= 0.0 else -1.0
        if slip_d(body, th, sigma, mu_k) > 0.0 and b_pos:
            zs = newton_euler(body, SLIP, th, om, sigma, mu_k)
            vdot = zs[1] - zs[0]
            tol = 1e-12 * (1.0 + abs(zs[1]) + abs(zs[0]))
            if zs[4] > 0.0 and (-sigma * vdot > 0.0 or abs(vdot) <= tol):
                return SLIP, sigma, "slip"
    # step 5
    if l_nonneg:
        return FLIGHT, 0.0, flight_kind
    return None, 0.0, "jam"


# ---------------------------------------------------------------------------------------------
# Segments
# ---------------------------------------------------------------------------------------------


def _event(fun, t0, direction):
    """Terminal event with a fixed direction; at the exact start time it returns a value on
    the not-yet-crossed side, so a zero at the start never fires."""
    pre = 1.0 if direction < 0 else -1.0

    def ev(t, y):
        if t == t0:
            return pre
        return fun(t, y)

    ev.terminal = True
    ev.direction = direction
    return ev


def _run(rhs, t0, y0, t_max, events, rtol, atol):
    return solve_ivp(
        rhs,
        (t0, t_max),
        y0,
        method="RK45",
        rtol=rtol,
        atol=atol,
        max_step=MAX_STEP,
        dense_output=False,
        events=events,
    )


def _fired(sol, names):
    """Name of the terminal event that ended ``sol`` (earliest; ties by list order)."""
    if sol.status != 1:
        return None, None
    best = None
    for name, te, ye in zip(names, sol.t_events, sol.y_events, strict=True):
        if len(te) and (best is None or te[-1] < best[1]):
            best = (name, te[-1], ye[-1])
    return best[0], best[2]


def _slip_events(body, sg, mu_k, p0):
    """The events every slip piece watches: B falls to 0, the slip velocity to 0 (y ends
    with θ, θ̇, l, l̇, q in both forms)."""

    def b_fall(_p, y):
        return -lift_l(body, y[-5], y[-4])

    def v_zero(_p, y):
        return -sg * (y[-2] - y[-4])

    return ["B_fall", "v_zero"], [_event(b_fall, p0, -1), _event(v_zero, p0, -1)]


def _slip_in_time(body, sg, mu_k, t, th, om, x, ld, t_max, rtol, atol):
    """A slip piece in time, state (θ, θ̇, l, l̇, q), until an event, D = ``D_SWITCH`` or
    t_max. Returns (event name or None, (t, θ, θ̇, l, l̇, q), nfev, failure message)."""

    def rhs(_t, y):
        z = newton_euler(body, SLIP, y[0], y[1], sg, mu_k)
        return [y[1], z[0], y[3], z[1], mu_k * z[4] * abs(y[3] - y[1])]

    names, events = _slip_events(body, sg, mu_k, t)
    names.append("D_switch")
    events.append(_event(lambda _t, y: slip_d(body, y[0], sg, mu_k) - D_SWITCH, t, -1))
    sol = _run(rhs, t, [th, om, x, ld, 0.0], t_max, events, rtol, atol)
    if sol.status < 0:
        return None, None, sol.nfev, sol.message
    name, y = _fired(sol, names)
    if y is None:
        y = sol.y[:, -1]
    return name, (float(sol.t[-1]), *y), sol.nfev, ""


def _slip_in_impulse(body, sg, mu_k, t, th, om, x, ld, t_max, rtol, atol):
    """A slip piece in the normal impulse P (dP = F_y dt), state (t, θ, θ̇, l, l̇, q), until
    an event, D = 2 ``D_SWITCH`` (back to time), t_max, D = ``D_JAM`` or P = ``P_MAX``."""

    def rhs(_p, y):
        a, b, w = newton_euler_impulse(body, y[1], y[2], sg, mu_k)  # θ̈/F_y, l̈/F_y, 1/F_y
        return [w, y[2] * w, a, y[4] * w, b, mu_k * abs(y[4] - y[2])]

    def d_of(y):
        return slip_d(body, y[1], sg, mu_k)

    if slip_d(body, th, sg, mu_k) <= D_JAM:
        return "D_jam", (t, th, om, x, ld, 0.0), 0, ""
    names, events = _slip_events(body, sg, mu_k, 0.0)
    names += ["D_back", "D_jam", "t_max"]
    events += [
        _event(lambda _p, y: d_of(y) - 2.0 * D_SWITCH, 0.0, +1),
        _event(lambda _p, y: d_of(y) - D_JAM, 0.0, -1),
        _event(lambda _p, y: y[0] - t_max, 0.0, +1),
    ]
    # |dθ̇/dP| = |K|/Ĩ_CM ≤ (1 + 2μ_k)/Ĩ_CM: a step changes θ̇ by at most MAX_STEP
    max_step = MAX_STEP * body.icm / (1.0 + 2.0 * mu_k)
    sol = solve_ivp(
        rhs,
        (0.0, P_MAX),
        [t, th, om, x, ld, 0.0],
        method="RK45",
        rtol=rtol,
        atol=atol,
        max_step=max_step,
        events=events,
    )
    if sol.status < 0:
        return None, None, sol.nfev, sol.message
    name, y = _fired(sol, names)
    if y is None:
        y = sol.y[:, -1]
        name = "P_max"
    return name, tuple(y), sol.nfev, ""


def _jam_message(name: str, t: float, th: float) -> str:
    what = f"D fell to {D_JAM:g}" if name == "D_jam" else f"the normal impulse reached {P_MAX:g}"
    where = f"t={t:.10g}, theta={math.degrees(th):.6f} deg"
    return f"Painlevé jam: {what} with the slip still on at {where}"


def simulate_reference(
    chi,
    km,
    alpha,
    *,
    mu_s,
    mu_k=None,
    restitution=0.0,
    rule="paper",
    theta0=0.0,
    omega0=0.0,
    slip0=0.0,
    t_max=100.0,
    max_transitions=20,
    rtol=1e-10,
    atol=1e-12,
) -> dict:
    """Full motion from a contact start (b = 1, ḃ = 0, l = 0, l̇ = θ̇0 + slip0).

    Returns {"transitions": [(t, from_mode, to_mode, reason, θ, θ̇, l, l̇, b, ḃ), ...],
    "status", "energy0", "energy_end", "dissipated_slip", "dissipated_impacts", "nfev",
    "end": (t, mode, θ, θ̇, l, l̇, b, ḃ), "message", "wall_time"}. ``max_transitions`` counts
    the transitions after the start entry.
    """
    t_wall = time.perf_counter()
    if rule not in ("paper", "normal_force"):
        raise ValueError(f"rule must be 'paper' or 'normal_force', got {rule!r}")
    if mu_k is None:
        mu_k = mu_s
    if mu_s < 0 or mu_k < 0 or not (0.0 <= restitution <= 1.0):
        raise ValueError("need mu_s, mu_k >= 0 and 0 <= restitution <= 1")
    body = Body(chi, km, alpha)
    chi = body.chi

    # x is l (C's position along the ramp; ruff's E741 forbids the name l)
    th, om, x, ld, b, bd = float(theta0), float(omega0), 0.0, float(omega0 + slip0), 1.0, 0.0
    t = 0.0
    e0 = energy(body, th, om, x, ld, b, bd)
    q_slip = 0.0
    q_imp = 0.0
    nfev = 0
    transitions = []
    status, message = None, ""
    next_form = None  # the form a slip goes on in after a switch (D_switch, D_back)
    impulse_pieces = 0

    def record(t, frm, to, reason):
        transitions.append((t, frm, to, reason, th, om, x, ld, b, bd))

    # initial mode
    if rule == "paper" and lift_l(body, th, om) > 0.0:
        mode, sigma = FLIGHT, 0.0
    else:
        mode, sigma, kind = decide(body, th, om, ld - om, rule, mu_s, mu_k)
    if mode in (ROLL, SLIP) and abs(ld - om) <= V_ZERO:
        ld = om
    record(0.0, None, mode, "start")
    if mode is None:
        status = "jam"

    while status is None:
        if len(transitions) - 1 >= max_transitions:
            status = "max_transitions"
            break
        if t >= t_max:
            status = "t_max"
            break
        try:
            if mode == ROLL:
                th_start, l_start = th, x

                def rhs_roll(_t, y):
                    z = newton_euler(body, ROLL, y[0], y[1])
                    return [y[1], z[0]]

                def fy_roll(_t, y):
                    return newton_euler(body, ROLL, y[0], y[1])[4]

                def cone_roll(_t, y):
                    z = newton_euler(body, ROLL, y[0], y[1])
                    return mu_s * z[4] - abs(z[3])

                names = ["Fy_fall", "cone_fall"]
                events = [_event(fy_roll, t, -1), _event(cone_roll, t, -1)]
                if rule == "paper":
                    names.insert(0, "L_rise")
                    events.insert(0, _event(lambda _t, y: lift_l(body, y[0], y[1]), t, +1))
                sol = _run(rhs_roll, t, [th, om], t_max, events, rtol, atol)
                nfev += sol.nfev
                if sol.status < 0:
                    status, message = "failed", sol.message
                    break
                name, y = _fired(sol, names)
                if y is None:
                    y = sol.y[:, -1]
                t = float(sol.t[-1])
                th, om = float(y[0]), float(y[1])
                x, ld, b, bd = l_start + (th - th_start), om, 1.0, 0.0
                if name is None:
                    status = "t_max"
                    break
                new, sigma, kind = decide(body, th, om, 0.0, rule, mu_s, mu_k, event=name)
                if new is None:
                    status = "jam"
                    break
                reason = "slip" if new == SLIP else kind
                if new == ROLL:
                    status, message = "failed", f"event {name} left ROLL consistent"
                    break
                mode = new
                record(t, ROLL, mode, reason)

            elif mode == SLIP:
                sg = sigma
                form = next_form or (
                    "impulse" if slip_d(body, th, sg, mu_k) <= D_SWITCH else "time"
                )
                next_form = None
                impulse_pieces += form == "impulse"
                piece = _slip_in_impulse if form == "impulse" else _slip_in_time
                name, y, nfev_piece, failure = piece(
                    body, sg, mu_k, t, th, om, x, ld, t_max, rtol, atol
                )
                nfev += nfev_piece
                if failure:
                    status, message = "failed", failure
                    break
                t, th, om, x, ld = (float(v_) for v_ in y[:5])
                q_slip += float(y[5])
                if name in ("D_switch", "D_back"):  # the same slip goes on in the other form
                    next_form = "impulse" if name == "D_switch" else "time"
                    continue
                if name in (None, "t_max"):
                    status = "t_max"
                    break
                if name in ("D_jam", "P_max"):
                    status, message = "painleve", _jam_message(name, t, th)
                    break
                v = ld - om
                if name == "v_zero":
                    ld = om
                    v = 0.0
                new, new_sigma, kind = decide(body, th, om, v, rule, mu_s, mu_k, event=name)
                if new is None:
                    status = "jam"
                    break
                if new == ROLL:
                    reason = "stick"
                elif new == SLIP:
                    reason = "reverse"
                    if name != "v_zero" or new_sigma == sg:
                        status, message = "failed", f"event {name} left SLIP consistent"
                        break
                else:
                    reason = kind
                mode, sigma = new, new_sigma
                record(t, SLIP, mode, reason)

            else:  # FLIGHT: θ̇ constant, free equations, state (θ, l, l̇, gap = b − 1, ḃ)
                omf = om

                def rhs_flight(_t, y, omf=omf):
                    th_ = y[0]
                    w2 = chi * omf * omf
                    return [
                        omf,
                        y[2],
                        w2 * math.sin(th_) + body.sa,
                        y[4],
                        w2 * math.cos(th_) - body.ca,
                    ]

                events = [_event(lambda _t, y: y[3], t, -1)]
                sol = _run(rhs_flight, t, [th, x, ld, b - 1.0, bd], t_max, events, rtol, atol)
                nfev += sol.nfev
                if sol.status < 0:
                    status, message = "failed", sol.message
                    break
                name, y = _fired(sol, ["touch"])
                if y is None:
                    y = sol.y[:, -1]
                t = float(sol.t[-1])
                th, x, ld, gap, bd = (float(v_) for v_ in y)
                b = 1.0 + gap
                if name is None:
                    status = "t_max"
                    break
                b = 1.0
                e_before = energy(body, th, om, x, ld, b, bd)
                try:
                    om, ld, bd, _, _ = apply_impact(body, th, om, ld, bd, mu_s, mu_k, restitution)
                except ZeroDivisionError as exc:
                    status, message = "failed", str(exc)
                    break
                reason = "impact"
                if bd > SETTLE_SPEED:
                    mode, sigma = FLIGHT, 0.0
                else:
                    if bd > 0.0:
                        # Zeno rule: one plastic impulse at the contact point ends the
                        # remaining bounces (it dissipates 1/2 du W^-1 du >= 0). Stuck
                        # (v = 0): P = -W^-1 (0, u_n) keeps it stuck; else normal only.
                        if restitution > 0.0:
                            reason = "settle"
                        wtt, wtn, wnn = contact_w(body, th)
                        if abs(ld - om) <= V_ZERO:
                            det = wtt * wnn - wtn * wtn
                            pt, pn = wtn * bd / det, -wtt * bd / det
                        else:
                            pt, pn = 0.0, -bd / wnn
                        c = 1.0 + body.chi * math.cos(th)
                        dom = (chi_sin(body, th) * pn - c * pt) / body.icm
                        om, ld = om + dom, ld + pt - body.chi * math.cos(th) * dom
                    bd = 0.0
                    new, sigma, kind = decide(body, th, om, ld - om, rule, mu_s, mu_k)
                    if new in (ROLL, SLIP) and abs(ld - om) <= V_ZERO:
                        ld = om
                    q_imp += e_before - energy(body, th, om, x, ld, b, bd)
                    if new is None:
                        status = "jam"
                        record(t, FLIGHT, None, reason)
                        break
                    mode = new
                    record(t, FLIGHT, mode, reason)
                    continue
                q_imp += e_before - energy(body, th, om, x, ld, b, bd)
                record(t, FLIGHT, mode, reason)
        except np.linalg.LinAlgError as exc:
            status, message = "failed", f"singular Newton–Euler system: {exc}"
            break
        if not all(math.isfinite(v_) for v_ in (t, th, om, x, ld, b, bd)):
            status, message = "failed", "non-finite state"
            break

    return {
        "transitions": transitions,
        "status": status,
        "message": message,
        "energy0": e0,
        "energy_end": energy(body, th, om, x, ld, b, bd),
        "dissipated_slip": q_slip,
        "dissipated_impacts": q_imp,
        "nfev": nfev,
        "impulse_pieces": impulse_pieces,
        "end": (t, mode, th, om, x, ld, b, bd),
        "wall_time": time.perf_counter() - t_wall,
    }


def format_transitions(res: dict) -> str:
    """One line per transition: t, from → to, reason, θ in degrees, θ̇, v, b, ḃ."""
    lines = []
    for t, frm, to, reason, th, om, _l, ld, b, bd in res["transitions"]:
        lines.append(
            f"t={t:10.6f} {frm or '-':>6} -> {to or '-':<6} {reason:<17} "
            f"theta={math.degrees(th):11.5f} deg om={om:+.6f} v={ld - om:+.3e} "
            f"b-1={b - 1:+.1e} bd={bd:+.3e}"
        )
    lines.append(f"status={res['status']} {res['message']}".rstrip())
    return "\n".join(lines)
